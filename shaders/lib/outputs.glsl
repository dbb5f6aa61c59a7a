// The scene pass's outputs besides colour, for measurement: they exist only when the
// target has them (OUTPUT_VISIBILITY, OUTPUT_GBUFFER), so a window's frame computes none.

layout (location = 0) out vec4 fragColor;
#if OUTPUT_VISIBILITY
layout (location = 1) out vec4 visibilityOut;  // r = shadow-test visibility, g = 1 on geometry
#endif
#if OUTPUT_GBUFFER
layout (location = 2) out vec4 worldPosOut;
layout (location = 3) out vec4 worldNormalOut;
uniform mat3 viewToWorld;  // the camera's rotation, transposed
#endif

// Writes the measurement outputs of the fragment `f`.
void writeOutputs(Fragment f)
{
#if OUTPUT_VISIBILITY
    visibilityOut = vec4(f.visibility, 1.0, 0.0, 1.0);
#endif
#if OUTPUT_GBUFFER
    // The view is rigid: its transposed rotation takes view-space position and normal back to
    // world space, relative to the camera (where the reference wants them).
    worldPosOut = vec4(viewToWorld * mvVertexPos, 1.0);
    worldNormalOut = vec4(normalize(viewToWorld * mvVertexNormal), 1.0);
#endif
}
