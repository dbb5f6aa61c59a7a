// A perspective map tested in linear depth (src/shadows/map2d.rs, map_depth): its slot's
// projection gives the depth along the light's axis, near (0) to far (1), as clip z
// (scene.vert), where it interpolates exactly. The tests divide by w, so it goes back in
// as a clip position whose z / w * 0.5 + 0.5 is that depth.
//
// perspective_depth = "linear": the map stores that depth too; the tests compare and bias
// as in any map.
vec4 linearDepthPosition(vec4 position)
{
    return vec4(position.xy, position.w * (2.0 * position.z - 1.0), position.w);
}

// perspective_depth = "hyperbolic-linear-bias": the map keeps its projection's depth; the
// bias comes off the fragment's linear depth (position.z as above), and the biased depth
// goes back to the projection's for the comparison. `range` is the light's (near, far).
uniform vec4 lightDepthRange[LIGHT_COUNT];

vec4 projectedBiasedPosition(vec4 position, float bias, vec4 range)
{
    float near = range.x;
    float far = range.y;
    // The distance along the light's axis; below half the near plane reads as in front of
    // everything (lit), not wrapped past the far plane.
    float axial = max(near + (position.z - bias) * (far - near), 0.5 * near);
    float depth = far / (far - near) * (1.0 - near / axial);
    return vec4(position.xy, position.w * (2.0 * depth - 1.0), position.w);
}
