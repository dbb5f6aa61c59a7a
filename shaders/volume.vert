#version 330 core
// Shadow volumes (src/shadows/volumes.rs), vertex stage: each vertex to view space exactly as
// scene.vert does it, so a caster's near cap lands on the very depths the scene wrote.

layout (location = 0) in vec3 position;

uniform mat4 modelViewMatrix;

out vec4 viewPos;

void main()
{
    viewPos = modelViewMatrix * vec4(position, 1.0);
}
