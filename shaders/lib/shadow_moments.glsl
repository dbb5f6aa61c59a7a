// The test of a light with a filterable map (src/shadows/moments.rs): one filtered lookup
// of the blurred moments, then a visibility reconstructed from them. Compiled with the
// defines of bias.glsl and:
//   MOMENT_MODE      1 = VSM, 2 = EVSM (2 components), 3 = EVSM (4), 4 = MSM
//   MIN_VARIANCE     the least variance Chebyshev's bound assumes (VSM; EVSM scales it)
//   BLEED_REDUCTION  bounds below it read as shadow, the rest stretch to [0, 1] (VSM, EVSM)
//   EVSM_POS, EVSM_NEG  EVSM's exponents (clamped)
//   MSM_BIAS, MSM_TOWARD  MSM's moment bias: alpha and the vec4 it pulls toward
//   BORDER_LIT       1 = lookups outside the map are lit (a fitted box's border)
//   BEYOND_FAR_LIT   as in shadow_2d.glsl

// Chebyshev's one-sided inequality: an upper bound on the lit fraction of a texel whose
// depths have mean m.x and second moment m.y, for a receiver at t (VSM, Donnelly and
// Lauritzen 2006). Fully lit when the receiver is in front of the mean.
float chebyshevUpperBound(vec2 m, float t, float minVariance)
{
    float variance = max(m.y - m.x * m.x, minVariance);
    float d = t - m.x;
    float bound = variance / (variance + d * d);
    return t <= m.x ? 1.0 : bound;
}

// Light-bleeding reduction: the tail of the bound (where a second occluder's variance
// lights what the first one shadows) is cut off and the rest rescaled.
float reduceLightBleeding(float p)
{
    return clamp((p - BLEED_REDUCTION) / (1.0 - BLEED_REDUCTION), 0.0, 1.0);
}

// Hamburger 4MSM (Peters and Klein 2015): of all depth distributions with these four
// moments, the one that shadows the receiver at zf most has its weight on three depths,
// zf and the two roots of a quadratic whose coefficients c solve B c = (1, zf, zf^2) for
// the moments' Hankel matrix B. The lit fraction follows from where zf lies among them.
float momentVisibility(vec4 moments, float zf)
{
    vec4 b = mix(moments, MSM_TOWARD, MSM_BIAS);
    // B = L D L^T with L unit lower triangular; D = (1, d22, d33).
    float d22 = b.y - b.x * b.x;
    float l32 = (b.z - b.x * b.y) / d22;
    float d33 = b.w - b.y * b.y - l32 * l32 * d22;
    // Forward: L y = (1, zf, zf^2); then y / D; then back: L^T c = y.
    float y1 = zf - b.x;
    float y2 = zf * zf - b.y - l32 * y1;
    float c2 = y2 / d33;
    float c1 = y1 / d22 - l32 * c2;
    float c0 = 1.0 - b.x * c1 - b.y * c2;
    // The roots of c0 + c1 x + c2 x^2, z1 <= z2.
    float p = c1 / c2;
    float q = c0 / c2;
    float r = sqrt(max(0.25 * p * p - q, 0.0));
    float z1 = -0.5 * p - r;
    float z2 = -0.5 * p + r;
    // Three cases, as selects: in front of both roots (lit), between them, behind both.
    float between = 1.0 - (zf * z2 - b.x * (zf + z2) + b.y) / ((z2 - z1) * (zf - z1));
    float behind = (z1 * z2 - b.x * (z1 + z2) + b.y) / ((zf - z1) * (zf - z2));
    float lit = zf <= z1 ? 1.0 : (zf <= z2 ? between : behind);
    return clamp(lit, 0.0, 1.0);
}

// 1 = lit, 0 = in shadow, like calcShadow; `position` is the fragment in the light's clip
// space.
float calcShadowMoments(sampler2D momentMap, vec4 position, vec3 normal, vec3 toLightDir)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float z = projCoords.z - depthBias(normal, toLightDir);
    vec4 m = texture(momentMap, projCoords.xy);
#if MOMENT_MODE == 1
    float lit = reduceLightBleeding(chebyshevUpperBound(m.xy, z, MIN_VARIANCE));
#elif MOMENT_MODE == 4
    float lit = momentVisibility(m, z);
#else
    // The receiver warped as the map's depths were; the least variance scales with the
    // warp's slope there.
    float w = 2.0 * clamp(z, 0.0, 1.0) - 1.0;
    float pos = exp(EVSM_POS * w);
    float slopePos = EVSM_POS * pos;
    float lit = chebyshevUpperBound(m.xy, pos, MIN_VARIANCE * slopePos * slopePos);
#if MOMENT_MODE == 3
    float neg = -exp(-EVSM_NEG * w);
    float slopeNeg = EVSM_NEG * neg;
    lit = min(lit, chebyshevUpperBound(m.zw, neg, MIN_VARIANCE * slopeNeg * slopeNeg));
#endif
    lit = reduceLightBleeding(lit);
#endif
#if BORDER_LIT
    bool outside = any(lessThan(projCoords.xy, vec2(0.0))) ||
                   any(greaterThan(projCoords.xy, vec2(1.0)));
    lit = outside ? 1.0 : lit;
#endif
#if BEYOND_FAR_LIT
    lit = projCoords.z > 1.0 ? 1.0 : lit;
#endif
    return lit;
}

// A light with a filterable 2D map (directional or spot): light i, its light-space
// position in slot p.
void addLightMoments(int i, int p, sampler2D momentMap, bool positional, bool cone,
                     inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    addLight(i, toLight, cone,
             calcShadowMoments(momentMap, mlightviewVertexPos[p], f.normal, toLight), f);
}
