//! Translucent casters against the transmittance truth: one sheet of opacity a leaves
//! 1 - a behind it (the truth), which `volumetric = "off"` renders as 1 and `"solid"` as 0;
//! two stacked sheets multiply; translucent items are blended by their opacity over what
//! is behind them, and the measurement outputs keep the receivers under them.

mod common;

use std::path::Path;

use common::context;
use shadowmap::compare::{compare, Comparison};
use shadowmap::scene::file::parse;
use shadowmap::settings::{ShadowSettings, Volumetric};
use shadowmap::Scene;

/// A floor (y = -1, 6 x 6) lit from nearly overhead, with `sheets`: (height, opacity) of a
/// 2 x 2 sheet each, stacked over the middle of the floor.
fn sheets_scene(sheets: &[(f32, f32)]) -> Scene {
    let mut text = String::from(
        "size = [320, 240]\n\
         [camera]\nposition = [0.0, 4.0, 3.0]\ntarget = [0.0, -1.0, 0.0]\n\
         [light]\ndirection = [0.15, 1.0, 0.1]\n\
         ortho = { left = -5.0, right = 5.0, bottom = -5.0, top = 5.0, near = -1.0, far = 12.0 }\n\
         [shadow]\nlight_view = \"look-at\"\nbias = 0.005\n\
         [[item]]\nname = \"floor\"\nmesh = \"plane\"\nposition = [0.0, -1.0, 0.0]\nscale = 3.0\n",
    );
    for (k, (y, a)) in sheets.iter().enumerate() {
        text += &format!(
            "[[item]]\nname = \"sheet{k}\"\nmesh = \"plane\"\nposition = [0.0, {y}, 0.0]\n\
             colour = [1.0, 0.5, 0.0, 1.0]\nopacity = {a}\n"
        );
    }
    parse(&text, Path::new("sheets.toml"), None).unwrap_or_else(|e| panic!("{e}"))
}

fn run(scene: &Scene, volumetric: Volumetric) -> Comparison {
    let settings = ShadowSettings {
        volumetric,
        ..scene.shadow
    };
    let ctx = context();
    let opts = common::frame_options(scene.size[0], scene.size[1]);
    compare(ctx.gl(), scene, &settings, &opts).unwrap_or_else(|e| panic!("compare: {e}"))
}

/// The truth's values over its receivers in the translucent shadow (below 1, above 0).
fn shadow_values(c: &Comparison) -> Vec<f32> {
    let truth = c
        .reference
        .transmittance
        .as_ref()
        .expect("a transmittance truth");
    (truth.iter())
        .filter(|r| r.receiver && r.visibility < 1.0)
        .map(|r| r.visibility)
        .collect()
}

#[test]
fn one_sheet_leaves_one_minus_its_opacity_which_off_renders_as_one_and_solid_as_zero() {
    let scene = sheets_scene(&[(0.0, 0.4)]);
    let off = run(&scene, Volumetric::Off);
    let values = shadow_values(&off);
    assert!(
        values.len() > 2000,
        "{} receivers in the sheet's shadow",
        values.len()
    );
    assert!(values.iter().all(|v| (v - 0.6).abs() < 1e-6), "{values:?}");
    let t = off.transmittance.expect("scored");
    assert_eq!(t.in_shadow, values.len());
    // `off` renders 1 there: wrong by the opacity, and right elsewhere.
    assert!((t.mae_in_shadow - 0.4).abs() < 0.01, "{t:?}");
    assert!(t.mae_outside < 0.005, "{t:?}");
    let solid = run(&scene, Volumetric::Solid)
        .transmittance
        .expect("scored");
    // `solid` renders 0 there (to the edge pixels PCF softens).
    assert!((solid.mae_in_shadow - 0.6).abs() < 0.02, "{solid:?}");
    assert!(solid.mae_outside < 0.01, "{solid:?}");
}

#[test]
fn stacked_sheets_multiply_in_the_truth() {
    let scene = sheets_scene(&[(0.0, 0.5), (1.0, 0.25)]);
    let values = shadow_values(&run(&scene, Volumetric::Off));
    let both = values.iter().filter(|v| (*v - 0.375).abs() < 1e-6).count();
    let lower = values.iter().filter(|v| (*v - 0.5).abs() < 1e-6).count();
    let upper = values.iter().filter(|v| (*v - 0.75).abs() < 1e-6).count();
    assert_eq!(
        both + lower + upper,
        values.len(),
        "other values: {values:?}"
    );
    assert!(
        both > 1000 && lower > 10 && upper > 10,
        "{both} {lower} {upper}"
    );
}

#[test]
fn a_translucent_item_is_blended_by_its_opacity_over_what_is_behind_it() {
    let ctx = context();
    let render = |scene: &mut Scene| {
        let settings = scene.shadow;
        common::render(&ctx, scene, &settings, 320, 240)
    };
    let mut bare = sheets_scene(&[]);
    let mut opaque = sheets_scene(&[(0.0, 1.0)]);
    let mut glass = sheets_scene(&[(0.0, 0.25)]);
    let (bare, opaque, glass) = (render(&mut bare), render(&mut opaque), render(&mut glass));
    // The middle of the frame shows the sheet.
    let i = (120 * 320 + 160) * 4;
    for c in 0..3 {
        let (floor, sheet) = (
            f32::from(bare.colour.rgba[i + c]),
            f32::from(opaque.colour.rgba[i + c]),
        );
        let expected = 0.25 * sheet + 0.75 * floor;
        let got = f32::from(glass.colour.rgba[i + c]);
        assert!(
            (got - expected).abs() <= 1.0,
            "channel {c}: {got} against {expected}"
        );
    }
    // The measurement outputs keep the floor under the glass: the bare floor's position.
    let p = |f: &shadowmap::frame::Frame| f.positions.as_ref().unwrap()[120 * 320 + 160];
    assert_eq!(p(&glass), p(&bare));
    assert_ne!(p(&opaque), p(&bare));
}

#[test]
fn the_smoke_scene_scores_both_wrongs_of_a_depth_map() {
    let scene = common::frozen("smoke");
    let size = |s: &Scene| Scene {
        size: [320, 180],
        ..s.clone()
    };
    let scene = size(&scene);
    let off = run(&scene, Volumetric::Off).transmittance.expect("scored");
    let solid = run(&scene, Volumetric::Solid)
        .transmittance
        .expect("scored");
    assert!(off.in_shadow > 500, "{off:?}");
    // Off is too bright by what the smoke and glass stop, solid too dark by what they pass.
    assert!(
        off.mae_in_shadow > 0.3 && solid.mae_in_shadow > 0.3,
        "{off:?} {solid:?}"
    );
    assert!(off.mae_outside < 0.01, "{off:?}");
}
