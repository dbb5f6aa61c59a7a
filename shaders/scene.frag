#version 330 core
// Scene pass fragment shader ("Shadows": scene_fragment.fs), for one to four lights: each
// adds its diffuse and specular light times its own shadow test, 1 = lit. The tests are in
// shaders/lib/ (shadow_2d.glsl: the chapter's calcShadow). `#include` is resolved by
// src/shaders.rs. src/shadows/program/slots.rs writes the two generated snippets (GLSL 3.30
// cannot index an array of samplers with a loop index): the lights' samplers, and
// `addLights`, which calls each light's test with that light's settings as arguments.
// `shadowmap shaders --scene S` prints the whole program as it is compiled.
//
// Defines (src/shadows/program/mod.rs, each only when a light uses it): the lighting's (BLINN,
// SPECULAR_POWER), the lights' layout (LIGHT_COUNT, MAP_SLOTS, VISIBILITY_LIGHT; CASCADES
// and more for a layered light; MULTIPASS with shadow volumes), the cached shadow mask's
// (SHADOW_MASK_WRITE, SHADOW_MASK_READ), the translucent items' tests per vertex
// (VERTEX_TESTS) and the target's outputs (OUTPUT_VISIBILITY, OUTPUT_GBUFFER).

in vec2 outTexCoord;
in vec3 mvVertexNormal;
in vec3 mvVertexPos;
in vec4 mlightviewVertexPos[MAP_SLOTS];  // slot p of each light with a 2D or cube map
// The same for every pixel of an item (see scene.vert: on llvmpipe a flat input costs a
// pixel far less than a uniform read).
flat in vec4 ambientColour;              // the material's colour x the ambient light; a:
                                         // the reflectance (specular = diffuse x it)
flat in vec3 diffuseColour[LIGHT_COUNT]; // the material's colour x light i (x intensity)
flat in vec3 lightVector[LIGHT_COUNT];   // view space: light i's position, or its direction

// The book's DirectionalLight, grown to cover positioned lights (LearnOpenGL shades from a
// light position; spot lights add a cone), as one array per field; its colour comes with
// the material's, its position or direction as lightVector. View space.
uniform float lightConeCos[LIGHT_COUNT];   // cos of a spot's half angle
uniform vec3 lightConeAxis[LIGHT_COUNT];   // the way the spot points

uniform sampler2D textureSampler;  // unit 0; shadow maps on units 1, 2, ... (one per light)
#ifdef MULTIPASS
// With shadow volumes (src/renderer/volume_pass.rs): the light this pass adds, -1 for the
// ambient pass. A light with volumes has no test here: its pass is drawn only where the
// stencil says lit, so its test is `passLight == i` (lit in its pass, 0 in the others).
uniform int passLight;
#endif

#ifdef SHADOW_MASK_READ
// The cached shadow mask (src/renderer/shadow_mask.rs): each light's test at this pixel,
// as a frame with the same camera, items and maps computed it (light i in component i).
uniform sampler2D shadowMask;
vec4 maskedLit;
#endif

#ifdef VERTEX_TESTS
// The translucent items' tests taken per vertex (scene.vert), light i in component i.
in vec4 vertexLit;
#endif

#include "lib/lighting.glsl"
#include "lib/outputs.glsl"
#include "generated/samplers.glsl"
#include "generated/lights.glsl"

void main()
{
    Fragment f;
    // Untextured items sample a 1 x 1 white texture: no per-pixel branch.
    f.base = texture(textureSampler, outTexCoord).rgb;
    f.normal = normalize(mvVertexNormal);
    f.light = vec3(0.0);
    f.visibility = 1.0;
    f.cascade = -1;
#ifdef SHADOW_MASK_WRITE
    f.lit = vec4(1.0);
#endif
#ifdef SHADOW_MASK_READ
    maskedLit = texelFetch(shadowMask, ivec2(gl_FragCoord.xy), 0);
#endif

    addLights(f);
#ifdef SHADOW_MASK_WRITE
    // The mask's pass: the tests, not a colour.
    fragColor = f.lit;
    return;
#endif

    // Ambient light is not shadowed. The book clamps to [0, 1]; the colour buffer is
    // normalised fixed point, which clamps on the way in, so the shader need not.
#ifdef MULTIPASS
    // Passes add up (blending ONE, ONE): the ambient term only in the ambient pass.
    fragColor = vec4(f.base * (ambientColour.rgb * float(passLight < 0) + f.light), 1.0);
#else
    fragColor = vec4(f.base * (ambientColour.rgb + f.light), 1.0);
#endif
#ifdef SHOW_CASCADES
    fragColor.rgb = cascadeTint(fragColor.rgb, f.cascade);
#endif
    writeOutputs(f);
}
