//! More light types against the exact reference: a point light inside a room of cubes
//! (omnidirectional shadows in a depth cube map) and a spot light's cone.

mod common;

use glam::Vec3;
use shadowmap::compare::{compare, CompareOptions};
use shadowmap::settings::{BiasMode, Filter, ShadowSettings};
use shadowmap::Scene;

fn measure(scene: &Scene, s: &ShadowSettings) -> shadowmap::reference::Metrics {
    let ctx = common::context();
    let opts = CompareOptions {
        width: 400,
        height: 300,
        supersample: 2,
        band: 1,
        light: 0,
    };
    compare(ctx.gl(), scene, s, &opts)
        .unwrap_or_else(|e| panic!("{e}"))
        .metrics
}

#[test]
fn point_light_in_a_room_of_cubes_matches_the_reference() {
    let mut scene = Scene::load("point-shadows").unwrap();
    // A view from a corner that sees walls, floor and the cubes' shadows on them.
    scene.camera.position = Vec3::new(3.5, 3.0, 4.5);
    scene.camera.rotation = Vec3::new(30.0, -35.0, 0.0);
    for z in [0.0f32, 2.0, -2.5] {
        let mut sc = scene.clone();
        if let shadowmap::scene::Light::Point(p) = &mut sc.lights[0] {
            p.position = Vec3::new(0.0, 0.0, z);
        }
        let hard = measure(&sc, &sc.shadow.clone());
        let soft = measure(
            &sc,
            &ShadowSettings {
                filter: Filter::Pcf3x3,
                bias: 0.15,
                ..sc.shadow
            },
        );
        eprintln!(
            "light at z = {z}: hard {:.3}% misclassified ({} outside the edge band), soft {:.3}%, MAE hard {:.4} soft {:.4}",
            hard.misclassified_rate * 100.0,
            hard.misclassified_outside_band,
            soft.misclassified_rate * 100.0,
            hard.mae.unwrap(),
            soft.mae.unwrap()
        );
        assert!(hard.receivers > 50_000, "the room must be in view");
        // Shadows exist and land where the rays say: errors only along edges.
        assert!(
            hard.misclassified_rate < 0.005,
            "z = {z}: {}",
            hard.misclassified_rate
        );
        assert!(
            (hard.misclassified_outside_band as f64) < 0.0005 * hard.outside_band_receivers as f64,
            "z = {z}: {} misclassified away from edges",
            hard.misclassified_outside_band
        );
        assert!(
            soft.misclassified_rate < 0.01,
            "z = {z}: soft {}",
            soft.misclassified_rate
        );
    }
    // Shadows are in view: the cubes darken parts of the walls and floor.
    let ctx = common::context();
    let frame = shadowmap::compare::render_visibility(ctx.gl(), &scene, &scene.shadow, 400, 300, 0)
        .unwrap();
    let dark = frame
        .visibility
        .unwrap()
        .iter()
        .flatten()
        .filter(|v| **v < 0.5)
        .count();
    assert!(dark > 1000, "only {dark} shadowed pixels in view");
    // Without a bias the cube map has acne, as the flat maps do.
    let acne = measure(
        &scene,
        &ShadowSettings {
            bias_mode: BiasMode::None,
            ..scene.shadow
        },
    );
    assert!(
        acne.false_shadow_rate > 0.05,
        "no bias should show acne: {}",
        acne.false_shadow_rate
    );
}

#[test]
fn spot_light_shadows_match_the_reference_inside_its_cone() {
    // The blog's bulb over its slab: a perspective shadow map from the light's position.
    let scene = Scene::load("playground").unwrap();
    let m = measure(&scene, &scene.shadow.clone());
    eprintln!(
        "playground spot: {:.3}% misclassified ({} outside the band)",
        m.misclassified_rate * 100.0,
        m.misclassified_outside_band
    );
    assert!(m.receivers > 20_000);
    assert!(
        m.false_shadow_outside_band * 1000 <= m.outside_band_receivers,
        "{m:?}"
    );
}

#[test]
fn layered_and_six_pass_cube_maps_agree() {
    use shadowmap::settings::PointPass;
    let ctx = common::context();
    let scene = Scene::load("point-shadows").unwrap();
    let render = |pass| {
        let s = ShadowSettings {
            point_pass: pass,
            ..scene.shadow
        };
        shadowmap::compare::render_visibility(ctx.gl(), &scene, &s, 200, 150, 0).unwrap()
    };
    let (a, b) = (render(PointPass::SixPasses), render(PointPass::Layered));
    assert_eq!(
        a.visibility, b.visibility,
        "the two ways of drawing the faces disagree"
    );
    assert_eq!(a.colour, b.colour);
}
