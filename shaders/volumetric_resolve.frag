#version 330 core
// The translucent map resolved for opaque receivers (src/shadows/volumetric/resolved.rs),
// one pass over the map's texels: each texel's curve read at the depth the light's depth
// map holds there (its nearest texel to this one's centre), where a lit opaque receiver
// lies. The technique's own function reads the curve: `curveAt`, generated with its
// library file.

layout (location = 0) out vec4 transmittanceOut;  // an R32F target: r

uniform sampler2DArray translucentMap;
uniform sampler2D depthMap;       // read with texelFetch: the stored depth, no comparison
// (x, y, 2 stored - 1, 1) in the light's normalised device coordinates to the fitted depth,
// as z / w (0 at the nearest translucent caster, 1 at the farthest).
uniform mat4 depthToFitted;

#include "generated/resolve.glsl"

void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy);
    vec2 uv = gl_FragCoord.xy / vec2(textureSize(translucentMap, 0).xy);
    ivec2 depthTexel = ivec2(uv * vec2(textureSize(depthMap, 0)));
    float stored = texelFetch(depthMap, depthTexel, 0).r;
    vec4 c = depthToFitted * vec4(uv * 2.0 - 1.0, stored * 2.0 - 1.0, 1.0);
    transmittanceOut = vec4(curveAt(texel, uv, c.z / c.w));
}
