#version 330 core
// Depth pass fragment shader ("Shadows", depth_fragment.fs). The book writes
// gl_FragDepth = gl_FragCoord.z, which stores the same value the fixed pipeline stores
// anyway, and says the line can go. We leave it out: writing gl_FragDepth turns off the
// early depth test and costs time for nothing.

void main()
{
}
