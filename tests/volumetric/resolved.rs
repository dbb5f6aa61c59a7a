//! Opaque receivers reading a resolved translucent map (`opaque_receivers = "resolved"`): a
//! floor behind one translucent sheet gets the light it gets from the curve; against the
//! transmittance truth on sharp cards the error stays within its measured bound; with no
//! translucent item no pixel changes; the map is resolved again exactly when either map is
//! drawn; and where it does nothing the setting says so.

use crate::common;

use std::path::Path;

use common::context;
use shadowmap::compare::compare;
use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::renderer::Target;
use shadowmap::scene::file::parse;
use shadowmap::settings::{OpaqueReceivers, ShadowSettings, Volumetric};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::{Renderer, Scene};

const TECHNIQUES: [Volumetric; 3] = [Volumetric::Osm, Volumetric::Fom, Volumetric::Avsm];

fn with(scene: &Scene, volumetric: Volumetric, receivers: OpaqueReceivers) -> ShadowSettings {
    ShadowSettings {
        volumetric,
        opaque_receivers: receivers,
        ..scene.shadow
    }
}

/// A floor lit from nearly overhead under a 6 x 6 sheet of opacity 0.4 at y = 4.5, above
/// the camera (not in view): every lit point of the floor lies behind the sheet alone.
fn covered_floor() -> Scene {
    let items = "\
         [[item]]\nname = \"cube\"\nmesh = \"cube\"\nposition = [0.5, -0.5, 0.0]\nscale = 0.5\n\
         [[item]]\nname = \"cover\"\nmesh = \"plane\"\nposition = [0.0, 4.5, 0.0]\nscale = 3.0\n\
         opacity = 0.4\n";
    let text = format!("{}{items}", common::OVERHEAD_FLOOR);
    parse(&text, Path::new("covered.toml"), None).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_floor_behind_one_sheet_gets_the_same_light_resolved_as_from_the_curve() {
    let ctx = context();
    let mut scene = covered_floor();
    for volumetric in TECHNIQUES {
        let mut frame = |r| {
            let s = with(&scene, volumetric, r);
            common::render(&ctx, &mut scene, &s, 320, 240)
        };
        let (curve, resolved) = (
            frame(OpaqueReceivers::Curve),
            frame(OpaqueReceivers::Resolved),
        );
        let visibility = |f: &shadowmap::frame::Frame| f.visibility.clone().expect("visibility");
        let (a, b) = (visibility(&curve), visibility(&resolved));
        let pairs = a.iter().zip(&b);
        let both: Vec<(f32, f32)> = pairs.filter_map(|(a, b)| Some(((*a)?, (*b)?))).collect();
        // Lit floor, 1 - 0.4 from the curve: the same from the resolved map to one step of
        // the 8-bit output, but at a few pixels where the sheet's shadow edge runs (the
        // curve filters what the technique stores, the resolved map the transmittance).
        let lit: Vec<f32> = (both.iter())
            .filter(|(c, _)| (c - 0.6).abs() < 0.01)
            .map(|(_, r)| *r)
            .collect();
        assert!(lit.len() > 20_000, "{volumetric:?}: {} lit", lit.len());
        let n = lit
            .iter()
            .filter(|r| (*r - 0.6).abs() > 1.5 / 255.0)
            .count();
        assert!(n * 1000 < lit.len(), "{volumetric:?}: {n} of {}", lit.len());
        // Everywhere, the cube's shadow edges too: within one 3 x 3 PCF step (1/9) of the
        // light, and the colour within one step of 8 bits at all but a few pixels.
        let worst = both.iter().map(|(c, r)| (c - r).abs()).fold(0.0, f32::max);
        assert!(worst <= 0.6 / 9.0 + 1e-3, "{volumetric:?}: {worst}");
        let pixels = curve
            .colour
            .rgba
            .chunks(4)
            .zip(resolved.colour.rgba.chunks(4));
        let off = pixels
            .filter(|(a, b)| a.iter().zip(b.iter()).any(|(x, y)| x.abs_diff(*y) > 1))
            .count();
        println!(
            "{volumetric:?}: {} lit, {n} off, worst {worst}, {off} pixels off",
            lit.len()
        );
        assert!(
            off < 100,
            "{volumetric:?}: {off} pixels differ by more than one step"
        );
    }
}

#[test]
fn on_sharp_cards_the_resolved_map_keeps_within_its_measured_error() {
    // Measured (640 x 360; `compare --scene tests/data/cards.toml --volumetric X
    // --opaque-receivers resolved`): 0.0023 over every receiver, 0.0121 within the
    // translucent shadow, for all three (a card is one crossing: each texel holds it
    // exactly, and the resolved map filters transmittance, as AVSM's lookup does).
    let scene = Scene::load("tests/data/cards.toml").unwrap_or_else(|e| panic!("{e}"));
    let ctx = context();
    let opts = common::frame_options(scene.size[0], scene.size[1]);
    for volumetric in TECHNIQUES {
        let s = with(&scene, volumetric, OpaqueReceivers::Resolved);
        let c = compare(ctx.gl(), &scene, &s, &opts).unwrap_or_else(|e| panic!("{e}"));
        let t = c.transmittance.expect("a transmittance truth");
        println!("{volumetric:?}: {t:?}");
        assert!(t.mae <= 0.0025, "{volumetric:?}: {t:?}");
        assert!(t.mae_in_shadow <= 0.0125, "{volumetric:?}: {t:?}");
    }
}

#[test]
fn without_translucent_items_the_resolved_map_changes_no_pixel() {
    let ctx = context();
    let mut scene = common::frozen("dummy");
    let plain = scene.shadow;
    let off = common::render(&ctx, &mut scene, &plain, 320, 240);
    for volumetric in TECHNIQUES {
        let s = with(&scene, volumetric, OpaqueReceivers::Resolved);
        let resolved = common::render(&ctx, &mut scene, &s, 320, 240);
        assert!(resolved.colour.rgba == off.colour.rgba, "{volumetric:?}");
        assert_eq!(resolved.visibility, off.visibility, "{volumetric:?}");
    }
}

#[test]
fn the_map_is_resolved_again_exactly_when_either_map_is_drawn() {
    // The smoke with the cache on and off side by side: nothing moves, the cube moves (its
    // depth map is drawn again, the translucent map kept), the glass moves (both). Every
    // frame is the uncached one; the cached renderer resolves at the first frame and after
    // each move.
    let ctx = context();
    let mut scene = common::frozen("smoke");
    let find = |scene: &Scene, name: &str| scene.items.iter().position(|i| i.name == name);
    let (cube, glass) = (
        find(&scene, "cube").unwrap(),
        find(&scene, "glass").unwrap(),
    );
    let outputs = Outputs {
        visibility: true,
        gbuffer: false,
    };
    for volumetric in TECHNIQUES {
        let mut renderers = [true, false].map(|cache| {
            let s = ShadowSettings {
                shadow_cache: cache,
                ..with(&scene, volumetric, OpaqueReceivers::Resolved)
            };
            let target = RenderTarget::new(ctx.gl(), 240, 160, outputs).unwrap();
            (Renderer::new(ctx.gl(), &scene, &s).unwrap(), target)
        });
        for frame in 0..6 {
            match frame {
                2 => scene.items[cube].position.z += 0.05,
                4 => scene.items[glass].position.x += 0.05,
                _ => {}
            }
            let [cached, fresh] = renderers.each_mut().map(|(renderer, target)| {
                renderer.render(&scene, Target::Offscreen(target)).unwrap();
                (target.read_colour(), target.read_visibility().unwrap())
            });
            assert!(cached == fresh, "{volumetric:?}, frame {frame}");
        }
        let draws = |k: usize| renderers[k].0.volumetric_maps().draws();
        assert_eq!(
            (draws(0).drawn, draws(0).resolved),
            (2, 3),
            "{volumetric:?}"
        );
        assert_eq!(
            (draws(1).drawn, draws(1).resolved),
            (6, 6),
            "{volumetric:?}"
        );
        scene.items[cube].position.z -= 0.05;
        scene.items[glass].position.x -= 0.05;
    }
}

fn idle_why(scene: &Scene, settings: &ShadowSettings) -> Option<String> {
    let plan = ShadowPlan::decide(&scene.lights, settings);
    let idle = plan.idle_in(scene).into_iter();
    idle.filter(|i| i.setting == "opaque_receivers")
        .map(|i| i.why)
        .next()
}

#[test]
fn opaque_receivers_says_where_it_does_nothing() {
    let smoke = common::frozen("smoke");
    let resolved = |s: &Scene, v| with(s, v, OpaqueReceivers::Resolved);
    assert_eq!(idle_why(&smoke, &resolved(&smoke, Volumetric::Osm)), None);
    assert_eq!(
        idle_why(&smoke, &resolved(&smoke, Volumetric::Solid)).as_deref(),
        Some(
            "no light's translucent map to resolve: only a 2D depth map with volumetric = \
             \"osm\", \"fom\" or \"avsm\" keeps a translucent map (--volumetric osm, fom or \
             avsm, on a directional or spot light)"
        )
    );
    let dummy = common::frozen("dummy");
    assert_eq!(
        idle_why(&dummy, &resolved(&dummy, Volumetric::Avsm)).as_deref(),
        Some(
            "the scene has no translucent caster (an item with opacity below 1): the \
             translucent map stays empty"
        )
    );
}
