#version 330 core
// Scene pass vertex shader ("Shadows": scene_vertex.vs with the light-space position).
// Compiled with NORMAL_OFFSET (defined when the lookups move along the normal),
// LIGHT_COUNT, MAP_COUNT / MAP_SLOTS and USES_CASCADES / CASCADES (see scene.frag). Lighting happens in view space, as in the book.
//
// Outputs are counted (src/shadows/program/slots.rs, `vertex_outputs`): GL 3.3 guarantees 64
// components, and four lights with cascades use all of them. So only lights with a 2D or
// cube map get a light-space position (slot p of MAP_SLOTS), the cascaded light gets its
// cascades' positions, and the G-buffer's world position and normal are rebuilt in the
// fragment shader from the view-space ones.

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

out vec2 outTexCoord;
out vec3 mvVertexNormal;
out vec3 mvVertexPos;
out vec4 mlightviewVertexPos[MAP_SLOTS];  // per mapped light: its clip space (a cube: from it)

uniform mat4 modelOriginMatrix;  // model, then minus the camera position
uniform mat4 modelViewMatrix;
uniform mat3 normalMatrix;       // inverse transpose of modelViewMatrix, for normals
uniform mat3 worldNormalMatrix;  // inverse transpose of modelMatrix
uniform mat4 projectionMatrix;
// One per mapped light (slot p, laid out by src/shadows/program/slots.rs).
uniform mat4 modelLightViewMatrix[MAP_SLOTS];
uniform mat4 orthoProjectionMatrix[MAP_SLOTS];
uniform mat3 lightRotation[MAP_SLOTS];    // world to light view, without the translation
uniform float normalOffset[MAP_SLOTS];    // world units along the normal (NORMAL_OFFSET builds)

// Per item and light, the same for every pixel: read here, once per vertex, and passed on
// flat. On llvmpipe each uniform a fragment shader reads costs every pixel a bounds-checked
// load; a flat input costs far less (measured: 10% of the learnopengl frame's instructions).
struct Material
{
    vec4 ambient;                 // rgb: the material's colour x the ambient light; a: reflectance
    vec3 diffuse[LIGHT_COUNT];    // the material's colour x light i's colour x intensity
};
uniform Material material;
uniform vec3 lightPositionOrDirection[LIGHT_COUNT];  // view space
flat out vec4 ambientColour;      // a: the reflectance (specular = diffuse x reflectance)
flat out vec3 diffuseColour[LIGHT_COUNT];
flat out vec3 lightVector[LIGHT_COUNT];

// Instanced draws (src/engine/instances.rs): with `instanced` set, the per-item values come
// from the instance buffer (a uniform block), instance gl_InstanceID's at instanceBase +
// gl_InstanceID x instanceStride, laid out by src/renderer/scene_pass.rs: modelViewMatrix
// (vec4s 0-3), normalMatrix (4-6), modelOriginMatrix (7-10), worldNormalMatrix (11-13),
// material.ambient (14), modelLightViewMatrix[p] (15 + 4p), material.diffuse[i]
// (15 + 4 MAP_SLOTS + i). The uniforms serve the passes that still draw one item at a time
// (translucent items).
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

mat3 instanceMat3(int i)
{
    return mat3(instanceTexel(i).xyz, instanceTexel(i + 1).xyz, instanceTexel(i + 2).xyz);
}

#ifdef USES_CASCADES
// The cascaded light (one per scene): camera-relative world position to each cascade's
// clip space, each cascade's normal offset in world units (its own texel size), and what
// its depth bias is multiplied by so that it spans the same world distance in every layer
// (the deepest box's over its own). Orthographic: w is free to carry it.
uniform mat4 cascadeMatrix[CASCADES];
uniform float cascadeNormalOffset[CASCADES];
uniform float cascadeBiasScale[CASCADES];
out vec4 cascadePos[CASCADES];
#endif

#ifdef VERTEX_TESTS
// Translucent items' program with translucent_receivers = "vertex": the tests of the lights
// that run per vertex, light i in component i, interpolated for the fragment. They are
// computed in world space by the capture program (VERTEX_CAPTURE; vertexTests from
// src/shadows/program/vertex.rs), kept while the maps and the items stay, and read
// here per vertex (src/renderer/vertex_light_cache.rs).
out vec4 vertexLit;
#ifdef VERTEX_CAPTURE
#include "generated/vertex_tests.glsl"
#else
layout (location = 3) in vec4 capturedLit;
#endif
#endif

void main()
{
    mat4 modelView = instanced ? instanceMat4(0) : modelViewMatrix;
    vec4 mvPos = modelView * vec4(position, 1.0);
    gl_Position = projectionMatrix * mvPos;
    outTexCoord = texCoord;
    // The book transforms normals by modelViewMatrix, right for its uniform scales; the
    // inverse transpose keeps them right for any scale.
    mvVertexNormal = normalize((instanced ? instanceMat3(4) : normalMatrix) * vertexNormal);
    mvVertexPos = mvPos.xyz;
    // The world normal, right under any scale; offsets along it are in world units.
    vec3 worldNormal = normalize((instanced ? instanceMat3(11) : worldNormalMatrix) * vertexNormal);
    ambientColour = instanced ? instanceTexel(14) : material.ambient;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        diffuseColour[i] = instanced ? instanceTexel(15 + 4 * MAP_SLOTS + i).rgb : material.diffuse[i];
        lightVector[i] = lightPositionOrDirection[i];
    }
    for (int p = 0; p < MAP_COUNT; ++p) {
        mat4 modelLightView = instanced ? instanceMat4(15 + 4 * p) : modelLightViewMatrix[p];
        vec4 lightViewPos = modelLightView * vec4(position, 1.0);
#ifdef NORMAL_OFFSET
        // Normal-offset bias: look the map up from a point pushed off the surface. The
        // light view is rigid, so the rotated unit normal keeps world lengths.
        lightViewPos.xyz += lightRotation[p] * worldNormal * normalOffset[p];
#endif
        mlightviewVertexPos[p] = orthoProjectionMatrix[p] * lightViewPos;
    }
#ifdef USES_CASCADES
    mat4 modelOrigin = instanced ? instanceMat4(7) : modelOriginMatrix;
    vec3 worldPos = (modelOrigin * vec4(position, 1.0)).xyz;
    for (int c = 0; c < CASCADES; ++c) {
#ifdef NORMAL_OFFSET
        cascadePos[c] = cascadeMatrix[c] * vec4(worldPos + worldNormal * cascadeNormalOffset[c], 1.0);
#else
        cascadePos[c] = cascadeMatrix[c] * vec4(worldPos, 1.0);
#endif
        cascadePos[c].w = cascadeBiasScale[c];
    }
#endif
#ifdef VERTEX_CAPTURE
    vertexTests();
#elif defined(VERTEX_TESTS)
    vertexLit = capturedLit;
#endif
}
