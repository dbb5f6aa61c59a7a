//! Cascaded shadow maps: the practical splits at the extremes, boxes that hold their
//! slices, no shimmer under sub-texel camera moves, and the reference's verdict against one
//! map of the same memory on the `large` scene.

use crate::common;

use glam::{DVec3, Vec3};
use shadowmap::compare::compare;
use shadowmap::settings::MAX_CASCADES;
use shadowmap::settings::{Filter, MapSize, ShadowSettings};
use shadowmap::shadows::cascades::{fit_cascades, practical_splits, CascadeSpec};
use shadowmap::Scene;

fn large() -> Scene {
    Scene::load("large").unwrap()
}

/// The `large` scene's settings with `cascades` layers of `map_size`.
fn cascaded(scene: &Scene, cascades: u32, map_size: u32) -> ShadowSettings {
    ShadowSettings {
        cascades,
        map_size: MapSize::square(map_size),
        ..scene.shadow
    }
}

#[test]
fn splits_are_finite_and_increasing_at_the_extremes() {
    for lambda in [0.0, 0.5, 1.0] {
        for near in [1e-3, 0.1, 1.0] {
            for far in [10.0, 1e3, 1e6] {
                for count in 1..=MAX_CASCADES {
                    let s = practical_splits(near, far, count, lambda);
                    assert_eq!(s.len(), count as usize + 1);
                    assert_eq!(s[0], near, "{s:?}");
                    assert_eq!(s[count as usize], far, "{s:?}");
                    assert!(s.iter().all(|d| d.is_finite()), "{s:?}");
                    assert!(
                        s.windows(2).all(|w| w[0] < w[1]),
                        "lambda {lambda}, near {near}, far {far}: {s:?}"
                    );
                }
            }
        }
    }
    // Lambda 1 is the logarithmic split: every slice has the same far/near ratio, the one
    // that keeps texels per pixel constant. Lambda 0 is uniform.
    let log = practical_splits(1e-3, 1e3, 4, 1.0);
    for w in log.windows(2) {
        assert!((w[1] / w[0] - 1e6f64.powf(0.25)).abs() < 1e-9, "{log:?}");
    }
    let uniform = practical_splits(1e-3, 1e3, 4, 0.0);
    for w in uniform.windows(2) {
        assert!(
            (w[1] - w[0] - (1e3 - 1e-3) / 4.0).abs() < 1e-9,
            "{uniform:?}"
        );
    }
}

#[test]
fn every_cascade_holds_its_slice_of_the_view() {
    let mut scene = large();
    let to_light = scene.light().as_directional().unwrap().direction;
    for (pitch, yaw) in [(8.0, 0.0), (-30.0, 90.0), (45.0, 200.0), (89.0, 10.0)] {
        scene.camera.rotation = Vec3::new(pitch, yaw, 0.0);
        let spec = CascadeSpec {
            count: 4,
            lambda: 0.75,
            blend: 0.1,
            far: f32::INFINITY,
            map_size: 1024,
            snap: true,
            light_depth: 21.0,
        };
        let boxes = shadowmap::shadows::camera::fitted::item_world_boxes(&scene);
        let cascades = fit_cascades(&scene, &boxes, to_light, &spec);
        let cam = scene.camera;
        let aspect = scene.size[0] as f64 / scene.size[1] as f64;
        let tan = ((cam.fov as f64).to_radians() * 0.5).tan();
        let inverse_view = cam.view_matrix64().inverse();
        for (i, c) in cascades.iter().enumerate() {
            let [l, r, b, t, n, f] = c.fitted.bounds;
            // The box holds its slice and the part of the previous one that fades into it.
            let from = match i {
                0 => c.near,
                _ => c.near - 0.1 * (c.near - cascades[i - 1].near),
            };
            for depth in [from, c.near, c.far] {
                for (sx, sy) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)] {
                    let corner = DVec3::new(sx * depth * tan * aspect, sy * depth * tan, -depth);
                    let world = inverse_view.transform_point3(corner);
                    let p = c.fitted.view.transform_point3(world);
                    let eps = 1e-9 * (1.0 + depth);
                    assert!(
                        p.x >= l - eps && p.x <= r + eps && p.y >= b - eps && p.y <= t + eps,
                        "pitch {pitch} yaw {yaw}: cascade {i} misses a corner at {p}"
                    );
                    assert!(
                        -p.z >= n - eps && -p.z <= f + eps,
                        "cascade {i}: corner depth {} outside [{n}, {f}]",
                        -p.z
                    );
                }
            }
            // Boxes grow with distance: each texel covers more of the world than the last.
            if i > 0 {
                assert!(c.fitted.texel > cascades[i - 1].fitted.texel);
            }
        }
    }
}

#[test]
fn snapped_cascades_do_not_shimmer_under_sub_texel_camera_moves() {
    let ctx = common::context();
    let scene = large();
    let (w, h) = (320, 180);
    let changed = |snap: bool| {
        let s = ShadowSettings {
            snap,
            filter: Filter::Single,
            ..cascaded(&scene, 4, 1024)
        };
        // Fractions of a millimetre: below a texel of even the nearest cascade.
        common::shimmer(&ctx, &scene, &s, (w, h), 0.0003, 5)
    };
    let (with, without) = (changed(true), changed(false));
    eprintln!("pixels changing under sub-texel moves: snapped {with}, unsnapped {without}");
    assert_eq!(with, 0.0, "snapped cascades must not shimmer");
    assert!(
        without > 0.0,
        "without snapping the boxes slide with the camera"
    );
}

