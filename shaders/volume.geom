#version 330 core
// Shadow volumes, geometry stage (the slides' last section): a triangle with its three
// neighbours (GL_TRIANGLES_ADJACENCY: 0 2 4 the triangle, 1 3 5 the vertex across each edge)
// in, the volume faces it owns out. A triangle that faces the light owns:
//   - its near cap: itself, a hair further from the camera so the caster's own lit pixels
//     count it as behind them (see capNudge);
//   - its far cap: itself projected to infinity away from the light, turned around (a
//     directional light's far cap is a single point, so it has none);
//   - a side for each silhouette edge (the neighbour across it does not face the light):
//     the edge extruded to infinity.
// Every face is wound outwards, so the stencil counts front faces down and back faces up.
// An open edge's "neighbour" is the triangle's own third vertex (src/shadows/volumes.rs): the
// neighbour is then this triangle turned around, which never faces the light with it, so the
// open edge is a silhouette and the triangle's volume stays closed.

layout (triangles_adjacency) in;
layout (triangle_strip, max_vertices = 18) out;

in vec4 viewPos[];

uniform mat4 projectionMatrix;
// View space: the light's position (w = 1) or the direction towards it (w = 0).
uniform vec4 lightVector;
// How far (in NDC depth, times w) the near cap moves away from the camera.
uniform float capNudge;

vec3 towardsLight(vec3 p)
{
    return lightVector.xyz - p * lightVector.w;
}

// Lexicographic order on positions, to start every triangle at the same corner.
bool before(vec3 p, vec3 q)
{
    return p.x < q.x || (p.x == q.x && (p.y < q.y || (p.y == q.y && p.z < q.z)));
}

// > 0 when the triangle a b c (counter-clockwise seen from its front) faces the light. The
// same triangle is tested by its own invocation and by each neighbour's, from different
// first corners; starting at its smallest corner makes all of them compute the very same
// number, so a triangle can never face the light for one and not for another (a crack).
float facing(vec3 a, vec3 b, vec3 c)
{
    if (before(b, a) && before(b, c)) {
        vec3 t = a; a = b; b = c; c = t;
    } else if (before(c, a) && before(c, b)) {
        vec3 t = c; c = b; b = a; a = t;
    }
    return dot(cross(b - a, c - a), towardsLight(a));
}

// The point p seen from the light, pushed to infinity.
vec4 atInfinity(vec3 p)
{
    return projectionMatrix * vec4(-towardsLight(p), 0.0);
}

void main()
{
    vec3 p[6];
    for (int k = 0; k < 6; ++k) {
        p[k] = viewPos[k].xyz;
    }
    if (facing(p[0], p[2], p[4]) <= 0.0) {
        return;
    }
    // Near cap.
    for (int k = 0; k < 6; k += 2) {
        gl_Position = projectionMatrix * viewPos[k];
        gl_Position.z += capNudge * gl_Position.w;
        EmitVertex();
    }
    EndPrimitive();
    // Far cap, reversed (only a positional light has one with an area).
    if (lightVector.w != 0.0) {
        gl_Position = atInfinity(p[0]);
        EmitVertex();
        gl_Position = atInfinity(p[4]);
        EmitVertex();
        gl_Position = atInfinity(p[2]);
        EmitVertex();
        EndPrimitive();
    }
    // Sides on the silhouette edges: edge a -> b, across it the neighbour a n b.
    for (int e = 0; e < 3; ++e) {
        int a = 2 * e;
        int b = (2 * e + 2) % 6;
        if (facing(p[a], p[a + 1], p[b]) > 0.0) {
            continue;
        }
        gl_Position = projectionMatrix * viewPos[a];
        EmitVertex();
        gl_Position = atInfinity(p[a]);
        EmitVertex();
        gl_Position = projectionMatrix * viewPos[b];
        EmitVertex();
        gl_Position = atInfinity(p[b]);
        EmitVertex();
        EndPrimitive();
    }
}
