// Cascaded shadow maps (past the chapters; LearnOpenGL's "Shadow Mapping" ends pointing at
// them): one directional light's map split into CASCADES layers of a depth array, each
// covering a slice of the view. Compiled with CASCADE_BLEND (the last fraction of each
// cascade that fades into the next) and the defines of shadow_layers.glsl (a layer's test,
// which it includes).

#include "lib/shadow_layers.glsl"

uniform float cascadeSplit[CASCADES + 1];  // view depths: cascade c serves [c, c + 1)

// The cascade is chosen by view depth; over the last CASCADE_BLEND of its range it fades
// into the next one, so the seam does not show. Past the last split (the shadow distance)
// everything is lit. Indices that vary per pixel go into local arrays and inputs
// (selects), never into uniform arrays (a gather per pixel on llvmpipe).
float calcShadowCascades(LAYER_SAMPLER map, float bias, inout Fragment f)
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
    float lit = layerLookup(map, c, bias);
    if (CASCADE_BLEND > 0.0 && c + 1 < CASCADES) {
        float end = splits[c + 1];
        float start = end - CASCADE_BLEND * (end - splits[c]);
        if (depth > start) {
            float next = layerLookup(map, c + 1, bias);
            lit = mix(lit, next, (depth - start) / (end - start));
        }
    }
    return lit;
}

// SHOW_CASCADES: tint each cascade's part of the frame. The colour is mixed toward the tint
// at the pixel's own brightness (its largest channel), so shadows stay dark and the tints
// tell apart on any surface colour (a product would only darken a pure blue floor).
vec3 cascadeTint(vec3 colour, int cascade)
{
    const vec3 tints[4] = vec3[](vec3(1.0, 0.1, 0.1), vec3(0.1, 1.0, 0.1),
                                 vec3(0.15, 0.35, 1.0), vec3(1.0, 0.85, 0.0));
    if (cascade >= 0) {
        float value = max(colour.r, max(colour.g, colour.b));
        colour = mix(colour, tints[cascade] * value, 0.7);
    }
    return colour;
}
