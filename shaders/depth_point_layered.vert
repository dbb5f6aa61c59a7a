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

// Instanced draws (src/engine/instances.rs): with `instanced` set, the per-item values come
// from the instance buffer (a uniform block), instance gl_InstanceID's at instanceBase +
// gl_InstanceID x instanceStride; the per-item uniforms serve the passes that still draw
// one item at a time.
uniform bool instanced;
const int INSTANCE_VEC4S = 1024;  // 16 KiB: GL 3.3's smallest block size
layout(std140) uniform Instances
{
    vec4 instanceData[INSTANCE_VEC4S];
};
uniform int instanceStride;
uniform int instanceBase;

vec4 instanceTexel(int i)
{
    return instanceData[instanceBase + gl_InstanceID * instanceStride + i];
}

mat4 instanceMat4(int i)
{
    return mat4(instanceTexel(i), instanceTexel(i + 1), instanceTexel(i + 2), instanceTexel(i + 3));
}

void main()
{
    gl_Position = (instanced ? instanceMat4(0) : modelLightMatrix) * vec4(position, 1.0);
    // The caster's faces (its texel 4 holds them as a float), for the geometry shader.
    casterFaces = instanced ? int(instanceTexel(4).x) : faceMask;
}
