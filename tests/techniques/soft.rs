//! Soft shadows against the area-light truth: PCSS hardens at contact as the
//! truth does and beats hard PCF on the DummyGame; with a light of no size every soft filter
//! agrees with the hard reference away from edges; every soft filter draws on every built-in
//! scene, or is refused with its reason.

use crate::common;

use common::{context, dummy};
use shadowmap::compare::{CompareOptions, Comparison};
use shadowmap::settings::{BiasMode, Filter, ShadowSettings};
use shadowmap::shadows::plan::{filter_refusal, ShadowPlan};
use shadowmap::Scene;

use crate::common::banded_options as opts;

/// `settings` with `filter` and LearnOpenGL's constant bias, 0.005: the book's 0.05 is a
/// world unit in the DummyGame's box, which detaches the cube's shadow from its lower half
/// (peter panning) whatever the filter.
fn with(settings: &ShadowSettings, filter: Filter) -> ShadowSettings {
    ShadowSettings {
        filter,
        bias_mode: BiasMode::Constant,
        bias: 0.005,
        ..*settings
    }
}

fn run(scene: &Scene, settings: &ShadowSettings, o: &CompareOptions) -> Comparison {
    common::compared(scene, settings, o)
}

#[test]
fn pcss_is_closer_to_the_area_light_than_hard_pcf_on_the_dummy_game() {
    let mut scene = dummy(45.0);
    scene.lights[0].set_size(5.0);
    let o = opts(640, 360, 1);
    let mae = |filter| {
        let c = run(&scene, &with(&scene.shadow, filter), &o);
        let a = c
            .area
            .expect("a light with a size is scored against its area truth");
        eprintln!("{}: {a:?}", filter.name());
        assert!(a.receivers > 50_000 && a.penumbra_edges > 100, "{a:?}");
        a.mae
    };
    let (pcss, pcf) = (mae(Filter::Pcss), mae(Filter::Pcf3x3));
    assert!(pcss < pcf, "PCSS's MAE {pcss} is not below pcf3x3's {pcf}");
}

/// Two thin slabs over a floor, 0.5 and 3 above it, under a 6-degree sun (the file says more).
const CONTACT: &str = include_str!("../data/contact.toml");

