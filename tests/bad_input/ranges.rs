//! Numbers outside their setting's range, from a flag and from a scene file alike: one
//! message naming the flag (or the file and field), the value and the range, and no image.
//! Settings that must be ordered (the slope bias' floor under its ceiling) are checked as a
//! pair; a map the driver cannot hold is refused with its memory; `compare --motion` needs
//! a pair of frames. And the other side: every value the program itself gives (the built-in
//! scenes, their steps, the presets, the bench's configurations) is within its range, so
//! a built-in value outside a range means the range is wrong.

use std::collections::BTreeMap;
use std::path::Path;

use shadowmap::measure::bench::{sweep, BiasPreset};
use shadowmap::settings::ShadowPatch;
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::{Scene, ShadowSettings};

use crate::{bad_generated, case_dir, check_error, report, run_in};

/// `shadowmap render --out <tmp>/x.png --size 64x36 <extra>`, checked as bad input.
fn bad_flags(case: &str, extra: &[&str], needles: &[&str]) -> Option<String> {
    let out = case_dir(case).join("x.png");
    let mut args = vec!["render", "--out", out.to_str().unwrap(), "--size", "64x36"];
    args.extend_from_slice(extra);
    let run = run_in(case, Path::new("."), &args);
    check_error(case, &run, &out, needles)
}

/// A scene of the DummyGame's light with `tables` after it, checked as bad input.
fn bad_tables(case: &str, tables: &str, needles: &[&str]) -> Option<String> {
    let text = format!("[light]\nangle = 45.0\n\n{tables}");
    bad_generated(case, &[("scene.toml", text.as_bytes())], needles)
}

const SLOPE_PAIR: &str = "shadow.bias_min = 0.5 is above shadow.bias = 0.001 with \
                          shadow.bias_mode = slope";

#[test]
fn numbers_outside_their_range_are_refused_from_flags_and_files_alike() {
    report(vec![
        bad_flags(
            "--bias 7",
            &["--bias", "7"],
            &["error: --bias: shadow.bias = 7: expected 0 to 1"],
        ),
        bad_flags(
            "--bias 1e30",
            &["--bias", "1e30"],
            &["--bias: shadow.bias = 1000000000000000000000000000000: expected 0 to 1"],
        ),
        bad_flags(
            "--normal-offset 1e9",
            &["--normal-offset", "1e9"],
            &["--normal-offset: shadow.normal_offset = 1000000000: expected 0 (off) to 16"],
        ),
        bad_flags(
            "--polygon-offset 1e9,4",
            &["--polygon-offset", "1e9,4"],
            &[
                "--polygon-offset: shadow.polygon_offset = [1000000000.0, 4.0]: expected two \
               numbers, each -1000 to 1000 [factor, units]",
            ],
        ),
        bad_flags(
            "--evsm-exponents 50,5",
            &["--filter", "evsm2", "--evsm-exponents", "50,5"],
            &[
                "--evsm-exponents: shadow.evsm_exponents = [50.0, 5.0]: expected two numbers, \
               each above 0, at most 42",
            ],
        ),
        bad_flags(
            "--min-variance 1",
            &["--filter", "vsm", "--min-variance", "1"],
            &["--min-variance: shadow.min_variance = 1: expected 0 to 0.25"],
        ),
        bad_flags(
            "--light-size 1e9 on a spot",
            &["--scene", "penumbra", "--light-size", "1e9"],
            &["--light-size 1000000000: expected a radius in world units >= 0 and under 1000"],
        ),
        bad_tables(
            "[shadow] bias = 7",
            "[shadow]\nbias = 7.0\n",
            &["scene.toml: shadow.bias = 7: expected 0 to 1"],
        ),
        bad_tables(
            "[shadow] bias = 1e30",
            "[shadow]\nbias = 1e30\n",
            &["scene.toml: shadow.bias = 1000000000000000000000000000000: expected 0 to 1"],
        ),
        bad_tables(
            "[shadow] normal_offset = 1e9",
            "[shadow]\nnormal_offset = 1e9\n",
            &["scene.toml: shadow.normal_offset = 1000000000: expected 0 (off) to 16"],
        ),
        bad_tables(
            "[light.shadow] bias = 7",
            "[light.shadow]\nbias = 7.0\n",
            &["light.shadow: shadow.bias = 7: expected 0 to 1"],
        ),
        bad_tables(
            "[steps] bias = 7",
            "[steps]\nbias = 7.0\n",
            &["steps.bias: 7: expected 0 to 1"],
        ),
    ]);
}

