// Fourier opacity maps' lookup (Jansen and Bavoil 2010; src/shadows/volumetric/fom.rs):
// the optical depth from the nearest translucent caster to the receiver at fitted depth t,
// the integral of the stored series,
//   D(t) = a0 t + sum_k sigma_k (a_k sin(2 pi k t) + b_k (1 - cos(2 pi k t))) / (pi k),
// each term damped by Lanczos' sigma factor sigma_k = sinc(k / (N + 1)) against ringing,
// and exp(-D) clamped to [0, 1]. At t = 1 (behind every caster) D is the exact sum.
//   map     the coefficients [a0, a1, b1, a2, b2, ...], four to a layer
//   coords  volumetricCoords (lib/volumetric.glsl)
//   terms   N, the cosine and sine pairs after the mean
float fomBasis(int n, float t, int terms)
{
    if (n == 0) {
        return t;
    }
    if (n > 2 * terms) {
        return 0.0;
    }
    const float PI = 3.141592653589793;
    float k = float((n + 1) / 2);
    float x = PI * k / float(terms + 1);
    float sigma = sin(x) / x;
    float phase = 2.0 * PI * k * t;
    float integral = n % 2 == 1 ? sin(phase) : 1.0 - cos(phase);
    return sigma * integral / (PI * k);
}

float fomTransmittance(sampler2DArray map, vec4 coords, int terms)
{
    if (coords.w == 0.0) {
        return 1.0;
    }
    float t = clamp(coords.z, 0.0, 1.0);
    float depth = 0.0;
    for (int l = 0; l < (2 * terms + 4) / 4; ++l) {
        vec4 basis = vec4(fomBasis(4 * l, t, terms), fomBasis(4 * l + 1, t, terms),
                          fomBasis(4 * l + 2, t, terms), fomBasis(4 * l + 3, t, terms));
        depth += dot(texture(map, vec3(coords.xy, float(l))), basis);
    }
    return clamp(exp(-depth), 0.0, 1.0);
}
