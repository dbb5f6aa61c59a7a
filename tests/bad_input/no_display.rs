//! The demo without a display: a headless picture instead, a bad `--screenshot` refused
//! first; and a short soak.

use std::path::Path;
use std::process::Command;

use crate::case_dir;

/// Runs the demo in `dir` with no display at all.
fn demo_without_display(dir: &Path, args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .current_dir(dir)
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap()
}

/// The fallback's one line, as `demo` prints it.
fn fallback_line(frames: &str, path: &Path, replacing: bool) -> String {
    format!(
        "No display for a window (DISPLAY and WAYLAND_DISPLAY are not set): rendered {frames} \
         of the dummy scene headless to {}{} instead. For a window, run under X11: \
         `apt-get install xvfb`, `Xvfb :99 &`, then `DISPLAY=:99 shadowmap`.\n",
        path.display(),
        if replacing {
            " (replacing the file there)"
        } else {
            ""
        }
    )
}

/// `--require-window` (the window tests pass it) refuses the headless fallback: with no
/// display, or a display with no X server behind it, the demo fails and writes nothing.
#[test]
fn require_window_refuses_the_fallback() {
    let dir = case_dir("require-window").canonicalize().unwrap();
    let args = [
        "demo",
        "--require-window",
        "--exit-after-frames",
        "2",
        "--size",
        "64x36",
    ];
    let out = demo_without_display(&dir, &args);
    assert!(!out.status.success());
    assert_eq!(String::from_utf8_lossy(&out.stdout), "");
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --require-window: no window (DISPLAY and WAYLAND_DISPLAY are not set); \
         nothing rendered\n"
    );
    // A display number no X server listens on.
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .current_dir(&dir)
        .env("DISPLAY", ":97")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --require-window: no window (the X server at DISPLAY=:97 refused the \
         connection); nothing rendered\n"
    );
    assert!(!dir.join("shadowmap-demo.png").exists());
}

#[test]
fn no_display_falls_back_to_a_headless_picture() {
    let dir = case_dir("no-display").canonicalize().unwrap();
    let demo_png = dir.join("shadowmap-demo.png");
    let out = demo_without_display(&dir, &[]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    // One line: no winit source path, nothing on standard error.
    assert_eq!(stdout, fallback_line("1 frame", &demo_png, false));
    assert_eq!(stderr, "");
    let png = std::fs::read(&demo_png).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let first = image::load_from_memory(&png).unwrap().to_rgba8();
    assert_eq!(
        first.dimensions(),
        (1280, 720),
        "the DummyGame's window size"
    );

    // Run again: the picture is replaced, and the line says so.
    let out = demo_without_display(&dir, &[]);
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("1 frame", &demo_png, true)
    );
}

#[test]
fn a_scripted_demo_without_display_renders_its_frames_headless_too() {
    // The same behaviour as `demo`: N frames headless, the last written to --screenshot.
    let dir = case_dir("no-display-scripted").canonicalize().unwrap();
    let shot = dir.join("shot.png");
    let out = demo_without_display(
        &dir,
        &[
            "demo",
            "--size",
            "64x36",
            "--exit-after-frames",
            "3",
            "--screenshot",
            "shot.png",
        ],
    );
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("3 frames", &shot, false)
    );
    let img = image::open(&shot).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (64, 36));
    // --screenshot is where it goes: the default picture is left alone.
    assert!(!dir.join("shadowmap-demo.png").exists());

    // Without --screenshot: the default picture, N frames.
    let out = demo_without_display(
        &dir,
        &["demo", "--size", "64x36", "--exit-after-frames", "2"],
    );
    assert!(out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stdout),
        fallback_line("2 frames", &dir.join("shadowmap-demo.png"), false)
    );
}

#[test]
fn a_bad_screenshot_path_is_refused_before_anything_opens() {
    let dir = case_dir("no-display-bad-shot");
    for (path, expected) in [
        (
            "missing/shot.png",
            "cannot write the image (given to --screenshot): the folder missing does not exist",
        ),
        (
            "shot.jpg",
            "cannot write .jpg images (given to --screenshot)",
        ),
    ] {
        let out = demo_without_display(
            &dir,
            &["demo", "--exit-after-frames", "2", "--screenshot", path],
        );
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert!(!out.status.success(), "{path}");
        assert!(stderr.starts_with(&format!("error: {path}: ")), "{stderr}");
        assert!(stderr.contains(expected), "{stderr}");
        assert_eq!(
            String::from_utf8_lossy(&out.stdout),
            "",
            "{path}: nothing rendered"
        );
        assert!(!dir.join("shadowmap-demo.png").exists());
    }
}

/// A short soak reports memory, and says truly how many frames it drew and when it took
/// its first figure (never a frame the run did not reach).
#[test]
fn a_short_soak_reports_memory_and_no_error() {
    for (frames, drawn, first) in [
        ("300", "300 frames", "after 100 frames"),
        ("50", "50 frames", "before the first frame"),
        ("1", "1 frame", "before the first frame"),
    ] {
        let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
            .args(["soak", "--frames", frames, "--size", "64x36"])
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        assert!(
            stdout.starts_with(&format!("soak: {drawn} of the dummy scene in ")),
            "{stdout}"
        );
        assert!(stdout.contains("no error; resident memory "), "{stdout}");
        assert!(
            stdout.contains(&format!(" MiB {first}, ")),
            "{frames}: {stdout}"
        );
        assert!(!stdout.contains("frame 100"), "{stdout}");
    }
}
