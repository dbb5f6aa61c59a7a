//! Exponential shadow maps against their closed form: behind one flat caster a receiver's
//! light is exp(-c d), d the depth gap between them, so a caster near its receiver leaks
//! light (ESM's bleeding at contact) and a larger exponent leaks less; at the exponent's
//! limit (exp(88) near 32-bit floats' largest) every value stays finite and lit stays lit,
//! even where exp(-c d) alone is below the least normal float (receivers at the map's far end);
//! past it the exponent is refused, from the flag and from the file.

use crate::common;

use crate::moments::options;
use glam::DVec3;
use shadowmap::compare::{compute_reference, render_visibility, Reference};
use shadowmap::settings::{BiasMode, Blur, Filter, ShadowSettings, ESM_MAX_EXPONENT};
use shadowmap::shadows::light_camera;
use shadowmap::Scene;

/// Two thin slabs over a floor, their tops 0.55 and 3.05 above it (the file says more),
/// under a directional light 45 degrees up and seen from the side the shadows fall to, so
/// that the floor under the low slab shows too; a point light, so the truth is the hard
/// shadow.
fn contact() -> Scene {
    contact_with(&[("position = [0.0, 9.0, 2.0]", "position = [0.0, 7.0, -7.0]")])
}

/// tests/data/contact.toml under a point light 45 degrees up, with `edits` too, each of
/// which must find its text.
fn contact_with(edits: &[(&str, &str)]) -> Scene {
    let mut text = include_str!("../data/contact.toml").to_string();
    let own = [
        ("size = 6.0", "size = 0.0"),
        ("angle = 80.0", "angle = 45.0"),
    ];
    for (from, to) in own.iter().chain(edits) {
        assert!(text.contains(from), "contact.toml has no {from}");
        text = text.replace(from, to);
    }
    let source = std::path::Path::new("tests/data/contact.toml (edited)");
    shadowmap::scene::file::parse(&text, source, None).unwrap_or_else(|e| panic!("{e}"))
}

/// ESM with exponent `c`, unblurred and unbiased, so the closed form holds texel for texel.
fn esm(scene: &Scene, c: f32) -> ShadowSettings {
    ShadowSettings {
        filter: Filter::Esm,
        esm_exponent: c,
        blur: Blur::None,
        bias_mode: BiasMode::None,
        ..scene.shadow
    }
}

/// A world point's depth in light 0's map, in [0, 1].
fn map_depth(scene: &Scene) -> impl Fn(DVec3) -> f64 {
    let view = light_camera(scene, 0, &scene.shadow);
    let clip = view.projection.as_dmat4() * view.view64;
    move |p: DVec3| {
        let c = clip * p.extend(1.0);
        c.z / c.w * 0.5 + 0.5
    }
}

/// The floor pixels well inside the shadow of the slab whose top is at `top` (x < 0: the
/// low slab, x > 0 the high one), each with the depth gap (in the map's [0, 1] depth)
/// between the floor and the slab top above it along the light.
fn umbra(scene: &Scene, reference: &Reference, top: f64) -> Vec<(usize, f64)> {
    let depth = map_depth(scene);
    let sun = scene.lights[0]
        .as_directional()
        .expect("a directional light");
    let to_light = sun.direction.as_dvec3().normalize();
    let centre_x = if top < 1.0 { -2.5 } else { 2.5 };
    (0..reference.hard.len())
        .filter(|&i| reference.hard[i].receiver && reference.hard[i].visibility == 0.0)
        .filter_map(|i| {
            let floor = reference.world_position(i);
            if floor.y.abs() > 1e-3 {
                return None;
            }
            let caster = floor + to_light * (top / to_light.y);
            let inside = (caster.x - centre_x).abs() < 0.7 && caster.z.abs() < 0.7;
            inside.then(|| (i, depth(floor) - depth(caster)))
        })
        .collect()
}

/// The worst |rendered - exp(-c gap)| over `pixels`, and the mean expected value.
fn worst_error(vis: &[Option<f32>], pixels: &[(usize, f64)], c: f32) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    let mut mean = 0.0;
    for &(i, gap) in pixels {
        let want = (-f64::from(c) * gap).exp();
        let got = f64::from(vis[i].expect("a floor pixel is a receiver"));
        worst = worst.max((got - want).abs());
        mean += want / pixels.len() as f64;
    }
    (worst, mean)
}

