// A perspective map that stores linear depth (src/shadows/map2d.rs, stores_linear_depth):
// its slot's projection gives that depth, near (0) to far (1), as clip z (scene.vert), where
// it interpolates exactly. The tests divide by w, so it goes back in as a clip position
// whose z / w * 0.5 + 0.5 is that depth; they then compare and bias as in any map.
vec4 linearDepthPosition(vec4 position)
{
    return vec4(position.xy, position.w * (2.0 * position.z - 1.0), position.w);
}
