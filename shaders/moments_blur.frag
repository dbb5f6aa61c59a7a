#version 330 core
// One pass of a moment map's separable Gaussian blur (src/engine/moment_map.rs runs it
// across, then down). Compiled with:
//   BLUR_RADIUS   taps either side of the centre
//   BLUR_WEIGHTS  BLUR_RADIUS + 1 weights, the centre's first (src/settings.rs: Blur)
// The vertex shader is depth_view.vert's full-screen triangle; reads are NEAREST texel
// centres, clamped at the edges.

in vec2 texCoords;
out vec4 blurred;

uniform sampler2D source;
uniform vec2 stepUv;  // one texel along this pass' axis

const float weights[BLUR_RADIUS + 1] = float[](BLUR_WEIGHTS);

void main()
{
    vec4 sum = weights[0] * texture(source, texCoords);
    for (int i = 1; i <= BLUR_RADIUS; ++i) {
        vec2 offset = stepUv * float(i);
        sum += weights[i] * (texture(source, texCoords + offset) + texture(source, texCoords - offset));
    }
    blurred = sum;
}
