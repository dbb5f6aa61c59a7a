#version 330 core
// Depth pass of a point light, one cube face at a time (LearnOpenGL's "Point Shadows",
// drawn in six passes on GL 3.3 instead of with a layered geometry shader).

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightMatrix;  // model, then minus the light's position
uniform mat4 faceProjection;    // 90-degree perspective x this face's view

out vec3 lightToFragment;

void main()
{
    vec4 p = modelLightMatrix * vec4(position, 1.0);
    lightToFragment = p.xyz;
    gl_Position = faceProjection * p;
}
