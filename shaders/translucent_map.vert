#version 330 core
// A translucent map's pass (src/shadows/volumetric/): the translucent casters as the light
// sees them, through the light's view and projection (the depth map's texels), each
// fragment carrying its depth along the light's axis fitted to the translucent casters:
// 0 at the nearest, 1 at the farthest.

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightViewMatrix;
uniform mat4 orthoProjectionMatrix;
uniform vec2 depthFit;  // the nearest translucent depth, 1 / (farthest - nearest)

out float fittedDepth;

void main()
{
    vec4 lightView = modelLightViewMatrix * vec4(position, 1.0);
    gl_Position = orthoProjectionMatrix * lightView;
    fittedDepth = (-lightView.z - depthFit.x) * depthFit.y;
}