#[test]
fn a_slope_bias_floor_above_its_ceiling_is_refused_naming_both() {
    let expected = "expected bias_min from 0 to 0.001, or bias from 0.5 to 1";
    report(vec![
        bad_flags(
            "--bias-mode slope --bias 0.001 --bias-min 0.5",
            &[
                "--bias-mode",
                "slope",
                "--bias",
                "0.001",
                "--bias-min",
                "0.5",
            ],
            &[
                "error: --bias-min, --bias and --bias-mode: ",
                SLOPE_PAIR,
                expected,
            ],
        ),
        // Only the ceiling given: the floor is the default's, the flags are still named.
        bad_flags(
            "--bias-mode slope --bias 0.001",
            &["--bias-mode", "slope", "--bias", "0.001"],
            &[
                "error: --bias and --bias-mode: shadow.bias_min = 0.005 is above shadow.bias \
                 = 0.001",
                "expected bias_min from 0 to 0.001, or bias from 0.005 to 1",
            ],
        ),
        bad_tables(
            "[shadow] slope bias 0.5..0.001",
            "[shadow]\nbias_mode = \"slope\"\nbias = 0.001\nbias_min = 0.5\n",
            &["scene.toml: ", SLOPE_PAIR, expected],
        ),
        bad_tables(
            "[light.shadow] slope bias 0.5..0.001",
            "[light.shadow]\nbias_mode = \"slope\"\nbias = 0.001\nbias_min = 0.5\n",
            &["light.shadow: ", SLOPE_PAIR, expected],
        ),
    ]);
}

#[test]
fn the_help_states_each_range() {
    let run = run_in("render --help", Path::new("."), &["render", "--help"]);
    assert!(run.success, "{}", run.stderr);
    // Each flag's help, from its name to the next flag.
    let help_of = |flag: &str| -> String {
        let start = run
            .stdout
            .find(&format!("      {flag} <"))
            .unwrap_or_else(|| panic!("{flag} missing from the help"));
        let rest = &run.stdout[start + flag.len() + 6..];
        let end = rest.find("\n      --").unwrap_or(rest.len());
        rest[..end].split_whitespace().collect::<Vec<_>>().join(" ")
    };
    for (flag, range) in [
        ("--bias", "[range: 0 to 1]"),
        ("--bias-min", "[range: 0 to 1]"),
        ("--normal-offset", "[range: 0 (off) to 16 (texels)]"),
        ("--cascades", "[range: 1 (one map) to 4]"),
        ("--min-variance", "[range: 0 to 0.25"),
        (
            "--polygon-offset",
            "[range: two numbers, each -1000 to 1000",
        ),
        (
            "--evsm-exponents",
            "[range: two numbers, each above 0, at most 42",
        ),
        ("--perspective-fov", "[range: degrees between 0 and 180]"),
        ("--pcss-filter-taps", "[range: 1 to 32"),
    ] {
        let help = help_of(flag);
        assert!(help.contains(range), "{flag}: {help}");
    }
}

#[test]
fn compare_motion_refuses_a_single_frame() {
    let case = "compare --motion --frames 1";
    let dir = case_dir(case).join("out");
    let args = [
        "compare",
        "--motion",
        "strafe",
        "--frames",
        "1",
        "--size",
        "64x36",
        "--out-dir",
    ];
    let mut args: Vec<&str> = args.to_vec();
    args.push(dir.to_str().unwrap());
    let run = run_in(case, Path::new("."), &args);
    report(vec![check_error(
        case,
        &run,
        &dir,
        &[
            "error: --frames 1: compare --motion scores the change between consecutive \
           frames, and 1 frame has no pair; expected at least 2",
        ],
    )]);
}

