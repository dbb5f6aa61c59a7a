#version 330 core
// One layer of AVSM's depth peeling (src/engine/depth_peel.rs, src/shadows/avsm/): the
// nearest translucent fragment behind the previous layer, as its fitted depth (the
// translucent map's, shaders/translucent_map.vert) and its opacity. The depth is written
// as the fragment's depth too, so the next layer compares like with like.
//
// With REMAINDER: the rest, every fragment behind the last layer allowed, as what it lets
// through (multiplied together by the blending) and its depth (the largest kept).

in float fittedDepth;
#ifdef REMAINDER
out vec4 rest;
#else
out vec2 crossing;
#endif

uniform sampler2D previousDepth;
uniform bool firstLayer;
uniform float opticalDepth;  // -ln(1 - opacity), from the translucent map's draw

void main()
{
    float depth = clamp(fittedDepth, 0.0, 1.0);
    if (!firstLayer && depth <= texelFetch(previousDepth, ivec2(gl_FragCoord.xy), 0).r) {
        discard;
    }
#ifdef REMAINDER
    rest = vec4(vec3(exp(-opticalDepth)), depth);
#else
    gl_FragDepth = depth;
    crossing = vec2(depth, 1.0 - exp(-opticalDepth));
#endif
}
