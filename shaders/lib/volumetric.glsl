// Where a fragment falls in its light's translucent map (src/shadows/volumetric/mod.rs,
// lookup_matrix): xy the map's texel, as the light's depth map has it; z its depth along
// the light's axis fitted to the translucent casters (0 the nearest, 1 the farthest); w 0
// where nothing translucent can be in the way, else 1. From the fragment's view-space
// position, so the lookup needs no vertex output of its own.
uniform mat4 volumetricMatrix[LIGHT_COUNT];
// The map's xy the casters were drawn over, a texel wider each side than the texels they
// cover (the lookups' filters reach one texel): min xy, max xy (src/shadows/volumetric/maps.rs).
// Every texel past it is empty.
uniform vec4 volumetricFootprint[LIGHT_COUNT];

vec4 volumetricCoords(int light)
{
    vec4 c = volumetricMatrix[light] * vec4(mvVertexPos, 1.0);
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    vec4 box = volumetricFootprint[light];
    bool onMap = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    bool underCasters = all(greaterThan(uv, box.xy)) && all(lessThan(uv, box.zw));
    // In front of the nearest caster (z <= 0) no crossing is in the way: exactly 1, as
    // every lookup would read it, without its reads.
    bool behindNearest = c.z > 0.0;
    return vec4(uv, c.z, onMap && underCasters && behindNearest ? 1.0 : 0.0);
}

// opaque_receivers = "resolved" (src/shadows/volumetric/resolved.rs): the light's
// translucent map read at the depth map's own depth, one filtered fetch where the
// fragment's light-space position (its map slot's, as the light's test reads it) falls.
// Outside the casters' footprint the map holds 1.
float resolvedTransmittance(sampler2D map, vec4 lightPosition)
{
    return texture(map, lightPosition.xy / lightPosition.w * 0.5 + 0.5).r;
}
