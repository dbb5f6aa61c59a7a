#version 330 core
// Stores the linear distance to the light over the far plane, so the scene pass compares
// distances directly whatever the face.

in vec3 lightToFragment;
uniform float farPlane;

void main()
{
    gl_FragDepth = length(lightToFragment) / farPlane;
}
