#version 330 core
// Scene pass fragment shader ("Shadows": scene_fragment.fs with calcShadow), for one to
// four lights. Compiled with defines from the shadow settings:
//   PCF_RADIUS      0 = one lookup, 1 = a 3x3 grid (the chapters' PCF), 2 = 5x5
//   HW_PCF          1 = lookups through shadow samplers with LINEAR (hardware 2x2 PCF each)
//   BIAS_MODE       0 = none, 1 = constant (bias), 2 = slope: max(bias * (1 - n.l), biasMin)
//   BEYOND_FAR_LIT  0 = the book (z > 1 compares and shadows), 1 = LearnOpenGL (z > 1 is lit)
//   CASCADES        layers of a cascaded light's map; CASCADE_BLEND, SHOW_CASCADES
//   SHADOW_MAP_SIZE texels per side of every 2D map and cascade (a constant, not a
//                   textureSize query per pixel)
// with the scene's lighting (branches on uniforms would run for every pixel):
//   BLINN            0 = the book's Phong specular, 1 = LearnOpenGL's Blinn-Phong
// and with the lights' layout from src/light_slots.rs:
//   LIGHT_COUNT      length of the per-light uniform arrays
//   LIGHT_SAMPLERS   one sampler declaration per casting light (shadowMapN, shadowCubeN or
//                    cascadeMapN: GLSL 3.30 cannot index an array of samplers in a loop)
//   LIGHT_CALLS      one add... call per light, with its kind's constants
//   VISIBILITY_LIGHT the light whose shadow test goes to the visibility output
// and with the target's outputs: OUTPUT_VISIBILITY, OUTPUT_GBUFFER.

in vec2 outTexCoord;
in vec3 mvVertexNormal;
in vec3 mvVertexPos;
in vec4 mlightviewVertexPos[MAP_SLOTS];  // slot p of each light with a 2D or cube map
// The same for every pixel of an item (see scene.vert: on llvmpipe a flat input costs a
// pixel far less than a uniform read).
flat in vec4 ambientColour;              // the material's colour x the ambient light; a:
flat in vec3 diffuseColour[LIGHT_COUNT]; // the material's colour x light i (x intensity)
                                         // the reflectance (specular = diffuse x it)
flat in vec3 lightVector[LIGHT_COUNT];   // view space: light i's position, or its direction

// The extra outputs exist only when the target has them (OUTPUT_VISIBILITY,
// OUTPUT_GBUFFER): a window's frame computes none of them.
layout (location = 0) out vec4 fragColor;
#if OUTPUT_VISIBILITY
layout (location = 1) out vec4 visibilityOut;  // r = shadow-test visibility, g = 1 on geometry
#endif
#if OUTPUT_GBUFFER
layout (location = 2) out vec4 worldPosOut;
layout (location = 3) out vec4 worldNormalOut;
uniform mat3 viewToWorld;  // the camera's rotation, transposed
#endif

#if HW_PCF
#define SHADOW_SAMPLER_2D sampler2DShadow
#define SHADOW_SAMPLER_ARRAY sampler2DArrayShadow
#else
#define SHADOW_SAMPLER_2D sampler2D
#define SHADOW_SAMPLER_ARRAY sampler2DArray
#endif

uniform sampler2D textureSampler;  // unit 0; shadows on units 1, 2, ... (one per light)
LIGHT_SAMPLERS

// The book's DirectionalLight, grown to cover positioned lights (LearnOpenGL shades from a
// light position; spot lights add a cone), as one array per field; its colour comes with
// the material's, its position or direction as lightVector. View space.
uniform float lightConeCos[LIGHT_COUNT];   // cos of a spot's half angle
uniform vec3 lightConeAxis[LIGHT_COUNT];   // the way the spot points
uniform float lightFar[LIGHT_COUNT];       // a point light's far plane (its cube stores d / far)

#if CASCADES > 1
// The cascaded light's position in each cascade's clip space (scene.vert: one light has
// cascades, so they fit among the inputs).
in vec4 cascadePos[CASCADES];
uniform float cascadeSplit[CASCADES + 1];     // view depths: cascade c serves [c, c + 1)
#endif
// SPECULAR_POWER, BIAS and BIAS_MIN are #defines too: constants the compiler can fold
// (measured: a few percent of the frame on llvmpipe).

// What a fragment gathers as each light is added.
struct Fragment
{
    vec3 base;         // the texture (white for untextured items)
    vec3 normal;       // view space
    vec3 light;        // diffuse + specular so far, per unit of base colour
    float visibility;  // VISIBILITY_LIGHT's shadow test
    int cascade;       // the cascade used, for SHOW_CASCADES (-1: none)
};

