//! Each chapter step does what its chapter says, measured against the exact reference on
//! the DummyGame and LearnOpenGL scenes.

#[path = "../common/mod.rs"]
mod common;

use glam::Vec3;
use shadowmap::compare::{compare, CompareOptions, Comparison};
use shadowmap::engine::Outputs;
use shadowmap::frame::render_frames;
use shadowmap::reference::Metrics;
use shadowmap::scene::StepList;
use shadowmap::settings::{BeyondFar, BiasMode, Cull, Filter, MapSize, ShadowSettings, Wrap};
use shadowmap::{steps, Scene};

fn scene(name: &str) -> Scene {
    let mut s = Scene::load(name).unwrap();
    s.items.iter_mut().for_each(|i| i.spin = Vec3::ZERO);
    if name == "learnopengl" {
        // LearnOpenGL's start camera sees only the top of one cube; the tutorial's readers
        // fly around. This view looks down on all three cubes, their contacts and shadows,
        // and on floor beyond the light's far plane.
        s.camera.position = Vec3::new(1.5, 7.0, 1.5);
        s.camera.rotation = Vec3::new(90.0, 0.0, 0.0);
    }
    s
}

fn measure(
    ctx: &shadowmap::engine::HeadlessContext,
    scene: &Scene,
    s: &ShadowSettings,
    size: (u32, u32),
    ss: u32,
) -> Comparison {
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width: size.0,
        height: size.1,
        supersample: ss,
        band: 1,
        light: 0,
    };
    compare(ctx.gl(), scene, s, &opts).unwrap_or_else(|e| panic!("{}: {e}", scene.name))
}

/// Scores only pixels whose surface lies inside the light's box (or not, with `inside` =
/// false), to separate acne and peter panning from over-sampling.
fn score_in_box(c: &Comparison, scene: &Scene, s: &ShadowSettings, inside: bool) -> Metrics {
    score_where(c, scene, s, |q| (q.abs().max_element() <= 1.0) == inside)
}

/// Scores only pixels whose surface, in the light's normalised device coordinates `q`,
/// passes `keep`.
fn score_where(
    c: &Comparison,
    scene: &Scene,
    s: &ShadowSettings,
    keep: impl Fn(Vec3) -> bool,
) -> Metrics {
    let sv = shadowmap::shadows::light_camera(scene, 0, s);
    let m = sv.projection * sv.view;
    let vis = c.frame.visibility.as_ref().unwrap();
    let masked: Vec<Option<f32>> = (0..vis.len())
        .map(|i| {
            let p = c.reference.world_position(i).as_vec3();
            keep(m.project_point3(p)).then_some(vis[i]).flatten()
        })
        .collect();
    c.reference.score(&masked, 1)
}

fn step(scene: &Scene, name: &str) -> ShadowSettings {
    steps::settings_for(scene, name).unwrap()
}

fn show(tag: &str, m: &Metrics) {
    eprintln!(
        "{tag}: false shadow {:.4}% ({} outside band), false light {:.4}% ({} outside band), MAE {:?}",
        m.false_shadow_rate * 100.0,
        m.false_shadow_outside_band,
        m.false_light_rate * 100.0,
        m.false_light_outside_band,
        m.mae
    );
}

/// Acne is judged inside the light's box; what happens outside it is the over-sampling test's.
#[test]
fn no_bias_has_acne_and_bias_removes_it() {
    let ctx = common::context();
    for name in ["dummy", "learnopengl"] {
        let sc = scene(name);
        let s = step(&sc, "no-bias");
        let none = score_in_box(&measure(&ctx, &sc, &s, (640, 360), 1), &sc, &s, true);
        show(&format!("{name} no-bias"), &none);
        let rate = none.false_shadow_outside_band as f64 / none.outside_band_receivers as f64;
        assert!(rate > 0.2, "{name}: no-bias should show acne, got {rate}");
        // A constant bias leaves a trace of acne on grazing faces; the slope bias scales
        // with the angle and removes it.
        for (s, limit) in [("bias", 0.002), ("slope-bias", 0.0005)] {
            let settings = step(&sc, s);
            let m = score_in_box(
                &measure(&ctx, &sc, &settings, (640, 360), 1),
                &sc,
                &settings,
                true,
            );
            show(&format!("{name} {s}"), &m);
            let rate = m.false_shadow_outside_band as f64 / m.outside_band_receivers as f64;
            assert!(
                rate < limit,
                "{name} {s}: false shadow outside the edge band {rate}"
            );
        }
    }
}

