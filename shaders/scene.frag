#version 330 core
// Scene pass fragment shader ("Shadows": scene_fragment.fs with calcShadow).
// Compiled with defines from the shadow settings:
//   PCF_RADIUS      0 = one lookup, 1 = a 3x3 grid (the chapters' PCF), 2 = 5x5
//   HW_PCF          1 = lookups through sampler2DShadow with LINEAR (hardware 2x2 PCF each)
//   BIAS_MODE       0 = none, 1 = constant (bias), 2 = slope: max(bias * (1 - n.l), biasMin)
//   BEYOND_FAR_LIT  0 = the book (z > 1 compares and shadows), 1 = LearnOpenGL (z > 1 is lit)
//   POINT_SHADOW    1 = a point light's depth cube map (distances in world units)
// and with the scene's lighting (branches on uniforms would run for every pixel):
//   LIGHT_POSITIONAL 0 = one direction for all fragments, 1 = from each fragment to a point
//   SPOT_CONE        1 = a spot light's cone limits the light
//   BLINN            0 = the book's Phong specular, 1 = LearnOpenGL's Blinn-Phong

in vec2 outTexCoord;
in vec3 mvVertexNormal;
in vec3 mvVertexPos;
in vec4 mlightviewVertexPos;
in vec3 worldPos;
in vec3 worldNormal;

layout (location = 0) out vec4 fragColor;
layout (location = 1) out vec4 visibilityOut;  // r = shadow-test visibility, g = 1 on geometry
layout (location = 2) out vec4 worldPosOut;
layout (location = 3) out vec4 worldNormalOut;

struct Material
{
    vec4 colour;
    vec3 specular;  // the light's colour x intensity x this material's reflectance (on the CPU)
};

// The book's DirectionalLight, grown to cover positioned lights (LearnOpenGL shades from a
// light position; spot lights add a cone). Directions and positions are in view space.
struct Light
{
    vec3 colour;      // x intensity
    vec3 direction;   // towards the light
    vec3 position;
    float coneCos;    // cos of the cone's half angle
    vec3 coneAxis;    // the way the spot points
};

uniform sampler2D textureSampler;  // unit 0
#if POINT_SHADOW
uniform samplerCube shadowMap;     // unit 1, linear distance / farPlane
uniform float farPlane;
#elif HW_PCF
uniform sampler2DShadow shadowMap; // unit 1, compare mode on
#else
uniform sampler2D shadowMap;       // unit 1
#endif
uniform Material material;
uniform Light light;
uniform vec3 ambientLight;
// SPECULAR_POWER, BIAS and BIAS_MIN are #defines too: constants the compiler can fold
// (measured: a few percent of the frame on llvmpipe).

// Diffuse plus specular of one light (the book's calcLightColour). `lightColour` already
// carries the intensity, `material.specular` the reflectance: products the CPU makes once.
vec4 calcLightColour(vec4 baseColour, vec3 lightColour, vec3 position, vec3 toLightDir,
                     vec3 normal)
{
    float diffuseFactor = max(dot(normal, toLightDir), 0.0);
    vec4 diffuse = baseColour * vec4(lightColour * diffuseFactor, 1.0);

    vec3 cameraDirection = normalize(-position);
#if BLINN
    float specularAngle = dot(normal, normalize(toLightDir + cameraDirection));
#else
    float specularAngle = dot(cameraDirection, normalize(reflect(-toLightDir, normal)));
#endif
    float specularFactor = pow(max(specularAngle, 0.0), SPECULAR_POWER);
    vec4 specular = baseColour * vec4(material.specular * specularFactor, 1.0);
    return diffuse + specular;
}