// Diffuse plus specular of one light (the book's calcLightColour), per unit of texture
// colour: the texture multiplies the sum of every light once, in main.
vec3 calcLightColour(vec3 diffuseColour, vec3 specularColour, vec3 position, vec3 toLightDir,
                     vec3 normal)
{
    float diffuseFactor = max(dot(normal, toLightDir), 0.0);

    vec3 cameraDirection = normalize(-position);
#if BLINN
    float specularAngle = dot(normal, normalize(toLightDir + cameraDirection));
#else
    float specularAngle = dot(cameraDirection, normalize(reflect(-toLightDir, normal)));
#endif
    float specularFactor = pow(max(specularAngle, 0.0), SPECULAR_POWER);
    return diffuseColour * diffuseFactor + specularColour * specularFactor;
}

// The comparison's offset against acne, in the map's depth units.
float depthBias(vec3 normal, vec3 toLightDir)
{
#if BIAS_MODE == 0
    return 0.0;
#elif BIAS_MODE == 1
    return BIAS;
#else
    return max(BIAS * (1.0 - dot(normal, toLightDir)), BIAS_MIN);
#endif
}

// One comparison: 1 = lit. With HW_PCF the hardware compares the 4 nearest texels
// (reference <= stored depth) and blends the results bilinearly.
#if HW_PCF
#define LIT_2D(map, uv, ref) texture(map, vec3(uv, ref))
#define LIT_ARRAY(map, uv, layer, ref) texture(map, vec4(uv, layer, ref))
#else
#define LIT_2D(map, uv, ref) step(ref, texture(map, uv).r)
#define LIT_ARRAY(map, uv, layer, ref) step(ref, texture(map, vec3(uv, layer)).r)
#endif
#define PCF_TAPS float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1))

// The lit fraction of a PCF_RADIUS grid of comparisons, one texel apart (the chapters' PCF).
float pcf2D(SHADOW_SAMPLER_2D map, vec2 uv, float current)
{
    vec2 inc = vec2(1.0 / float(SHADOW_MAP_SIZE));
    float lit = 0.0;
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            lit += LIT_2D(map, uv + vec2(row, col) * inc, current);
        }
    }
    return lit / PCF_TAPS;
}

// The same grid in one layer of a cascade array.
float pcfArray(SHADOW_SAMPLER_ARRAY map, vec2 uv, float layer, float current)
{
    vec2 inc = vec2(1.0 / float(SHADOW_MAP_SIZE));
    float lit = 0.0;
    for (int row = -PCF_RADIUS; row <= PCF_RADIUS; ++row) {
        for (int col = -PCF_RADIUS; col <= PCF_RADIUS; ++col) {
            lit += LIT_ARRAY(map, uv + vec2(row, col) * inc, layer, current);
        }
    }
    return lit / PCF_TAPS;
}

// 1 = lit, 0 = in shadow (the book's calcShadow, returning 1 - shadowFactor), for a light
// with one 2D map; `position` is the fragment in the light's clip space.
float shadow2D(SHADOW_SAMPLER_2D map, vec4 position, vec3 normal, vec3 toLightDir)
{
    // Clip to normalised device coordinates (w = 1 for an orthographic light), then
    // [-1, 1] to texture coordinates [0, 1].
    vec3 projCoords = position.xyz / position.w * 0.5 + 0.5;
    float lit = pcf2D(map, projCoords.xy, projCoords.z - depthBias(normal, toLightDir));
#if BEYOND_FAR_LIT
    // A select, not an early return: no branch per pixel, and n.l is shared with the
    // lighting.
    lit = projCoords.z > 1.0 ? 1.0 : lit;
#endif
    return lit;
}

// A point light's omnidirectional test (LearnOpenGL's ShadowCalculation for cube maps):
// `fragToLight` is the fragment relative to the light; distances are world units, and so
// is the bias. PCF_RADIUS > 0 selects its soft variant: 20 samples on a grid disk whose
// radius grows with the distance from the viewer.
float shadowCube(samplerCube map, vec3 fragToLight, float farPlane, vec3 normal,
                 vec3 toLightDir)
{
    float current = length(fragToLight);
#if BEYOND_FAR_LIT
    if (current > farPlane) {
        return 1.0;
    }
#endif
    float b = depthBias(normal, toLightDir);
#if PCF_RADIUS == 0
    float closest = texture(map, fragToLight).r * farPlane;
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
        float closest = texture(map, fragToLight + offsets[i] * radius).r * farPlane;
        shadowed += current - b > closest ? 1.0 : 0.0;
    }
    return 1.0 - shadowed / 20.0;
#endif
}

#if CASCADES > 1
// The test in cascade `c` (the position already pushed along the normal by the cascade's
// own texel size, in scene.vert).
float cascadeLookup(SHADOW_SAMPLER_ARRAY map, int c, vec3 normal, vec3 toLightDir)
{
    vec3 projCoords = cascadePos[c].xyz * 0.5 + 0.5;
    float lit = pcfArray(map, projCoords.xy, float(c),
                         projCoords.z - depthBias(normal, toLightDir));
    return projCoords.z > 1.0 ? 1.0 : lit;
}

