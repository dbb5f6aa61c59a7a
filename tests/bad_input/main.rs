//! Bad input, through the real binary: one clear error and a non-zero exit, never a panic, a
//! hang, a GL error or a black image. Every message must start with "error: ", name the file
//! (or the flag) and say what was expected; no output image may be written.
//!
//! Committed inputs live in tests/data/bad/ (each scene there can be tried by hand with
//! `shadowmap render --scene tests/data/bad/<case>.toml`); binary ones (PNGs, a binary OBJ) are
//! made here, in a folder under CARGO_TARGET_TMPDIR.

#[path = "../common/mod.rs"]
mod common;
mod flags;
mod models;
mod no_display;
mod ranges;
mod scene_files;
// FIFOs, links to /dev/zero: Unix files.
#[cfg(unix)]
mod unreadable;

use std::path::{Path, PathBuf};
use std::time::Duration;

/// No case may take longer than this (a hang is a failure).
const TIMEOUT: Duration = Duration::from_secs(120);

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bad")
        .join(name)
}

/// A fresh, empty folder for one case's generated files and output.
fn case_dir(case: &str) -> PathBuf {
    common::case_dir("bad_input", case)
}

use common::Run;

/// Runs the binary in `cwd` with a time limit; a hang kills it and fails the case.
fn run_in(case: &str, cwd: &Path, args: &[&str]) -> Run {
    common::run_binary(case, cwd, args, TIMEOUT)
}

/// `shadowmap render --scene <scene> --out <dir>/x.png --size 64x36 <extra>`.
fn render(case: &str, cwd: &Path, scene: &str, extra: &[&str]) -> (Run, PathBuf) {
    let dir = case_dir(case);
    let out = dir.join("x.png");
    let mut args = vec![
        "render",
        "--scene",
        scene,
        "--out",
        out.to_str().unwrap(),
        "--size",
        "64x36",
    ];
    args.extend_from_slice(extra);
    (run_in(case, cwd, &args), out)
}

/// Checks one bad-input run; returns a description of what is wrong, or None.
/// `needles`: everything stderr must contain (the file or flag, the line or field, and what
/// was expected).
fn check_error(case: &str, run: &Run, out: &Path, needles: &[&str]) -> Option<String> {
    let e = &run.stderr;
    // Shown with --nocapture: what the user sees for each case.
    println!("[{case}] {}", e.trim_end().replace('\n', " | "));
    let mut wrong = Vec::new();
    if run.success {
        wrong.push("exit status 0".to_string());
    }
    if e.contains("panicked") {
        wrong.push("panicked".to_string());
    }
    if !e.starts_with("error: ") {
        wrong.push("stderr does not start with \"error: \"".to_string());
    }
    for n in needles {
        if !e.contains(n) {
            wrong.push(format!("stderr lacks {n:?}"));
        }
    }
    if out.exists() {
        wrong.push(format!("{} was written", out.display()));
    }
    (!wrong.is_empty()).then(|| {
        format!(
            "[{case}] {}\n    stderr: {}\n    stdout: {}",
            wrong.join("; "),
            e.trim_end().replace('\n', "\n            "),
            run.stdout.trim_end()
        )
    })
}

/// A bad committed scene: stderr must name the scene file and contain every needle.
fn bad_scene(case: &str, scene: &str, needles: &[&str]) -> Option<String> {
    let path = data(scene);
    let (run, out) = render(case, Path::new("."), path.to_str().unwrap(), &[]);
    let mut all = vec![scene];
    all.extend_from_slice(needles);
    check_error(case, &run, &out, &all)
}

/// A bad scene written to a temporary folder with its generated files.
fn bad_generated(case: &str, files: &[(&str, &[u8])], needles: &[&str]) -> Option<String> {
    let dir = case_dir(&format!("{case}-input"));
    for (name, bytes) in files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let scene = dir.join("scene.toml");
    let (run, out) = render(case, Path::new("."), scene.to_str().unwrap(), &[]);
    let mut all = vec!["scene.toml"];
    all.extend_from_slice(needles);
    check_error(case, &run, &out, &all)
}

/// Fails with every broken case listed, so one run shows them all.
fn report(failures: Vec<Option<String>>) {
    let failures: Vec<String> = failures.into_iter().flatten().collect();
    assert!(
        failures.is_empty(),
        "{} case(s) failed:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

/// A successful render: exit 0, the image written, and something other than the clear colour
/// drawn at each of `pixels` (x, y from the top left of the 64 x 36 frame).
fn check_success(case: &str, run: &Run, out: &Path, pixels: &[(u32, u32)]) -> Option<String> {
    println!(
        "[{case}] exit {}: {}",
        if run.success { "0" } else { "non-zero" },
        run.stdout.trim_end()
    );
    if !run.success || run.stderr.contains("panicked") {
        return Some(format!(
            "[{case}] must succeed but failed\n    stderr: {}",
            run.stderr.trim_end()
        ));
    }
    let image = match image::open(out) {
        Ok(i) => i.to_rgba8(),
        Err(e) => return Some(format!("[{case}] {} not readable: {e}", out.display())),
    };
    if image.dimensions() != (64, 36) {
        return Some(format!(
            "[{case}] image is {:?}, not 64x36",
            image.dimensions()
        ));
    }
    for &(x, y) in pixels {
        let p = image.get_pixel(x, y).0;
        if p[0].max(p[1]).max(p[2]) < 40 {
            return Some(format!(
                "[{case}] pixel ({x}, {y}) is {p:?}: the model is not drawn there (black image?)"
            ));
        }
    }
    None
}
