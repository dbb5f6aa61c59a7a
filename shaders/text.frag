#version 330 core
// The atlas holds glyph coverage in its red channel; coverage scales the colour's alpha, and
// blending lays the result over the frame.

in vec2 texCoord;
in vec4 tint;

out vec4 fragColour;

uniform sampler2D atlas;

void main()
{
    fragColour = vec4(tint.rgb, tint.a * texture(atlas, texCoord).r);
}
