// The test of a light with a filterable map (src/shadows/moments/mod.rs): one filtered lookup
// of the blurred moments, then a visibility reconstructed from them: one function per
// filter (VSM, EVSM, MSM, ESM), each with the light's own constants as arguments:
//   minVariance     the least variance Chebyshev's bound assumes (VSM; EVSM scales it)
//   bleedReduction  bounds below it read as shadow, the rest stretch to [0, 1] (VSM, EVSM)
//   exponent        ESM's c (the map holds exp(c z))
//   borderLit       lookups outside the map are lit (a fitted box's border)
//   position, bias, beyondFarLit  as calcShadow's (shadow_2d.glsl)

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
float reduceLightBleeding(float p, float amount)
{
    return clamp((p - amount) / (1.0 - amount), 0.0, 1.0);
}

// Hamburger 4MSM (Peters and Klein 2015): of all depth distributions with these four
// moments, the one that shadows the receiver at zf most has its weight on three depths,
// zf and the two roots of a quadratic whose coefficients c solve B c = (1, zf, zf^2) for
// the moments' Hankel matrix B. The lit fraction follows from where zf lies among them.
// The moments are first pulled by `alpha` toward `toward` (the moment bias).
float momentVisibility(vec4 moments, float zf, float alpha, vec4 toward)
{
    vec4 b = mix(moments, toward, alpha);
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

// Lookups outside the map (with borderLit) and past its far plane (with beyondFarLit) are
// lit; the others keep `lit`.
float outsideLit(vec3 projCoords, float lit, bool borderLit, bool beyondFarLit)
{
    bool outside = any(lessThan(projCoords.xy, vec2(0.0))) ||
                   any(greaterThan(projCoords.xy, vec2(1.0)));
    lit = borderLit && outside ? 1.0 : lit;
    return beyondFarLit && projCoords.z > 1.0 ? 1.0 : lit;
}

// Variance shadow maps: Chebyshev's bound on the mean and second moment of the depths.
float calcShadowVsm(sampler2D momentMap, vec4 position, float bias, float minVariance,
                    float bleedReduction, bool borderLit, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float z = projCoords.z - bias;
    vec4 m = texture(momentMap, projCoords.xy);
    float lit = reduceLightBleeding(chebyshevUpperBound(m.xy, z, minVariance), bleedReduction);
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}

// Exponential variance shadow maps: the bound on depths warped by exp(exponents.x w), and
// with `negative` (the 4-component map) also by -exp(-exponents.y w), the lesser of the two.
// The receiver is warped as the map's depths were; the least variance scales with the
// warp's slope there.
float calcShadowEvsm(sampler2D momentMap, vec4 position, float bias, float minVariance,
                     float bleedReduction, vec2 exponents, bool negative, bool borderLit,
                     bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float z = projCoords.z - bias;
    vec4 m = texture(momentMap, projCoords.xy);
    float w = 2.0 * clamp(z, 0.0, 1.0) - 1.0;
    float pos = exp(exponents.x * w);
    float slopePos = exponents.x * pos;
    float lit = chebyshevUpperBound(m.xy, pos, minVariance * slopePos * slopePos);
    if (negative) {
        float neg = -exp(-exponents.y * w);
        float slopeNeg = exponents.y * neg;
        lit = min(lit, chebyshevUpperBound(m.zw, neg, minVariance * slopeNeg * slopeNeg));
    }
    lit = reduceLightBleeding(lit, bleedReduction);
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}

// Exponential shadow maps: the map holds E = the filtered exp(c z); a receiver at d is lit
// by exp(-c d) E, which is exp(-c (d - z)) behind one caster at z and the lit share of the
// footprint where part of it lies behind the receiver. In logarithms, so that neither
// factor leaves float range when c is near its limit (exp(-88) is below the normal floats).
// Where the footprint also holds farther surfaces than the receiver, E grows past exp(c d)
// and the clamp lights it: ESM's light bleeding, at depth edges and near contact.
float calcShadowEsm(sampler2D momentMap, vec4 position, float bias, float exponent,
                    bool borderLit, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float z = projCoords.z - bias;
    float e = texture(momentMap, projCoords.xy).r;
    float lit = exp(min(log(max(e, 1.0)) - exponent * z, 0.0));
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}

// Moment shadow maps: momentVisibility, its moment bias `alpha` toward `toward`.
float calcShadowMsm(sampler2D momentMap, vec4 position, float bias, float alpha, vec4 toward,
                    bool borderLit, bool beyondFarLit)
{
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float z = projCoords.z - bias;
    vec4 m = texture(momentMap, projCoords.xy);
    float lit = momentVisibility(m, z, alpha, toward);
    return outsideLit(projCoords, lit, borderLit, beyondFarLit);
}
