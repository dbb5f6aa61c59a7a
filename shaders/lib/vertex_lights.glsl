// The translucent items' tests taken per vertex (`translucent_receivers = "vertex"`,
// src/shadows/program/vertex.rs): each light's lines run in the vertex shader as the
// fragment shader has them, against these stand-ins for lib/lighting.glsl's `Fragment`,
// `toLightOf` and `addLight`, which keep each light's test in `f.lit` (light i in component
// i) and add no light.
struct Fragment
{
    vec3 normal;
    vec4 lit;
};

vec3 toLightOf(int i, bool positional)
{
    return positional ? normalize(lightVector[i] - mvVertexPos) : normalize(lightVector[i]);
}

void addLight(int i, vec3 toLight, bool cone, float lit, inout Fragment f)
{
    f.lit[i] = lit;
}
