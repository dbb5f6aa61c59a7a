#version 330 core
// The depth-map debug view (LearnOpenGL's debug quad). An orthographic map stores linear
// depth and is shown raw; a perspective map is linearised first, or everything but the
// nearest surfaces would look white.

in vec2 texCoords;
out vec4 fragColor;

uniform sampler2D depthMap;
uniform int linearize;
uniform float nearPlane;
uniform float farPlane;

// Depth in [0, 1] back to eye distance, then scaled to [0, 1] over [near, far].
float linearDepth(float depth)
{
    float z = depth * 2.0 - 1.0;
    float eye = (2.0 * nearPlane * farPlane) / (farPlane + nearPlane - z * (farPlane - nearPlane));
    return (eye - nearPlane) / (farPlane - nearPlane);
}

void main()
{
    float d = texture(depthMap, texCoords).r;
    float shown = linearize == 1 ? linearDepth(d) : d;
    fragColor = vec4(vec3(shown), 1.0);
}
