#version 330 core
// Each incoming triangle, once per cube face: projected with that face's matrix and
// routed to the face with gl_Layer.

layout (triangles) in;
layout (triangle_strip, max_vertices = 18) out;

uniform mat4 faceProjections[6];  // 90-degree perspective x each face's view

out vec3 lightToFragment;

void main()
{
    for (int face = 0; face < 6; ++face) {
        for (int i = 0; i < 3; ++i) {
            gl_Layer = face;
            lightToFragment = gl_in[i].gl_Position.xyz;
            gl_Position = faceProjections[face] * gl_in[i].gl_Position;
            EmitVertex();
        }
        EndPrimitive();
    }
}
