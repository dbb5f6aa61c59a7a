#version 330 core
// Depth pass ("Shadows", the book's depth_vertex.vs): the scene as the light sees it.
// Same inputs as the scene shader so one VAO serves both; only the position is used.

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightViewMatrix;
uniform mat4 orthoProjectionMatrix;

// Instanced draws (src/engine/instances.rs): with `instanced` set, the per-item values are
// per-instance vertex attributes (divisor 1) from the instance buffer; the per-item uniforms
// serve the passes that still draw one item at a time.
uniform bool instanced;
layout (location = 3) in mat4 instanceMatrix;  // locations 3 to 6

#ifdef LINEAR_DEPTH
// A perspective map's linear depth (depth.frag): clip w is the distance along the light's
// axis, so (w - near) / (far - near) runs from 0 to 1 and interpolates exactly.
uniform vec2 depthRange;  // the light's near and far planes
out float lightDepth;
#endif

void main()
{
    mat4 modelLightView = instanced ? instanceMatrix : modelLightViewMatrix;
    gl_Position = orthoProjectionMatrix * modelLightView * vec4(position, 1.0);
#ifdef LINEAR_DEPTH
    lightDepth = (gl_Position.w - depthRange.x) / (depthRange.y - depthRange.x);
#endif
}
