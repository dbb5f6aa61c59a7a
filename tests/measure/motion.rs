//! Motion paths (`--motion`) and the flicker `compare --motion` scores against the truth:
//! refusals before any work, a still path's exact zero, the stable techniques' figures,
//! the filters' energy order, and the pictures moving along the path.

use crate::common;

use common::{bin, stdout_of};

/// Runs the binary expecting a refusal; returns its standard error.
fn refused(args: &[&str]) -> String {
    let out = bin().args(args).output().expect("the binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(!out.status.success(), "{args:?} succeeded: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

fn metrics(dir: &std::path::Path) -> serde_json::Value {
    let text = std::fs::read_to_string(dir.join("metrics.json")).expect("metrics.json");
    serde_json::from_str(&text).expect("metrics.json is JSON")
}

#[test]
fn a_light_sweep_on_a_point_light_is_refused_before_any_file() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    let e = refused(&[
        "compare",
        "--scene",
        "point-shadows",
        "--motion",
        "light-sweep",
        "--out-dir",
        out.to_str().unwrap(),
    ]);
    assert!(e.contains("--motion light-sweep"), "{e}");
    assert!(e.contains("only a directional light has an angle"), "{e}");
    assert!(!out.exists(), "the folder was made before the refusal");
    let png = dir.path().join("frame.png");
    let e = refused(&[
        "render",
        "--scene",
        "point-shadows",
        "--motion",
        "light-sweep",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(e.contains("only a directional light has an angle"), "{e}");
    assert!(!png.exists());
}

#[test]
fn bad_paths_frames_and_steps_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    let out = out.to_str().unwrap();
    let e = refused(&[
        "compare",
        "--motion",
        "still",
        "--frames",
        "0",
        "--out-dir",
        out,
    ]);
    assert!(e.contains("'0'") && e.contains("--frames"), "{e}");
    // A light the scene lacks: refused before any work, nothing written.
    let e = refused(&[
        "compare",
        "--motion",
        "still",
        "--light",
        "5",
        "--out-dir",
        out,
    ]);
    assert!(e.starts_with("error: --light 5: the scene"), "{e}");
    assert!(!dir.path().join("cmp").exists());
    let e = refused(&["compare", "--motion", "wobble", "--out-dir", out]);
    assert!(e.contains("'wobble'") && e.contains("light-sweep"), "{e}");
    for step in ["nan", "inf", "-inf"] {
        let e = refused(&[
            "compare",
            "--motion",
            "strafe",
            "--motion-step",
            step,
            "--out-dir",
            out,
        ]);
        assert!(e.contains("expected a finite number"), "{step}: {e}");
    }
    let e = refused(&["render", "--motion-step", "0.1", "--out", "x.png"]);
    assert!(e.contains("--motion"), "{e}");
    let e = refused(&["compare", "--motion", "keyframes", "--out-dir", out]);
    assert!(e.contains("no [motion] keyframes"), "{e}");
    assert!(!dir.path().join("cmp").exists());
}

#[test]
fn a_still_path_flickers_exactly_zero() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("still");
    let stdout = stdout_of(bin().args([
        "compare",
        "--scene",
        "dummy",
        "--size",
        "160x90",
        "--supersample",
        "1",
        "--motion",
        "still",
        "--frames",
        "3",
        "--out-dir",
        out.to_str().unwrap(),
    ]));
    let line = "motion: 3 frames, still: flicker energy 0.0000 (beyond the truth's own steps \
                0.0000; the truth's own 0.0000); false flicker 0.000% of receivers a frame \
                (the truth's own change 0.000%)";
    assert!(stdout.contains(line), "{stdout}");
    let m = metrics(&out);
    assert_eq!(m["motion"]["energy"], 0.0);
    assert_eq!(m["motion"]["excess_energy"], 0.0);
    assert_eq!(m["motion"]["frames"][2]["energy"], 0.0);
    assert_eq!(m["motion"]["false_flicker"], 0.0);
    assert_eq!(m["motion"]["truth_change"], 0.0);
    assert_eq!(m["motion"]["frames"].as_array().unwrap().len(), 3);
    // The frames have their own error: the zero is not an empty comparison.
    assert!(m["motion"]["frames"][2]["misclassified"].as_f64().unwrap() > 0.0);
    assert!(m["motion"]["frames"][2]["matched"].as_u64().unwrap() > 1000);
    let apng = std::fs::read(out.join("motion-error.png")).unwrap();
    assert!(
        apng.windows(4).any(|w| w == b"acTL"),
        "motion-error.png is not animated"
    );
    assert!(out.join("motion-flicker.png").exists());
}

/// `compare --motion` over 4 frames at 320x180 (or the size `args` give): its `"motion"`.
fn motion_of(args: &[&str]) -> serde_json::Value {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    let mut all = vec!["compare", "--supersample", "1", "--frames", "4"];
    if !args.contains(&"--size") {
        all.extend(["--size", "320x180"]);
    }
    all.extend_from_slice(args);
    all.extend(["--out-dir", out.to_str().unwrap()]);
    stdout_of(bin().args(&all));
    metrics(&out)["motion"].clone()
}

fn figure(motion: &serde_json::Value, name: &str) -> f64 {
    motion[name]
        .as_f64()
        .unwrap_or_else(|| panic!("no {name}: {motion}"))
}

/// With `--snap on` the path flickers at most a quarter of what it does with `off`, which
/// must flicker (else there is nothing to hold still), by the energy and by the share.
fn snapping_holds_still(args: &[&str]) {
    let on = motion_of(&[args, &["--snap", "on"]].concat());
    let off = motion_of(&[args, &["--snap", "off"]].concat());
    for name in ["energy", "false_flicker"] {
        let (on, off) = (figure(&on, name), figure(&off, name));
        assert!(off > 0.0, "{args:?}: unsnapped, nothing flickered ({name})");
        assert!(
            on <= off / 4.0,
            "{args:?}: {name} snapped {on} against unsnapped {off}"
        );
    }
}

#[test]
fn snapped_cascades_strafing_flicker_at_most_a_quarter_of_unsnapped() {
    snapping_holds_still(&["--scene", "large", "--cascades", "4", "--motion", "strafe"]);
}

#[test]
fn a_snapped_fitted_box_dollying_flickers_at_most_a_quarter_of_unsnapped() {
    snapping_holds_still(&["--scene", "large", "--fit", "scene", "--motion", "dolly"]);
}

/// The energy and the excess energy of a light sweep under each filter, in the order given.
fn sweep_energies(scene: &[&str], filters: &[&str]) -> Vec<(f64, f64)> {
    let path = ["--motion", "light-sweep"];
    (filters.iter())
        .map(|f| motion_of(&[scene, &path, &["--filter", f]].concat()))
        .map(|m| (figure(&m, "energy"), figure(&m, "excess_energy")))
        .collect()
}

#[test]
fn on_the_light_sweep_each_filter_crawls_less_than_the_single_lookup_and_5x5_less_than_3x3() {
    // At the scene's own size, where a pixel is about a texel (at a quarter of it a filter's
    // ramp is within a pixel and every filter draws nearly the single lookup's step).
    let filters = ["single", "hw2x2", "pcf3x3", "pcf5x5"];
    let e = sweep_energies(&["--scene", "dummy", "--size", "1280x720"], &filters);
    let shown = || format!("{:?}", filters.iter().zip(&e).collect::<Vec<_>>());
    for figure in [|e: &(f64, f64)| e.0, |e: &(f64, f64)| e.1] {
        let e: Vec<f64> = e.iter().map(figure).collect();
        assert!(e[0] > 0.0, "{}", shown());
        for i in 1..4 {
            assert!(
                e[i] < e[0],
                "{} above the single lookup: {}",
                filters[i],
                shown()
            );
        }
        assert!(e[3] < e[2], "5x5 not below 3x3: {}", shown());
    }
}

#[test]
fn against_the_area_light_the_soft_filters_crawl_less_than_a_hard_lookup() {
    // The penumbra's spot rises about its target; the hard lookup's edge jumps where the
    // soft truth's changes little.
    let scene = ["--scene", "penumbra", "--size", "320x240"];
    let e = sweep_energies(&scene, &["single", "pcss", "vssm"]);
    assert!(e[1].0 < e[0].0 / 2.0 && e[2].0 < e[0].0 / 2.0, "{e:?}");
}

#[test]
fn render_moves_along_the_path() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("f.png");
    let stdout = stdout_of(bin().args([
        "render",
        "--size",
        "64x36",
        "--motion",
        "strafe",
        "--frames",
        "3",
        "--out",
        png.to_str().unwrap(),
    ]));
    assert!(
        stdout.contains("motion: strafe, 0.05 world units a frame; the image is frame 2"),
        "{stdout}"
    );
}

