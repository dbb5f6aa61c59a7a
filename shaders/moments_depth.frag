#version 330 core
// Depth pass of a filterable shadow map (src/shadows/moments.rs): instead of depth, the
// moments of depth, which stay meaningful when averaged (blurred, filtered). Compiled with:
//   MOMENT_DEPTH_VSM, _EVSM, _MSM or _ESM: one of them, named by the filter's MomentDepth
//                (src/shadows/moment_mode.rs): VSM (z, z^2), EVSM (the exponentials and
//                their squares), MSM (z, z^2, z^3, z^4), ESM (exp(c z))
//   EVSM_POS, EVSM_NEG  EVSM's exponents, already clamped (src/settings.rs)
//   ESM_EXPONENT        ESM's c, already clamped so exp(c) is a finite float
// The vertex shader is the chapter's depth.vert.

out vec4 moments;

void main()
{
    float z = gl_FragCoord.z;
#if defined(MOMENT_DEPTH_VSM)
    moments = vec4(z, z * z, 0.0, 0.0);
#elif defined(MOMENT_DEPTH_MSM)
    float z2 = z * z;
    moments = vec4(z, z2, z2 * z, z2 * z2);
#elif defined(MOMENT_DEPTH_EVSM)
    // Depth warped to [-1, 1], then through both exponentials: a caster's e^(c z) dwarfs a
    // receiver's behind it, so Chebyshev's bound is tight where VSM's bleeds.
    float w = 2.0 * z - 1.0;
    float pos = exp(EVSM_POS * w);
    float neg = -exp(-EVSM_NEG * w);
    moments = vec4(pos, pos * pos, neg, neg * neg);
#elif defined(MOMENT_DEPTH_ESM)
    // The exponential of depth itself (Annen et al. 2008): its average over a texel's
    // footprint, times exp(-c d), is the receiver's lit fraction where the footprint's
    // casters lie in front of it.
    moments = vec4(exp(ESM_EXPONENT * z), 0.0, 0.0, 0.0);
#else
#error expected one of the MOMENT_DEPTH defines of MomentMode in src/shadows/moment_mode.rs
#endif
}
