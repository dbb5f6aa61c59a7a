#version 330 core
// Fourier opacity maps (Jansen and Bavoil 2010; src/shadows/volumetric/fom.rs): each
// crossing at fitted depth t adds its optical depth d = -ln(1 - a) times the basis at t:
// [d, d cos(2 pi t), d sin(2 pi t), d cos(4 pi t), ...], TERMS cosine and sine pairs after
// the mean, four floats to a layer; blending ONE, ONE sums them.

in float fittedDepth;
uniform float opticalDepth;

layout (location = 0) out vec4 layers[LAYERS];

const float TWO_PI = 6.283185307179586;

void main()
{
    float t = clamp(fittedDepth, 0.0, 1.0);
    for (int l = 0; l < LAYERS; ++l) {
        vec4 basis;
        for (int j = 0; j < 4; ++j) {
            int n = 4 * l + j;
            float phase = TWO_PI * float((n + 1) / 2) * t;
            float b = n == 0 ? 1.0 : (n % 2 == 1 ? cos(phase) : sin(phase));
            basis[j] = n <= 2 * TERMS ? b : 0.0;
        }
        layers[l] = opticalDepth * basis;
    }
}
