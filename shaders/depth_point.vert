#version 330 core
// Depth pass of a point light, one cube face at a time (LearnOpenGL's "Point Shadows",
// drawn in six passes on GL 3.3 instead of with a layered geometry shader).

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightMatrix;  // model, then minus the light's position
uniform mat4 faceProjection;    // 90-degree perspective x this face's view

// Instanced draws (src/engine/instances.rs): with `instanced` set, the per-item values are
// per-instance vertex attributes (divisor 1) from the instance buffer; the per-item uniforms
// serve the passes that still draw one item at a time.
uniform bool instanced;
layout (location = 3) in mat4 instanceMatrix;  // locations 3 to 6

out vec3 lightToFragment;

void main()
{
    vec4 p = (instanced ? instanceMatrix : modelLightMatrix) * vec4(position, 1.0);
    lightToFragment = p.xyz;
    gl_Position = faceProjection * p;
}
