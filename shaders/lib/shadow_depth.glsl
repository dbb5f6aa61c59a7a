// One depth of a 2D map, `shadowDepth(map, uv)`: on the desktop the book's
// `texture(shadowMap, uv).r`, which the sampler interpolates where the light asks for it
// (the shadow-playground's `depth_lookup = "linear"`, its colour map read with LINEAR).
// OpenGL ES 3.0 and WebGL2 cannot filter depth texels without a comparison, so their
// dialect defines SHADOW_DEPTH_IN_SHADER: there the sampler reads NEAREST and the shader
// blends the four texels around `uv` as LINEAR would, for the light whose
// shadowDepthInterpolated[i] says so. SHADOW_DEPTH_OF(i, test) wraps light i's test.
#ifdef SHADOW_DEPTH_IN_SHADER
uniform bool shadowDepthInterpolated[LIGHT_COUNT];
// The light whose test runs now interpolates (set by SHADOW_DEPTH_OF).
bool shadowDepthInterpolating = false;

float shadowDepth(sampler2D map, vec2 uv)
{
    if (!shadowDepthInterpolating) {
        return texture(map, uv).r;
    }
    // LINEAR's weights: the texel centres around uv, and uv's place between them.
    vec2 size = vec2(textureSize(map, 0));
    vec2 t = uv * size - 0.5;
    vec2 f = fract(t);
    vec2 c = (floor(t) + 0.5) / size;
    vec2 d = 1.0 / size;
    float a = texture(map, c).r;
    float b = texture(map, c + vec2(d.x, 0.0)).r;
    float e = texture(map, c + vec2(0.0, d.y)).r;
    float g = texture(map, c + d).r;
    return mix(mix(a, b, f.x), mix(e, g, f.x), f.y);
}
#define SHADOW_DEPTH_OF(i, test) ((shadowDepthInterpolating = shadowDepthInterpolated[i]), (test))
#else
#define shadowDepth(map, uv) texture(map, uv).r
#define SHADOW_DEPTH_OF(i, test) (test)
#endif