// A cascaded light: the cascade is chosen by view depth; over the last CASCADE_BLEND of
// its range it fades into the next one, so the seam does not show. Past the last split
// (the shadow distance) everything is lit. Indices that vary per pixel go into local
// arrays and inputs (selects), never into uniform arrays (a gather per pixel on llvmpipe).
float shadowCascades(SHADOW_SAMPLER_ARRAY map, vec3 normal, vec3 toLightDir, inout Fragment f)
{
    float depth = -mvVertexPos.z;
    float splits[CASCADES + 1];
    for (int k = 0; k <= CASCADES; ++k) {
        splits[k] = cascadeSplit[k];
    }
    if (depth >= splits[CASCADES]) {
        return 1.0;
    }
    int c = 0;
    for (int k = 1; k < CASCADES; ++k) {
        c += depth >= splits[k] ? 1 : 0;
    }
    f.cascade = c;
    float lit = cascadeLookup(map, c, normal, toLightDir);
    if (CASCADE_BLEND > 0.0 && c + 1 < CASCADES) {
        float end = splits[c + 1];
        float start = end - CASCADE_BLEND * (end - splits[c]);
        if (depth > start) {
            float next = cascadeLookup(map, c + 1, normal, toLightDir);
            lit = mix(lit, next, (depth - start) / (end - start));
        }
    }
    return lit;
}
#endif

// From the fragment towards light i (view space).
vec3 toLightOf(int i, bool positional)
{
    return positional ? normalize(lightVector[i] - mvVertexPos) : normalize(lightVector[i]);
}

// Adds light i, scaled by its shadow test `lit`, to the fragment.
void addLight(int i, vec3 toLight, bool cone, float lit, inout Fragment f)
{
    vec3 light = calcLightColour(diffuseColour[i], diffuseColour[i] * ambientColour.a,
                                 mvVertexPos, toLight, f.normal);
    if (cone) {
        // A spot's cone, with a soft rim of about a degree.
        float c = dot(-toLight, normalize(lightConeAxis[i]));
        light *= smoothstep(lightConeCos[i], lightConeCos[i] + 0.01, c);
    }
    f.light += light * lit;
    if (i == VISIBILITY_LIGHT) {
        f.visibility = lit;
    }
}

// One function per kind of shadow; LIGHT_CALLS calls one per light with constants, which
// the compiler folds.
void addLightUnshadowed(int i, bool positional, bool cone, inout Fragment f)
{
    addLight(i, toLightOf(i, positional), cone, 1.0, f);
}

void addLight2D(int i, int p, SHADOW_SAMPLER_2D map, bool positional, bool cone,
                inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    addLight(i, toLight, cone, shadow2D(map, mlightviewVertexPos[p], f.normal, toLight), f);
}

void addLightCube(int i, int p, samplerCube map, bool positional, bool cone, inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    float lit = shadowCube(map, mlightviewVertexPos[p].xyz, lightFar[i], f.normal, toLight);
    addLight(i, toLight, cone, lit, f);
}

#if CASCADES > 1
void addLightCascades(int i, SHADOW_SAMPLER_ARRAY map, bool positional, bool cone,
                      inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    addLight(i, toLight, cone, shadowCascades(map, f.normal, toLight, f), f);
}
#endif

void main()
{
    Fragment f;
    // Untextured items sample a 1 x 1 white texture: no per-pixel branch.
    f.base = texture(textureSampler, outTexCoord).rgb;
    f.normal = normalize(mvVertexNormal);
    f.light = vec3(0.0);
    f.visibility = 1.0;
    f.cascade = -1;

    LIGHT_CALLS

    // Ambient light is not shadowed. The book clamps to [0, 1]; the colour buffer is
    // normalised fixed point, which clamps on the way in, so the shader need not.
    fragColor = vec4(f.base * (ambientColour.rgb + f.light), 1.0);
#if SHOW_CASCADES
    const vec3 tints[4] = vec3[](vec3(1.0, 0.35, 0.35), vec3(0.35, 1.0, 0.35),
                                 vec3(0.35, 0.5, 1.0), vec3(1.0, 1.0, 0.3));
    if (f.cascade >= 0) {
        fragColor.rgb = mix(fragColor.rgb, fragColor.rgb * tints[f.cascade], 0.6);
    }
#endif

#if OUTPUT_VISIBILITY
    visibilityOut = vec4(f.visibility, 1.0, 0.0, 1.0);
#endif
#if OUTPUT_GBUFFER
    // The view is rigid: its transposed rotation takes view-space position and normal back to
    // world space, relative to the camera (where the reference wants them).
    worldPosOut = vec4(viewToWorld * mvVertexPos, 1.0);
    worldNormalOut = vec4(normalize(viewToWorld * mvVertexNormal), 1.0);
#endif
}
