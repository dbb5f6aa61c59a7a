// A point light's omnidirectional test (LearnOpenGL's "Point Shadows": ShadowCalculation
// with a cube map). The cube stores each direction's nearest distance over the far plane,
// so distances (and the bias) are world units. Compiled with the defines of bias.glsl and
// PCF_RADIUS (0 = one lookup; more = the soft variant: 20 samples on a disk whose radius
// grows with the distance from the viewer) and BEYOND_FAR_LIT.

// 1 = lit; `fragToLight` is the fragment relative to the light.
float calcShadowCube(samplerCube map, vec3 fragToLight, float farPlane, vec3 normal,
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

// A point light: light i, its position relative to the fragment in slot p.
void addLightCube(int i, int p, samplerCube map, bool positional, bool cone, inout Fragment f)
{
    vec3 toLight = toLightOf(i, positional);
    float lit = calcShadowCube(map, mlightviewVertexPos[p].xyz, lightFar[i], f.normal, toLight);
    addLight(i, toLight, cone, lit, f);
}
