#version 330 core
// One pass of a summed-area table's build (src/engine/summed_area.rs): each texel adds
// SAT_RADIX texels of the previous pass, stepTexels apart, towards the origin (recursive
// doubling; texels before the map's edge add nothing). Compiled with:
//   SAT_RADIX     texels added per pass
//   SAT_SCALE     fixed-point units per unit of a moment
//   SOURCE_FLOAT  the first pass: reads the float moments and turns them into fixed point
// The vertex shader is depth_view.vert's full-screen triangle.

out uvec4 sums;

#ifdef SOURCE_FLOAT
uniform sampler2D source;
#else
uniform usampler2D partial;
#endif
uniform vec2 stepTexels;  // (step, 0) across, (0, step) down

uvec4 texelAt(ivec2 p)
{
#ifdef SOURCE_FLOAT
    // Moments lie in [0, 1]; rounded to the nearest unit.
    vec4 m = clamp(texelFetch(source, p, 0), 0.0, 1.0);
    return uvec4(m * float(SAT_SCALE) + 0.5);
#else
    return texelFetch(partial, p, 0);
#endif
}

void main()
{
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 step = ivec2(stepTexels);
    uvec4 sum = texelAt(p);
    for (int k = 1; k < SAT_RADIX; ++k) {
        ivec2 q = p - k * step;
        // Unsigned sums wrap around; a box's difference of corners undoes it.
        sum += q.x >= 0 && q.y >= 0 ? texelAt(q) : uvec4(0u);
    }
    sums = sum;
}
