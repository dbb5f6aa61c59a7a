// The chapter's shadow test for a light with one 2D depth map ("Shadows": calcShadow in
// scene_fragment.fs; LearnOpenGL: ShadowCalculation). It returns 1 = lit, 0 = in shadow:
// the book's 1 - shadowFactor, counted as lit lookups so that filters and lights multiply.
// Each light calls it with its own settings (the technique writes the call: src/shadows/map2d/glsl.rs):
//   position      the fragment in the light's clip space (the book's mlightviewVertexPos)
//   bias          taken off the fragment's depth against shadow acne (lib/bias.glsl)
//   texel         one texel of the map, 1 / its size (the book asks textureSize per pixel)
//   radius        1 = the book's 3 x 3 PCF, 0 = one lookup, 2 = 5 x 5
//   beyondFarLit  false = the book (past the far plane still compares: shadowed),
//                 true = LearnOpenGL (lit)
float calcShadow(sampler2D shadowMap, vec4 position, float bias, vec2 texel, int radius,
                 bool beyondFarLit)
{
    // A point behind a perspective map's light (w <= 0) is in no texel of the map: the
    // division below would mirror it into the map, past the far plane. It is lit. (An
    // orthographic map's w is 1.)
    if (position.w <= 0.0) {
        return 1.0;
    }
    // Clip space to normalised device coordinates (w = 1 for an orthographic light), then
    // [-1, 1] to the map's [0, 1].
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float currentDepth = projCoords.z - bias;

    // Percentage-closer filtering: the lit fraction of a grid of lookups one texel apart.
    // shadowDepth(shadowMap, uv) is the book's texture(shadowMap, uv).r (lib/shadow_depth.glsl).
    float lit = 0.0;
    for (int row = -radius; row <= radius; ++row) {
        for (int col = -radius; col <= radius; ++col) {
            float textDepth = shadowDepth(shadowMap, projCoords.xy + vec2(row, col) * texel);
            lit += currentDepth > textDepth ? 0.0 : 1.0;
        }
    }
    lit /= float((2 * radius + 1) * (2 * radius + 1));

    if (beyondFarLit && projCoords.z > 1.0) {
        lit = 1.0;
    }
    return lit;
}
