// Percentage-closer soft shadows on a 2D map (past the chapters), a whole test like
// calcShadow (shadow_2d.glsl), 1 = lit. Its receiver-plane bias and its per-pixel turn read
// a fragment's screen derivatives and its pixel: a fragment shader's file alone. The soft
// moment filters (soft_moments.glsl) share its light constants and penumbra.

// 32 points in the unit disk, each added where it was farthest from those before it, so
// that every prefix (the first 16, the first 8) is itself spread over the disk; then scaled
// (by 0.916) so that the first 16's mean squared radius is a uniform disc's, 1/2 (that way
// leans to the rim, and a kernel that leans to its rim draws a wider penumbra).
const vec2 PCSS_DISK[32] = vec2[](
    vec2(-0.4413, 0.3392), vec2(0.6465, -0.6317), vec2(0.7088, 0.5042), vec2(-0.5195, -0.6471),
    vec2(0.1753, -0.0034), vec2(0.0857, 0.8264), vec2(0.8958, -0.0627), vec2(0.0630, -0.7726),
    vec2(-0.7560, -0.0514), vec2(0.1042, 0.4098), vec2(-0.2713, -0.2288), vec2(-0.5357, 0.7241),
    vec2(0.4908, -0.2406), vec2(0.0830, -0.3919), vec2(-0.8107, 0.3881), vec2(0.5461, 0.2099),
    vec2(-0.7443, -0.4019), vec2(0.4463, 0.7306), vec2(-0.1523, 0.0830), vec2(-0.2099, -0.5887),
    vec2(-0.1610, 0.5793), vec2(0.3447, -0.5497), vec2(-0.4530, 0.0319), vec2(0.8359, -0.3527),
    vec2(-0.2984, 0.8627), vec2(0.3748, 0.4642), vec2(-0.2621, -0.8722), vec2(0.6485, -0.0073),
    vec2(0.3278, -0.8325), vec2(-0.5477, -0.2168), vec2(0.8478, 0.1985), vec2(-0.0478, -0.1187));
// The blocker search reaches at most this many texels (thin blockers far from the receiver
// of a large light are missed beyond it, as in every PCSS).
const float PCSS_MAX_SEARCH_TEXELS = 64.0;
// The steepest receiver plane followed, in depth per map width: steeper (grazing) planes
// keep this slope, so a receiver seen edge-on to the light cannot cancel its shadow.
const float PCSS_MAX_SLOPE = 8.0;

// PCSS: a light's size in its map's units per distance, and its map's near and far planes:
// (S.x, S.y, near, far), set per light by the renderer.
uniform vec4 lightPenumbra[LIGHT_COUNT];

// A map depth in [0, 1] as a distance from the light (`light` is lightPenumbra[i]): a
// perspective map's depth is LearnOpenGL's LinearizeDepth, an orthographic map's is linear
// from near to far.
float pcssDistance(float z, vec4 light, bool perspective)
{
    float ndc = z * 2.0 - 1.0;
    return perspective ? 2.0 * light.z * light.w / (light.w + light.z - ndc * (light.w - light.z))
                       : light.z + z * (light.w - light.z);
}

// Half the penumbra's width in the map (uv) for a receiver at distance dr behind a blocker
// at db, by similar triangles: a disc light of radius R at the light's eye gives
// R (dr - db) / db in the world at the receiver, R (dr - db) / (db dr) in the map's
// tangent units (S = R x the projection's scale / 2); parallel rays within a cone of
// angular radius a give tan(a) (dr - db) (S = tan(a) x the projection's scale / 2).
vec2 pcssPenumbra(float dr, float db, vec4 light, bool perspective)
{
    return perspective ? light.xy * max(dr - db, 0.0) / max(dr * db, 1e-12)
                       : light.xy * max(dr - db, 0.0);
}

// Percentage-closer soft shadows: (1) the blocker search: the mean depth of the texels
// nearer than the fragment over the region of the map through which the light's disc
// can be hidden (blockers at the near plane at most); (2) the penumbra those blockers
// cast; (3) PCF over a disc that wide. Both stages use the Poisson disk turned by a
// per-pixel angle (interleaved gradient noise), which trades banding for fine noise. At
// least one texel wide, so a light of size 0 filters like a small PCF. `blockerTaps` and
// `filterTaps` are the first points of the disk each stage takes; `perspective`: the map
// is a perspective one (its depth is not linear).
float pcss(sampler2D shadowMap, vec4 position, float bias, vec2 texel, vec4 light,
           int blockerTaps, int filterTaps, bool perspective, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    vec2 uv = projCoords.xy;
    float z = projCoords.z;
    float current = z - bias;
    // Receiver-plane depth bias: over a wide kernel a surface tilted to the light differs
    // from its own depth at the centre by more than any constant bias, and would shadow
    // itself. The fragment's depth is taken as a plane in the map, z + dot(slope, offset),
    // its slope from the screen-space derivatives of (uv, z) (a 2 x 2 solve; none where the
    // solve is singular, at silhouettes, and at most PCSS_MAX_SLOPE).
    vec3 ddx = dFdx(vec3(uv, z));
    vec3 ddy = dFdy(vec3(uv, z));
    float det = ddx.x * ddy.y - ddx.y * ddy.x;
    vec2 slope = abs(det) > 1e-14
        ? vec2(ddx.z * ddy.y - ddx.y * ddy.z, ddx.x * ddy.z - ddy.x * ddx.z) / det
        : vec2(0.0);
    slope = clamp(slope, -PCSS_MAX_SLOPE, PCSS_MAX_SLOPE);
    float turn = 6.2831853 * fract(52.9829189 * fract(dot(gl_FragCoord.xy,
                                                             vec2(0.06711056, 0.00583715))));
    mat2 rotation = mat2(cos(turn), sin(turn), -sin(turn), cos(turn));
    float dr = pcssDistance(z, light, perspective);
    vec2 search = clamp(pcssPenumbra(dr, light.z, light, perspective), texel,
                        PCSS_MAX_SEARCH_TEXELS * texel);
    float blockers = 0.0;
    float blockerDepth = 0.0;
    for (int k = 0; k < blockerTaps; ++k) {
        vec2 offset = rotation * PCSS_DISK[k] * search;
        float d = shadowDepth(shadowMap, uv + offset);
        float nearer = d < current + dot(slope, offset) ? 1.0 : 0.0;
        blockers += nearer;
        blockerDepth += nearer * d;
    }
    // No blocker found: lit, and the filter's lookups are skipped.
    if (blockers == 0.0) {
        return 1.0;
    }
    float db = pcssDistance(blockerDepth / blockers, light, perspective);
    vec2 radius = max(pcssPenumbra(dr, db, light, perspective), texel);
    float lit = 0.0;
    for (int k = 0; k < filterTaps; ++k) {
        vec2 offset = rotation * PCSS_DISK[k] * radius;
        lit += step(current + dot(slope, offset), shadowDepth(shadowMap, uv + offset));
    }
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit / float(filterTaps);
}
