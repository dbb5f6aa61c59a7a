// Adaptive volumetric shadow maps' lookup (Salvi et al. 2010; src/shadows/avsm/): in each
// of the four texels around the receiver, the segment of the curve holding its depth,
// linear between its two nodes (1 before the first node, the last one's value past it);
// the four blended bilinearly. The node textures are never filtered by the hardware: a
// blend of two texels' depths is no node of either.
//   map     the nodes, (depth, transmittance) pairs, two to an RGBA32F layer
//   coords  volumetricCoords (lib/volumetric.glsl): xy the texel, z the fitted depth
//   nodes   nodes per texel

const float AVSM_EMPTY_DEPTH = 2.0;

float avsmTexel(sampler2DArray map, ivec2 texel, float depth, int nodes)
{
    float left = 1.0;
    vec2 a = vec2(-1.0, 1.0);
    for (int l = 0; l < (nodes + 1) / 2; ++l) {
        vec4 v = texelFetch(map, ivec3(texel, l), 0);
        for (int k = 0; k < 2; ++k) {
            vec2 b = k == 0 ? v.xy : v.zw;
            if (b.x >= AVSM_EMPTY_DEPTH) {
                return left;
            }
            if (b.x > depth) {
                if (a.x >= 0.0) {
                    left = a.y + (b.y - a.y) * ((depth - a.x) / (b.x - a.x));
                }
                return left;
            }
            a = b;
            left = b.y;
        }
    }
    return left;
}

float avsmTransmittance(sampler2DArray map, vec4 coords, int nodes)
{
    if (coords.w == 0.0) {
        return 1.0;
    }
    ivec2 size = textureSize(map, 0).xy;
    vec2 p = coords.xy * vec2(size) - 0.5;
    vec2 f = fract(p);
    ivec2 t0 = clamp(ivec2(floor(p)), ivec2(0), size - 1);
    ivec2 t1 = clamp(ivec2(floor(p)) + 1, ivec2(0), size - 1);
    float l00 = avsmTexel(map, t0, coords.z, nodes);
    float l10 = avsmTexel(map, ivec2(t1.x, t0.y), coords.z, nodes);
    float l01 = avsmTexel(map, ivec2(t0.x, t1.y), coords.z, nodes);
    float l11 = avsmTexel(map, t1, coords.z, nodes);
    return mix(mix(l00, l10, f.x), mix(l01, l11, f.x), f.y);
}
