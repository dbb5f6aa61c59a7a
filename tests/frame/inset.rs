//! `shadowmap render --inset`: the shadow-map inset lands in the bottom-right corner (a
//! quarter of the frame's height on a side, 8 pixels from the edges) and nowhere else, shows
//! the map (grey), and leaves the other outputs as they were. `--hud` alone draws no inset.

use crate::common;

use common::{bin, stdout_of};

fn load(path: &std::path::Path) -> image::RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

/// The inset's rectangle in image coordinates (y down) for 640 x 360: side 90, its right
/// edge 8 from the right, its bottom edge 8 from the bottom.
const INSET: (u32, u32, u32, u32) = (542, 262, 632, 352);

fn inside(x: u32, y: u32) -> bool {
    (INSET.0..INSET.2).contains(&x) && (INSET.1..INSET.3).contains(&y)
}

#[test]
fn render_inset_changes_only_its_corner_and_shows_the_map() {
    let dir = std::env::temp_dir().join(format!("shadowmap-inset-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |name: &str, extra: &[&str]| {
        let (out, vis) = (
            dir.join(format!("{name}.png")),
            dir.join(format!("{name}-vis.png")),
        );
        stdout_of(
            bin()
                .args(["render", "--size", "640x360", "--frames", "2"])
                .args(extra)
                .arg("--out")
                .arg(&out)
                .arg("--shadow-out")
                .arg(&vis),
        );
        (load(&out), load(&vis))
    };
    let (plain, plain_vis) = render("plain", &[]);
    let (inset, inset_vis) = render("inset", &["--inset"]);
    let (mut outside, mut changed, mut grey) = (0, 0, 0);
    for (x, y, p) in inset.enumerate_pixels() {
        let q = plain.get_pixel(x, y);
        match (inside(x, y), p == q) {
            (false, false) => outside += 1,
            (true, false) => changed += 1,
            _ => {}
        }
        if inside(x, y) && p[0] == p[1] && p[1] == p[2] && p[3] == 255 {
            grey += 1;
        }
    }
    assert_eq!(outside, 0, "the inset drew outside its corner");
    // 90 x 90 = 8100 pixels, all of them the map's grey; most differ from the scene there.
    assert_eq!(grey, 8100, "inset pixels that are not grey");
    assert!(changed > 6000, "only {changed} pixels of the inset differ");
    // The map is not flat: the cube stands out from the plane.
    let levels: std::collections::HashSet<u8> = inset
        .enumerate_pixels()
        .filter(|(x, y, _)| inside(*x, *y))
        .map(|(_, _, p)| p[0])
        .collect();
    assert!(
        levels.len() > 10,
        "{} grey levels in the inset",
        levels.len()
    );
    assert!(
        inset_vis == plain_vis,
        "--inset changed the visibility image"
    );

    // --hud draws the HUD only; with --inset both.
    let (hud, _) = render("hud", &["--hud"]);
    let (both, _) = render("both", &["--hud", "--inset"]);
    for (x, y, p) in hud.enumerate_pixels() {
        if inside(x, y) {
            assert_eq!(
                p,
                plain.get_pixel(x, y),
                "--hud drew into the inset at {x},{y}"
            );
            assert_eq!(both.get_pixel(x, y), inset.get_pixel(x, y), "at {x},{y}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn render_inset_on_a_frame_too_small_for_it_warns_and_draws_the_frame() {
    let dir = std::env::temp_dir().join(format!("shadowmap-inset-none-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = bin()
        .args(["render", "--size", "16x16", "--inset", "--out"])
        .arg(dir.join("small.png"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    assert!(
        stderr.contains("warning: --inset: a 16x16 frame is too small for the inset"),
        "{stderr}"
    );
    assert!(dir.join("small.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}
