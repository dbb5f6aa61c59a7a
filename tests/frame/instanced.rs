//! Items sharing a mesh are drawn with one instanced call per pass: a frame's draw calls
//! follow the meshes and passes, not the items.

use crate::common;

use shadowmap::engine::counters::draws;
use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::renderer::{Renderer, Target};
use shadowmap::settings::PointPass;
use shadowmap::Scene;

/// The draw calls of the second frame of `scene` under its settings changed by `tweak`
/// (shadow cache off, so every map is drawn), and the scene's item count.
fn draws_of_a_frame(
    name: &str,
    tweak: impl Fn(&mut shadowmap::settings::ShadowSettings),
) -> (u64, usize) {
    let context = common::context();
    let gl = context.gl();
    let mut scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
    scene.size = [160, 90];
    let mut settings = scene.shadow;
    settings.shadow_cache = false;
    tweak(&mut settings);
    let target = RenderTarget::new(gl, 160, 90, Outputs::default()).unwrap();
    let mut renderer = Renderer::new(gl, &scene, &settings).unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    let before = draws();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    (draws() - before, scene.items.len())
}

#[test]
fn four_cascades_of_the_large_scene_take_a_draw_per_mesh_and_pass() {
    let (drawn, items) = draws_of_a_frame("large", |s| s.cascades = 4);
    // Four layers and the scene pass, a draw per mesh in each (700 one at a time).
    assert!(items > 120, "{items} items");
    assert!(drawn <= 30, "{drawn} draws a frame for {items} items");
}

#[test]
fn a_cube_map_takes_a_draw_per_mesh_in_either_point_pass() {
    let meshes = Scene::load("point-shadows").unwrap().meshes.len() as u64;
    let (layered, items) = draws_of_a_frame("point-shadows", |s| s.point_pass = PointPass::Layered);
    assert!(
        layered <= 2 * meshes,
        "{layered} draws, {meshes} meshes, {items} items"
    );
    let (six, _) = draws_of_a_frame("point-shadows", |s| s.point_pass = PointPass::SixPasses);
    assert!(six <= 7 * meshes, "{six} draws, {meshes} meshes");
    assert!(items as u64 > 2 * meshes, "{items} items, {meshes} meshes");
}

#[test]
fn runs_longer_than_the_instance_block_draw_every_instance() {
    // 900 cubes: more than one window of the 16 KiB block in the depth pass (256 instances)
    // and in the scene pass (64), so every window's instances must land where they belong.
    let scene = Scene::load("tests/data/crowd.toml").unwrap();
    assert!(scene.items.len() > 900, "{} items", scene.items.len());
    let c = common::compared(&scene, &scene.shadow, &common::frame_options(320, 180));
    let m = &c.metrics;
    assert!(m.receivers > 20_000, "{} receivers", m.receivers);
    // The truth is traced from the rendered G-buffer's positions: a cube drawn with another
    // instance's matrix moves the receivers themselves, so check the crowd is where it
    // stands (its shadows cover much of the floor) as well as the shadow test.
    let shadowed = (c.reference.hard.iter())
        .filter(|p| p.receiver && p.visibility < 0.5)
        .count();
    let share = shadowed as f64 / m.receivers as f64;
    assert!(
        share > 0.1,
        "{:.1}% of the receivers in shadow",
        100.0 * share
    );
    assert!(
        m.misclassified_rate < 0.01,
        "{:.3}% misclassified ({} false shadow, {} false light)",
        100.0 * m.misclassified_rate,
        m.false_shadow,
        m.false_light
    );
}
