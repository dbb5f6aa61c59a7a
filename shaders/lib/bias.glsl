// The depth comparison's offset against shadow acne, and one comparison. Shared by every
// shadow-map test (2D, cube, cascades). Compiled with:
//   BIAS_MODE  0 = none, 1 = constant (BIAS), 2 = slope: max(BIAS * (1 - n.l), BIAS_MIN)
//   HW_PCF     1 = lookups through shadow samplers with LINEAR filtering (hardware 2x2 PCF)
// BIAS and BIAS_MIN are literals the compiler folds (measured: a few percent of the frame
// on llvmpipe against uniforms).

// Each casting light includes this file with its own constants (src/shadows/slots.rs), so
// the macros below are made anew each time.
#undef SHADOW_SAMPLER_2D
#undef SHADOW_SAMPLER_ARRAY
#undef LIT_2D
#undef LIT_ARRAY
#undef PCF_TAPS

// The comparison's offset, in the map's own units (depth for 2D maps, world units for a
// cube map's distances).
float depthBias(vec3 normal, vec3 toLightDir)
{
#if BIAS_MODE == 0
    return 0.0;
#elif BIAS_MODE == 1
    return BIAS;
#else
    return max(BIAS * (1.0 - dot(normal, toLightDir)), BIAS_MIN);
#endif
}

// The samplers a 2D map and a cascade array are read through.
#if HW_PCF
#define SHADOW_SAMPLER_2D sampler2DShadow
#define SHADOW_SAMPLER_ARRAY sampler2DArrayShadow
#else
#define SHADOW_SAMPLER_2D sampler2D
#define SHADOW_SAMPLER_ARRAY sampler2DArray
#endif

// One comparison: 1 = lit. With HW_PCF the hardware compares the 4 nearest texels
// (reference <= stored depth) and blends the results bilinearly.
#if HW_PCF
#define LIT_2D(map, uv, ref) texture(map, vec3(uv, ref))
#define LIT_ARRAY(map, uv, layer, ref) texture(map, vec4(uv, layer, ref))
#else
#define LIT_2D(map, uv, ref) step(ref, texture(map, uv).r)
#define LIT_ARRAY(map, uv, layer, ref) step(ref, texture(map, vec3(uv, layer)).r)
#endif
// Lookups in a PCF grid: PCF_RADIUS 0 = one, 1 = 3 x 3 (the chapters'), 2 = 5 x 5.
#define PCF_TAPS float((2 * PCF_RADIUS + 1) * (2 * PCF_RADIUS + 1))