#[test]
fn pcss_hardens_at_contact_as_the_area_light_does() {
    let dir = std::env::temp_dir().join(format!("shadowmap-contact-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("contact.toml");
    std::fs::write(&path, CONTACT).unwrap();
    let scene = Scene::load(path.to_str().unwrap()).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let o = opts(640, 360, 1);
    // Mean 10%-90% widths (truth, image) of the edges under the low and the high slab.
    let widths = |filter| {
        let c = run(
            &scene,
            &ShadowSettings {
                filter,
                ..scene.shadow
            },
            &o,
        );
        let (low, high) = common::penumbra_widths_by_side(&c, 640, 360);
        eprintln!("{}: low {low:?}, high {high:?}", filter.name());
        (low, high)
    };
    let ((truth_low, pcss_low), (truth_high, pcss_high)) = widths(Filter::Pcss);
    // Measured: 1.14 and 5.58 px, 4.9 times wider under the high slab.
    let ratio = truth_high / truth_low;
    assert!(
        (4.0..6.0).contains(&ratio),
        "the truth: {truth_low} px under the low slab, {truth_high} px under the high one"
    );
    assert!(
        pcss_high > 3.0 * pcss_low,
        "PCSS: {pcss_low} px under the low slab, {pcss_high} px under the high one"
    );
    // Close to the truth's widths, within a third.
    for (pcss, truth) in [(pcss_low, truth_low), (pcss_high, truth_high)] {
        assert!(
            (pcss - truth).abs() < truth / 3.0,
            "PCSS {pcss} px, truth {truth} px"
        );
    }
    // A fixed kernel does not harden: hard PCF's edges are as wide under both slabs.
    let ((_, pcf_low), (_, pcf_high)) = widths(Filter::Pcf3x3);
    assert!(
        pcf_high < 1.5 * pcf_low.max(1.0),
        "pcf3x3: {pcf_low} px and {pcf_high} px"
    );
}

#[test]
fn with_a_light_of_no_size_every_soft_filter_agrees_with_the_hard_reference_off_edges() {
    let scene = dummy(45.0);
    assert_eq!(scene.lights[0].size(), 0.0);
    // Six pixels each side of an edge: the soft filters reach 1.5 texels (the weighted 4 x
    // 4), a texel here is about four pixels on the floor.
    let o = opts(640, 360, 6);
    for filter in Filter::SOFT {
        let c = run(&scene, &with(&scene.shadow, filter), &o);
        assert!(
            c.reference.area.is_none() && c.area.is_none(),
            "no area truth"
        );
        let m = &c.metrics;
        eprintln!("{}: {m:?}", filter.name());
        assert!(m.outside_band_receivers > 50_000, "{m:?}");
        assert!(
            m.misclassified_outside_band_rate < 2e-4,
            "{}: {:.4}% misclassified away from edges",
            filter.name(),
            m.misclassified_outside_band_rate * 100.0
        );
    }
}

/// The built-in scenes, as `--scene` names them.
const SCENES: [&str; 7] = [
    "dummy",
    "learnopengl",
    "slides",
    "playground",
    "point-shadows",
    "large",
    "three-lights",
];

#[test]
fn every_soft_filter_draws_on_every_built_in_scene_or_is_refused_with_its_reason() {
    let ctx = context();
    for name in SCENES {
        for cascades in [1, 4] {
            let mut scene = Scene::load(name).unwrap();
            for filter in Filter::SOFT {
                let settings = ShadowSettings {
                    filter,
                    cascades,
                    ..scene.shadow
                };
                // The first casting light a filter cannot serve: a point light's cube map
                // (any soft filter), the cascaded sun (PCSS and the Poisson disk).
                let kinds = ShadowPlan::decide(&scene.lights, &settings).kinds();
                use shadowmap::shadows::ShadowKind;
                let on_layers = [Filter::Pcss, Filter::Poisson, Filter::PoissonRotated];
                let refused = kinds.iter().position(|k| match k {
                    ShadowKind::Cube => true,
                    ShadowKind::Cascades => on_layers.contains(&filter),
                    _ => false,
                });
                let drawn = shadowmap::frame::render_frames(
                    ctx.gl(),
                    &mut scene,
                    &settings,
                    96,
                    54,
                    1,
                    Default::default(),
                );
                let case = format!("{name}, {cascades} cascade(s), {}", filter.name());
                match (refused, drawn) {
                    (None, Ok(_)) => {
                        shadowmap::engine::check::check_gl(ctx.gl(), &case)
                            .unwrap_or_else(|e| panic!("{case}: {e}"));
                    }
                    (Some(i), Err(e)) => {
                        let why =
                            filter_refusal(filter, kinds[i] == ShadowKind::Cube, true).unwrap();
                        assert_eq!(
                            e.to_string(),
                            format!(
                                "shadow.filter = {}: light {i} cannot use it: {why}",
                                filter.name()
                            ),
                            "{case}"
                        );
                    }
                    (None, Err(e)) => panic!("{case}: {e}"),
                    (Some(i), Ok(_)) => panic!("{case}: drawn, though light {i} cannot use it"),
                }
            }
        }
    }
}

#[test]
fn the_command_line_refuses_what_a_light_cannot_use_with_its_reason() {
    let dir = std::env::temp_dir().join(format!("shadowmap-soft-refused-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let cases: [(&[&str], &str); 4] = [
        (
            &["--scene", "point-shadows", "--filter", "soft-pcf"],
            "error: --filter: shadow.filter = soft-pcf: light 0 cannot use it: a point light's \
             cube map takes single, pcf3x3, pcf5x5, hw2x2 or hw3x3 (the soft filters read a 2D \
             map's texel grid)",
        ),
        (
            &["--scene", "large", "--cascades", "4", "--filter", "pcss"],
            "error: --filter: shadow.filter = pcss: light 0 cannot use it: cascades and caster \
             groups do not take pcss (its penumbra is measured in one light camera's \
             units, and each layer has its own box)",
        ),
        (
            &[
                "--scene",
                "learnopengl",
                "--caster-groups",
                "2",
                "--filter",
                "pcss",
            ],
            "error: --filter: shadow.filter = pcss: light 0 cannot use it: cascades and caster \
             groups do not take pcss (its penumbra is measured in one light camera's \
             units, and each layer has its own box)",
        ),
        (
            &["--scene", "dummy", "--light-size", "90"],
            "error: --light-size 90: expected an angular diameter in degrees (the sun: 0.53) \
             under 90 (0 = a point); the dummy scene has a directional light",
        ),
    ];
    for (args, message) in cases {
        let mut all = vec!["render"];
        all.extend_from_slice(args);
        all.extend_from_slice(&["--out", "x.png"]);
        let run = common::run_binary(message, &dir, &all, std::time::Duration::from_secs(60));
        assert!(!run.success, "{args:?} succeeded");
        assert_eq!(run.stderr.trim_end(), message, "{args:?}");
        assert!(!dir.join("x.png").exists(), "{args:?} wrote its image");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_bench_with_a_sized_light_has_the_soft_filters_as_a_series_scored_against_its_area_truth() {
    let dir = std::env::temp_dir().join(format!("shadowmap-soft-bench-{}", std::process::id()));
    let stdout = common::stdout_of(
        common::bin()
            .args([
                "bench",
                "--quick",
                "--frames",
                "2",
                "--warmup",
                "1",
                "--size",
                "160x90",
                "--light-size",
                "5",
                "--rays",
                "16",
                "--out-dir",
            ])
            .arg(&dir),
    );
    let csv = std::fs::read_to_string(dir.join("bench.csv")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // Every row against the area truth (16 rays), none empty.
    for row in &rows {
        assert_eq!(row[col("area_rays")], "16", "{row:?}");
        for name in ["area_mae", "light_bleed_rate", "penumbra_width_error_px"] {
            let v: f64 = row[col(name)].parse().unwrap();
            assert!(v.is_finite() && v >= 0.0, "{name} in {row:?}");
        }
    }
    // Against a 5-degree sun, PCSS's best row is closer to the truth than one lookup's.
    let best = |filter: &str| {
        rows.iter()
            .filter(|r| r[col("filter")] == filter && r[col("family")] != "volumes")
            .map(|r| r[col("area_mae")].parse::<f64>().unwrap())
            .fold(f64::INFINITY, f64::min)
    };
    assert!(
        best("pcss") < best("single"),
        "pcss {} single {}",
        best("pcss"),
        best("single")
    );
    // The soft filters, each a row of the "soft" series.
    let soft: Vec<Filter> = Filter::SOFT
        .into_iter()
        .chain(Filter::SOFT_MOMENTS)
        .collect();
    for &filter in &soft {
        assert!(
            rows.iter()
                .any(|r| r[col("family")] == "soft" && r[col("filter")] == filter.name()),
            "no {} row",
            filter.name()
        );
    }
    assert!(
        rows.iter()
            .all(|r| (r[col("family")] == "soft")
                == soft.iter().any(|f| f.name() == r[col("filter")]))
    );
    // Each states its lookups per fragment: 16 + 16 for PCSS by default.
    for (filter, lookups) in [
        ("single", "1"),
        ("pcf3x3", "9"),
        ("pcf4x4-weighted", "16"),
        ("soft-pcf", "16"),
        ("pcss", "32"),
        ("vssm", "50"),
        ("msm-soft", "50"),
    ] {
        // (Shadow volumes read no map: their row states 0. Caster groups read every layer.)
        for r in rows
            .iter()
            .filter(|r| r[col("filter")] == filter && r[col("family")] != "volumes")
        {
            let layers: u32 = match r[col("family")] {
                "groups" => r[col("caster_groups")].parse().unwrap(),
                _ => 1,
            };
            let expected = lookups.parse::<u32>().unwrap() * layers;
            assert_eq!(r[col("taps")], expected.to_string(), "{r:?}");
        }
    }
    // The table shows them, with the area figures' columns.
    assert!(stdout.contains("| MAE vs area light |"), "{stdout}");
    assert!(
        stdout.contains("pcss learnopengl-0.005 cull-none 24"),
        "{stdout}"
    );
}

#[test]
fn compare_writes_the_area_figures_for_a_sized_light_and_none_for_a_point() {
    let base = std::env::temp_dir().join(format!("shadowmap-soft-compare-{}", std::process::id()));
    for (size, sized) in [("4", true), ("0", false)] {
        let dir = base.join(size);
        let stdout = common::stdout_of(
            common::bin()
                .args([
                    "compare",
                    "--scene",
                    "dummy",
                    "--size",
                    "320x180",
                    "--supersample",
                    "1",
                    "--rays",
                    "8",
                    "--filter",
                    "pcss",
                    "--light-size",
                    size,
                    "--out-dir",
                ])
                .arg(&dir),
        );
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("metrics.json")).unwrap())
                .unwrap();
        let area = &json["area_light"];
        assert_eq!(json["light_size"].as_f64(), Some(size.parse().unwrap()));
        for file in ["reference-area.png", "error-area.png"] {
            assert_eq!(dir.join(file).exists(), sized, "{file} for size {size}");
        }
        assert_eq!(
            stdout.contains("against the area light (8 rays"),
            sized,
            "{stdout}"
        );
        match sized {
            true => {
                assert_eq!(area["rays"], 8);
                for key in [
                    "mae",
                    "light_bleed_rate",
                    "false_shadow_rate",
                    "penumbra_width_error_px",
                ] {
                    let v = area[key].as_f64().unwrap_or(f64::NAN);
                    assert!(v.is_finite() && v >= 0.0, "{key}: {area}");
                }
                // PCSS against the 4-degree sun's truth on the dummy: the book's bias detaches
                // the shadow a little (0.026 here); a blank or inverted map is far off.
                assert!(area["mae"].as_f64().unwrap_or(1.0) < 0.05, "{area}");
                assert!(area["penumbra_edges"].as_u64().unwrap_or(0) > 10, "{area}");
            }
            false => assert!(area.is_null(), "{area}"),
        }
    }
    std::fs::remove_dir_all(&base).unwrap();
}

/// The playground's bulb has its size, so `compare` scores a soft filter against the area
/// light by default; on a light of size 0 it says the truth is hard.
#[test]
fn compare_says_when_a_soft_filters_truth_is_hard() {
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("hard_truth");
    let compare_with = |scene: &str| {
        common::stdout_of(
            common::bin()
                .args([
                    "compare",
                    "--scene",
                    scene,
                    "--filter",
                    "pcss",
                    "--size",
                    "80x60",
                    "--rays",
                    "16",
                    "--out-dir",
                ])
                .arg(dir.join(scene)),
        )
    };
    let note = "note: --filter pcss softens edges, but the measured light has size 0";
    let playground = compare_with("playground");
    assert!(
        playground.contains("against the area light (16 rays per pixel)"),
        "{playground}"
    );
    assert!(!playground.contains(note), "{playground}");
    let dummy = compare_with("dummy");
    assert!(dummy.contains(note), "{dummy}");
    assert!(!dummy.contains("against the area light ("), "{dummy}");
}

#[test]
fn the_poisson_disk_is_closer_to_a_sized_light_than_one_lookup_and_its_turn_breaks_the_bands() {
    let mut scene = dummy(45.0);
    scene.lights[0].set_size(5.0);
    let o = opts(640, 360, 1);
    let c = |filter| run(&scene, &with(&scene.shadow, filter), &o);
    let (single, fixed, turned) = (
        c(Filter::Single),
        c(Filter::Poisson),
        c(Filter::PoissonRotated),
    );
    let mae = |c: &Comparison| c.area.as_ref().expect("an area truth").mae;
    eprintln!(
        "area MAE: single {}, poisson {}, poisson-rotated {}",
        mae(&single),
        mae(&fixed),
        mae(&turned)
    );
    for (name, c) in [("poisson", &fixed), ("poisson-rotated", &turned)] {
        assert!(
            mae(c) < mae(&single),
            "{name}'s MAE {} is not below one lookup's {}",
            mae(c),
            mae(&single)
        );
    }
    // The same taps turned per pixel: another picture within the edges' band alone.
    let m = (&fixed.metrics, &turned.metrics);
    eprintln!("{:?}\n{:?}", m.0, m.1);
    assert!(
        (m.0.misclassified_outside_band_rate - m.1.misclassified_outside_band_rate).abs() < 2e-4,
        "{m:?}"
    );
}