#[test]
fn a_large_bias_detaches_shadows_and_culling_front_faces_shrinks_the_gap() {
    let ctx = common::context();
    for name in ["dummy", "learnopengl"] {
        let sc = scene(name);
        // A bias large against the caster's thickness along the light: the book's own 0.05
        // (1.05 units of its 21-unit depth range, over the 0.5-unit gap under its cube), and
        // 0.2 for LearnOpenGL's resting unit cubes (1.3 of its 6.5 units). Peter panning
        // needs the bias to exceed the depth through the caster.
        let bias = if name == "dummy" { 0.05 } else { 0.2 };
        let large = ShadowSettings {
            bias_mode: BiasMode::Constant,
            bias,
            ..step(&sc, "bias")
        };
        let gap = score_in_box(
            &measure(&ctx, &sc, &large, (640, 360), 1),
            &sc,
            &large,
            true,
        );
        let culled = step(&sc, "cull-front");
        assert_eq!(culled.cull, Cull::Front);
        let fixed = score_in_box(
            &measure(&ctx, &sc, &culled, (640, 360), 1),
            &sc,
            &culled,
            true,
        );
        show(&format!("{name} bias {bias}"), &gap);
        show(&format!("{name} cull-front"), &fixed);
        assert!(
            gap.false_light_rate > 0.001,
            "{name}: no measurable gap: {}",
            gap.false_light_rate
        );
        assert!(
            fixed.false_light_rate * 3.0 < gap.false_light_rate,
            "{name}: cull-front should shrink the false light from {} (got {})",
            gap.false_light_rate,
            fixed.false_light_rate
        );
    }
}

#[test]
fn over_sampling_outside_the_light_box() {
    let ctx = common::context();
    let mut sc = scene("learnopengl");
    // A box narrower than the view (LearnOpenGL's floor runs past its light's box): +-3 still
    // holds the three cubes, and REPEAT then tiles their shadows 6 units apart, into view.
    let light = sc.light_mut().as_directional_mut().unwrap();
    (
        light.ortho.left,
        light.ortho.right,
        light.ortho.bottom,
        light.ortho.top,
    ) = (-3.0, 3.0, -3.0, 3.0);
    let beyond_far = |q: Vec3| q.z > 1.0;
    let outside_xy = |q: Vec3| q.x.abs() > 1.0 || q.y.abs() > 1.0;
    // REPEAT: the map tiles across the floor outside the box: false shadows there.
    let repeat = step(&sc, "over-sampling-repeat");
    assert_eq!(repeat.wrap, Wrap::Repeat);
    let c = measure(&ctx, &sc, &repeat, (640, 360), 1);
    let out = score_where(&c, &sc, &repeat, |q| outside_xy(q) && q.z <= 1.0);
    show("repeat, outside the box sideways", &out);
    assert!(
        out.receivers > 1000,
        "the view must see floor outside the box"
    );
    assert!(
        out.false_shadow > 100,
        "REPEAT should tile shadows outside the box"
    );
    // The book: CLAMP_TO_EDGE and no far test: everything beyond the far plane is dark.
    let book = step(&sc, "over-sampling-book");
    assert_eq!(book.beyond_far, BeyondFar::Shadowed);
    let c = measure(&ctx, &sc, &book, (640, 360), 1);
    let far = score_where(&c, &sc, &book, beyond_far);
    show("book, beyond the far plane", &far);
    assert!(
        far.receivers > 1000,
        "the view must see floor beyond the far plane"
    );
    assert!(
        far.false_shadow > 1000,
        "beyond the far plane lit floor turns dark"
    );
    // Not one receiver clearly beyond the far plane (past what the bias can reach back)
    // is rendered lit.
    let sv = shadowmap::shadows::light_camera(&sc, 0, &book);
    let m = sv.projection * sv.view;
    let vis = c.frame.visibility.as_ref().unwrap();
    let lit_beyond = (0..vis.len())
        .filter(|&i| c.reference.hard[i].receiver)
        .filter(|&i| m.project_point3(c.reference.world_position(i).as_vec3()).z > 1.2)
        .filter(|&i| vis[i].is_some_and(|v| v >= 0.5))
        .count();
    assert_eq!(
        lit_beyond, 0,
        "the book shadows everything beyond the far plane"
    );
    // LearnOpenGL's fix: a border of depth 1 and z > 1 lit: no false shadow outside the box.
    let fixed = step(&sc, "over-sampling");
    let c = measure(&ctx, &sc, &fixed, (640, 360), 1);
    let outside = score_in_box(&c, &sc, &fixed, false);
    show("fixed, outside the box", &outside);
    assert!(outside.receivers > 2000);
    assert_eq!(
        outside.false_shadow, 0,
        "the fix leaves no false shadow outside the box"
    );
}

