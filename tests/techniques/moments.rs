//! The filterable maps (vsm, evsm2, evsm4, msm, esm) against the exact reference: VSM's light
//! bleeding under overlapping occluders and what cuts it, agreement away from shadow edges,
//! every built-in scene drawn (or refused with its exact message), and their costs.

use crate::common;

use shadowmap::compare::{compute_reference, render_visibility, CompareOptions};
use shadowmap::engine::Outputs;
use shadowmap::frame::render_frames;
use shadowmap::settings::{Filter, ShadowSettings};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::shadows::{filter_cost as cost, ShadowKind};
use shadowmap::Scene;

const MOMENT_FILTERS: [Filter; 5] = Filter::MOMENTS;

fn overlap() -> Scene {
    Scene::load("overlap").unwrap_or_else(|e| panic!("{e}"))
}

pub(crate) fn options(scene: &Scene) -> CompareOptions {
    CompareOptions {
        width: scene.size[0],
        height: scene.size[1],
        supersample: 1,
        band: 1,
        light: 0,
        rays: shadowmap::compare::AREA_RAYS,
    }
}

#[test]
fn vsm_bleeds_under_overlapping_occluders_and_reduction_and_msm_cut_it() {
    let ctx = common::context();
    let scene = overlap();
    let opts = options(&scene);
    let reference = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts).unwrap();
    // "Bleed": receivers lit above 0.5 where the (hard) truth is fully shadowed, away from
    // the truth's shadow edges (so a filter's soft edge does not count as bleeding).
    let bleed = |s: &ShadowSettings| {
        let frame = render_visibility(ctx.gl(), &scene, s, opts.width, opts.height, 0).unwrap();
        let m = reference.score(frame.visibility.as_deref().unwrap(), opts.band);
        m.false_light_outside_band
    };
    let with = |filter, bleed_reduction| ShadowSettings {
        filter,
        bleed_reduction,
        ..scene.shadow
    };
    let raw = bleed(&with(Filter::Vsm, 0.0));
    let reduced = bleed(&with(Filter::Vsm, 0.15));
    let strong = bleed(&with(Filter::Vsm, 0.4));
    let msm = bleed(&with(Filter::Msm, 0.0));
    let pcf = bleed(&with(Filter::Pcf3x3, 0.0));
    eprintln!(
        "bleeding pixels: vsm {raw}, reduced 0.15 {reduced}, 0.4 {strong}; msm {msm}; pcf3x3 {pcf}"
    );
    // A depth map does not bleed here; VSM does, visibly.
    assert!(pcf <= 5, "pcf3x3 bleeds {pcf} pixels");
    assert!(raw >= 50, "vsm without reduction bleeds only {raw} pixels");
    assert!(reduced < raw, "reduction 0.15: {reduced} vs {raw}");
    assert!(
        strong < reduced,
        "reduction 0.4: {strong} vs 0.15: {reduced}"
    );
    assert!(
        msm * 2 < reduced,
        "msm bleeds {msm}, vsm with Filament's reduction {reduced}"
    );
}

#[test]
fn away_from_edges_the_moment_filters_agree_with_the_hard_reference() {
    let ctx = common::context();
    let mut worst = Vec::new();
    for scene in [
        Scene::load("playground").unwrap(),
        Scene::load("learnopengl").unwrap(),
        overlap(),
    ] {
        let opts = options(&scene);
        let reference = compute_reference(ctx.gl(), &scene, &scene.shadow, &opts).unwrap();
        for filter in MOMENT_FILTERS {
            let s = ShadowSettings {
                filter,
                ..scene.shadow
            };
            let frame = render_visibility(ctx.gl(), &scene, &s, opts.width, opts.height, 0)
                .unwrap_or_else(|e| panic!("{} {}: {e}", scene.name, filter.name()));
            let m = reference.score(frame.visibility.as_deref().unwrap(), opts.band);
            worst.push((
                scene.name.clone(),
                filter.name(),
                m.misclassified_outside_band_rate,
            ));
            // Something is shadowed and something lit: not a blank map.
            assert!(m.receivers > 1000, "{} {}", scene.name, filter.name());
            let vis = frame.visibility.as_deref().unwrap().iter().flatten();
            let lit = vis.clone().filter(|v| **v > 0.9).count();
            let dark = vis.filter(|v| **v < 0.1).count();
            assert!(
                lit > 100 && dark > 100,
                "{} {}: {lit} lit, {dark} shadowed pixels",
                scene.name,
                filter.name()
            );
        }
    }
    eprintln!("misclassified outside the band: {worst:?}");
    for (scene, filter, rate) in worst {
        assert!(
            rate < 0.01,
            "{scene} {filter}: {:.3}% misclassified away from edges",
            rate * 100.0
        );
    }
}

