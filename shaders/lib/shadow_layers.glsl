// One layer of a layered directional light's depth array (src/shadows/layers.rs): the
// test shared by cascades (shadow_cascades.glsl: a layer per slice of the view) and caster
// groups (shadow_groups.glsl: a layer per group of casters), which include it. Compiled
// with the defines of bias.glsl and:
//   CASCADES       layers (2 to 4)
//   SHADOW_TEXEL, PCF_RADIUS, FILTER_KERNEL as for the 2D test (PCSS is refused for
//                  layers: src/settings.rs, Filter::refused_for)

// The layered light's position in each layer's clip space (scene.vert: one light is
// layered, so they fit among the vertex outputs).
in vec4 cascadePos[CASCADES];

#define KERNEL_MAP SHADOW_SAMPLER_ARRAY map, float layer
#define KERNEL_DEPTH(uv) texture(map, vec3(uv, layer)).r
#include "lib/soft_filters.glsl"
#undef KERNEL_MAP
#undef KERNEL_DEPTH

// The PCF grid of calcShadow (or the playground's soft taps), in one layer of the array.
float pcfArray(SHADOW_SAMPLER_ARRAY map, vec2 uv, float layer, float current)
{
#if FILTER_KERNEL == 1 || FILTER_KERNEL == 2
    return softTaps(map, layer, uv, current);
#else
    vec2 inc = SHADOW_TEXEL;
    float lit = 0.0;
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            lit += LIT_ARRAY(map, uv + vec2(row, col) * inc, layer, current);
        }
    }
    return lit / PCF_TAPS;
#endif
}

// The test in layer `c` (the position already pushed along the normal by the layer's own
// texel size, in scene.vert). A layer's box covers exactly what it must: beyond its far
// plane is lit, as outside it (the border).
float layerLookup(SHADOW_SAMPLER_ARRAY map, int c, vec3 normal, vec3 toLightDir)
{
    vec3 projCoords = cascadePos[c].xyz * 0.5 + 0.5;
    float lit = pcfArray(map, projCoords.xy, float(c),
                         projCoords.z - depthBias(normal, toLightDir));
    return projCoords.z > 1.0 ? 1.0 : lit;
}
