//! `scripts/gpu-figures.sh`, the run meant for a machine with a GPU, run here with `--quick`
//! on the driver the tests have (llvmpipe): every row it promises comes out with a finite
//! positive ratio, and the bench's CSVs and the runs' figures parse, so the script keeps
//! working while no GPU is at hand. Also the two things it reads from the binary: the GPU
//! pass times `render --frames N` prints, and `SHADOWMAP_INSTANCING=off`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::time::Instant;

/// The rows of `results-gpu.md` that must carry a ratio: every measurement the script
/// names, the bench's by scene.
const RENDER_ROWS: [&str; 12] = [
    "avsm, maps kept",
    "avsm, maps redrawn",
    "fom, maps kept",
    "fom, maps redrawn",
    "osm, maps kept",
    "osm, maps redrawn",
    "vssm vs pcf5x5, map redrawn",
    "msm-soft vs pcf5x5, map redrawn",
    "vssm vs pcss, map redrawn",
    "msm-soft vs pcss, map redrawn",
    "large --cascades 4, instanced vs one draw per item",
    "shadow cache, static frame (on vs off)",
];

/// The bench's rows present on every run (at a tutorial's error something at least as
/// accurate exists: the tutorial's own sweep row; `low` always has a pick).
fn bench_rows() -> Vec<String> {
    let mut rows = Vec::new();
    for scene in ["dummy", "learnopengl --view code"] {
        for tutorial in ["book", "learnopengl"] {
            rows.push(format!(
                "{scene}: at {tutorial}'s error or better, least GPU overhead"
            ));
        }
        rows.push(format!("{scene}: preset low"));
    }
    rows
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("scripts/gpu-figures.sh")
}

fn run_script(args: &[&str]) -> Output {
    Command::new("bash")
        .arg(script())
        .arg(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .output()
        .expect("bash runs the script")
}

/// The ratio cell (the second) of the row named `name`.
fn ratio_of(md: &str, name: &str) -> f64 {
    let start = format!("| {name} |");
    let line = md
        .lines()
        .find(|l| l.starts_with(&start))
        .unwrap_or_else(|| panic!("no row {name:?} in results-gpu.md:\n{md}"));
    let cell = line.split(" | ").nth(1).unwrap_or_default().trim();
    cell.parse()
        .unwrap_or_else(|_| panic!("row {name:?}: the ratio {cell:?} is not a number: {line}"))
}

/// A CSV file's rows as maps from its header's names, checking every row has every column.
fn csv_rows(path: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let mut reader = csv::Reader::from_path(path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let header: Vec<String> = reader.headers().unwrap().iter().map(String::from).collect();
    let rows: Vec<_> = reader
        .records()
        .map(|r| {
            let r = r.unwrap_or_else(|e| panic!("{path:?}: {e}"));
            header
                .iter()
                .cloned()
                .zip(r.iter().map(String::from))
                .collect()
        })
        .collect();
    assert!(!rows.is_empty(), "{path:?} has no rows");
    rows
}

fn number(row: &std::collections::HashMap<String, String>, column: &str) -> f64 {
    let cell = row
        .get(column)
        .unwrap_or_else(|| panic!("no column {column}"));
    cell.parse()
        .unwrap_or_else(|_| panic!("{column} = {cell:?} is not a number"))
}

#[test]
fn the_quick_run_writes_a_finite_positive_ratio_for_every_row() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("figures");
    let start = Instant::now();
    // The script bounds itself: past the limit it stops with an error naming the step.
    let run = run_script(&["--quick", "--out", out.to_str().unwrap(), "--limit", "300"]);
    let took = start.elapsed().as_secs_f64();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "the quick run failed:\n{stderr}");
    println!("scripts/gpu-figures.sh --quick took {took:.0} s");
    // A progress line a step, the last one the count of them all.
    assert!(stderr.contains("[1/"), "{stderr}");
    assert!(stderr.contains("wrote "), "{stderr}");

    let md = std::fs::read_to_string(out.join("results-gpu.md")).unwrap();
    let renderer = md
        .lines()
        .find_map(|l| l.strip_prefix("GL renderer: "))
        .unwrap_or_else(|| panic!("no renderer line:\n{md}"));
    assert!(renderer.contains("OpenGL"), "{renderer}");
    for name in RENDER_ROWS
        .iter()
        .map(|s| s.to_string())
        .chain(bench_rows())
    {
        let ratio = ratio_of(&md, &name);
        assert!(ratio.is_finite() && ratio > 0.0, "{name}: ratio {ratio}");
    }
    assert!(md.contains("The Pareto front of dummy"), "{md}");
    assert!(
        md.contains("against learnopengl ("),
        "the bench's own text: {md}"
    );

    for scene in ["dummy", "learnopengl"] {
        let rows = csv_rows(&out.join(format!("bench-{scene}.csv")));
        assert!(rows.iter().any(|r| r["tutorial"] == "learnopengl"));
        for r in &rows {
            for column in [
                "overhead_gpu_ms",
                "depth_gpu_ms_median",
                "scene_gpu_ms_median",
            ] {
                assert!(number(r, column).is_finite(), "{scene}: {column}");
            }
        }
        assert!(out.join(format!("bench-{scene}.md")).is_file());
    }
    // Every side of every round, each with its GPU and wall times.
    let runs = csv_rows(&out.join("runs.csv"));
    assert_eq!(runs.len(), 3 * 19, "3 rounds of 19 sides");
    for r in &runs {
        assert!(number(r, "wall_ms") > 0.0, "{r:?}");
        assert!(number(r, "gpu_frame_ms") >= 0.0, "{r:?}");
    }
    // Redrawn means drawn every frame, kept means kept.
    let side = |name: &str| runs.iter().find(|r| r["side"] == name).unwrap();
    assert_eq!(number(side("smoke/avsm-redrawn"), "translucent_kept"), 0.0);
    assert!(number(side("smoke/avsm-kept"), "translucent_kept") > 0.0);
}

