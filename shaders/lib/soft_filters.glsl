// The soft filters of a 2D map with fixed taps (past the chapters: the shadow-playground's
// PCF demos). Each is a whole test like calcShadow (shadow_2d.glsl), with its arguments
// (position, bias, texel, beyondFarLit), and returns 1 = lit. None reads a fragment's own
// inputs, so a vertex shader can take them too (percentage-closer soft shadows, which do,
// are pcss.glsl).

// The playground's 16 taps sit +-0.5 and +-1.5 texels from the lookup: the inner 2 x 2
// weigh 0.6 in all, the outer 12 weigh 0.4.
float playgroundWeight(vec2 offset)
{
    return abs(offset.x) < 1.0 && abs(offset.y) < 1.0 ? 0.6 / 4.0 : 0.4 / 12.0;
}

// The playground's weighted 4 x 4 PCF: a tap is lit when the stored depth is at least the
// fragment's (the bias is the playground's epsilon).
float pcf4x4Weighted(sampler2D shadowMap, vec4 position, float bias, vec2 texel,
                     bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float currentDepth = projCoords.z - bias;
    float lit = 0.0;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            vec2 offset = vec2(col, row) - 1.5;
            float diff = shadowDepth(shadowMap, projCoords.xy + offset * texel) - currentDepth;
            lit += playgroundWeight(offset) * step(0.0, diff);
        }
    }
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit;
}

// The playground's soft PCF: the same taps, each depth difference passed through a steep
// sigmoid, 1 / (1 + exp(-1000 diff)), rather than a step.
float softPcf(sampler2D shadowMap, vec4 position, float bias, vec2 texel, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float currentDepth = projCoords.z - bias;
    float lit = 0.0;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            vec2 offset = vec2(col, row) - 1.5;
            float diff = shadowDepth(shadowMap, projCoords.xy + offset * texel) - currentDepth;
            lit += playgroundWeight(offset) / (1.0 + exp(-1000.0 * diff));
        }
    }
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit;
}

// Poisson-disk PCF (opengl-tutorial.org, "Shadow mapping": "Poisson Sampling" and its
// rotated variant): the comparisons sit on a fixed disk of points no two of them close,
// rather than on a grid, so the edge's steps do not line up. The rotated test takes its
// pixel as an argument (the call passes gl_FragCoord.xy).

// The tutorial's 16 points in the unit disk.
const vec2 POISSON_DISK[16] = vec2[](
    vec2(-0.94201624, -0.39906216), vec2(0.94558609, -0.76890725),
    vec2(-0.094184101, -0.92938870), vec2(0.34495938, 0.29387760),
    vec2(-0.91588581, 0.45771432), vec2(-0.81544232, -0.87912464),
    vec2(-0.38277543, 0.27676845), vec2(0.97484398, 0.75648379),
    vec2(0.44323325, -0.97511554), vec2(0.53742981, -0.47373420),
    vec2(-0.26496911, -0.41893023), vec2(0.79197514, 0.19090188),
    vec2(-0.24188840, 0.99706507), vec2(-0.81409955, 0.91437590),
    vec2(0.19984126, 0.78641367), vec2(0.14383161, -0.14100790));
// The tutorial spreads the disk over 1 / 700 of its map, 1024 texels wide: in texels.
const float POISSON_SPREAD_TEXELS = 1024.0 / 700.0;

// The 16 comparisons on the disk turned by `rotation`, averaged.
float poissonTaps(sampler2D shadowMap, vec4 position, float bias, vec2 texel, mat2 rotation,
                  bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float current = projCoords.z - bias;
    float lit = 0.0;
    for (int k = 0; k < 16; ++k) {
        vec2 offset = rotation * POISSON_DISK[k] * POISSON_SPREAD_TEXELS * texel;
        lit += step(current, shadowDepth(shadowMap, projCoords.xy + offset));
    }
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit / 16.0;
}

// The fixed disk.
float poissonPcf(sampler2D shadowMap, vec4 position, float bias, vec2 texel,
                 bool beyondFarLit)
{
    return poissonTaps(shadowMap, position, bias, texel, mat2(1.0), beyondFarLit);
}

// The disk turned by an angle per pixel (interleaved gradient noise of `pixel`, the
// fragment's gl_FragCoord.xy).
float poissonPcfRotated(sampler2D shadowMap, vec4 position, float bias, vec2 texel,
                        vec2 pixel, bool beyondFarLit)
{
    float turn = 6.2831853 * fract(52.9829189 * fract(dot(pixel, vec2(0.06711056, 0.00583715))));
    mat2 rotation = mat2(cos(turn), sin(turn), -sin(turn), cos(turn));
    return poissonTaps(shadowMap, position, bias, texel, rotation, beyondFarLit);
}
