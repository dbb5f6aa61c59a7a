// Caster groups (past the chapters; src/shadows/groups.rs): a directional light's casters
// split into groups, each with its own box fitted to it in a layer of the depth array.
// Compiled with the defines of shadow_layers.glsl (CASCADES: here the groups' layers).

#include "lib/shadow_layers.glsl"

// Every layer is read and the darkest wins: a caster is drawn only in its group's layer,
// whose box covers every receiver it can shadow, and reads lit in the others (outside
// their boxes, or where they hold none of its depths).
float calcShadowGroups(LAYER_SAMPLER map, float bias)
{
    float lit = 1.0;
    for (int c = 0; c < CASCADES; ++c) {
        lit = min(lit, layerLookup(map, c, bias));
    }
    return lit;
}
