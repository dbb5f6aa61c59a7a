// The chapter's shadow test for a light with one 2D depth map ("Shadows": calcShadow in
// scene_fragment.fs; LearnOpenGL: ShadowCalculation). Compiled with the defines of
// bias.glsl and:
//   PCF_RADIUS      0 = one lookup, 1 = the chapters' 3 x 3 PCF, 2 = 5 x 5
//   SHADOW_TEXEL    one texel: vec2(1 / width, 1 / height) of the map (a constant, not a
//                   textureSize query per pixel)
//   BEYOND_FAR_LIT  0 = the book (z > 1 compares, and reads as shadowed),
//                   1 = LearnOpenGL (z > 1 is lit)
//   FILTER_KERNEL   0 = the grid of PCF_RADIUS; 1 to 3 = a soft filter (soft_filters.glsl)

#define KERNEL_MAP SHADOW_SAMPLER_2D shadowMap
#define KERNEL_DEPTH(uv) texture(shadowMap, uv).r
#include "lib/soft_filters.glsl"
#undef KERNEL_MAP
#undef KERNEL_DEPTH

// 1 = lit, 0 = in shadow: the book returns the shadow factor, we return what is left of
// the light (1 - shadowFactor), so filters and lights multiply. `position` is the
// fragment in the light's clip space (the book's mlightviewVertexPos).
float calcShadow(SHADOW_SAMPLER_2D shadowMap, vec4 position, vec3 normal, vec3 toLightDir)
{
    // Clip space to normalised device coordinates (w = 1 for an orthographic light), then
    // [-1, 1] to the map's [0, 1].
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float currentDepth = projCoords.z - depthBias(normal, toLightDir);

#if FILTER_KERNEL == 1 || FILTER_KERNEL == 2
    float lit = softTaps(shadowMap, projCoords.xy, currentDepth);
#elif FILTER_KERNEL == 3
    float lit = pcss(shadowMap, projCoords.xy, projCoords.z, currentDepth);
#else
    // Percentage-closer filtering: the lit fraction of a grid of comparisons, one texel
    // apart.
    vec2 inc = SHADOW_TEXEL;
    float lit = 0.0;
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            lit += LIT_2D(shadowMap, projCoords.xy + vec2(row, col) * inc, currentDepth);
        }
    }
    lit /= PCF_TAPS;
#endif
#if BEYOND_FAR_LIT
    // A select, not an early return: no branch per pixel.
    lit = projCoords.z > 1.0 ? 1.0 : lit;
#endif
    return lit;
}

// A light with a 2D map (directional or spot): light i, its light-space position in slot p.
void addLight2D(int i, int p, SHADOW_SAMPLER_2D shadowMap, bool positional, bool cone,
                inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    addLight(i, toLight, cone, calcShadow(shadowMap, mlightviewVertexPos[p], f.normal, toLight),
             f);
}
