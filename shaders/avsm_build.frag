#version 330 core
// AVSM's per-texel build (Salvi et al. 2010, section 3; src/shadows/avsm/curve.rs is the
// same on the CPU, in the same float operations): the texel's curve, read from the
// previous build, takes the peeled layer's crossing (inserted in depth order, every node
// behind it scaled), and when over AVSM_NODES nodes drops the interior node whose removal
// changes the area under the curve least. Nodes are (depth, transmittance) pairs, two to
// an RGBA32F layer; unused ones hold depth AVSM_EMPTY. Compiled with:
//   AVSM_NODES   nodes per texel
//   AVSM_LAYERS  AVSM_NODES / 2, rounded up

layout (location = 0) out vec4 nodesOut[AVSM_LAYERS];

uniform sampler2DArray curve;  // the previous build's nodes
uniform sampler2D layer;       // the peeled layer: (depth, opacity), opacity 0 = none
uniform bool firstLayer;       // no previous build: start from an empty curve
uniform bool rest;             // `layer` is the rest past the last layer: RGB what it lets
                               // through, A its farthest depth

const float AVSM_EMPTY = 2.0;

// One more than the curve keeps: room for the insertion before a compression, and an
// odd count's unused half of the last layer.
vec2 node[AVSM_NODES + 1];
int count;

// The curve's light left at `depth`: 1 before the first node, linear between two nodes,
// the last one's value past it.
float lookup(float depth)
{
    float left = 1.0;
    for (int i = 0; i < count; ++i) {
        if (node[i].x > depth) {
            if (i > 0) {
                vec2 a = node[i - 1];
                float w = (depth - a.x) / (node[i].x - a.x);
                left = a.y + (node[i].y - a.y) * w;
            }
            return left;
        }
        left = node[i].y;
    }
    return left;
}

// Drops the interior node whose triangle with its neighbours is smallest (the nearest on
// a tie); the first and the last stay.
void compress()
{
    int drop = 1;
    float least = 0.0;
    for (int i = 1; i < count - 1; ++i) {
        vec2 a = node[i - 1];
        vec2 m = node[i];
        vec2 b = node[i + 1];
        float area = 0.5 * abs((m.x - a.x) * (b.y - a.y) - (b.x - a.x) * (m.y - a.y));
        if (i == 1 || area < least) {
            least = area;
            drop = i;
        }
    }
    for (int i = 1; i < AVSM_NODES; ++i) {
        if (i >= drop) {
            node[i] = node[i + 1];
        }
    }
    count -= 1;
}

void insertCrossing(float depth, float opacity)
{
    float pass = 1.0 - clamp(opacity, 0.0, 1.0);
    int at = count;
    for (int i = count - 1; i >= 0; --i) {
        if (node[i].x > depth) {
            at = i;
        }
    }
    float before = lookup(depth);
    for (int i = AVSM_NODES; i > 0; --i) {
        if (i <= count && i > at) {
            node[i] = vec2(node[i - 1].x, node[i - 1].y * pass);
        }
    }
    node[at] = vec2(depth, before * pass);
    count += 1;
    if (count > AVSM_NODES) {
        compress();
    }
}

void main()
{
    ivec2 texel = ivec2(gl_FragCoord.xy);
    count = 0;
    for (int l = 0; l < AVSM_LAYERS; ++l) {
        vec4 v = firstLayer ? vec4(AVSM_EMPTY, 1.0, AVSM_EMPTY, 1.0)
                            : texelFetch(curve, ivec3(texel, l), 0);
        node[2 * l] = v.xy;
        node[2 * l + 1] = v.zw;
    }
    node[AVSM_NODES] = vec2(AVSM_EMPTY, 1.0);
    for (int i = 0; i < AVSM_NODES; ++i) {
        if (node[i].x < AVSM_EMPTY) {
            count = i + 1;
        }
    }
    vec4 fetched = texelFetch(layer, texel, 0);
    vec2 crossing = rest ? vec2(fetched.a, 1.0 - fetched.r) : fetched.xy;
    if (crossing.y > 0.0) {
        insertCrossing(crossing.x, crossing.y);
    }
    for (int i = count; i <= AVSM_NODES; ++i) {
        node[i] = vec2(AVSM_EMPTY, 1.0);
    }
    for (int l = 0; l < AVSM_LAYERS; ++l) {
        nodesOut[l] = vec4(node[2 * l], node[2 * l + 1]);
    }
}
