// One layer of a layered directional light's depth array (src/shadows/layers.rs): the
// test shared by cascades (shadow_cascades.glsl: a layer per slice of the view) and caster
// groups (shadow_groups.glsl: a layer per group of casters), which include it. A scene has
// one layered light, so its filter is the program's (src/shadows/layers.rs defines it):
//   CASCADES       layers (2 to 4)
//   LAYER_SAMPLER  sampler2DArrayShadow for the hardware filters, else sampler2DArray
//   LAYER_TEXEL    one texel of a layer, vec2(1 / width, 1 / height)
//   LAYER_RADIUS   the PCF grid's half size, as calcShadow's radius
//   LAYER_TAPS_GRID, LAYER_TAPS_WEIGHTED_4X4 or LAYER_TAPS_SOFT_PCF: one of them, named by
//                  the filter's Kernel (src/shadows/map2d.rs): that grid, the playground's
//                  weighted 4 x 4, its soft PCF
// (PCSS is refused for layers: src/scene/refusals.rs, filter_refusal.)

// The layered light's position in each layer's clip space (scene.vert: one light is
// layered, so they fit among the vertex outputs); w, 1 in an orthographic box, carries the
// layer's bias scale: the bias is a fraction of the deepest layer's depth range, the same
// world distance in every layer.
in vec4 cascadePos[CASCADES];

// One comparison in a layer: 1 = lit. Through a shadow sampler the hardware compares the
// 4 nearest texels and blends the results.
float compareLayer(sampler2DArray map, vec2 uv, float layer, float current)
{
    return step(current, texture(map, vec3(uv, layer)).r);
}

float compareLayer(sampler2DArrayShadow map, vec2 uv, float layer, float current)
{
    return texture(map, vec4(uv, layer, current));
}

// The test in layer `c` (the position already pushed along the normal by the layer's own
// texel size, in scene.vert). A layer's box covers exactly what it must: beyond its far
// plane is lit, as outside it (the border).
float layerLookup(LAYER_SAMPLER map, int c, float bias)
{
    vec3 projCoords = cascadePos[c].xyz * 0.5 + 0.5;
    vec2 uv = projCoords.xy;
    float layer = float(c);
    float current = projCoords.z - bias * cascadePos[c].w;
    float lit = 0.0;
#if defined(LAYER_TAPS_GRID)
    for (int row = -LAYER_RADIUS; row <= LAYER_RADIUS; ++row) {
        for (int col = -LAYER_RADIUS; col <= LAYER_RADIUS; ++col) {
            lit += compareLayer(map, uv + vec2(row, col) * LAYER_TEXEL, layer, current);
        }
    }
    lit /= float((2 * LAYER_RADIUS + 1) * (2 * LAYER_RADIUS + 1));
#elif defined(LAYER_TAPS_WEIGHTED_4X4) || defined(LAYER_TAPS_SOFT_PCF)
    // The playground's taps (soft_filters.glsl), in the layer.
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            vec2 offset = vec2(col, row) - 1.5;
            float weight = abs(offset.x) < 1.0 && abs(offset.y) < 1.0 ? 0.6 / 4.0 : 0.4 / 12.0;
            float diff = texture(map, vec3(uv + offset * LAYER_TEXEL, layer)).r - current;
#if defined(LAYER_TAPS_SOFT_PCF)
            lit += weight / (1.0 + exp(-1000.0 * diff));
#else
            lit += weight * step(0.0, diff);
#endif
        }
    }
#else
#error expected one of the LAYER_TAPS defines of Kernel in src/shadows/map2d.rs
#endif
    return projCoords.z > 1.0 ? 1.0 : lit;
}
