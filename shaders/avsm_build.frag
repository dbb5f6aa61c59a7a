#version 330 core
// AVSM's build (Salvi et al. 2010, section 3; src/shadows/avsm/curve.rs is the same on the
// CPU, in the same float operations), one pass over the texels: the texel's curve, held in
// locals, takes the peeled layers' crossings nearest first (each inserted in depth order,
// every node behind it scaled; when over AVSM_NODES nodes, the interior node whose removal
// changes the area under the curve least goes), then the rest past the last layer, and is
// written once. Nodes are (depth, transmittance) pairs, two to an RGBA32F layer; unused
// ones hold depth AVSM_EMPTY. Compiled with:
//   AVSM_NODES   nodes per texel
//   AVSM_LAYERS  AVSM_NODES / 2, rounded up

layout (location = 0) out vec4 nodesOut[AVSM_LAYERS];

uniform sampler2DArray layers;  // the peeled layers: (depth, opacity), depth 2 = none
uniform int layerCount;         // how many were peeled
uniform sampler2D rest;         // the rest past the last layer: RGB what it lets through,
uniform bool hasRest;           // A its farthest depth; only when `hasRest`

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
    for (int i = 0; i <= AVSM_NODES; ++i) {
        node[i] = vec2(AVSM_EMPTY, 1.0);
    }
    // A texel a layer missed is missed by every layer behind it, and by the rest.
    bool covered = true;
    for (int l = 0; l < layerCount && covered; ++l) {
        vec2 crossing = texelFetch(layers, ivec3(texel, l), 0).xy;
        covered = crossing.x < AVSM_EMPTY;
        if (crossing.y > 0.0) {
            insertCrossing(crossing.x, crossing.y);
        }
    }
    if (hasRest && covered) {
        vec4 fetched = texelFetch(rest, texel, 0);
        vec2 crossing = vec2(fetched.a, 1.0 - fetched.r);
        if (crossing.y > 0.0) {
            insertCrossing(crossing.x, crossing.y);
        }
    }
    for (int i = count; i <= AVSM_NODES; ++i) {
        node[i] = vec2(AVSM_EMPTY, 1.0);
    }
    for (int l = 0; l < AVSM_LAYERS; ++l) {
        nodesOut[l] = vec4(node[2 * l], node[2 * l + 1]);
    }
}
