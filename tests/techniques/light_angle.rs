//! The light angle (the demo's arrow keys, `--light-angle`) on lights with an azimuth: the
//! light turns about the horizontal axis across its azimuth, and the DummyGame's stays the
//! book's (0, sin a, cos a).

use crate::common;

use common::bin;
use glam::Vec3;
use shadowmap::scene::DirectionalLight;
use shadowmap::Scene;

fn directional(scene: &Scene) -> DirectionalLight {
    *scene
        .light()
        .as_directional()
        .expect("a directional first light")
}

fn close(a: Vec3, b: Vec3, what: &str) {
    assert!((a - b).length() < 1e-5, "{what}: {a} vs {b}");
}

#[test]
fn the_dummy_game_keeps_the_books_direction_bit_for_bit() {
    let mut scene = Scene::load("dummy").unwrap();
    assert_eq!(scene.light_azimuth(), Some(Vec3::Z));
    for tenth in 0..=1800 {
        let a = tenth as f32 / 10.0;
        assert!(scene.set_light_angle(a));
        let r = a.to_radians();
        let book = Vec3::new(0.0, r.sin(), r.cos()).normalize();
        let got = directional(&scene).direction;
        assert_eq!(got, book, "angle {a}");
        assert_eq!(got.x, 0.0, "angle {a}: left the YZ plane");
        // Past the overhead too, the angle reads back from +Z (the book's atan2(y, z)).
        assert!(
            (directional(&scene).angle_deg() - a).abs() < 1e-3,
            "angle {a}"
        );
    }
    // The book clamps; at the clamp the angle reads back as 180 (not -180, which the next
    // key step would clamp to 0: the light would jump to the other horizon).
    scene.set_light_angle(200.0);
    let at_180 = directional(&scene);
    assert_eq!(
        at_180.direction,
        DirectionalLight::direction_from_angle(180.0)
    );
    assert!(
        (at_180.angle_deg() - 180.0).abs() < 1e-3,
        "{}",
        at_180.angle_deg()
    );
    scene.set_light_angle(at_180.angle_deg() + 0.05);
    assert_eq!(directional(&scene).direction, at_180.direction);
}

#[test]
fn learnopengl_keeps_its_azimuth_distance_and_shading_position() {
    let mut scene = Scene::load("learnopengl").unwrap();
    let p = Vec3::new(-2.0, 4.0, -1.0);
    let azimuth = Vec3::new(-2.0, 0.0, -1.0).normalize();
    close(scene.light_azimuth().unwrap(), azimuth, "azimuth");
    let start = directional(&scene).angle_deg();
    assert!((start - 60.79).abs() < 0.01, "its angle as loaded: {start}");

    assert!(scene.set_light_angle(30.0));
    let l = directional(&scene);
    let want =
        (azimuth * 30f32.to_radians().cos() + Vec3::Y * 30f32.to_radians().sin()).normalize();
    close(l.direction, want, "direction at 30");
    close(l.azimuth(), azimuth, "azimuth at 30");
    let shading = l.shading_position.expect("a light given by position");
    assert!(
        (shading.length() - p.length()).abs() < 1e-4,
        "distance {shading}"
    );
    close(shading, want * p.length(), "shading position");
    close(l.position(), shading, "shadow camera and shading point");

    // Through the overhead and back, about the azimuth taken once (as the demo does).
    let kept = scene.light_azimuth().unwrap();
    for a in [90.0, 120.0, 179.0] {
        scene.set_light_angle_about(kept, a);
        let l = directional(&scene);
        assert!((l.angle_about(kept) - a).abs() < 1e-3, "angle {a}");
        let h = Vec3::new(l.direction.x, 0.0, l.direction.z);
        assert!(
            h.cross(azimuth).length() < 1e-5,
            "angle {a}: left the plane"
        );
    }
    scene.set_light_angle_about(kept, start);
    close(
        directional(&scene).shading_position.unwrap(),
        p,
        "back where it was",
    );
}

#[test]
fn three_lights_sun_turns_about_its_azimuth() {
    let mut scene = Scene::load("three-lights").unwrap();
    let before = directional(&scene);
    let azimuth = before.azimuth();
    assert_ne!(azimuth, Vec3::Z, "the sun has an azimuth of its own");
    assert!(scene.set_light_angle(20.0));
    let after = directional(&scene);
    close(after.azimuth(), azimuth, "azimuth");
    assert!((after.angle_deg() - 20.0).abs() < 1e-3);
    // The other lights do not move.
    assert_eq!(
        scene.lights[1..],
        Scene::load("three-lights").unwrap().lights[1..]
    );
}

