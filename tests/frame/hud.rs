//! `shadowmap render --hud`: the HUD lands in the frame's top-left corner and nowhere else,
//! and the other outputs are the same with it as without.

use crate::common;

use common::{bin, hud_difference, stdout_of};

fn load(path: &std::path::Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

#[test]
fn render_hud_changes_only_its_corner() {
    let dir = std::env::temp_dir().join(format!("shadowmap-hud-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |name: &str, hud: bool| {
        let (out, shadow) = (
            dir.join(format!("{name}.png")),
            dir.join(format!("{name}-vis.png")),
        );
        let mut cmd = bin();
        cmd.args(["render", "--size", "640x360", "--frames", "2", "--out"])
            .arg(&out)
            .arg("--shadow-out")
            .arg(&shadow);
        if hud {
            cmd.arg("--hud");
        }
        stdout_of(&mut cmd);
        (load(&out), load(&shadow))
    };
    let (with, with_vis) = render("hud", true);
    let (without, without_vis) = render("plain", false);
    let d = hud_difference(&with, &without, (0, 0, 420, 160));
    assert_eq!(d.outside, 0, "the HUD drew outside its corner: {d:?}");
    assert!(d.inside > 3000, "too little of the HUD: {d:?}");
    assert!(d.glyphs > 800, "too few bright glyph pixels: {d:?}");
    // The text writes colour only: the shadow test's output is untouched under it.
    assert!(
        with_vis == without_vis,
        "--hud changed the visibility image"
    );
    std::fs::remove_dir_all(&dir).ok();
}
