#version 330 core
// Depth pass fragment shader ("Shadows", depth_fragment.fs). The book writes
// gl_FragDepth = gl_FragCoord.z, which stores the same value the fixed pipeline stores
// anyway, and says the line can go. We leave it out: writing gl_FragDepth turns off the
// early depth test and costs time for nothing.
//
// LINEAR_DEPTH (a perspective map that stores linear depth, src/shadows/map2d.rs): the
// depth along the light's axis from its near plane (0) to its far plane (1) replaces the
// projection's z / w, so a bias means the same distance at any near plane
// (docs/techniques/perspective-depth.md). Written here, as a point light's distance is.

#ifdef LINEAR_DEPTH
in float lightDepth;
// glPolygonOffset does not move a depth the shader writes, so its (factor, units x the
// format's least step) are added here as GL would: factor x the depth's slope + units.
uniform vec2 polygonOffset;
#endif

void main()
{
#ifdef LINEAR_DEPTH
    float offset = 0.0;
    if (polygonOffset != vec2(0.0)) {
        float slope = max(abs(dFdx(lightDepth)), abs(dFdy(lightDepth)));
        offset = polygonOffset.x * slope + polygonOffset.y;
    }
    gl_FragDepth = lightDepth + offset;
#endif
}