#[test]
fn spot_and_point_lights_have_no_angle() {
    for name in ["point-shadows", "slides", "playground"] {
        let mut scene = Scene::load(name).unwrap();
        assert!(scene.light().as_directional().is_none(), "{name}");
        let lights = scene.lights.clone();
        assert_eq!(scene.light_azimuth(), None, "{name}");
        assert!(!scene.set_light_angle(45.0), "{name}");
        assert_eq!(scene.lights, lights, "{name}: changed");
    }
}

#[test]
fn light_angle_flag_turns_learnopengls_light_and_says_where() {
    let dir = std::env::temp_dir().join(format!("shadowmap-angle-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let stdout = common::stdout_of(
        bin()
            .args(["render", "--scene", "learnopengl", "--size", "80x60"])
            .args(["--light-angle", "30", "--out"])
            .arg(dir.join("a.png")),
    );
    assert!(
        stdout.contains("light 30.0 deg over azimuth [-0.89, 0.00, -0.45]"),
        "{stdout}"
    );
    // Point lights: refused, naming the flag.
    let out = bin()
        .args([
            "render",
            "--scene",
            "point-shadows",
            "--light-angle",
            "30",
            "--out",
        ])
        .arg(dir.join("b.png"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("--light-angle: the point-shadows scene's light is not directional"),
        "{stderr}"
    );
    assert!(!dir.join("b.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn light_angle_help_says_what_the_angle_means() {
    let out = bin().args(["render", "--help"]).output().unwrap();
    // The help is wrapped to the terminal: read it as one run of words.
    let help = String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ");
    for fragment in [
        "0 is the horizon",
        "towards the azimuth, 90 overhead, 180 the opposite horizon",
        "(0, sin a, cos a)",
        "Spot and point",
    ] {
        assert!(
            help.contains(fragment),
            "--help lacks {fragment:?}:\n{help}"
        );
    }
}

#[test]
fn demo_help_lists_the_angle_keys_and_the_inset() {
    // The key table is the one the HUD's key panel shows.
    let demo = common::stdout_of(bin().args(["demo", "--help"]));
    for fragment in [
        "lower it (0 to 180, about its azimuth)",
        "the shadow-map inset (bottom-right)",
        "--inset",
        "0 is the horizon",
    ] {
        assert!(
            demo.contains(fragment),
            "demo --help lacks {fragment:?}:\n{demo}"
        );
    }
}

/// A scene file's `angle` and `--light-angle` take the same degrees and refuse the rest in
/// the same words, the file's message naming its line: 450 is not silently 90, nor -45
/// accepted.
#[test]
fn the_scene_files_angle_and_the_flag_refuse_alike() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let out = common::bin()
            .current_dir(dir.path())
            .args(["render", "--size", "32x24", "--out", "o.png"])
            .args(args)
            .output()
            .unwrap();
        (
            out.status.success(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    for angle in ["450", "-45", "180.5"] {
        let file = dir.path().join("s.toml");
        std::fs::write(&file, format!("[light]\nangle = {angle}\n")).unwrap();
        let scene = file.to_str().unwrap();
        let rule = format!("{angle}: expected degrees from 0 to 180 (90 = overhead)\n");
        let (ok, stderr) = run(&["--scene", scene]);
        assert!(!ok);
        assert_eq!(
            stderr,
            format!("error: {scene}: light.angle: line 2, column 9: {rule}")
        );
        let (ok, stderr) = run(&["--light-angle", angle]);
        assert!(!ok);
        assert_eq!(stderr, format!("error: --light-angle {rule}"));
    }
    assert!(!dir.path().join("o.png").exists(), "nothing written");
    for angle in ["0", "180", "90.5"] {
        std::fs::write(
            dir.path().join("s.toml"),
            format!("[light]\nangle = {angle}\n"),
        )
        .unwrap();
        assert!(run(&["--scene", "s.toml"]).0, "{angle}");
        assert!(run(&["--light-angle", angle]).0, "{angle}");
    }
}
