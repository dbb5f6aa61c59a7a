// The soft filters of a 2D texel grid (past the chapters: the shadow-playground's PCF demos,
// and percentage-closer soft shadows). Compiled with the defines of bias.glsl and:
//   FILTER_KERNEL      1 = the playground's weighted 4 x 4 PCF, 2 = its soft PCF, 3 = PCSS
//   SHADOW_TEXEL       one texel of the map
//   PCSS_BLOCKER_TAPS, PCSS_FILTER_TAPS, PCSS_PERSPECTIVE, LIGHT_INDEX   (PCSS)
// The includer says how its map is read: KERNEL_MAP (the parameters naming the map, e.g. a
// 2D map, or an array and a layer), KERNEL_DEPTH(uv) (the depth stored at uv).

#if FILTER_KERNEL == 1 || FILTER_KERNEL == 2
// The playground's 16 taps, +-0.5 and +-1.5 texels from the lookup: the inner 2 x 2 weigh
// 0.6 in all, the outer 12 weigh 0.4. The weighted 4 x 4 counts a tap lit when the stored
// depth is at least the fragment's (the bias is the playground's epsilon); the soft PCF
// passes the difference through a steep sigmoid instead, 1 / (1 + exp(-1000 diff)).
float softTaps(KERNEL_MAP, vec2 uv, float current)
{
    float lit = 0.0;
    for (int row = 0; row < 4; ++row) {
        for (int col = 0; col < 4; ++col) {
            vec2 offset = vec2(col, row) - 1.5;
            float weight = abs(offset.x) < 1.0 && abs(offset.y) < 1.0 ? 0.6 / 4.0 : 0.4 / 12.0;
            float diff = KERNEL_DEPTH(uv + offset * SHADOW_TEXEL) - current;
#if FILTER_KERNEL == 2
            lit += weight / (1.0 + exp(-1000.0 * diff));
#else
            lit += weight * step(0.0, diff);
#endif
        }
    }
    return lit;
}
#endif

#if FILTER_KERNEL == 3
#ifndef PCSS_DISK_DEFINED
#define PCSS_DISK_DEFINED
// 32 points in the unit disk, each added where it was farthest from those before it, so
// that every prefix (the first 16, the first 8) is itself spread over the disk.
const vec2 PCSS_DISK[32] = vec2[](
    vec2(-0.4820, 0.3705), vec2(0.7061, -0.6899), vec2(0.7741, 0.5506), vec2(-0.5674, -0.7067),
    vec2(0.1914, -0.0037), vec2(0.0936, 0.9025), vec2(0.9783, -0.0685), vec2(0.0688, -0.8438),
    vec2(-0.8257, -0.0561), vec2(0.1138, 0.4476), vec2(-0.2963, -0.2499), vec2(-0.5850, 0.7908),
    vec2(0.5360, -0.2628), vec2(0.0906, -0.4280), vec2(-0.8854, 0.4239), vec2(0.5964, 0.2292),
    vec2(-0.8129, -0.4389), vec2(0.4874, 0.7979), vec2(-0.1663, 0.0906), vec2(-0.2292, -0.6429),
    vec2(-0.1758, 0.6327), vec2(0.3765, -0.6003), vec2(-0.4947, 0.0348), vec2(0.9129, -0.3852),
    vec2(-0.3259, 0.9422), vec2(0.4093, 0.5070), vec2(-0.2862, -0.9526), vec2(0.7083, -0.0080),
    vec2(0.3580, -0.9092), vec2(-0.5982, -0.2368), vec2(0.9259, 0.2168), vec2(-0.0522, -0.1296));
// The blocker search reaches at most this many texels (thin blockers far from the receiver
// of a large light are missed beyond it, as in every PCSS).
const float PCSS_MAX_SEARCH_TEXELS = 64.0;
#endif

// A map depth in [0, 1] as a distance from the light. lightPenumbra[i] (scene.frag) is
// (S.x, S.y, near, far): a perspective map's depth is LearnOpenGL's LinearizeDepth, an
// orthographic map's is linear from near to far.
float pcssDistance(float z, vec4 light)
{
#if PCSS_PERSPECTIVE
    float ndc = z * 2.0 - 1.0;
    return 2.0 * light.z * light.w / (light.w + light.z - ndc * (light.w - light.z));
#else
    return light.z + z * (light.w - light.z);
#endif
}

// Half the penumbra's width in the map (uv) for a receiver at distance dr behind a blocker
// at db, by similar triangles: a disc light of radius R at the light's eye gives
// R (dr - db) / db in the world at the receiver, R (dr - db) / (db dr) in the map's
// tangent units (S = R x the projection's scale / 2); parallel rays within a cone of
// angular radius a give tan(a) (dr - db) (S = tan(a) x the projection's scale / 2).
vec2 pcssPenumbra(float dr, float db, vec4 light)
{
#if PCSS_PERSPECTIVE
    return light.xy * max(dr - db, 0.0) / max(dr * db, 1e-12);
#else
    return light.xy * max(dr - db, 0.0);
#endif
}

// Percentage-closer soft shadows: (1) the blocker search: the mean depth of the texels
// nearer than the fragment over the region of the map through which the light's disc
// can be hidden (blockers at the near plane at most); (2) the penumbra those blockers
// cast; (3) PCF over a disc that wide. Both stages use the Poisson disk turned by a
// per-pixel angle (interleaved gradient noise), which trades banding for fine noise. At
// least one texel wide, so a light of size 0 filters like a small PCF.
float pcss(KERNEL_MAP, vec2 uv, float z, float current)
{
    vec4 light = lightPenumbra[LIGHT_INDEX];
    float turn = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy,
                                                             vec2(0.06711056, 0.00583715))));
    mat2 rotation = mat2(cos(turn), sin(turn), -sin(turn), cos(turn));
    float dr = pcssDistance(z, light);
    vec2 search = clamp(pcssPenumbra(dr, light.z, light), SHADOW_TEXEL,
                        PCSS_MAX_SEARCH_TEXELS * SHADOW_TEXEL);
    float blockers = 0.0;
    float blockerDepth = 0.0;
    for (int k = 0; k < PCSS_BLOCKER_TAPS; ++k) {
        float d = KERNEL_DEPTH(uv + rotation * PCSS_DISK[k] * search);
        float nearer = d < current ? 1.0 : 0.0;
        blockers += nearer;
        blockerDepth += nearer * d;
    }
    float db = pcssDistance(blockerDepth / max(blockers, 1.0), light);
    vec2 radius = max(pcssPenumbra(dr, db, light), SHADOW_TEXEL);
    float lit = 0.0;
    for (int k = 0; k < PCSS_FILTER_TAPS; ++k) {
        lit += step(current, KERNEL_DEPTH(uv + rotation * PCSS_DISK[k] * radius));
    }
    // No blocker found: lit (a select, not a branch per pixel).
    return blockers > 0.0 ? lit / float(PCSS_FILTER_TAPS) : 1.0;
}
#endif
