#version 330 core
// Shadow volumes, geometry stage (the slides' last section): a triangle with its three
// neighbours (GL_TRIANGLES_ADJACENCY: 0 2 4 the triangle, 1 3 5 the vertex across each edge)
// in, the volume faces it owns out. A triangle that faces the light owns:
//   - its near cap: itself, a hair off towards its dark side so that its own pixels are
//     outside its volume (see `near`);
//   - its far cap: itself projected to infinity away from the light, turned around (a
//     directional light's far cap is a single point, so it has none);
//   - a side for each silhouette edge (the neighbour across it does not face the light):
//     the edge extruded to infinity.
// Every face is wound outwards, so the stencil counts front faces down and back faces up.
// An open edge's "neighbour" is the triangle's own third vertex (src/shadows/volumes.rs): the
// neighbour is then this triangle turned around, which always faces the other way, so the
// open edge is a silhouette and the triangle's volume stays closed. An open mesh casts from
// both sides (twoSided): a triangle lit from behind casts as if turned around.

layout (triangles_adjacency) in;
layout (triangle_strip, max_vertices = 18) out;

in vec4 viewPos[];

uniform mat4 projectionMatrix;
// View space: the light's position (w = 1) or the direction towards it (w = 0).
uniform vec4 lightVector;
// How far (in NDC depth, times w) the near cap moves away from the camera.
uniform float capNudge;
// The mesh is open (or non-manifold): every triangle casts, from whichever side is lit.
uniform bool twoSided;

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

// Corner k of the triangle where the volume starts: where the scene drew it, a hair off
// towards the side the light does not reach (`nudge` is +-capNudge, see main). The near
// cap and the sides share these corners exactly, so the volume is watertight, and a
// surface the volume starts on (a caster's lit side, the rim of an open mesh) is on the
// lit side of its own volume, as the exact reference's ray starts off the surface on the
// side its normal faces.
vec4 near(int k, float nudge)
{
    vec4 p = projectionMatrix * viewPos[k];
    p.z += nudge * p.w;
    return p;
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
    float own = facing(p[0], p[2], p[4]);
    // A closed mesh casts from its light-facing triangles; an open one from both sides of
    // each (src/shadows/volumes.rs), a triangle lit from behind taken turned around.
    if (own == 0.0 || (own < 0.0 && !twoSided)) {
        return;
    }
    bool front = own > 0.0;
    int i1 = front ? 2 : 4;
    int i2 = front ? 4 : 2;
    // The volume's start moves away from the camera: the caster's lit pixels count the cap
    // as behind them, their surface outside the volume. An open mesh seen from behind
    // (the eye is at the view-space origin) is shaded and traced from its lit side, as if
    // the camera saw that: its start moves towards the camera, leaving it outside again.
    // (A closed mesh's caps seen from behind are hidden behind its own front: they keep
    // the away nudge, which the front faces they meet at shared edges need.)
    vec3 lit = cross(p[i1] - p[0], p[i2] - p[0]);
    float nudge = twoSided && dot(lit, -p[0]) < 0.0 ? -capNudge : capNudge;
    // Near cap.
    gl_Position = near(0, nudge);
    EmitVertex();
    gl_Position = near(i1, nudge);
    EmitVertex();
    gl_Position = near(i2, nudge);
    EmitVertex();
    EndPrimitive();
    // Far cap, reversed (only a positional light has one with an area).
    if (lightVector.w != 0.0) {
        gl_Position = atInfinity(p[0]);
        EmitVertex();
        gl_Position = atInfinity(p[i2]);
        EmitVertex();
        gl_Position = atInfinity(p[i1]);
        EmitVertex();
        EndPrimitive();
    }
    // Sides on the silhouette edges. Edge a -> b has the neighbour a n b across it; the
    // edge is a silhouette when the neighbour faces the other way from this triangle
    // (a neighbour facing the same way owns the same face, turned around: they cancel).
    for (int e = 0; e < 3; ++e) {
        int a = 2 * e;
        int b = (2 * e + 2) % 6;
        float across = facing(p[a], p[a + 1], p[b]);
        if (front ? across > 0.0 : across < 0.0) {
            continue;
        }
        // Along the edge in the order that faces the light.
        int s = front ? a : b;
        int t = front ? b : a;
        gl_Position = near(s, nudge);
        EmitVertex();
        gl_Position = atInfinity(p[s]);
        EmitVertex();
        gl_Position = near(t, nudge);
        EmitVertex();
        gl_Position = atInfinity(p[t]);
        EmitVertex();
        EndPrimitive();
    }
}
