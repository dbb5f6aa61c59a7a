// The light a fragment gets, before shadows: the book's calcLightColour (Phong) or
// LearnOpenGL's Blinn-Phong (BLINN), plus the per-light bookkeeping the scene shader needs.
// Included by scene.frag.

// What a fragment gathers as each light is added.
struct Fragment
{
    vec3 base;         // the texture (white for untextured items)
    vec3 normal;       // view space
    vec3 light;        // diffuse + specular so far, per unit of base colour
    float visibility;  // VISIBILITY_LIGHT's shadow test
    int cascade;       // the cascade used, for SHOW_CASCADES (-1: none)
#ifdef SHADOW_MASK_WRITE
    vec4 lit;          // each light's shadow test (light i in component i), for the mask
#endif
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

// From the fragment towards light i (view space).
vec3 toLightOf(int i, bool positional)
{
    return positional ? normalize(lightVector[i] - mvVertexPos) : normalize(lightVector[i]);
}

// Adds light i, scaled by its shadow test `lit` (1 = lit), to the fragment.
void addLight(int i, vec3 toLight, bool cone, float lit, inout Fragment f)
{
    vec3 light = calcLightColour(diffuseColour[i], diffuseColour[i] * ambientColour.a,
                                 mvVertexPos, toLight, f.normal);
    if (cone) {
        // A spot's cone, with a soft rim of about a degree.
        float c = dot(-toLight, normalize(lightConeAxis[i]));
        light *= smoothstep(lightConeCos[i], lightConeCos[i] + 0.01, c);
    }
#ifdef MULTIPASS
    // Shadow volumes draw the frame in passes: ambient (passLight = -1), then one per light,
    // added where that light's stencil says lit. Each pass adds only its own light.
    f.light += light * (lit * float(passLight == i));
#else
    f.light += light * lit;
#endif
    if (i == VISIBILITY_LIGHT) {
        f.visibility = lit;
    }
#ifdef SHADOW_MASK_WRITE
    f.lit[i] = lit;
#endif
}

// A light that casts no shadow lights everything it faces.
void addLightUnshadowed(int i, bool positional, bool cone, inout Fragment f)
{
    addLight(i, toLightOf(i, positional), cone, 1.0, f);
}
