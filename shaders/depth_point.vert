#version 330 core
// Depth pass of a point light, one cube face at a time (LearnOpenGL's "Point Shadows",
// drawn in six passes on GL 3.3 instead of with a layered geometry shader).

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightMatrix;  // model, then minus the light's position
uniform mat4 faceProjection;    // 90-degree perspective x this face's view

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

out vec3 lightToFragment;

void main()
{
    vec4 p = (instanced ? instanceMat4(0) : modelLightMatrix) * vec4(position, 1.0);
    lightToFragment = p.xyz;
    gl_Position = faceProjection * p;
}
