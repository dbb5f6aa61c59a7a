//! Motion paths (`--motion`) and the false flicker `compare --motion` scores against the
//! truth: refusals before any work, a still path's exact zero, and the stable techniques'
//! figures.

mod common;

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
    let line = "motion: 3 frames, still: false flicker 0.000% of receivers a frame (the \
                truth's own change 0.000%)";
    assert!(stdout.contains(line), "{stdout}");
    let m = metrics(&out);
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

fn false_flicker(args: &[&str]) -> f64 {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("cmp");
    let mut all = vec![
        "compare",
        "--supersample",
        "1",
        "--frames",
        "4",
        "--size",
        "320x180",
    ];
    all.extend_from_slice(args);
    all.extend(["--out-dir", out.to_str().unwrap()]);
    stdout_of(bin().args(&all));
    metrics(&out)["motion"]["false_flicker"].as_f64().unwrap()
}

/// With `--snap on` the path flickers at most a quarter of what it does with `off`, which
/// must flicker (else there is nothing to hold still).
fn snapping_holds_still(args: &[&str]) {
    let on = false_flicker(&[args, &["--snap", "on"]].concat());
    let off = false_flicker(&[args, &["--snap", "off"]].concat());
    assert!(off > 0.0, "{args:?}: unsnapped, nothing flickered");
    assert!(
        on <= off / 4.0,
        "{args:?}: snapped {on} against unsnapped {off}"
    );
}

#[test]
fn snapped_cascades_strafing_flicker_at_most_a_quarter_of_unsnapped() {
    snapping_holds_still(&["--scene", "large", "--cascades", "4", "--motion", "strafe"]);
}

#[test]
fn a_snapped_fitted_box_dollying_flickers_at_most_a_quarter_of_unsnapped() {
    snapping_holds_still(&["--scene", "large", "--fit", "scene", "--motion", "dolly"]);
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
    let (flicker, family) = (at("false_flicker"), at("family"));
    let rows: Vec<csv::StringRecord> = rows.records().map(|r| r.unwrap()).collect();
    let of = |r: &csv::StringRecord| r[flicker].parse::<f64>().unwrap();
    // The stencil volumes are exact: they flip exactly where the truth does.
    let volumes = rows.iter().find(|r| r[family].contains("volume")).unwrap();
    assert_eq!(of(volumes), 0.0);
    assert!(
        rows.iter().any(|r| of(r) > 0.0),
        "no map flickered on the sweep"
    );
    assert!(std::fs::read_to_string(out.join("bench.md"))
        .unwrap()
        .contains("false flicker a frame"));
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
