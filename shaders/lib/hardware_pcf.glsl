// calcShadow (shadow_2d.glsl) read through a shadow sampler with LINEAR filtering (the
// filters hw2x2 and hw3x3): each lookup has the hardware compare the 4 nearest texels with
// the fragment's depth (lit where it is <= the stored depth) and blend the 4 results.
float calcShadowHardware(sampler2DShadow shadowMap, vec4 position, float bias, vec2 texel,
                         int radius, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float currentDepth = projCoords.z - bias;
    float lit = 0.0;
    for (int row = -radius; row <= radius; ++row) {
        for (int col = -radius; col <= radius; ++col) {
            vec2 uv = projCoords.xy + vec2(row, col) * texel;
            lit += texture(shadowMap, vec3(uv, currentDepth));
        }
    }
    lit /= float((2 * radius + 1) * (2 * radius + 1));
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit;
}
