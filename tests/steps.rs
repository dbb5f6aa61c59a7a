//! Each chapter step does what its chapter says, measured against the exact reference on
//! the DummyGame and LearnOpenGL scenes.

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

#[test]
fn the_playground_has_its_demo_pages_as_steps() {
    use shadowmap::settings::{Filter, MapSize};
    let scene = Scene::load("playground").unwrap();
    let names: Vec<&str> = steps::of(&scene).iter().map(|s| s.name).collect();
    assert_eq!(
        names,
        ["basic", "pcf", "soft-pcf", "variance", "moment", "pcss", "vssm", "msm-soft"]
    );
    let at = |name| steps::settings_for(&scene, name).unwrap();
    let basic = at("basic");
    assert_eq!((basic.filter, basic.bias), (Filter::Single, 0.005));
    assert_eq!(
        basic.map_size,
        MapSize {
            width: 400,
            height: 300
        }
    );
    // The PCF pages: the weighted taps, epsilon 1.125e-2, a map twice the canvas; each
    // later page keeps them.
    for (name, filter) in [
        ("pcf", Filter::Pcf4x4Weighted),
        ("soft-pcf", Filter::SoftPcf),
        ("pcss", Filter::Pcss),
    ] {
        let s = at(name);
        assert_eq!((s.filter, s.bias), (filter, 1.125e-2), "{name}");
        assert_eq!(
            s.map_size,
            MapSize {
                width: 800,
                height: 600
            },
            "{name}"
        );
    }
    // The bulb is a sphere of radius 1 in the scene itself, so every command sees it.
    assert_eq!(scene.lights[0].size(), 1.0);
    // Each scene takes its own list's steps, and says which it has.
    let e = steps::settings_for(&scene, "cull-front")
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "unknown step 'cull-front' for the playground scene (its [steps] list is \"playground\"): \
         expected one of basic, pcf, soft-pcf, variance, moment, pcss, vssm, msm-soft"
    );
    let dummy = Scene::load("dummy").unwrap();
    let e = steps::settings_for(&dummy, "soft-pcf")
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(
            "unknown step 'soft-pcf' for the dummy scene (its [steps] list is \"chapters\")"
        ),
        "{e}"
    );
}

/// The text of each `<td>` of an HTML table row, tags inside it removed.
fn cells(row: &str) -> Vec<String> {
    row.split("<td")
        .skip(1)
        .map(|c| {
            let inner = c.split_once('>').map_or("", |(_, rest)| rest);
            let inner = inner.split("</td>").next().unwrap_or("");
            // Drop nested tags (links, <small> notes).
            let mut text = String::new();
            let mut in_tag = false;
            for ch in inner.chars() {
                match ch {
                    '<' => in_tag = true,
                    '>' => in_tag = false,
                    c if !in_tag => text.push(c),
                    _ => {}
                }
            }
            text.trim().to_string()
        })
        .collect()
}

/// A cell's percentage.
fn pct(cell: &str) -> f64 {
    cell.trim_end_matches('%')
        .parse()
        .unwrap_or_else(|_| panic!("not a percentage: {cell}"))
}

