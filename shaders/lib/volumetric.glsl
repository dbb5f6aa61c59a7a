// Where a fragment falls in its light's translucent map (src/shadows/volumetric/mod.rs,
// lookup_matrix): xy the map's texel, as the light's depth map has it; z its depth along
// the light's axis fitted to the translucent casters (0 the nearest, 1 the farthest); w 0
// outside the map (nothing translucent there), else 1. From the fragment's view-space
// position, so the lookup needs no vertex output of its own.
uniform mat4 volumetricMatrix[LIGHT_COUNT];

vec4 volumetricCoords(int light)
{
    vec4 c = volumetricMatrix[light] * vec4(mvVertexPos, 1.0);
    vec2 uv = c.xy / c.w * 0.5 + 0.5;
    bool inside = all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    return vec4(uv, c.z, inside ? 1.0 : 0.0);
}
