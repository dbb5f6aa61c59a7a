//! `--step` means one picture in every command: the scene each command draws a step with
//! (its camera, lights and items) and its settings are `render --step`'s.

use clap::Parser;
use shadowmap::{steps, Scene, ShadowSettings};

use super::cli::{Cli, Command};

/// What a command draws: the camera's place and angles, the items' places, the first
/// light's box, and the settings.
type Drawn = (
    glam::Vec3,
    glam::Vec3,
    Vec<glam::Vec3>,
    String,
    ShadowSettings,
);

fn drawn(scene: &Scene, settings: ShadowSettings) -> Drawn {
    let items = scene.items.iter().map(|i| i.position).collect();
    let light = format!("{:?}", scene.light().as_directional().map(|l| l.ortho));
    (
        scene.camera.position,
        scene.camera.rotation,
        items,
        light,
        settings,
    )
}

/// The scene and settings `command` (with `args` after it) draws with.
fn drawn_by(command: &str, args: &[&str]) -> Drawn {
    let mut line = vec!["shadowmap", command];
    line.extend_from_slice(args);
    if command == "compare" || command == "bench" {
        line.extend_from_slice(&["--out-dir", "unused"]);
    }
    if command == "render" {
        line.extend_from_slice(&["--out", "unused.png"]);
    }
    let cli = Cli::try_parse_from(&line).unwrap_or_else(|e| panic!("{line:?}: {e}"));
    let (scene, settings) = match cli.command.expect("a command") {
        Command::Render(a) => a.scene.load_with(&a.settings).unwrap(),
        Command::Compare(a) => a.scene.load_with(&a.settings).unwrap(),
        Command::Bench(a) => super::bench::load_still_scene(&a).unwrap(),
        Command::Soak(a) => {
            let loaded = a.scene.load().unwrap();
            super::soak::at_step(&a, &loaded, a.settings.step.as_deref()).unwrap()
        }
        Command::Demo(a) => {
            let (_, scene, settings) = super::demo::scenes(&a).unwrap();
            (scene, settings)
        }
        _ => unreachable!("{command}"),
    };
    drawn(&scene, settings)
}

#[test]
fn every_command_draws_a_staged_step_as_render_does() {
    let mut staged = 0;
    for name in steps::STAGED_SCENES {
        let scene = Scene::load(name).unwrap();
        for step in steps::of(&scene)
            .iter()
            .filter(|s| s.stage(&scene).is_some())
        {
            let args = ["--scene", name, "--step", step.name];
            let render = drawn_by("render", &args);
            // The step's view is not the scene's own: a command that took only the
            // step's settings would draw another picture.
            let own = drawn_by("render", &["--scene", name]);
            assert_ne!(
                (render.0, render.1, &render.2, &render.3),
                (own.0, own.1, &own.2, &own.3)
            );
            for command in ["demo", "compare", "bench", "soak"] {
                let got = drawn_by(command, &args);
                assert_eq!(got, render, "{command} --scene {name} --step {}", step.name);
            }
            staged += 1;
        }
    }
    assert!(staged >= 8, "{staged} staged steps");
}

#[test]
fn a_camera_flag_keeps_its_camera_in_a_step_in_every_command() {
    let args = [
        "--scene",
        "dummy",
        "--step",
        "cull-front",
        "--camera-position",
        "0,1,4",
    ];
    let render = drawn_by("render", &args);
    assert_eq!(render.0, glam::Vec3::new(0.0, 1.0, 4.0));
    for command in ["demo", "compare", "bench", "soak"] {
        assert_eq!(drawn_by(command, &args), render, "{command}");
    }
}

#[test]
fn learnopengl_opens_above_its_cubes_and_keeps_the_codes_camera_as_a_view() {
    let above = drawn_by("render", &["--scene", "learnopengl"]);
    assert!(
        above.0.y > 3.0,
        "the camera looks down on the cubes: {:?}",
        above.0
    );
    let code = drawn_by("render", &["--scene", "learnopengl", "--view", "code"]);
    assert_eq!(code.0, glam::Vec3::new(0.0, 0.0, 3.0));
    assert_eq!(code.1, glam::Vec3::ZERO);
    // The library's scene is the file's [camera]: the code's, which the original's tests use.
    assert_eq!(Scene::load("learnopengl").unwrap().camera.position, code.0);
    let e = Cli::try_parse_from([
        "shadowmap",
        "render",
        "--scene",
        "dummy",
        "--view",
        "x",
        "--out",
        "f.png",
    ])
    .map(|c| match c.command {
        Some(Command::Render(a)) => a.scene.load().map(|_| ()),
        _ => unreachable!(),
    })
    .unwrap()
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "--view x: the dummy scene has no named views (its file has no [views])"
    );
}
