#version 330 core
// Each incoming triangle, once per cube face its caster may land in (casterFaces, bit f
// for face f, worked out per caster on the CPU): projected with that face's matrix and routed to
// the face with gl_Layer.

layout (triangles) in;
layout (triangle_strip, max_vertices = 18) out;

uniform mat4 faceProjections[6];  // 90-degree perspective x each face's view
flat in int casterFaces[];  // the caster's faces, from the vertex shader

out vec3 lightToFragment;

void main()
{
    for (int face = 0; face < 6; ++face) {
        if ((casterFaces[0] & (1 << face)) == 0) {
            continue;
        }
        for (int i = 0; i < 3; ++i) {
            gl_Layer = face;
            lightToFragment = gl_in[i].gl_Position.xyz;
            gl_Position = faceProjections[face] * gl_in[i].gl_Position;
            EmitVertex();
        }
        EndPrimitive();
    }
}