/// The message the shadow plan gives a point light under a moment filter.
fn point_light_refusal(filter: Filter, light: usize) -> String {
    format!(
        "shadow.filter = {}: light {light} cannot use it: the moment maps (vsm, evsm2, evsm4, \
         msm, esm) need one 2D map and a point light's shadow is a cube map; give the light a depth \
         filter of its own (shadow = {{ filter = \"pcf3x3\" }}) or use one for the scene",
        filter.name()
    )
}

#[test]
fn every_moment_filter_draws_every_built_in_scene_or_is_refused_exactly() {
    let ctx = common::context();
    let outputs = Outputs {
        visibility: true,
        gbuffer: false,
    };
    for name in Scene::builtin_names() {
        let scene = Scene::load(name).unwrap();
        let point = scene
            .lights
            .iter()
            .position(|l| matches!(l, shadowmap::scene::Light::Point(p) if p.casts_shadows));
        for filter in MOMENT_FILTERS {
            let s = ShadowSettings {
                filter,
                ..scene.shadow
            };
            let (w, h) = (320, 240);
            let result = render_frames(ctx.gl(), &mut scene.clone(), &s, w, h, 1, outputs);
            match point {
                Some(i) => {
                    let e = result.err().map(|e| e.to_string());
                    assert_eq!(e, Some(point_light_refusal(filter, i)), "{name}");
                    // With a depth filter of its own, the point light keeps its cube map
                    // and the other lights their moment maps, in one program.
                    let mut mixed = scene.clone();
                    for light in &mut mixed.lights {
                        if matches!(light, shadowmap::scene::Light::Point(_)) {
                            light.shadow_patch_mut().filter = Some(Filter::Pcf3x3);
                        }
                    }
                    let kinds = ShadowPlan::decide(&mixed.lights, &s).kinds();
                    let frame = render_frames(ctx.gl(), &mut mixed, &s, w, h, 1, outputs)
                        .unwrap_or_else(|e| panic!("{name} {} mixed: {e}", filter.name()));
                    assert!(frame.visibility.is_some());
                    assert!(kinds.contains(&ShadowKind::Cube), "{name}: {kinds:?}");
                    if name == "three-lights" {
                        // The sun and the spot: two moment maps, each with its own snippet.
                        let moments = kinds.iter().filter(|k| **k == ShadowKind::Moments);
                        assert_eq!(moments.count(), 2, "{kinds:?}");
                    }
                }
                None => {
                    // No GL error (render checks after each pass), and a picture with
                    // both light and shadow in the measured light's test.
                    let frame = result.unwrap_or_else(|e| panic!("{name} {}: {e}", filter.name()));
                    let vis: Vec<f32> = frame
                        .visibility
                        .as_ref()
                        .unwrap()
                        .iter()
                        .flatten()
                        .copied()
                        .collect();
                    // ESM's shadow is exp(-c gap), the gap in the map's [0, 1] depth: under
                    // a box fitted to the large scene's 200-unit terrain a pillar's gap is a
                    // few hundredths, so its shadows are grey, not black.
                    let shadowed = if filter == Filter::Esm { 0.5 } else { 0.1 };
                    let lit = vis.iter().filter(|v| **v > 0.9).count();
                    let dark = vis.iter().filter(|v| **v < shadowed).count();
                    assert!(
                        lit > 100 && dark > 100,
                        "{name} {}: {lit} lit, {dark} shadowed pixels",
                        filter.name()
                    );
                }
            }
        }
    }
}

#[test]
fn cascades_and_the_cli_refuse_moment_filters_by_name() {
    let ctx = common::context();
    let scene = Scene::load("dummy").unwrap();
    let s = ShadowSettings {
        filter: Filter::Evsm4,
        cascades: 3,
        ..scene.shadow
    };
    let outputs = Outputs::default();
    let e = render_frames(ctx.gl(), &mut scene.clone(), &s, 64, 64, 1, outputs)
        .err()
        .map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some(
            "shadow.filter = evsm4: light 0 cannot use it: the moment maps (vsm, evsm2, evsm4, msm, esm) \
             need one 2D map and cascades and caster groups have a layer each; use cascades = 1 \
             and caster_groups = 1, or a depth filter (pcf3x3) for the light"
        )
    );
    // On the command line: before any GL work, naming the flag.
    let dir = std::env::temp_dir().join(format!("shadowmap-moments-{}", std::process::id()));
    let out = common::bin()
        .args([
            "render",
            "--scene",
            "point-shadows",
            "--filter",
            "vsm",
            "--out",
        ])
        .arg(dir.join("x.png"))
        .output()
        .unwrap();
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(&format!(
            "--filter: {}",
            point_light_refusal(Filter::Vsm, 0)
        )),
        "{stderr}"
    );
    assert!(!dir.exists());
}

