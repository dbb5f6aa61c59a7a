#version 330 core
// The HUD's quads: positions arrive already in clip space (the CPU knows the frame's size),
// with the atlas coordinate and colour of each corner.

layout (location = 0) in vec2 position;
layout (location = 1) in vec2 atlasCoord;
layout (location = 2) in vec4 colour;

out vec2 texCoord;
out vec4 tint;

void main()
{
    texCoord = atlasCoord;
    tint = colour;
    gl_Position = vec4(position, 0.0, 1.0);
}
