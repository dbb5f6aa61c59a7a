//! Stencil shadow volumes against the exact CPU reference (issue 14's "must hold"): closed
//! casters at 640 x 360 leave nothing wrong outside a 1-pixel band around the true shadow
//! edges and at most 0.05% of receivers wrong inside it; the same with the camera inside a
//! volume, at a grazing light and far from the origin; open meshes cast as documented in
//! `shadowmap::shadows::volumes`.

mod common;

use common::context;
use glam::Vec3;
use shadowmap::compare::{compare, CompareOptions};
use shadowmap::engine::HeadlessContext;
use shadowmap::settings::ShadowTechnique;
use shadowmap::{Scene, ShadowSettings};

fn volumes(scene: &Scene) -> ShadowSettings {
    ShadowSettings {
        technique: ShadowTechnique::Volumes,
        ..scene.shadow
    }
}

/// Scores light `light`'s volumes in `scene` at 640 x 360 against the reference and checks
/// the bounds; returns (receivers, misclassified) for further checks.
fn holds(ctx: &HeadlessContext, scene: &Scene, light: usize, what: &str) -> (usize, usize) {
    let opts = CompareOptions {
        width: 640,
        height: 360,
        supersample: 1,
        band: 1,
        light,
    };
    let c =
        compare(ctx.gl(), scene, &volumes(scene), &opts).unwrap_or_else(|e| panic!("{what}: {e}"));
    let m = &c.metrics;
    let vis = c.frame.visibility.as_ref().unwrap();
    let wrong: Vec<String> = (0..vis.len())
        .filter(|&i| {
            let r = c.reference.hard[i];
            r.receiver && vis[i].is_some_and(|v| (v - r.visibility).abs() > 0.5)
        })
        .take(8)
        .map(|i| {
            format!(
                "({}, {}) at {:.4} rendered {:?} reference {}",
                i % 640,
                i / 640,
                c.reference.world_position(i),
                vis[i],
                c.reference.hard[i].visibility
            )
        })
        .collect();
    assert!(
        m.receivers > 10_000,
        "{what}: only {} receivers",
        m.receivers
    );
    assert_eq!(
        m.misclassified_outside_band, 0,
        "{what}: {m:?}; first wrong pixels: {wrong:?}"
    );
    let in_band = m.misclassified - m.misclassified_outside_band;
    assert!(
        in_band as f64 <= 0.0005 * m.receivers as f64,
        "{what}: {in_band} of {} receivers wrong in the band; {wrong:?}",
        m.receivers
    );
    (m.receivers, m.misclassified)
}

/// The scene's shadowed receivers under light `light` as the reference sees them (so a
/// test cannot pass on a frame with no shadow at all).
fn shadowed_receivers(ctx: &HeadlessContext, scene: &Scene, light: usize) -> usize {
    let opts = CompareOptions {
        width: 640,
        height: 360,
        supersample: 1,
        band: 1,
        light,
    };
    let c = compare(ctx.gl(), scene, &volumes(scene), &opts).unwrap();
    c.reference
        .hard
        .iter()
        .filter(|r| r.receiver && r.visibility < 0.5)
        .count()
}

#[test]
fn closed_casters_match_the_reference() {
    let ctx = context();
    for name in ["dummy", "learnopengl", "point-shadows"] {
        let scene = common::frozen(name);
        holds(&ctx, &scene, 0, name);
        assert!(shadowed_receivers(&ctx, &scene, 0) > 500, "{name}");
    }
    let scene = common::frozen("three-lights");
    for (light, what) in [(0, "three-lights' sun"), (1, "three-lights' spot")] {
        holds(&ctx, &scene, light, what);
        assert!(shadowed_receivers(&ctx, &scene, light) > 500, "{what}");
    }
}