/// Whether the tests' driver is Mesa's llvmpipe, whose textures hold at most 1 GiB.
fn on_llvmpipe() -> bool {
    let ctx = shadowmap::engine::HeadlessContext::new()
        .unwrap_or_else(|e| panic!("headless EGL context: {e}"));
    shadowmap::engine::check::renderer_name(ctx.gl()).contains("llvmpipe")
}

#[test]
fn a_map_beyond_the_drivers_memory_says_how_much_it_needs() {
    let llvmpipe = on_llvmpipe();
    // On llvmpipe, what it does make is suggested with its memory.
    let suggestion = "expected a smaller map, like shadow.map_size = 8192 (1 GiB, which the \
                      driver makes)";
    let cascades: &[&str] = &[
        "error: --map-size and --cascades: shadow.map_size = 16384: light 0's map \
         (shadow.cascades = 4 layers of 16384 x 16384) needs 4 GiB of GPU memory",
        "within its GL_MAX_TEXTURE_SIZE of ",
        "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT",
        if llvmpipe { suggestion } else { "" },
    ];
    let cases: [(&str, &[&str], &[&str]); 2] = [
        (
            "4 cascades of 16384",
            &["--scene", "large", "--cascades", "4", "--map-size", "16384"],
            cascades,
        ),
        (
            "a cube of 8192",
            &["--scene", "point-shadows", "--map-size", "8192"],
            &[
                "error: --map-size: shadow.map_size = 8192: light 0's map (a cube of six 8192 x \
               8192 faces) needs 1.5 GiB of GPU memory",
            ],
        ),
    ];
    let mut failures = Vec::new();
    for (case, extra, needles) in cases {
        let out = case_dir(case).join("x.png");
        let mut args = vec!["render", "--out", out.to_str().unwrap(), "--size", "64x36"];
        args.extend_from_slice(extra);
        let run = run_in(case, Path::new("."), &args);
        // A driver with the memory draws it; llvmpipe (at most 1 GiB a texture) cannot,
        // and where any driver refuses, the refusal must say why.
        if llvmpipe || !run.success {
            failures.push(check_error(case, &run, &out, needles));
        }
    }
    report(failures);
}

/// Checks `s`, and each light's own settings over it, against every range and order.
fn check_within(scene: &Scene, s: &ShadowSettings, what: &str) {
    s.validate_values()
        .unwrap_or_else(|e| panic!("{what}: {e}"));
    let plan = ShadowPlan::decide(&scene.lights, s);
    for (i, light) in plan.lights.iter().enumerate() {
        light
            .settings
            .validate_values()
            .unwrap_or_else(|e| panic!("{what}, light {i}'s own table: {e}"));
    }
}

#[test]
fn every_built_in_value_is_within_its_range() {
    let presets: BTreeMap<String, ShadowPatch> =
        toml::from_str(include_str!("../../assets/quality.toml")).unwrap();
    assert_eq!(presets.len(), 3, "{:?}", presets.keys());
    let mut checked = 0;
    for name in Scene::builtin_names() {
        // Loading checks the file's tables as a user's file is checked.
        let scene = Scene::load(name).unwrap_or_else(|e| panic!("{name}: {e}"));
        check_within(&scene, &scene.shadow, name);
        for step in shadowmap::steps::of(&scene) {
            let s = shadowmap::steps::settings_for(&scene, step.name).unwrap();
            check_within(&scene, &s, &format!("{name}, --step {}", step.name));
            checked += 1;
        }
        for (preset, patch) in &presets {
            let mut s = scene.shadow;
            patch.apply_to(&mut s);
            check_within(&scene, &s, &format!("{name}, --quality {preset}"));
        }
        for preset in BiasPreset::ALL {
            let mut s = scene.shadow;
            preset.apply(&mut s);
            check_within(
                &scene,
                &s,
                &format!("{name}, bias preset {}", preset.name()),
            );
        }
        for quick in [true, false] {
            for config in sweep(&scene.shadow, quick, 16384, &scene.lights[0]) {
                let what = format!("{name}, bench configuration {}", config.settings.summary());
                check_within(&scene, &config.settings, &what);
                checked += 1;
            }
        }
    }
    assert!(checked > 100, "only {checked} steps and configurations");
}
