// The depth comparison's offset against shadow acne, in the map's own units (depth for 2D
// maps, world units for a cube map's distances). A light with a constant bias (the book's
// 0.05) or none passes the number itself; with the slope bias (LearnOpenGL's) it passes
// this, which grows as the surface turns away from the light.
float slopeBias(vec3 normal, vec3 toLightDir, float bias, float least)
{
    return max(bias * (1.0 - dot(normal, toLightDir)), least);
}
