#version 330 core
// Depth pass of a point light in one draw per item: the geometry shader below sends each
// triangle to all six cube faces through gl_Layer (LearnOpenGL's way, which it writes for
// GL 4.1 instancing; here a loop, so GL 3.3 is enough).

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightMatrix;  // model, then minus the light's position

void main()
{
    gl_Position = modelLightMatrix * vec4(position, 1.0);
}
