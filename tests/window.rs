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
            out.contains(&format!("swap included; window through {api} on X11)")),
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

/// The environment variable `.ci/run` sets for a platform test, or a failure that says how
/// to run the test (these tests must not pass by skipping).
fn required_env(name: &str, what: &str) -> String {
    std::env::var(name)
        .ok()
        .filter(|v| !v.is_empty())
        .unwrap_or_else(|| panic!("{name} is not set: {what} (see .ci/run)"))
}

/// `--size 640x360 --no-animation --no-hud`: the still DummyGame, for comparing platforms.
fn still_dummy(cmd: &mut std::process::Command) -> &mut std::process::Command {
    cmd.args(["--no-animation", "--no-hud", "--size", "640x360"])
}

/// The headless Linux frame of the still DummyGame (what every platform must draw).
fn linux_headless_dummy(dir: &std::path::Path) -> std::path::PathBuf {
    let path = dir.join("linux-headless.png");
    stdout_of(
        bin()
            .args(["render", "--size", "640x360", "--out"])
            .arg(&path),
    );
    path
}

/// Asserts that at most 1% of the pixels of `shot` differ from `reference`.
fn within_one_percent(what: &str, shot: &std::path::Path, reference: &std::path::Path) {
    let share = common::step_frames::differing_share(shot, reference);
    assert!(
        share <= 0.01,
        "{what}: {:.2}% of the pixels differ from {}",
        share * 100.0,
        reference.display()
    );
}

#[test]
#[ignore = "needs a Wayland compositor: .ci/run starts weston's headless backend"]
fn wayland_window_draws_the_frame_x11_and_headless_draw() {
    let socket = required_env(
        "SHADOWMAP_WAYLAND_DISPLAY",
        "the name of a Wayland compositor's socket, such as weston --backend=headless-backend.so",
    );
    let dir = display_and_dir("wayland");
    let headless = linux_headless_dummy(&dir);
    let x11 = dir.join("x11.png");
    let out = window_stdout_of(
        still_dummy(bin().args(["demo", "--require-window"]))
            .args(["--exit-after-frames", "5", "--screenshot"])
            .arg(&x11),
    );
    assert!(out.contains("window through GLX on X11)"), "{out}");
    let wayland = dir.join("wayland.png");
    let wayland_demo = |extra: &[&str]| {
        let mut cmd = bin();
        cmd.env_remove("DISPLAY")
            .env("WAYLAND_DISPLAY", &socket)
            .args(["demo", "--require-window"])
            .args(extra);
        cmd
    };
    let out = window_stdout_of(
        still_dummy(&mut wayland_demo(&[]))
            .args(["--exit-after-frames", "5", "--screenshot"])
            .arg(&wayland),
    );
    // The demo's own report: a Wayland window's EGL context, not X11 and not the fallback.
    assert!(out.contains("window through EGL on Wayland)"), "{out}");
    assert_eq!(load(&wayland).dimensions(), (640, 360));
    within_one_percent("the Wayland window", &wayland, &x11);
    within_one_percent("the Wayland window", &wayland, &headless);

    // GLX is X11's: on Wayland it is refused with the list of what there is.
    let refused = wayland_demo(&["--gl-api", "glx", "--exit-after-frames", "2"])
        .output()
        .unwrap();
    assert!(!refused.status.success());
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains(
            "--gl-api glx: a window on Wayland gets its OpenGL context through EGL; \
             expected one of: auto, egl"
        ),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// Runs the Windows build under Wine in `dir` (its relative paths are Windows paths there).
fn wine(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    let exe = required_env(
        "SHADOWMAP_WINDOWS_EXE",
        "the x86_64-pc-windows-gnu build of shadowmap.exe, run under wine",
    );
    std::process::Command::new("wine")
        .arg(&exe)
        .args(args)
        .current_dir(dir)
        .env("WINEDEBUG", "-all")
        .output()
        .unwrap_or_else(|e| panic!("cannot run wine {exe}: {e}"))
}

/// stdout of a successful run under Wine.
fn wine_stdout(dir: &std::path::Path, args: &[&str]) -> String {
    let out = wine(dir, args);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        out.status.success(),
        "wine {args:?}: {:?}\n{stderr}",
        out.status
    );
    assert!(!stderr.contains("panicked"), "{stderr}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
#[ignore = "needs Wine and an X display: .ci/run builds the Windows program and runs it"]
fn windows_build_under_wine_draws_the_linux_frame_through_wgl() {
    let dir = display_and_dir("wine");
    let headless = linux_headless_dummy(&dir);
    let still = ["--no-animation", "--no-hud", "--size", "640x360"];

    // The demo in a window: WGL (Wine hands it to the X server's GLX), 30 frames.
    let args = [&["demo", "--require-window"][..], &still[..]].concat();
    let args = [
        &args[..],
        &["--exit-after-frames", "30", "--screenshot", "demo.png"],
    ]
    .concat();
    let out = wine_stdout(&dir, &args);
    assert!(out.contains("window through WGL on Windows)"), "{out}");
    assert_eq!(load(&dir.join("demo.png")).dimensions(), (640, 360));
    within_one_percent("the demo under Wine", &dir.join("demo.png"), &headless);

    // Headless: an invisible window's context drawing into the program's own framebuffer.
    wine_stdout(
        &dir,
        &["render", "--size", "640x360", "--out", "render.png"],
    );
    within_one_percent("render under Wine", &dir.join("render.png"), &headless);

    // GLX is X11's: refused on Windows with the list of what there is.
    let out = wine(&dir, &["demo", "--require-window", "--gl-api", "glx"]);
    assert!(!out.status.success());
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains(
            "--gl-api glx: a window on Windows gets its OpenGL context through WGL or EGL; \
             expected one of: auto, wgl, egl"
        ),
        "{stderr}"
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
#[ignore = "needs an X display: .ci/run runs it under Xvfb"]
fn window_moves_along_a_path_by_frames_as_render_does() {
    let dir = display_and_dir("motion");
    let path = [
        "--scene",
        "dummy",
        "--size",
        "640x360",
        "--motion",
        "light-sweep",
    ];
    // Two runs of the window, however fast their frames came: the same picture.
    let shots: Vec<image::RgbaImage> = (0..2)
        .map(|run| {
            let shot = dir.join(format!("demo-{run}.png"));
            window_stdout_of(
                bin()
                    .args(["demo", "--require-window", "--no-hud"])
                    .args(path)
                    .args(["--exit-after-frames", "40", "--screenshot"])
                    .arg(&shot),
            );
            load(&shot)
        })
        .collect();
    assert!(shots[0] == shots[1], "two runs of 40 frames differ");
    // The 40th frame drawn is the path's frame 39, as `render --frames 40` draws it: nearer
    // it than the frames either side, and far from the same 40 frames without the path
    // (the cube spun alike, the light still).
    let render = |frames: &str, path: &[&str]| {
        let out = dir.join(format!("render-{frames}-{}.png", path.len()));
        stdout_of(
            bin()
                .arg("render")
                .args(path)
                .args(["--frames", frames, "--out"])
                .arg(&out),
        );
        mean_difference(&shots[0], &load(&out))
    };
    let (at, before, after) = (
        render("40", &path),
        render("36", &path),
        render("44", &path),
    );
    let still = render("40", &path[..4]);
    assert!(
        at < 1.0,
        "the window's frame 39 differs from render's by {at}"
    );
    assert!(
        at < before && at < after && at * 4.0 < still,
        "frame 39 {at}, 35 {before}, 43 {after}, without the path {still}"
    );
    std::fs::remove_dir_all(&dir).ok();
}
