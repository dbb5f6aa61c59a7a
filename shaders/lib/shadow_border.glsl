// The lit border around a 2D map (LearnOpenGL's over-sampling fix: GL_CLAMP_TO_BORDER with a
// border depth of 1, so that what lies outside the light's box is lit), where the sampler has
// no border: OpenGL ES 3.0 and WebGL2, whose dialect defines SHADOW_BORDER_IN_SHADER. There a
// fragment outside the map gets what every lookup of the border would give it: lit, unless
// it lies past the far plane of a light that leaves that shadowed. On the desktop the sampler
// keeps the border and SHADOW_BORDER(...) is its test's value unchanged.
//   i        the light, whose shadowBorderLit[i] says whether its map has the border
//   position the fragment in the light's clip space (mlightviewVertexPos)
//   farLit   the test's beyondFarLit
//   lit      the test's value
#ifdef SHADOW_BORDER_IN_SHADER
uniform bool shadowBorderLit[LIGHT_COUNT];

float shadowBorder(int i, vec4 position, bool farLit, float lit)
{
    if (!shadowBorderLit[i] || position.w <= 0.0) {
        return lit;
    }
    vec3 p = position.xyz / position.w * 0.5 + 0.5;
    if (any(lessThan(p.xy, vec2(0.0))) || any(greaterThan(p.xy, vec2(1.0)))) {
        return (p.z > 1.0 && !farLit) ? 0.0 : 1.0;
    }
    return lit;
}
#define SHADOW_BORDER(i, position, farLit, lit) shadowBorder(i, position, farLit, lit)
#else
#define SHADOW_BORDER(i, position, farLit, lit) (lit)
#endif
