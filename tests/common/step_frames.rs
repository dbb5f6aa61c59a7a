//! A step's frame as the demo draws it and as `render` draws it, to compare.

use std::path::{Path, PathBuf};

use shadowmap::{steps, Scene};

use super::{bin, stdout_of, window_stdout_of};

/// The share of pixels whose colour differs by more than 8 levels in any channel.
pub fn differing_share(a: &Path, b: &Path) -> f64 {
    let open = |p: &Path| {
        image::open(p)
            .unwrap_or_else(|e| panic!("{}: {e}", p.display()))
            .to_rgba8()
    };
    let (a, b) = (open(a), open(b));
    assert_eq!(a.dimensions(), b.dimensions());
    let differ = a
        .pixels()
        .zip(b.pixels())
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 8))
        .count();
    differ as f64 / f64::from(a.width() * a.height())
}

/// Every staged step (a step with a view of its own), by scene.
pub fn staged_steps() -> Vec<(&'static str, &'static str)> {
    let mut out = Vec::new();
    for name in steps::STAGED_SCENES {
        let scene = Scene::load(name).unwrap();
        for step in steps::of(&scene)
            .iter()
            .filter(|s| s.stage(&scene).is_some())
        {
            out.push((name, step.name));
        }
    }
    out
}

/// The demo's frame and render's of `step` on `scene`, in `dir`; `display`: whether the
/// demo opens a window (`--require-window`; else it runs without a display and renders
/// headless).
pub fn demo_and_render(dir: &Path, scene: &str, step: &str, display: bool) -> (PathBuf, PathBuf) {
    let (demo, render) = (
        dir.join(format!("{scene}-{step}-demo.png")),
        dir.join(format!("{scene}-{step}-render.png")),
    );
    let common = ["--scene", scene, "--step", step, "--size", "320x180"];
    let demo_cmd = || {
        let mut cmd = bin();
        cmd.arg("demo")
            .args(common)
            .args(["--no-hud", "--no-animation", "--exit-after-frames", "2"])
            .arg("--screenshot")
            .arg(&demo);
        match display {
            true => cmd.arg("--require-window"),
            false => cmd.env_remove("DISPLAY").env_remove("WAYLAND_DISPLAY"),
        };
        cmd
    };
    let out = match display {
        true => window_stdout_of(&mut demo_cmd()),
        false => stdout_of(&mut demo_cmd()),
    };
    // The fallback's frame where no display is asked for.
    assert_eq!(out.contains("No display for a window"), !display, "{out}");
    stdout_of(bin().arg("render").args(common).arg("--out").arg(&render));
    (demo, render)
}