#[test]
fn pcf_gives_intermediate_values_and_lowers_mae_when_texels_are_small() {
    let ctx = common::context();
    for name in ["dummy", "learnopengl"] {
        let sc = scene(name);
        let hard = step(&sc, "over-sampling");
        let soft = step(&sc, "pcf");
        assert_eq!((hard.filter, soft.filter), (Filter::Single, Filter::Pcf3x3));
        let count_between = |c: &Comparison| {
            c.frame
                .visibility
                .as_ref()
                .unwrap()
                .iter()
                .flatten()
                .filter(|v| **v > 0.0 && **v < 1.0)
                .count()
        };
        let h = measure(&ctx, &sc, &hard, (640, 360), 1);
        let p = measure(&ctx, &sc, &soft, (640, 360), 1);
        assert_eq!(
            count_between(&h),
            0,
            "{name}: one comparison gives only 0 or 1"
        );
        assert!(
            count_between(&p) > 500,
            "{name}: PCF should give intermediate values"
        );
        // PCF averages over 3 texels. It approximates a pixel's partial coverage of a hard
        // edge when a texel is no larger than a pixel: a 4096 map seen at 320 x 180.
        let (hard4k, soft4k) = (
            ShadowSettings {
                map_size: MapSize::square(4096),
                ..hard
            },
            ShadowSettings {
                map_size: MapSize::square(4096),
                ..soft
            },
        );
        let mh = measure(&ctx, &sc, &hard4k, (320, 180), 4).metrics;
        let mp = measure(&ctx, &sc, &soft4k, (320, 180), 4).metrics;
        show(&format!("{name} single, 4096 at 320x180"), &mh);
        show(&format!("{name} pcf, 4096 at 320x180"), &mp);
        assert!(
            mp.mae.unwrap() < mh.mae.unwrap(),
            "{name}: PCF should lower the MAE"
        );
    }
}

#[test]
fn hi_res_narrows_the_misclassified_band() {
    let ctx = common::context();
    for name in ["dummy", "learnopengl"] {
        let sc = scene(name);
        let (lo, hi) = (step(&sc, "pcf"), step(&sc, "hi-res"));
        assert_eq!(
            (lo.map_size, hi.map_size),
            (MapSize::square(1024), MapSize::square(4096))
        );
        let ml = measure(&ctx, &sc, &lo, (640, 360), 1).metrics;
        let mh = measure(&ctx, &sc, &hi, (640, 360), 1).metrics;
        show(&format!("{name} 1024"), &ml);
        show(&format!("{name} 4096"), &mh);
        assert!(
            mh.misclassified * 2 < ml.misclassified,
            "{name}: {} misclassified at 4096 against {} at 1024",
            mh.misclassified,
            ml.misclassified
        );
    }
}

#[test]
fn every_scene_and_step_renders_without_gl_errors() {
    let ctx = common::context();
    for name in Scene::builtin_names() {
        let mut sc = Scene::load(name).unwrap();
        for st in steps::of(&sc) {
            let settings = steps::settings_for(&sc, st.name).unwrap();
            let outputs = Outputs {
                visibility: true,
                gbuffer: true,
            };
            let frame = render_frames(ctx.gl(), &mut sc, &settings, 160, 90, 2, outputs)
                .unwrap_or_else(|e| panic!("{name} / {}: {e}", st.name));
            // Not a black image: something was drawn.
            let lit = frame
                .colour
                .rgba
                .chunks_exact(4)
                .filter(|p| p[0] > 10 || p[1] > 10 || p[2] > 10)
                .count();
            assert!(
                lit > 1000,
                "{name} / {}: only {lit} non-black pixels",
                st.name
            );
        }
    }
}

mod bias;
mod lessons;
mod page;
mod playground;

/// The volumetric list starts from the smoke scene as it is (its bias and filter), so each
/// step shows what translucent casters do, not acne: against the transmittance truth,
/// `off` and `solid` err within the translucent shadow by about half the light, the
/// translucent maps by under 0.02, and outside it every step stays near exact.
#[test]
fn the_volumetric_steps_show_translucent_shadows_not_acne() {
    let ctx = common::context();
    let sc = scene("smoke");
    for st in steps::of(&sc) {
        let s = step(&sc, st.name);
        let t = measure(&ctx, &sc, &s, (320, 180), 1).transmittance.unwrap();
        eprintln!(
            "{}: MAE {:.4}, within {:.4}, outside {:.4}",
            st.name, t.mae, t.mae_in_shadow, t.mae_outside
        );
        assert!(
            t.mae_outside < 0.005,
            "{}: outside {}",
            st.name,
            t.mae_outside
        );
        let wrong = matches!(st.name, "volumetric-off" | "volumetric-solid");
        match wrong {
            true => assert!(t.mae_in_shadow > 0.3, "{}: {}", st.name, t.mae_in_shadow),
            false => assert!(t.mae_in_shadow < 0.02, "{}: {}", st.name, t.mae_in_shadow),
        }
    }
}
