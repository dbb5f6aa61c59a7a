//! A perspective map's test for a point behind its light (clip w <= 0): lit, not mirrored
//! into the map past its far plane (shaders/lib/shadow_2d.glsl, `calcShadow`).

use crate::common;

use shadowmap::Scene;

#[test]
fn a_ceiling_behind_a_spot_light_is_lit() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/behind_spot.toml");
    let scene = Scene::load(path).unwrap();
    let ctx = common::context();
    let frame = shadowmap::compare::render_visibility(ctx.gl(), &scene, &scene.shadow, 320, 240, 0)
        .unwrap();
    let visibility = frame.visibility.as_ref().unwrap();
    let positions = frame.positions.as_ref().unwrap();
    // The camera is level with the light: world y is the G-buffer's y.
    let y = |i: usize| positions[i][1] + frame.origin.y as f32;
    let vis = |i: usize| visibility[i];
    let ceiling: Vec<f32> = (0..visibility.len())
        .filter(|&i| y(i) > 2.0)
        .filter_map(vis)
        .collect();
    assert!(ceiling.len() > 10_000, "{} ceiling pixels", ceiling.len());
    let shadowed = ceiling.iter().filter(|&&v| v < 1.0).count();
    assert_eq!(shadowed, 0, "of {} ceiling pixels", ceiling.len());
    // The test still shadows in front of the light: the block's shadow on the floor.
    let floor_shadowed = (0..visibility.len())
        .filter(|&i| y(i) < -2.5 && vis(i).is_some_and(|v| v < 0.5))
        .count();
    assert!(
        floor_shadowed > 100,
        "{floor_shadowed} shadowed floor pixels"
    );
}