/// The pixels of a PNG.
fn pixels(path: &std::path::Path) -> Vec<u8> {
    let image = image::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    image.to_rgba8().into_raw()
}

/// What `render` of the dummy at 320x180 with `args` wrote to `--shadow-out`.
fn shadow_of(args: &[&str]) -> Vec<u8> {
    let dir = tempfile::tempdir().unwrap();
    let (png, shadow) = (dir.path().join("f.png"), dir.path().join("s.png"));
    stdout_of(
        bin()
            .args(["render", "--scene", "dummy", "--size", "320x180"])
            .args(args)
            .arg("--out")
            .arg(&png)
            .arg("--shadow-out")
            .arg(&shadow),
    );
    pixels(&shadow)
}

#[test]
fn a_light_sweeps_last_frame_is_the_scene_at_that_angle() {
    // 40 frames of 0.5 degrees from the scene's 45: the shadows at 64.5 degrees (the cube
    // spun alike over the 40 frames), not at 45.
    let swept = shadow_of(&["--motion", "light-sweep", "--frames", "40"]);
    let at = |angle| shadow_of(&["--light-angle", angle, "--frames", "40"]);
    assert!(
        swept == at("64.5"),
        "frame 39 of the sweep is not the light at 64.5"
    );
    assert!(swept != at("45"), "the sweep did not move the shadows");
}

