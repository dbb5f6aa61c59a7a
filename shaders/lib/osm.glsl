// Opacity shadow maps' lookup (Kim and Neumann 2001; src/shadows/volumetric/osm.rs): the
// optical depth of the slices before the receiver's, and of the part of its own slice it
// is past (the crossings taken as spread evenly over a slice), as a transmittance,
// 1 = nothing translucent in the way. Past the last slice: the exact product.
//   map     the slices, four to a layer
//   coords  volumetricCoords (lib/volumetric.glsl)
//   slices  the map's slice count
float osmTransmittance(sampler2DArray map, vec4 coords, int slices)
{
    if (coords.w == 0.0) {
        return 1.0;
    }
    float x = clamp(coords.z, 0.0, 1.0) * float(slices);
    float depth = 0.0;
    for (int l = 0; l < (slices + 3) / 4; ++l) {
        vec4 first = vec4(float(4 * l)) + vec4(0.0, 1.0, 2.0, 3.0);
        depth += dot(texture(map, vec3(coords.xy, float(l))), clamp(x - first, 0.0, 1.0));
    }
    return exp(-depth);
}
