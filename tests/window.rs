//! The demo in a real window. Needs an X display, so it is `#[ignore]`d here and run
//! explicitly under Xvfb by `.ci/run` (`cargo test --test window -- --ignored`).

mod common;

use common::{bin, hud_difference, stdout_of, window_stdout_of};

fn load(path: &std::path::Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// The mean absolute difference per channel of two images of the same size (0..255).
fn mean_difference(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let diff: u64 = a
        .as_raw()
        .iter()
        .zip(b.as_raw())
        .map(|(x, y)| u64::from(x.abs_diff(*y)))
        .sum();
    diff as f64 / a.as_raw().len() as f64
}

/// Fails unless there is a display (these tests must not pass by skipping), and makes a
/// fresh folder for the test's images.
fn display_and_dir(name: &str) -> std::path::PathBuf {
    assert!(
        std::env::var_os("DISPLAY").is_some(),
        "DISPLAY is not set: run this test under Xvfb (see .ci/run)"
    );
    let dir = std::env::temp_dir().join(format!("shadowmap-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_shows_the_scene_and_its_shadow() {
    let dir = display_and_dir("window");
    let shot = dir.join("window.png");
    let headless = dir.join("headless.png");

    let out = window_stdout_of(
        bin()
            .args([
                "demo",
                "--require-window",
                "--no-animation",
                "--no-hud",
                "--size",
                "640x360",
                "--exit-after-frames",
                "5",
            ])
            .arg("--screenshot")
            .arg(&shot),
    );
    // A scripted run reports its frame times as `render --frames` does: 4 after the first.
    assert!(
        out.contains("frame time over 4 frames after the first: median "),
        "{out}"
    );
    stdout_of(
        bin()
            .args(["render", "--size", "640x360", "--out"])
            .arg(&headless),
    );

    let win = load(&shot);
    let head = load(&headless);
    assert_eq!(
        win.dimensions(),
        (640, 360),
        "the window's framebuffer size"
    );

    // The scene: green cube, blue plane, and the plane's shadow (blue at ambient level only).
    let count = |f: &dyn Fn(&image::Rgba<u8>) -> bool| win.pixels().filter(|p| f(p)).count();
    let green = count(&|p| p[1] > 200 && p[0] < 50 && p[2] < 50);
    let lit_blue = count(&|p| p[2] > 200 && p[0] < 50 && p[1] < 50);
    let shadow = count(&|p| (50..110).contains(&p[2]) && p[0] < 30 && p[1] < 30);
    assert!(green > 20000, "cube pixels: {green}");
    assert!(lit_blue > 20000, "lit plane pixels: {lit_blue}");
    assert!(shadow > 2000, "shadow pixels: {shadow}");

    // The window draws the same frame as the headless path (same driver, same settings).
    let mean = mean_difference(&win, &head);
    assert!(
        mean < 1.0,
        "window and headless frames differ by {mean} per channel"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_survives_a_resize_storm_and_a_minimise() {
    let dir = display_and_dir("storm");
    let shot = dir.join("after-storm.png");
    let stdout = window_stdout_of(
        bin()
            .args([
                "demo",
                "--require-window",
                "--no-animation",
                "--size",
                "640x360",
                "--stress-window",
            ])
            .args(["--exit-after-frames", "40", "--screenshot"])
            .arg(&shot),
    );
    // Nothing was drawn while the window was 0 x 0, and drawing resumed after.
    assert!(
        stdout.contains("stress: 40 frames drawn, 5 redraws skipped while minimised"),
        "{stdout}"
    );
    let img = load(&shot);
    assert_eq!(img.dimensions(), (640, 360), "restored to its size");
    let count = |f: &dyn Fn(&image::Rgba<u8>) -> bool| img.pixels().filter(|p| f(p)).count();
    let green = count(&|p| p[1] > 200 && p[0] < 50 && p[2] < 50);
    let shadow = count(&|p| (50..110).contains(&p[2]) && p[0] < 30 && p[1] < 30);
    assert!(
        green > 20000 && shadow > 2000,
        "the scene after the storm: {green} cube, {shadow} shadow pixels"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_draws_several_lights_and_cascades_as_headless_does() {
    let dir = display_and_dir("lights");
    for (i, (name, extra)) in [
        ("three-lights", &[][..]),
        (
            "large",
            &["--cascades", "4", "--map-size", "1024", "--show-cascades"][..],
        ),
        // Shadow volumes need the window's stencil buffer.
        ("three-lights", &["--technique", "volumes"][..]),
    ]
    .into_iter()
    .enumerate()
    {
        let shot = dir.join(format!("{i}-{name}-window.png"));
        let headless = dir.join(format!("{i}-{name}-headless.png"));
        window_stdout_of(
            bin()
                .args([
                    "demo",
                    "--require-window",
                    "--no-animation",
                    "--no-hud",
                    "--scene",
                    name,
                    "--size",
                    "480x270",
                ])
                .args(extra)
                .args(["--exit-after-frames", "5", "--screenshot"])
                .arg(&shot),
        );
        stdout_of(
            bin()
                .args(["render", "--scene", name, "--size", "480x270"])
                .args(extra)
                .arg("--out")
                .arg(&headless),
        );
        let (win, head) = (load(&shot), load(&headless));
        assert_eq!(win.dimensions(), (480, 270), "{name}");
        let mean = mean_difference(&win, &head);
        assert!(mean < 1.0, "{name}: window and headless differ by {mean}");
        // Not a blank frame: many distinct colours (lights of three colours, tints).
        let colours: std::collections::HashSet<[u8; 3]> = win
            .pixels()
            .map(|p| [p[0] >> 3, p[1] >> 3, p[2] >> 3])
            .collect();
        assert!(colours.len() > 100, "{name}: {} colours", colours.len());
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_screenshots_carry_the_hud_in_the_top_left_corner() {
    let dir = display_and_dir("hud");
    let shot = |name: &str, extra: &[&str]| {
        let path = dir.join(name);
        window_stdout_of(
            bin()
                .args([
                    "demo",
                    "--require-window",
                    "--no-animation",
                    "--size",
                    "640x360",
                ])
                .args(extra)
                .args(["--exit-after-frames", "5", "--screenshot"])
                .arg(&path),
        );
        load(&path)
    };
    let with = shot("hud.png", &[]);
    let without = shot("no-hud.png", &["--no-hud"]);
    // Eight lines of 15-pixel text in a panel at (8, 8): inside 420 x 180.
    let d = hud_difference(&with, &without, (0, 0, 420, 180));
    assert_eq!(d.outside, 0, "the HUD drew outside its corner: {d:?}");
    assert!(d.inside > 3000, "too little of the HUD: {d:?}");
    assert!(d.glyphs > 800, "too few bright glyph pixels: {d:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_draws_the_shadow_map_inset_in_its_corner_as_headless_does() {
    let dir = display_and_dir("inset");
    let shot = |name: &str, extra: &[&str]| {
        let path = dir.join(name);
        window_stdout_of(
            bin()
                .args([
                    "demo",
                    "--require-window",
                    "--no-animation",
                    "--no-hud",
                    "--size",
                    "640x360",
                ])
                .args(extra)
                .args(["--exit-after-frames", "5", "--screenshot"])
                .arg(&path),
        );
        load(&path)
    };
    let with = shot("inset.png", &["--inset"]);
    let without = shot("plain.png", &[]);
    // 640 x 360: a 90-pixel square 8 pixels from the right and bottom edges.
    let inside = |x: u32, y: u32| (542..632).contains(&x) && (262..352).contains(&y);
    let (mut outside, mut changed) = (0, 0);
    for (x, y, p) in with.enumerate_pixels() {
        match (inside(x, y), p == without.get_pixel(x, y)) {
            (false, false) => outside += 1,
            (true, false) => changed += 1,
            _ => {}
        }
    }
    assert_eq!(outside, 0, "the inset drew outside its corner");
    assert!(changed > 6000, "only {changed} inset pixels differ");
    // The same picture as `render --inset`.
    let headless = dir.join("headless.png");
    stdout_of(
        bin()
            .args(["render", "--size", "640x360", "--inset", "--out"])
            .arg(&headless),
    );
    let mean = mean_difference(&with, &load(&headless));
    assert!(mean < 1.0, "window and headless insets differ by {mean}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_draws_the_same_frame_through_glx_and_through_egl() {
    // GLX is the default on X11 (its swap reaches the X server through shared
    // memory); EGL stays selectable. Both must draw the headless frame and say which they are.
    let dir = display_and_dir("gl-api");
    let headless = dir.join("headless.png");
    stdout_of(
        bin()
            .args(["render", "--scene", "learnopengl", "--size", "480x270"])
            .arg("--out")
            .arg(&headless),
    );
    let head = load(&headless);
    for (flag, api) in [("auto", "GLX"), ("glx", "GLX"), ("egl", "EGL")] {
        let shot = dir.join(format!("{flag}.png"));
        let out = window_stdout_of(
            bin()
                .args([
                    "demo",
                    "--require-window",
                    "--no-animation",
                    "--no-hud",
                    "--scene",
                    "learnopengl",
                ])
                .args(["--size", "480x270", "--gl-api", flag])
                .args(["--exit-after-frames", "5", "--screenshot"])
                .arg(&shot),
        );
        assert!(
            out.contains(&format!("swap included; window through {api})")),
            "--gl-api {flag}: {out}"
        );
        let win = load(&shot);
        assert_eq!(win.dimensions(), (480, 270), "--gl-api {flag}");
        let mean = mean_difference(&win, &head);
        assert!(
            mean < 1.0,
            "--gl-api {flag}: window and headless differ by {mean}"
        );
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_runs_the_configuration_target_error_chose_and_the_quality_preset() {
    let dir = display_and_dir("target");
    let shot = dir.join("window.png");
    let headless = dir.join("headless.png");
    let out = window_stdout_of(
        bin()
            .args([
                "demo",
                "--require-window",
                "--no-animation",
                "--no-hud",
                "--size",
                "160x90",
                "--target-error",
                "0.02",
                "--exit-after-frames",
                "3",
                "--screenshot",
            ])
            .arg(&shot),
    );
    let flags = out
        .lines()
        .find_map(|l| l.trim().strip_prefix("as flags: "))
        .unwrap_or_else(|| panic!("no choice printed: {out}"));
    // The window draws what the chosen flags draw headless.
    stdout_of(
        bin()
            .args(["render", "--size", "160x90"])
            .args(flags.split_whitespace())
            .arg("--out")
            .arg(&headless),
    );
    let mean = mean_difference(&load(&shot), &load(&headless));
    assert!(mean < 1.0, "window and headless differ by {mean} ({flags})");
    let out = window_stdout_of(bin().args([
        "demo",
        "--require-window",
        "--no-animation",
        "--size",
        "160x90",
        "--quality",
        "low",
        "--exit-after-frames",
        "2",
    ]));
    assert!(out.contains("quality low: map_size "), "{out}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn the_window_draws_each_staged_step_as_render_does() {
    use common::step_frames::{demo_and_render, differing_share, staged_steps};
    let dir = display_and_dir("window-steps");
    for (scene, step) in staged_steps() {
        let (demo, render) = demo_and_render(&dir, scene, step, true);
        let share = differing_share(&demo, &render);
        assert!(
            share <= 0.01,
            "{scene} {step}: {:.2}% of the window's pixels differ from render's",
            share * 100.0
        );
    }
}
