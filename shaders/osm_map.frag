#version 330 core
// Opacity shadow maps (Kim and Neumann 2001; src/shadows/volumetric/osm.rs): each crossing
// adds its optical depth, -ln(1 - a), to the slice of the fitted depth it falls in;
// blending ONE, ONE sums them. SLICES slices, four to a layer, LAYERS layers.

in float fittedDepth;
uniform float opticalDepth;

layout (location = 0) out vec4 layers[LAYERS];

void main()
{
    int slice = clamp(int(floor(fittedDepth * float(SLICES))), 0, SLICES - 1);
    for (int l = 0; l < LAYERS; ++l) {
        layers[l] = opticalDepth * vec4(equal(ivec4(4 * l) + ivec4(0, 1, 2, 3), ivec4(slice)));
    }
}
