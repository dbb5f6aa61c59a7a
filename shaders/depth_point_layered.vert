#version 330 core
// Depth pass of a point light in one draw per mesh, its casters instanced: the geometry
// shader below sends each triangle to its caster's cube faces through gl_Layer
// (LearnOpenGL's way, which it writes for GL 4.1 instancing; here a loop, so GL 3.3 is
// enough).

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightMatrix;  // model, then minus the light's position
uniform int faceMask;           // drawn one item at a time: its faces
flat out int casterFaces;

// Instanced draws (src/engine/instances.rs): with `instanced` set, the per-item values are
// per-instance vertex attributes (divisor 1) from the instance buffer; the per-item uniforms
// serve the passes that still draw one item at a time.
uniform bool instanced;
layout (location = 3) in mat4 instanceMatrix;  // locations 3 to 6
layout (location = 7) in vec4 instanceFaces;  // x: the caster's faces as a float

void main()
{
    gl_Position = (instanced ? instanceMatrix : modelLightMatrix) * vec4(position, 1.0);
    // The caster's faces, for the geometry shader.
    casterFaces = instanced ? int(instanceFaces.x) : faceMask;
}