#[test]
fn cascades_beat_one_map_of_the_same_memory_on_the_large_scene() {
    let ctx = common::context();
    let scene = large();
    let opts = common::frame_options(640, 360);
    let measure = |s: &ShadowSettings| compare(ctx.gl(), &scene, s, &opts).unwrap().metrics;
    // 2048^2 = 4 x 1024^2: the same 16 MiB of depth.
    let one = measure(&cascaded(&scene, 1, 2048));
    let four = measure(&cascaded(&scene, 4, 1024));
    eprintln!(
        "large, 640x360: one fitted 2048^2 map {:.3}% misclassified ({:.3}% outside the band), \
         4 x 1024^2 cascades {:.3}% ({:.3}%)",
        one.misclassified_rate * 100.0,
        one.misclassified_outside_band_rate * 100.0,
        four.misclassified_rate * 100.0,
        four.misclassified_outside_band_rate * 100.0
    );
    assert!(one.receivers > 100_000, "the terrain must fill the view");
    assert!(
        (four.misclassified as f64) < 0.8 * one.misclassified as f64,
        "cascades {} vs one map {}",
        four.misclassified,
        one.misclassified
    );
    assert!(
        four.misclassified_rate < 0.01,
        "{}",
        four.misclassified_rate
    );
}

#[test]
fn the_debug_view_tints_cascades_from_the_camera_out() {
    let ctx = common::context();
    let mut scene = large();
    let s = cascaded(&scene, 4, 512);
    let tinted = ShadowSettings {
        show_cascades: true,
        ..s
    };
    let plain = common::render(&ctx, &mut scene.clone(), &s, 320, 180);
    let debug = common::render(&ctx, &mut scene, &tinted, 320, 180);
    // The bottom rows are the ground at the camera's feet: cascade 0, tinted red.
    let redness = |rgba: &[u8]| {
        let rows = &rgba[320 * 4 * 160..];
        rows.chunks_exact(4)
            .map(|p| f64::from(p[0]) - f64::from(p[1]))
            .sum::<f64>()
            / (rows.len() / 4) as f64
    };
    let (before, after) = (redness(&plain.colour.rgba), redness(&debug.colour.rgba));
    eprintln!("red minus green at the bottom: {before:.1} plain, {after:.1} tinted");
    assert!(after > before + 20.0, "{before} -> {after}");
    // The shadow test itself is untouched by the tint.
    assert_eq!(plain.visibility, debug.visibility);
}

/// The DummyGame's camera reaches 1000 units over a scene 5 across: cascades cut from the
/// far plane made each texel and the book's depth-unit bias huge and lost the shadow (6.9%
/// of the receivers falsely lit with 2 cascades). Cut from the scene's bounds, with the
/// bias meaning what it does for one map, cascades do about as well as one map.
#[test]
fn cascades_on_the_dummy_game_keep_the_shadow() {
    let ctx = common::context();
    let scene = Scene::load("dummy").unwrap();
    let opts = common::frame_options(640, 360);
    let measure = |cascades: u32| {
        let s = ShadowSettings {
            cascades,
            ..scene.shadow
        };
        compare(ctx.gl(), &scene, &s, &opts).unwrap().metrics
    };
    let one = measure(1);
    for cascades in 2..=MAX_CASCADES {
        let many = measure(cascades);
        eprintln!(
            "dummy, 640x360: one map {:.3}% misclassified, {cascades} cascades {:.3}% \
             (false light {:.3}%)",
            one.misclassified_rate * 100.0,
            many.misclassified_rate * 100.0,
            many.false_light_rate * 100.0
        );
        assert!(one.receivers > 50_000, "the plane must fill the view");
        assert!(
            many.misclassified <= 2 * one.misclassified,
            "{cascades} cascades misclassify {} pixels, one map {}",
            many.misclassified,
            one.misclassified
        );
    }
}

#[test]
fn cascades_cover_the_scene_not_the_far_plane() {
    use shadowmap::shadows::cascades::scene_depth_range;
    let scene = Scene::load("dummy").unwrap();
    let boxes = shadowmap::shadows::camera::fitted::item_world_boxes(&scene);
    let aspect = 16.0 / 9.0;
    // The camera at z = 2 looking down -z over a plane reaching to z = -2.5: 4.5 deep
    // (rounded up to the next 1/8 of 4), whatever the far plane says.
    let (near, far) = scene_depth_range(&scene.camera, aspect, &boxes, f64::INFINITY);
    assert_eq!(near, scene.camera.near as f64);
    assert_eq!(far, 5.0);
    // A small move keeps the range (and so the boxes' sizes).
    let mut moved = scene.camera;
    moved.position += Vec3::new(0.01, 0.0, 0.005);
    moved.rotation.y += 0.1;
    assert_eq!(
        scene_depth_range(&moved, aspect, &boxes, f64::INFINITY),
        (near, far)
    );
    // A shadow distance nearer than the scene wins.
    let (_, far) = scene_depth_range(&scene.camera, aspect, &boxes, 3.0);
    assert_eq!(far, 3.0);
    // Looking away from everything: a short range, all lit, still increasing.
    let mut away = scene.camera;
    away.rotation = Vec3::new(0.0, 180.0, 0.0);
    away.position = Vec3::new(0.0, 0.0, 10.0);
    let (near, far) = scene_depth_range(&away, aspect, &boxes, f64::INFINITY);
    assert!(near < far && far <= 2.0 * near, "{near} {far}");
}
