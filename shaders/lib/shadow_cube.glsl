// A point light's omnidirectional test (LearnOpenGL's "Point Shadows": ShadowCalculation
// with a cube map). The cube stores each direction's nearest distance over the far plane,
// so distances (and the bias) are world units. `fragToLight` is the fragment relative to
// the light; `farPlane` the light's (lightFar[i]); 1 = lit.

uniform float lightFar[LIGHT_COUNT];  // each point light's far plane

// One lookup (a filter of radius 0: single, hw2x2).
float calcShadowCube(samplerCube map, vec3 fragToLight, float farPlane, float bias,
                     bool beyondFarLit)
{
    float current = length(fragToLight);
    if (beyondFarLit && current > farPlane) {
        return 1.0;
    }
    float closest = texture(map, fragToLight).r * farPlane;
    return current - bias > closest ? 0.0 : 1.0;
}

// LearnOpenGL's soft variant (pcf3x3, pcf5x5, hw3x3): 20 lookups on a disk whose radius grows
// with the distance from the viewer.
float calcShadowCubeSoft(samplerCube map, vec3 fragToLight, float farPlane, float bias,
                         bool beyondFarLit)
{
    float current = length(fragToLight);
    if (beyondFarLit && current > farPlane) {
        return 1.0;
    }
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
        shadowed += current - bias > closest ? 1.0 : 0.0;
    }
    return 1.0 - shadowed / 20.0;
}