#[test]
fn bad_arguments_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("never");
    let out = out.to_str().unwrap();
    for (args, says) in [
        (vec!["--quick"], "--out DIR is required"),
        (vec!["--out", out, "--rounds", "0"], "--rounds 0"),
        (vec!["--out", out, "--frames", "1"], "--frames 1"),
        (vec!["--out", out, "--size", "640"], "--size 640"),
        (vec!["--out", out, "--fast"], "unknown flag --fast"),
        (vec!["--out", out, "--limit", "soon"], "--limit soon"),
        (vec!["--out"], "--out needs a value"),
    ] {
        let run = run_script(&args);
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert!(!run.status.success(), "{args:?} was accepted");
        assert!(stderr.contains(says), "{args:?}: {stderr}");
        assert!(!Path::new(out).exists(), "{args:?} wrote {out}");
    }
    let run = Command::new("bash")
        .arg(script())
        .args(["/no/such/shadowmap", "--out", out])
        .output()
        .unwrap();
    assert!(!run.status.success());
    assert!(String::from_utf8_lossy(&run.stderr).contains("not an executable file"));
    assert!(!Path::new(out).exists());
    let help = Command::new("bash")
        .arg(script())
        .arg("--help")
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&help.stdout);
    assert!(help.status.success());
    for flag in [
        "--out DIR",
        "--quick",
        "--rounds",
        "--frames",
        "--size",
        "--limit",
    ] {
        assert!(text.contains(flag), "--help says nothing of {flag}: {text}");
    }
}

/// `GPU time over N frames after the first: median F ms a frame (depth passes D ms, scene
/// pass S ms), ...`: F, D and S.
fn gpu_line(stdout: &str) -> [f64; 3] {
    let line = stdout
        .lines()
        .find(|l| l.starts_with("GPU time over "))
        .unwrap_or_else(|| panic!("no GPU time line: {stdout}"));
    let after = |word: &str| -> f64 {
        let rest = &line[line.find(word).unwrap_or_else(|| panic!("{line}")) + word.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let times = [
        after("median "),
        after("depth passes "),
        after("scene pass "),
    ];
    assert!(times.iter().all(|t| t.is_finite() && *t >= 0.0), "{line}");
    assert!(line.contains("timer queries; "), "{line}");
    times
}

fn render(dir: &Path, name: &str, instancing: &str, args: &[&str]) -> (String, Vec<u8>) {
    let png = dir.join(format!("{name}.png"));
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .env("SHADOWMAP_INSTANCING", instancing)
        .arg("render")
        .args(args)
        .args(["--size", "160x90", "--frames", "3", "--out"])
        .arg(&png)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout).into_owned();
    (stdout, std::fs::read(&png).unwrap())
}

#[test]
fn render_prints_each_passes_gpu_time_and_instancing_off_draws_the_same_frame() {
    let dir = tempfile::tempdir().unwrap();
    let large = [
        "--scene",
        "large",
        "--cascades",
        "4",
        "--shadow-cache",
        "off",
    ];
    let (on, on_png) = render(dir.path(), "on", "on", &large);
    let (off, off_png) = render(dir.path(), "off", "off", &large);
    let [frame, depth, scene] = gpu_line(&on);
    assert!(depth > 0.0 && frame >= scene, "{on}");
    gpu_line(&off);
    assert!(!on.contains("instancing off"), "{on}");
    assert!(
        off.contains("instancing off (SHADOWMAP_INSTANCING=off)"),
        "{off}"
    );
    assert!(on_png == off_png, "one draw per item drew another picture");

    // The depth view has no scene pass: its query is never begun, and reads as 0.
    let (view, _) = render(
        dir.path(),
        "view",
        "on",
        &["--scene", "dummy", "--show-depth-map"],
    );
    let [_, depth, scene] = gpu_line(&view);
    assert_eq!(scene, 0.0, "{view}");
    assert!(depth > 0.0, "{view}");
}