#if POINT_SHADOW
// A point light's omnidirectional test (LearnOpenGL's ShadowCalculation for cube maps):
// `position` holds the fragment relative to the light; distances are world units, and so
// is the bias. PCF_RADIUS > 0 selects its soft variant: 20 samples on a grid disk whose
// radius grows with the distance from the viewer.
float calcShadow(vec4 position, vec3 normal, vec3 toLightDir)
{
    vec3 fragToLight = position.xyz;
    float current = length(fragToLight);
#if BEYOND_FAR_LIT
    if (current > farPlane) {
        return 1.0;
    }
#endif
#if BIAS_MODE == 0
    float b = 0.0;
#elif BIAS_MODE == 1
    float b = BIAS;
#else
    float b = max(BIAS * (1.0 - dot(normal, toLightDir)), BIAS_MIN);
#endif
#if PCF_RADIUS == 0
    float closest = texture(shadowMap, fragToLight).r * farPlane;
    return current - b > closest ? 0.0 : 1.0;
#else
    const vec3 offsets[20] = vec3[](
        vec3(1, 1, 1), vec3(1, -1, 1), vec3(-1, -1, 1), vec3(-1, 1, 1),
        vec3(1, 1, -1), vec3(1, -1, -1), vec3(-1, -1, -1), vec3(-1, 1, -1),
        vec3(1, 1, 0), vec3(1, -1, 0), vec3(-1, -1, 0), vec3(-1, 1, 0),
        vec3(1, 0, 1), vec3(-1, 0, 1), vec3(1, 0, -1), vec3(-1, 0, -1),
        vec3(0, 1, 1), vec3(0, -1, 1), vec3(0, -1, -1), vec3(0, 1, -1));
    float radius = (1.0 + length(mvVertexPos) / farPlane) / 25.0;
    float shadowed = 0.0;
    for (int i = 0; i < 20; ++i) {
        float closest = texture(shadowMap, fragToLight + offsets[i] * radius).r * farPlane;
        shadowed += current - b > closest ? 1.0 : 0.0;
    }
    return 1.0 - shadowed / 20.0;
#endif
}
#else
// 1 = lit, 0 = in shadow (the book's calcShadow, returning 1 - shadowFactor).
float calcShadow(vec4 position, vec3 normal, vec3 toLightDir)
{
    // Clip to normalised device coordinates (w = 1 for an orthographic light), then
    // [-1, 1] to texture coordinates [0, 1].
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
#if BEYOND_FAR_LIT
    if (projCoords.z > 1.0) {
        return 1.0;
    }
#endif
#if BIAS_MODE == 0
    float b = 0.0;
#elif BIAS_MODE == 1
    float b = BIAS;
#else
    float b = max(BIAS * (1.0 - dot(normal, toLightDir)), BIAS_MIN);
#endif
    float current = projCoords.z - b;
#if HW_PCF
    // The hardware returns the lit fraction (reference <= stored depth), bilinearly blended.
    float lit = 0.0;
    vec2 inc = 1.0 / vec2(textureSize(shadowMap, 0));
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            lit += texture(shadowMap, vec3(projCoords.xy + vec2(row, col) * inc, current));
        }
    }
    return lit / float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
#else
    float shadowFactor = 0.0;
#if PCF_RADIUS == 0
    shadowFactor = current > texture(shadowMap, projCoords.xy).r ? 1.0 : 0.0;
#else
    vec2 inc = 1.0 / vec2(textureSize(shadowMap, 0));
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            float textDepth = texture(shadowMap, projCoords.xy + vec2(row, col) * inc).r;
            shadowFactor += current > textDepth ? 1.0 : 0.0;
        }
    }
    shadowFactor /= float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1));
#endif
    return 1.0 - shadowFactor;
#endif
}
#endif

void main()
{
    // Untextured items sample a 1 x 1 white texture: no per-pixel branch.
    vec4 baseColour = texture(textureSampler, outTexCoord) * material.colour;
    vec3 normal = normalize(mvVertexNormal);
#if LIGHT_POSITIONAL
    vec3 toLight = normalize(light.position - mvVertexPos);
#else
    vec3 toLight = normalize(light.direction);
#endif
    vec4 diffuseSpecular = calcLightColour(baseColour, light.colour, mvVertexPos, toLight,
                                           normal);
#if SPOT_CONE
    // A spot's cone, with a soft rim of about a degree.
    float c = dot(-toLight, normalize(light.coneAxis));
    diffuseSpecular *= smoothstep(light.coneCos, light.coneCos + 0.01, c);
#endif
    float shadow = calcShadow(mlightviewVertexPos, normal, toLight);
    // Ambient light is not shadowed.
    fragColor = clamp(baseColour * vec4(ambientLight, 1.0) + diffuseSpecular * shadow, 0.0, 1.0);
    fragColor.a = 1.0;

    visibilityOut = vec4(shadow, 1.0, 0.0, 1.0);
    worldPosOut = vec4(worldPos, 1.0);
    worldNormalOut = vec4(normalize(worldNormal), 1.0);
}
