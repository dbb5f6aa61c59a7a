//! The shadow lands where the geometry says it must (headless EGL, asserting pixel counts).

use crate::common;

use common::{context, dummy, plane_pixels, render};
use glam::Vec3;
use shadowmap::settings::{Filter, ShadowSettings};
use shadowmap::Scene;

/// Does the ray from `p` towards the light hit the DummyGame's cube ([-0.5, 0.5]^3)?
fn ray_hits_cube(p: Vec3, to_light: Vec3) -> bool {
    let (mut t0, mut t1) = (1e-4f32, f32::INFINITY);
    for a in 0..3 {
        let (o, d) = (p[a], to_light[a]);
        if d.abs() < 1e-9 {
            if o.abs() > 0.5 {
                return false;
            }
        } else {
            let (ta, tb) = ((-0.5 - o) / d, (0.5 - o) / d);
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
    }
    t0 <= t1
}

/// True if the answer changes within `r` of `p` on the plane: an edge pixel, not judged.
fn near_edge(p: Vec3, to_light: Vec3, r: f32) -> bool {
    let here = ray_hits_cube(p, to_light);
    (0..16).any(|k| {
        let a = k as f32 * std::f32::consts::TAU / 16.0;
        ray_hits_cube(p + Vec3::new(a.cos(), 0.0, a.sin()) * r, to_light) != here
    })
}

/// Counts (agreeing shadowed, agreeing lit, disagreeing) plane pixels away from edges.
fn classify(scene: &Scene, settings: &ShadowSettings, edge: f32) -> (usize, usize, usize) {
    let ctx = context();
    let mut scene = scene.clone();
    let frame = render(&ctx, &mut scene, settings, 640, 360);
    let to_light = scene.light().as_directional().unwrap().direction;
    let (mut shadowed, mut lit, mut wrong) = (0, 0, 0);
    for (p, v) in plane_pixels(&frame) {
        if near_edge(p, to_light, edge) {
            continue;
        }
        match (ray_hits_cube(p, to_light), v < 0.5) {
            (true, true) => shadowed += 1,
            (false, false) => lit += 1,
            _ => wrong += 1,
        }
    }
    eprintln!(
        "light {:.0} deg: {shadowed} shadowed, {lit} lit, {wrong} wrong",
        scene.light().as_directional().unwrap().angle_deg()
    );
    (shadowed, lit, wrong)
}

#[test]
fn overhead_light_shadows_exactly_the_cube_footprint() {
    // The book's configuration (bias 0.05, 3x3 PCF): with the light straight above, the
    // cube's top face is 1.5 units above the plane, more than the bias' 1.05, so the whole
    // footprint |x|, |z| < 0.5 must be dark. PCF blurs one texel (20 / 1024 units); the
    // edge band of 0.05 units covers it.
    let scene = dummy(90.0);
    let (shadowed, lit, wrong) = classify(&scene, &scene.shadow.clone(), 0.05);
    assert!(shadowed > 2000, "too few footprint pixels seen: {shadowed}");
    assert!(lit > 20000, "too few lit plane pixels: {lit}");
    assert_eq!(
        wrong, 0,
        "misclassified plane pixels away from the footprint's edge"
    );
}

#[test]
fn without_the_cube_nothing_on_the_plane_is_shadowed() {
    let mut scene = dummy(90.0);
    scene.items.retain(|i| i.name != "cube");
    let ctx = context();
    let frame = render(&ctx, &mut scene.clone(), &scene.shadow, 640, 360);
    let plane = plane_pixels(&frame);
    assert!(
        plane.len() > 50000,
        "plane not in view: {} pixels",
        plane.len()
    );
    let dark = plane.iter().filter(|(_, v)| *v < 1.0).count();
    assert_eq!(dark, 0, "{dark} plane pixels shadowed with no caster");
}

#[test]
fn moving_the_light_moves_the_shadow_where_rays_say() {
    // A small bias (0.002 of the 21-unit depth range = 0.04 units) and one tap, so the
    // rendered shadow should match the ray test everywhere but at edges.
    let settings = ShadowSettings {
        bias: 0.002,
        filter: Filter::Single,
        ..dummy(90.0).shadow
    };
    let mut centres = Vec::new();
    for angle in [60.0, 75.0, 105.0, 120.0] {
        let scene = dummy(angle);
        let (shadowed, lit, wrong) = classify(&scene, &settings, 0.04);
        assert!(
            shadowed > 500,
            "angle {angle}: only {shadowed} shadow pixels seen"
        );
        assert!(lit > 20000, "angle {angle}: only {lit} lit pixels");
        let total = shadowed + wrong;
        assert!(
            wrong * 1000 <= total,
            "angle {angle}: {wrong} of {total} judged pixels disagree with the ray test"
        );
        // Where the rendered shadow's centre of mass lies along z, to check its direction.
        let ctx = context();
        let mut s = scene.clone();
        let frame = render(&ctx, &mut s, &settings, 640, 360);
        let dark: Vec<_> = plane_pixels(&frame)
            .into_iter()
            .filter(|(_, v)| *v < 0.5)
            .collect();
        let mean_z = dark.iter().map(|(p, _)| p.z).sum::<f32>() / dark.len() as f32;
        centres.push((angle, mean_z));
    }
    // A light from +Z (angles below 90) throws the shadow towards -Z, and the other way round.
    assert!(centres[0].1 < centres[1].1, "{centres:?}");
    assert!(centres[1].1 < 0.0 && centres[2].1 > 0.0, "{centres:?}");
    assert!(centres[2].1 < centres[3].1, "{centres:?}");
}

#[test]
fn with_shadows_off_no_map_is_made_and_everything_facing_the_light_is_lit() {
    use shadowmap::engine::{Outputs, RenderTarget};
    use shadowmap::renderer::{Renderer, Target};
    let ctx = common::context();
    let scene = common::dummy(45.0);
    let off = shadowmap::ShadowSettings {
        shadows: false,
        ..scene.shadow
    };
    let mut renderer = Renderer::new(ctx.gl(), &scene, &off).unwrap();
    let target = RenderTarget::new(
        ctx.gl(),
        160,
        90,
        Outputs {
            visibility: true,
            gbuffer: false,
        },
    )
    .unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    assert_eq!(renderer.shadow_memory(), (0, 0));
    let vis = target.read_visibility().unwrap();
    let on_geometry: Vec<f32> = vis.iter().flatten().copied().collect();
    assert!(
        on_geometry.len() > 1000,
        "{} pixels of geometry",
        on_geometry.len()
    );
    assert!(on_geometry.iter().all(|v| *v == 1.0));
    // With shadows on, the same frame has shadowed pixels.
    renderer.set_settings(&scene.shadow).unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    let shadowed = target
        .read_visibility()
        .unwrap()
        .iter()
        .flatten()
        .filter(|v| **v < 0.5)
        .count();
    assert!(shadowed > 100, "{shadowed} shadowed pixels");
}