/// The page `steps` writes: every step's frame beside its errors, each figure a share of the
/// same receivers (so the parts add up), and each step told against what it builds on.
#[test]
fn the_steps_page_shows_each_step_with_consistent_figures() {
    let dir = std::env::temp_dir().join(format!("shadowmap-gallery-{}", std::process::id()));
    let args = [
        "steps",
        "--scene",
        "dummy",
        "--size",
        "320x180",
        "--supersample",
        "1",
    ];
    common::stdout_of(common::bin().args(args).arg("--out-dir").arg(&dir));
    let html = std::fs::read_to_string(dir.join("index.html")).unwrap();
    let scene = Scene::load("dummy").unwrap();
    let sections: Vec<&str> = html.split("<section").skip(1).collect();
    assert_eq!(sections.len(), steps::of(&scene).len());
    for (i, (st, section)) in steps::of(&scene).iter().zip(&sections).enumerate() {
        let frame = format!("{:02}-{}.png", i + 1, st.name);
        let errors = format!("{:02}-{}-error.png", i + 1, st.name);
        assert!(
            section.contains(&format!("id=\"{}\"", st.name)),
            "{}",
            st.name
        );
        assert!(section.contains(&format!("src=\"{frame}\"")), "{}", st.name);
        assert!(dir.join(&frame).is_file(), "{frame}");
        let depth_view = steps::settings_for(&scene, st.name).unwrap().show_depth_map;
        assert_eq!(section.contains(&format!("src=\"{errors}\"")), !depth_view);
        assert_eq!(dir.join(&errors).is_file(), !depth_view, "{errors}");
        let lesson = st.change.replace('&', "&amp;").replace('>', "&gt;");
        assert!(section.contains(&lesson), "{}: its lesson", st.name);
        if depth_view {
            continue;
        }
        // The step's own table: at edges + away from edges = misclassified = the two kinds.
        let value = |label: &str| {
            let row = section
                .split("<tr>")
                .find(|r| r.starts_with(&format!("<td class=n>{label} ")))
                .unwrap_or_else(|| panic!("{}: no row {label}", st.name));
            pct(&cells(row)[1])
        };
        let total = value("misclassified");
        let near = 0.0015;
        assert!((value("false shadow") + value("false light") - total).abs() <= near);
        assert!((value("at edges") + value("away from edges") - total).abs() <= near);
        assert!(value("away from edges") <= total, "{}", st.name);
        if st.name == "no-bias" {
            assert!(
                value("away from edges") > 20.0,
                "no-bias: acne away from edges"
            );
        }
    }
    // Variants do not carry over: the fix is told against the step before them.
    let fix = sections[7];
    assert!(fix.contains("(against step 5, cull-front)"), "{fix}");
    // The overview lists every step with the same figures.
    let overview = html.split("<h2>All steps</h2>").nth(1).unwrap();
    let overview = overview.split("</table>").next().unwrap();
    let rows: Vec<Vec<String>> = overview.split("<tr>").skip(2).map(cells).collect();
    assert_eq!(rows.len(), steps::of(&scene).len());
    for row in rows.iter().filter(|r| r.len() > 2) {
        assert!(
            (pct(&row[1]) + pct(&row[2]) - pct(&row[3])).abs() <= 0.0015,
            "{row:?}"
        );
        assert!(pct(&row[4]) <= pct(&row[3]), "{row:?}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// The playground's variance and moment pages subtract no epsilon (their demos have none);
/// the PCF pages' epsilon comes back for PCSS, and only the pages that read depth per tap
/// read it as the playground does (interpolated).
#[test]
fn the_playgrounds_moment_pages_carry_no_bias_and_its_pcf_pages_read_depth_linear() {
    use shadowmap::settings::DepthLookup;
    let scene = Scene::load("playground").unwrap();
    for name in ["variance", "moment", "vssm"] {
        let s = step(&scene, name);
        assert_eq!(s.bias_mode, BiasMode::None, "{name}");
        assert!(s.summary().contains("no bias"), "{name}: {}", s.summary());
        let text = steps::of(&scene).iter().find(|st| st.name == name).unwrap();
        assert!(
            text.change.contains("no epsilon"),
            "{name}: {}",
            text.change
        );
    }
    let pcss = step(&scene, "pcss");
    assert_eq!((pcss.bias_mode, pcss.bias), (BiasMode::Constant, 1.125e-2));
    assert_eq!(pcss.depth_lookup, DepthLookup::Nearest);
    for name in ["basic", "pcf", "soft-pcf"] {
        assert_eq!(
            step(&scene, name).depth_lookup,
            DepthLookup::Linear,
            "{name}"
        );
    }
    // The chapters' steps keep the book's NEAREST lookups.
    let dummy = Scene::load("dummy").unwrap();
    for st in steps::of(&dummy) {
        assert_eq!(step(&dummy, st.name).depth_lookup, DepthLookup::Nearest);
    }
}

/// Visibility of the playground under `s` at 400 x 300, and how far two such pictures
/// differ: (pixels that differ by more than 0.05, mean difference over pixels where either
/// is between 0 and 1).
fn playground_visibility(
    ctx: &shadowmap::engine::HeadlessContext,
    s: &ShadowSettings,
) -> Vec<Option<f32>> {
    let mut scene = Scene::load("playground").unwrap();
    common::render(ctx, &mut scene, s, 400, 300)
        .visibility
        .unwrap()
}

fn visibility_difference(a: &[Option<f32>], b: &[Option<f32>]) -> (usize, f64) {
    let pairs: Vec<(f32, f32)> = a
        .iter()
        .zip(b)
        .filter_map(|(x, y)| Some(((*x)?, (*y)?)))
        .collect();
    let differ = pairs.iter().filter(|(x, y)| (x - y).abs() > 0.05).count();
    let soft: Vec<f64> = pairs
        .iter()
        .filter(|(x, y)| (*x > 0.0 && *x < 1.0) || (*y > 0.0 && *y < 1.0))
        .map(|(x, y)| (x - y).abs() as f64)
        .collect();
    (differ, soft.iter().sum::<f64>() / soft.len().max(1) as f64)
}

#[test]
fn linear_depth_lookups_change_the_pcf_penumbra_and_nothing_where_they_are_idle() {
    use shadowmap::settings::DepthLookup;
    use shadowmap::shadows::plan::ShadowPlan;
    let ctx = common::context();
    let scene = Scene::load("playground").unwrap();
    let with = |s: &ShadowSettings, lookup| ShadowSettings {
        depth_lookup: lookup,
        ..*s
    };
    let pcf = step(&scene, "pcf");
    let linear = playground_visibility(&ctx, &with(&pcf, DepthLookup::Linear));
    let nearest = playground_visibility(&ctx, &with(&pcf, DepthLookup::Nearest));
    let (differ, mean) = visibility_difference(&linear, &nearest);
    eprintln!("pcf: {differ} pixels differ, penumbra mean difference {mean:.4}");
    assert!(differ >= 150, "{differ} pixels differ");
    assert!(mean >= 0.03, "penumbra mean difference {mean}");
    // Where the setting is idle the picture is the same, pixel for pixel, and the plan
    // says why.
    let idle = [
        (Filter::Hardware2x2, "hardware"),
        (Filter::Vsm, "moment map"),
        (Filter::Msm, "moment map"),
    ];
    for (filter, why) in idle {
        let s = ShadowSettings { filter, ..pcf };
        let a = playground_visibility(&ctx, &with(&s, DepthLookup::Linear));
        let b = playground_visibility(&ctx, &with(&s, DepthLookup::Nearest));
        assert!(a == b, "{filter:?}: linear lookups changed the picture");
        let plan = ShadowPlan::decide(&scene.lights, &with(&s, DepthLookup::Linear));
        let idle = plan.lights[0]
            .idle
            .iter()
            .find(|i| i.setting == "depth_lookup");
        assert!(
            idle.is_some_and(|i| i.why.contains(why)),
            "{filter:?}: {idle:?}"
        );
    }
    let plan = ShadowPlan::decide(&scene.lights, &with(&pcf, DepthLookup::Linear));
    assert!(!plan.lights[0].is_idle("depth_lookup"));
    assert!(!plan.idle.iter().any(|i| i.setting == "depth_lookup"));
    // A point light's cube map is read NEAREST whatever the setting says.
    let mut point = Scene::load("point-shadows").unwrap();
    point.items.iter_mut().for_each(|i| i.spin = Vec3::ZERO);
    let s = ShadowSettings {
        filter: Filter::Pcf3x3,
        ..point.shadow
    };
    let frames = [DepthLookup::Linear, DepthLookup::Nearest]
        .map(|l| common::render(&ctx, &mut point, &with(&s, l), 160, 90).visibility);
    assert!(
        frames[0] == frames[1],
        "a cube map changed with linear lookups"
    );
    let plan = ShadowPlan::decide(&point.lights, &with(&s, DepthLookup::Linear));
    let why = plan.idle.iter().find(|i| i.setting == "depth_lookup");
    assert!(why.is_some_and(|i| i.why.contains("cube maps")), "{why:?}");
}

/// The scenes the step lists were written for: the chapters' on the DummyGame and on
/// LearnOpenGL's, the playground's and the translucent casters' on their own. (Other scenes take the chapters' list too,
/// without stages of their own.)
const STEP_SCENES: [&str; 4] = ["dummy", "learnopengl", "playground", "smoke"];

/// A pixel has changed when a channel moved by more than this many levels of 255.
const CHANGED_LEVELS: i32 = 8;

/// A step shows its lesson when at least this share of the frame's pixels change (an edge
/// that softens or moves changes a few hundred pixels of a 320-pixel-wide frame).
const VISIBLE_SHARE: f64 = 0.0005;

/// A step that says it keeps its predecessor's picture changes fewer than this share of the
/// pixels (a few isolated ones).
const SAME_SHARE: f64 = 0.0001;

/// Of a staged step's changed pixels, at least this share lie in the region its caption
/// names.
const IN_REGION_SHARE: f64 = 0.9;

/// `scene` seen as step `st` is shown, drawn with `settings` 320 pixels wide in the scene's
/// aspect: the colours and each pixel's world position (NaN where no geometry).
fn staged_frame(
    ctx: &shadowmap::engine::HeadlessContext,
    scene: &Scene,
    st: &steps::Step,
    settings: &ShadowSettings,
) -> (Vec<u8>, Vec<[f32; 3]>) {
    let mut staged = scene.clone();
    st.set_stage(&mut staged, false).unwrap();
    let outputs = Outputs {
        visibility: false,
        gbuffer: true,
    };
    let height = 320 * staged.size[1] / staged.size[0];
    let frame = render_frames(ctx.gl(), &mut staged, settings, 320, height, 1, outputs)
        .unwrap_or_else(|e| panic!("{} / {}: {e}", scene.name, st.name));
    let positions = frame.world_positions().unwrap();
    (frame.colour.rgba, positions)
}

/// The pixels (by index) whose colours differ by more than [`CHANGED_LEVELS`].
fn changed_pixels(a: &[u8], b: &[u8]) -> Vec<usize> {
    let far = |p: &[u8], q: &[u8]| {
        (0..3).any(|k| (i32::from(p[k]) - i32::from(q[k])).abs() > CHANGED_LEVELS)
    };
    a.chunks_exact(4)
        .zip(b.chunks_exact(4))
        .enumerate()
        .filter_map(|(i, (p, q))| far(p, q).then_some(i))
        .collect()
}

/// Where a step's caption says its change shows, as a test of a pixel's world position:
/// outside the light's box or beyond its far plane for the over-sampling steps, on the floor
/// (at the contact, not on the caster) for culling; `None` for the whole frame.
fn named_region(
    scene: &Scene,
    st: &steps::Step,
    settings: &ShadowSettings,
) -> Option<Box<dyn Fn(Vec3) -> bool>> {
    let mut staged = scene.clone();
    st.set_stage(&mut staged, false).unwrap();
    match st.name {
        "over-sampling-repeat" | "over-sampling-book" | "over-sampling" => {
            let sv = shadowmap::shadows::light_camera(&staged, 0, settings);
            let m = sv.projection * sv.view;
            Some(Box::new(move |p| {
                let q = m.project_point3(p);
                q.x.abs() > 1.0 || q.y.abs() > 1.0 || q.z > 1.0
            }))
        }
        "cull-front" => {
            let floor = staged
                .items
                .iter()
                .find(|i| ["plane", "floor"].contains(&&*i.name));
            let y = floor.unwrap().position.y;
            Some(Box::new(move |p: Vec3| (p.y - y).abs() < 0.01))
        }
        _ => None,
    }
}

/// Every step of every list, on the scene it was written for, changes the picture of the
/// step before it visibly (in the region its caption names, where it has a stage), both drawn
/// as the step is shown; or it says why it is the picture of the step it builds on, and is.
#[test]
fn every_step_shows_its_change_or_says_why_not() {
    let ctx = common::context();
    for name in STEP_SCENES {
        let mut sc = scene(name);
        sc.camera = sc.steps_camera();
        sc.use_steps_light_size();
        let list = steps::of(&sc);
        let mut base = steps::start(&sc);
        for (i, st) in list.iter().enumerate() {
            let settings = step(&sc, st.name);
            let before = match (i, st.same_picture_on(&sc)) {
                (_, Some(_)) => base,
                (0, None) => steps::start(&sc),
                (_, None) => step(&sc, list[i - 1].name),
            };
            let (now, positions) = staged_frame(&ctx, &sc, st, &settings);
            let (was, _) = staged_frame(&ctx, &sc, st, &before);
            let changed = changed_pixels(&now, &was);
            let share = changed.len() as f64 / (now.len() / 4) as f64;
            let region = named_region(&sc, st, &settings);
            let region = region.filter(|_| st.same_picture_on(&sc).is_none());
            let inside = region.as_ref().map(|keep| {
                let n = changed
                    .iter()
                    .filter(|&&i| keep(Vec3::from(positions[i])))
                    .count();
                n as f64 / changed.len().max(1) as f64
            });
            let most = now
                .iter()
                .zip(&was)
                .map(|(a, b)| a.abs_diff(*b))
                .max()
                .unwrap_or(0);
            eprintln!(
                "{name} {}: {:.3}% of pixels changed (at most by {most} levels){}",
                st.name,
                share * 100.0,
                inside.map_or(String::new(), |s| format!(
                    ", {:.1}% of them where its caption says",
                    s * 100.0
                ))
            );
            match st.same_picture_on(&sc) {
                Some(why) => assert!(
                    share < SAME_SHARE,
                    "{name} {}: says it is the same picture ({why}), but {} pixels change",
                    st.name,
                    changed.len()
                ),
                None => assert!(
                    share >= VISIBLE_SHARE,
                    "{name} {}: {:.3}% of pixels change, under {}%",
                    st.name,
                    share * 100.0,
                    VISIBLE_SHARE * 100.0
                ),
            }
            if let Some(s) = inside {
                assert!(
                    s >= IN_REGION_SHARE,
                    "{name} {}: {s} in its region",
                    st.name
                );
            }
            if st.cumulative {
                base = settings;
            }
        }
    }
}

/// `render --help` (for `--step`) and `steps --help` say which scenes take which steps: each
/// list's line names exactly the built-in scenes that load with it, and the next line its
/// steps in order.
#[test]
fn the_help_names_each_scenes_steps() {
    for command in ["render", "steps"] {
        let help = common::stdout_of(common::bin().args([command, "--help"]));
        // The help wraps to the terminal: read it as one run of words.
        let flat = help.split_whitespace().collect::<Vec<_>>().join(" ");
        let mut listed: Vec<String> = Vec::new();
        for list in [
            StepList::Chapters,
            StepList::Playground,
            StepList::Volumetric,
        ] {
            let scenes: Vec<Scene> = Scene::builtin_names()
                .into_iter()
                .map(|n| Scene::load(n).unwrap())
                .filter(|s| s.steps.list == list)
                .collect();
            let names: Vec<&str> = scenes.iter().map(|s| s.name.as_str()).collect();
            let head = format!("{} (scenes {}):", list.name(), names.join(", "));
            let at = flat.find(&head);
            let at = at.unwrap_or_else(|| panic!("{command} --help lacks '{head}':\n{help}"));
            let steps: Vec<&str> = steps::of(&scenes[0]).iter().map(|s| s.name).collect();
            let after = flat[at + head.len()..].trim_start();
            assert!(
                after.starts_with(&steps.join(", ")),
                "{command} --help: after '{head}': {after}"
            );
            listed.extend(names.iter().map(|n| n.to_string()));
        }
        listed.sort_unstable();
        let mut all: Vec<String> = Scene::builtin_names()
            .iter()
            .map(|n| n.to_string())
            .collect();
        all.sort_unstable();
        assert_eq!(listed, all, "{command} --help: every built-in scene once");
    }
}
