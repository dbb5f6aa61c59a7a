#version 330 core
// Shadow volumes, fragment stage: the stencil pass writes no colour (its colour mask is
// off); the debug view draws the volume faces in this colour, blended.

layout (location = 0) out vec4 fragColor;

uniform vec4 volumeColour;

void main()
{
    fragColor = volumeColour;
}
