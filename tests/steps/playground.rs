//! The playground's steps: its demo pages, their biases and linear depth.

use super::*;

#[test]
fn the_playground_has_its_demo_pages_as_steps() {
    use shadowmap::settings::{Filter, MapSize};
    let scene = Scene::load("playground").unwrap();
    let names: Vec<&str> = steps::of(&scene).iter().map(|s| s.name).collect();
    assert_eq!(
        names,
        ["basic", "pcf", "soft-pcf", "variance", "moment", "esm", "pcss", "vssm", "msm-soft"]
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
         expected one of basic, pcf, soft-pcf, variance, moment, esm, pcss, vssm, msm-soft"
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
