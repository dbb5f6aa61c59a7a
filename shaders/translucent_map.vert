#version 330 core
// A translucent map's pass (src/shadows/volumetric/): the translucent casters as the light
// sees them, through the light's view and projection (the depth map's texels), each
// fragment carrying its depth along the light's axis fitted to the translucent casters:
// 0 at the nearest, 1 at the farthest, and its caster's optical depth.

layout (location = 0) in vec3 position;
layout (location = 1) in vec2 texCoord;
layout (location = 2) in vec3 vertexNormal;

uniform mat4 modelLightViewMatrix;
uniform float itemOpticalDepth;  // -ln(1 - opacity)
uniform mat4 orthoProjectionMatrix;
uniform vec2 depthFit;  // the nearest translucent depth, 1 / (farthest - nearest)

// Instanced draws (src/engine/instances.rs), as the depth programs: with `instanced` set, a
// caster's matrix and optical depth (x) are per-instance vertex attributes; the uniforms
// above serve a mesh drawn for one caster.
uniform bool instanced;
layout (location = 3) in mat4 instanceMatrix;  // locations 3 to 6
layout (location = 7) in vec4 instanceValues;

out float fittedDepth;
flat out float opticalDepth;

void main()
{
    mat4 modelLightView = instanced ? instanceMatrix : modelLightViewMatrix;
    vec4 lightView = modelLightView * vec4(position, 1.0);
    gl_Position = orthoProjectionMatrix * lightView;
    fittedDepth = (-lightView.z - depthFit.x) * depthFit.y;
    opticalDepth = instanced ? instanceValues.x : itemOpticalDepth;
}