#[test]
fn behind_one_flat_caster_the_light_left_is_exp_of_minus_c_times_the_depth_gap() {
    let ctx = common::context();
    let scene = contact();
    let opts = options(&scene);
    let reference = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts).unwrap();
    let (low, high) = (
        umbra(&scene, &reference, 0.55),
        umbra(&scene, &reference, 3.05),
    );
    assert!(
        low.len() > 500 && high.len() > 500,
        "{} and {}",
        low.len(),
        high.len()
    );
    let mut leaks = Vec::new();
    for c in [10.0, 40.0, 80.0, ESM_MAX_EXPONENT] {
        let frame = render_visibility(ctx.gl(), &scene, &esm(&scene, c), 640, 360, 0).unwrap();
        let vis = frame.visibility.as_deref().unwrap();
        let (low_error, low_leak) = worst_error(vis, &low, c);
        let (high_error, high_leak) = worst_error(vis, &high, c);
        eprintln!(
            "c = {c}: the low slab leaks {low_leak:.4} (worst error {low_error:.4}), \
             the high one {high_leak:.6} (worst error {high_error:.4})"
        );
        assert!(low_error < 0.01, "c = {c}: low slab off by {low_error}");
        assert!(high_error < 0.01, "c = {c}: high slab off by {high_error}");
        // Every value is a visibility: finite, in [0, 1] (no overflow at the limit).
        let all = vis.iter().flatten();
        assert!(all
            .clone()
            .all(|v| v.is_finite() && (0.0..=1.0).contains(v)));
        // The floor away from both shadows is fully lit, at every exponent.
        let lit = (0..reference.hard.len())
            .filter(|&i| reference.hard[i].receiver && reference.hard[i].visibility == 1.0)
            .filter(|&i| reference.world_position(i).x.abs() > 4.0)
            .map(|i| vis[i].unwrap());
        assert!(lit.clone().count() > 1000);
        assert!(
            lit.clone().all(|v| v > 0.999),
            "c = {c}: lit floor darkened"
        );
        leaks.push(low_leak);
    }
    // The nearer the caster, the more it leaks; the larger c, the less.
    assert!(leaks.windows(2).all(|w| w[1] < w[0]), "{leaks:?}");
    assert!(leaks[0] > 0.5 && leaks[3] < 0.25, "{leaks:?}");
}

/// The contact scene with the light's box reaching 1,500 units behind the light, so that
/// every receiver lies in the last 1% of the map's depth: at c = 88, exp(-c d) there is
/// below the least normal 32-bit float, which a GPU may flush to zero.
fn far_receivers() -> Scene {
    contact_with(&[("near = -10.0, far = 20.0", "near = -1500.0, far = 16.0")])
}

#[test]
fn at_the_exponents_limit_a_receiver_at_the_far_end_of_the_map_stays_lit() {
    let ctx = common::context();
    let scene = far_receivers();
    let opts = options(&scene);
    let reference = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts).unwrap();
    let depth = map_depth(&scene);
    let c = ESM_MAX_EXPONENT;
    // Lit receivers away from both slabs' shadows (whose edges a map's texels blur).
    let lit: Vec<usize> = (0..reference.hard.len())
        .filter(|&i| reference.hard[i].receiver && reference.hard[i].visibility == 1.0)
        .filter(|&i| reference.world_position(i).x.abs() > 4.0)
        .collect();
    assert!(lit.len() > 10_000, "{} lit receivers", lit.len());
    // The case this holds: exp(-c d) alone is not a normal float at any of them.
    let nearest = (lit.iter())
        .map(|&i| depth(reference.world_position(i)))
        .fold(f64::INFINITY, f64::min);
    assert!(
        (-f64::from(c) * nearest).exp() < f64::from(f32::MIN_POSITIVE),
        "the nearest lit receiver's depth {nearest} leaves exp(-c d) a normal float"
    );
    let frame = render_visibility(ctx.gl(), &scene, &esm(&scene, c), 640, 360, 0).unwrap();
    let vis = frame.visibility.as_deref().unwrap();
    let dark = lit.iter().filter(|&&i| vis[i].unwrap() < 0.999).count();
    assert_eq!(dark, 0, "{dark} of {} lit receivers darkened", lit.len());
}

#[test]
fn the_exponent_past_the_float_limit_is_refused_from_the_flag_and_the_file() {
    let dir = std::env::temp_dir().join(format!("shadowmap-esm-bad-{}", std::process::id()));
    let expected = "shadow.esm_exponent = 89: expected above 0, at most 88 (exp(88 x 1) stays \
                    inside 32-bit floats)";
    let out = common::bin()
        .args(["render", "--filter", "esm", "--esm-exponent", "89", "--out"])
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(stderr.trim(), format!("error: --esm-exponent: {expected}"));
    assert!(
        !dir.exists(),
        "nothing is written before the arguments are checked"
    );
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("hot.toml");
    let text = include_str!("../data/contact.toml")
        .replace("filter = \"pcss\"", "filter = \"esm\"\nesm_exponent = 89.0");
    std::fs::write(&path, text).unwrap();
    let png = dir.join("x.png");
    let out = common::bin()
        .args(["render", "--scene", path.to_str().unwrap(), "--out"])
        .arg(&png)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert!(
        stderr.contains("hot.toml") && stderr.contains("esm_exponent"),
        "{stderr}"
    );
    assert!(!png.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
