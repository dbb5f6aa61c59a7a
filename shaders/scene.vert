#version 330 core
// Scene pass vertex shader ("Shadows": scene_vertex.vs with the light-space position).
// Compiled with NORMAL_OFFSET 0/1, LIGHT_COUNT and CASCADES (see scene.frag). The
// G-buffer outputs are dropped by the linker when the fragment shader does not write them.
// Lighting happens in view space, as in the book; world position (relative to the camera,
// so it keeps its precision far from the origin) and normal are passed on for the G-buffer
// outputs that tests and the exact reference read.

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

out vec2 outTexCoord;
out vec3 mvVertexNormal;
out vec3 mvVertexPos;
out vec4 mlightviewVertexPos[LIGHT_COUNT];  // per light: its clip space (a cube light: from it)
out vec3 worldPos;
out vec3 worldNormal;

uniform mat4 modelOriginMatrix;  // model, then minus the camera position (G-buffer outputs)
uniform mat4 modelViewMatrix;
uniform mat3 normalMatrix;       // inverse transpose of modelViewMatrix, for normals
uniform mat3 worldNormalMatrix;  // inverse transpose of modelMatrix
uniform mat4 projectionMatrix;
// One per light (LIGHT_COUNT, laid out by src/light_slots.rs).
uniform mat4 modelLightViewMatrix[LIGHT_COUNT];
uniform mat4 orthoProjectionMatrix[LIGHT_COUNT];
uniform float normalOffset[LIGHT_COUNT];  // world units along the normal (NORMAL_OFFSET builds)

// Per item and light, the same for every pixel: read here, once per vertex, and passed on
// flat. On llvmpipe each uniform a fragment shader reads costs every pixel a bounds-checked
// load; a flat input costs far less (measured: 10% of the learnopengl frame's instructions).
struct Material
{
    vec3 ambient;                 // the material's colour x the ambient light
    vec3 diffuse[LIGHT_COUNT];    // the material's colour x light i's colour x intensity
    float reflectance;
};
uniform Material material;
uniform vec3 lightPositionOrDirection[LIGHT_COUNT];  // view space
flat out vec3 ambientColour;
flat out vec3 diffuseColour[LIGHT_COUNT];
flat out float reflectance;
flat out vec3 lightVector[LIGHT_COUNT];

#if CASCADES > 1
// The cascaded light (one per scene): camera-relative world position to each cascade's
// clip space, and each cascade's normal offset in world units (its own texel size).
uniform mat4 cascadeMatrix[CASCADES];
uniform float cascadeNormalOffset[CASCADES];
out vec4 cascadePos[CASCADES];
#endif

void main()
{
    vec4 mvPos = modelViewMatrix * vec4(position, 1.0);
    gl_Position = projectionMatrix * mvPos;
    outTexCoord = texCoord;
    // The book transforms normals by modelViewMatrix, right for its uniform scales; the
    // inverse transpose keeps them right for any scale.
    mvVertexNormal = normalize(normalMatrix * vertexNormal);
    mvVertexPos = mvPos.xyz;
    ambientColour = material.ambient;
    reflectance = material.reflectance;
    for (int i = 0; i < LIGHT_COUNT; ++i) {
        diffuseColour[i] = material.diffuse[i];
        lightVector[i] = lightPositionOrDirection[i];
        vec4 lightViewPos = modelLightViewMatrix[i] * vec4(position, 1.0);
#if NORMAL_OFFSET
        // Normal-offset bias: look the map up from a point pushed off the surface. The
        // light view is rigid, so the normalised normal keeps world lengths.
        lightViewPos.xyz += normalize(mat3(modelLightViewMatrix[i]) * vertexNormal)
                            * normalOffset[i];
#endif
        mlightviewVertexPos[i] = orthoProjectionMatrix[i] * lightViewPos;
    }
    worldPos = (modelOriginMatrix * vec4(position, 1.0)).xyz;
    worldNormal = normalize(worldNormalMatrix * vertexNormal);
#if CASCADES > 1
    for (int c = 0; c < CASCADES; ++c) {
#if NORMAL_OFFSET
        cascadePos[c] = cascadeMatrix[c] * vec4(worldPos + worldNormal * cascadeNormalOffset[c], 1.0);
#else
        cascadePos[c] = cascadeMatrix[c] * vec4(worldPos, 1.0);
#endif
    }
#endif
}