#[test]
fn the_demo_without_a_display_draws_the_paths_frame_as_render_does() {
    let dir = tempfile::tempdir().unwrap();
    let (shot, frame) = (dir.path().join("demo.png"), dir.path().join("render.png"));
    let common = [
        "--scene",
        "dummy",
        "--size",
        "320x180",
        "--motion",
        "light-sweep",
    ];
    let out = stdout_of(
        bin()
            .env_remove("DISPLAY")
            .env_remove("WAYLAND_DISPLAY")
            .arg("demo")
            .args(common)
            .args(["--no-hud", "--exit-after-frames", "40", "--screenshot"])
            .arg(&shot),
    );
    assert!(out.contains("No display for a window"), "{out}");
    stdout_of(
        bin()
            .arg("render")
            .args(common)
            .args(["--frames", "40", "--out"])
            .arg(&frame),
    );
    assert!(
        pixels(&shot) == pixels(&frame),
        "the demo's frame 39 is not render's"
    );
    // The same 40 frames without the path (the cube spun alike): the light did move.
    let still = dir.path().join("still.png");
    stdout_of(
        bin()
            .args([
                "render", "--scene", "dummy", "--size", "320x180", "--frames", "40",
            ])
            .arg("--out")
            .arg(&still),
    );
    assert!(
        pixels(&shot) != pixels(&still),
        "the demo's path did not move"
    );
}

#[test]
fn bench_gains_a_false_flicker_column_with_motion() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("bench");
    stdout_of(bin().args([
        "bench",
        "--quick",
        "--scene",
        "dummy",
        "--size",
        "160x90",
        "--frames",
        "1",
        "--warmup",
        "0",
        "--supersample",
        "1",
        "--motion",
        "light-sweep",
        "--motion-frames",
        "3",
        "--out-dir",
        out.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(out.join("bench.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(text.as_bytes());
    let header = rows.headers().unwrap().clone();
    let at = |name: &str| header.iter().position(|h| h == name).unwrap();
    let (flicker, family, energy) = (at("false_flicker"), at("family"), at("flicker_energy"));
    let rows: Vec<csv::StringRecord> = rows.records().map(|r| r.unwrap()).collect();
    let of = |r: &csv::StringRecord| r[flicker].parse::<f64>().unwrap();
    let energy_of = |r: &csv::StringRecord| r[energy].parse::<f64>().unwrap();
    // The stencil volumes are exact: they flip exactly where the truth does.
    let volumes = rows.iter().find(|r| r[family].contains("volume")).unwrap();
    assert_eq!(of(volumes), 0.0);
    assert_eq!(energy_of(volumes), 0.0);
    assert!(
        rows.iter().any(|r| of(r) > 0.0 && energy_of(r) > 0.0),
        "no map flickered on the sweep"
    );
    let table = std::fs::read_to_string(out.join("bench.md")).unwrap();
    assert!(
        table.contains("flicker energy") && table.contains("false flicker a frame"),
        "{table}"
    );
}

#[test]
fn scene_file_keyframes_out_of_order_are_refused_by_field() {
    let dir = tempfile::tempdir().unwrap();
    let scene = dir.path().join("k.toml");
    std::fs::write(
        &scene,
        "[light]\nangle = 45.0\n[[item]]\nmesh = \"cube\"\n[motion]\n\
         keyframes = [{ frame = 5 }, { frame = 2 }]\n",
    )
    .unwrap();
    let png = dir.path().join("k.png");
    let e = refused(&[
        "render",
        "--scene",
        scene.to_str().unwrap(),
        "--motion",
        "keyframes",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(
        e.contains(
            "motion.keyframes[1].frame: 2: expected a frame after the previous keyframe's 5"
        ),
        "{e}"
    );
    assert!(!png.exists());
}
