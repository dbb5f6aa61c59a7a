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
