//! Caster groups (src/shadows/groups.rs): a box per group of casters, measured against the
//! exact reference where one fitted box must stretch over casters far apart, and checked
//! to read as one fitted box where there is a single caster (the spare layer is lit).

use crate::common;

use shadowmap::compare::compare;
use shadowmap::settings::{Filter, Fit, MapSize, ShadowSettings};

fn settings(scene: &shadowmap::Scene, groups: u32, size: u32) -> ShadowSettings {
    ShadowSettings {
        fit: Fit::Scene,
        filter: Filter::Hardware2x2,
        map_size: MapSize::square(size),
        caster_groups: groups,
        ..scene.shadow
    }
}

#[test]
fn two_groups_cut_learnopengls_error_where_one_fitted_box_cannot() {
    // LearnOpenGL's camera sees the shadows of cube1 (in the middle) and of cube3 (at the
    // frame's corner): one box holds both and its texels are coarse over cube1's shadow
    // edge; a box each keeps cube1's as fine as if it were alone.
    let ctx = common::context();
    let scene = common::frozen("learnopengl");
    let opts = common::frame_options(800, 600);
    let measure = |s: &ShadowSettings| compare(ctx.gl(), &scene, s, &opts).unwrap().metrics;
    for size in [512, 1024] {
        let one = measure(&settings(&scene, 1, size));
        let two = measure(&settings(&scene, 2, size));
        eprintln!(
            "learnopengl {size}^2 hw2x2: one fitted box {:.4}% misclassified, two caster groups \
             {:.4}%",
            one.misclassified_rate * 100.0,
            two.misclassified_rate * 100.0
        );
        assert!(one.receivers > 200_000, "the floor must fill the view");
        assert!(
            two.misclassified * 2 < one.misclassified,
            "{size}: two groups misclassify {} pixels, one box {}",
            two.misclassified,
            one.misclassified
        );
        // Every error left lies on the shadows' edges.
        assert_eq!(two.misclassified_outside_band_rate, 0.0, "{size}");
    }
}

#[test]
fn one_caster_in_two_groups_reads_as_one_fitted_box() {
    // The DummyGame's light shadows one cube: the first layer's box is the fitted box, the
    // second holds nothing and must read lit everywhere.
    let ctx = common::context();
    let mut scene = common::dummy(60.0);
    let (s1, s2) = (settings(&scene, 1, 1024), settings(&scene, 2, 1024));
    let one = common::render(&ctx, &mut scene, &s1, 320, 180);
    let two = common::render(&ctx, &mut scene, &s2, 320, 180);
    let (a, b) = (one.visibility.unwrap(), two.visibility.unwrap());
    let shadowed = a.iter().flatten().filter(|v| **v < 0.5).count();
    let differ = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| match (x, y) {
            (Some(x), Some(y)) => (x - y).abs() > 0.5,
            (x, y) => x.is_some() != y.is_some(),
        })
        .count();
    eprintln!("dummy: {shadowed} shadowed pixels, {differ} differ between one box and two groups");
    assert!(shadowed > 1000, "the cube's shadow must be in view");
    assert_eq!(differ, 0, "{differ} of {shadowed} shadowed pixels differ");
}

#[test]
fn a_caster_spanning_the_view_does_not_swallow_the_groups() {
    // The `large` scene's terrain casts too and spans the whole view: joined by the
    // pillars it would keep them all in one box as coarse as the single one. Grouped by
    // area x casters, the pillars get boxes of their own and the error falls.
    let ctx = common::context();
    let scene = common::frozen("large");
    let opts = common::frame_options(640, 360);
    let measure = |groups: u32| {
        let s = ShadowSettings {
            caster_groups: groups,
            ..scene.shadow
        };
        compare(ctx.gl(), &scene, &s, &opts).unwrap().metrics
    };
    let (one, four) = (measure(1), measure(4));
    eprintln!(
        "large 640x360: one box {:.3}% misclassified, four caster groups {:.3}%",
        one.misclassified_rate * 100.0,
        four.misclassified_rate * 100.0
    );
    assert!(one.receivers > 100_000, "the terrain must fill the view");
    assert!(
        (four.misclassified as f64) < 0.6 * one.misclassified as f64,
        "four groups {} against one box {}",
        four.misclassified,
        one.misclassified
    );
}

#[test]
fn a_second_sun_keeps_one_map_and_takes_what_one_map_takes() {
    // Only the first directional light that asks for layers gets them; a second keeps one
    // 2D map, so PCSS (refused for layers) is its to use, and the frame draws.
    let ctx = common::context();
    let mut scene = common::frozen("learnopengl");
    let mut second = scene.lights[0];
    second.shadow_patch_mut().filter = Some(Filter::Pcss);
    scene.lights.push(second);
    let s = ShadowSettings {
        caster_groups: 2,
        ..scene.shadow
    };
    use shadowmap::shadows::plan::ShadowPlan;
    use shadowmap::shadows::ShadowKind;
    let plan = ShadowPlan::resolve(&scene.lights, &s, None).unwrap();
    assert_eq!(plan.kinds(), [ShadowKind::Groups, ShadowKind::Map]);
    let frame = common::render(&ctx, &mut scene, &s, 160, 120);
    assert!(frame.visibility.unwrap().iter().flatten().any(|v| *v < 0.5));
    // Asked of the first light, PCSS is still refused, naming it.
    scene.lights.swap(0, 1);
    let e = ShadowPlan::resolve(&scene.lights, &s, None)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("shadow.filter = pcss: light 0 cannot use it: cascades and caster groups"),
        "{e}"
    );
}