#[test]
fn costs_state_taps_passes_and_memory() {
    let base = ShadowSettings::default();
    let of = |filter, blur| {
        cost(&ShadowSettings {
            filter,
            blur,
            ..base
        })
    };
    use shadowmap::settings::Blur;
    let pcf = of(Filter::Pcf5x5, Blur::None);
    assert_eq!((pcf.taps, pcf.passes, pcf.bytes_per_texel), (25, 1, 4));
    let vsm = of(Filter::Vsm, Blur::Playground3x3);
    // One lookup; depth, across and down; two RG32F textures and a 24-bit depth buffer.
    assert_eq!((vsm.taps, vsm.passes, vsm.blur_taps), (1, 3, 6));
    assert_eq!(vsm.bytes_per_texel, 2 * 8 + 4);
    let msm = of(Filter::Msm, Blur::Gauss9);
    assert_eq!(
        (msm.passes, msm.blur_taps, msm.bytes_per_texel),
        (3, 18, 2 * 16 + 4)
    );
    assert_eq!(of(Filter::Evsm2, Blur::None).passes, 1);
}

#[test]
fn bad_moment_settings_get_their_messages() {
    let dir = std::env::temp_dir().join(format!("shadowmap-moments-bad-{}", std::process::id()));
    for (flag, value, message) in [
        (
            "--bleed-reduction",
            "1",
            "error: --bleed-reduction: shadow.bleed_reduction = 1: expected 0 (off) to below 1",
        ),
        (
            "--evsm-exponents",
            "40,-5",
            "error: --evsm-exponents: shadow.evsm_exponents = [40.0, -5.0]: expected two numbers, \
             each above 0, at most 42 [positive, negative], like [40, 5] (exp(2 x 42) stays \
             inside 32-bit floats)",
        ),
        (
            "--msm-bias",
            "2",
            "error: --msm-bias: shadow.msm_bias = 2: expected 0 to 1 (3e-5 for [0, 1] depth)",
        ),
        (
            "--min-variance",
            "-1",
            "error: --min-variance: shadow.min_variance = -1: expected 0 to 0.25 (a depth in \
             [0, 1] varies at most 0.25)",
        ),
    ] {
        let out = common::bin()
            .args(["render", "--filter", "vsm", flag, value, "--out"])
            .arg(dir.join("x.png"))
            .output()
            .unwrap();
        assert!(!out.status.success(), "{flag} {value}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(stderr.trim(), message, "{flag} {value}");
    }
    assert!(!dir.exists());
}

#[test]
fn the_blur_scissored_to_the_casters_changes_no_pixel() {
    // The blur runs only over the casters' footprint in the map (the rest is the cleared far
    // moments, which a blur keeps). On the overlap scene with a floor that only receives,
    // the plates' outlines are the footprint's edges, and their shadows' edges are in view.
    // A small caster behind the camera, in the map's corner, grows the footprint to most of
    // the map (a blur as good as unscissored): where the camera looks, nothing may change.
    let ctx = common::context();
    let mut scene = overlap();
    scene.items[0].casts_shadows = false;
    let mut wide = scene.clone();
    let mut far_off = wide.items[1].clone();
    far_off.name = "far-off plate".into();
    far_off.position = glam::Vec3::new(-4.5, 0.0, 5.0);
    far_off.scale = glam::Vec3::splat(0.1);
    wide.items.push(far_off);
    let view = shadowmap::shadows::light_camera(&scene, 0, &scene.shadow);
    let area = |s: &Scene| {
        let f = shadowmap::shadows::moments::caster_footprint(
            s,
            &shadowmap::shadows::camera::fitted::item_world_boxes(s),
            0,
            &view,
            scene.shadow.map_size,
        )
        .unwrap();
        u64::from(f.width) * u64::from(f.height)
    };
    assert!(
        area(&wide) > 2 * area(&scene),
        "{} vs {}",
        area(&wide),
        area(&scene)
    );
    for filter in MOMENT_FILTERS {
        for blur in [
            shadowmap::settings::Blur::Playground3x3,
            shadowmap::settings::Blur::Gauss9,
        ] {
            let s = ShadowSettings {
                filter,
                blur,
                ..scene.shadow
            };
            let a = common::render(&ctx, &mut scene.clone(), &s, 320, 240);
            let b = common::render(&ctx, &mut wide.clone(), &s, 320, 240);
            let (va, vb) = (a.visibility.unwrap(), b.visibility.unwrap());
            let shadowed = va.iter().flatten().filter(|v| **v < 0.5).count();
            assert!(shadowed > 100, "{}: {shadowed}", filter.name());
            let changed = va.iter().zip(&vb).filter(|(x, y)| x != y).count();
            assert_eq!(
                changed,
                0,
                "{} {}: pixels changed",
                filter.name(),
                blur.name()
            );
        }
    }
}
