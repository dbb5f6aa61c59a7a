#version 330 core
// The depth-map debug view: one triangle that covers the viewport, no vertex buffer.

out vec2 texCoords;

void main()
{
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    texCoords = p;
    gl_Position = vec4(p * 2.0 - 1.0, 0.0, 1.0);
}
