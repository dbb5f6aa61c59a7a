//! The chapters' one-file programs (`examples/`) against the renderer: each draws the frame
//! `shadowmap render` draws for its scene, to within one level per channel, from the same
//! depth map.

use crate::common;

#[allow(dead_code)]
#[path = "../../examples/lwjgl_dummygame.rs"]
mod dummygame;
#[allow(dead_code)]
#[path = "../../examples/learnopengl_3_1_3.rs"]
mod learnopengl;

use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::{render_frames, Frame};
use shadowmap::settings::{BiasMode, Cull, Filter, MapSize};
use shadowmap::Scene;

/// The tool's frame of a scene with its own settings, as `shadowmap render --scene NAME
/// --size WxH` draws it (one frame, nothing animated yet).
fn tool_frame(ctx: &HeadlessContext, scene: &mut Scene, width: u32, height: u32) -> Frame {
    let settings = scene.shadow;
    let outputs = Outputs::default();
    render_frames(ctx.gl(), scene, &settings, width, height, 1, outputs)
        .unwrap_or_else(|e| panic!("{}: {e}", scene.name))
}

/// The largest channel difference between two RGBA8 images, and how many pixels differ.
fn colour_difference(ours: &[u8], theirs: &[u8]) -> (u8, usize) {
    assert_eq!(ours.len(), theirs.len(), "the frames' sizes differ");
    let pixels = ours.chunks_exact(4).zip(theirs.chunks_exact(4));
    pixels.fold((0, 0), |(max, count), (a, b)| {
        let d = a
            .iter()
            .zip(b)
            .map(|(x, y)| x.abs_diff(*y))
            .max()
            .unwrap_or(0);
        (max.max(d), count + usize::from(d > 0))
    })
}

/// Checks an example's frame against the tool's: no channel more than one level apart,
/// and at most `max_share` of the pixels differing at all (rounding: the two compose their
/// matrices in different orders and precisions).
fn assert_same_frame(what: &str, example: &[u8], tool: &Frame, max_share: f64) {
    let (max, differing) = colour_difference(example, &tool.colour.rgba);
    let share = differing as f64 / (tool.width * tool.height) as f64;
    eprintln!(
        "{what}: {differing} pixels differ ({:.4}%), by at most {max} level(s)",
        share * 100.0
    );
    assert!(max <= 1, "{what}: a channel differs by {max} levels");
    assert!(
        share <= max_share,
        "{what}: {:.4}% of the pixels differ",
        share * 100.0
    );
}

/// The example's depth map (rows bottom to top, as GL reads them) against the tool's
/// (rows top to bottom): the largest difference, and how many texels differ.
fn depth_difference(example: &[f32], tool: &Frame) -> (f32, usize) {
    let (size, depth) = tool.depth_map.as_ref().expect("the tool's frame has a map");
    assert_eq!(*size, MapSize::square(1024));
    assert_eq!(example.len(), depth.len());
    let row = size.width as usize;
    let flipped = example.chunks_exact(row).rev().flatten();
    flipped
        .zip(depth)
        .fold((0.0f32, 0), |(max, count), (a, b)| {
            let d = (a - b).abs();
            (max.max(d), count + usize::from(d > 0.0))
        })
}

#[test]
fn dummygame_example_draws_the_tools_dummy_frame() {
    // The book's last stage ("Shadow Mapping improvements": bias 0.05, 3 x 3 PCF, no
    // culling) is the dummy scene's own settings. `--step pcf` is a different frame: it
    // carries the earlier cumulative steps (the slope bias, front faces culled, the border
    // clamp), which the book never takes.
    let mut scene = common::frozen("dummy");
    let s = scene.shadow;
    assert_eq!((s.bias_mode, s.bias), (BiasMode::Constant, 0.05));
    assert_eq!((s.filter, s.cull), (Filter::Pcf3x3, Cull::None));

    let ctx = common::context();
    let game = dummygame::DummyGame::new(ctx.gl()).unwrap();
    game.render_frame();
    let frame = tool_frame(&ctx, &mut scene, dummygame::WIDTH, dummygame::HEIGHT);
    // Measured: identical. The same Transformation formulas give the same matrices, and
    // the shaders compute the same values.
    assert_same_frame("DummyGame", &game.read_colour(), &frame, 0.0);
    let (max, texels) = depth_difference(&game.read_depth(), &frame);
    assert_eq!(texels, 0, "{texels} depth texels differ, by up to {max:e}");
}

#[test]
fn learnopengl_example_draws_the_tools_learnopengl_frame() {
    let ctx = common::context();
    let program = learnopengl::ShadowMapping::new(ctx.gl()).unwrap();
    program.render_frame();
    let (width, height) = (learnopengl::SCR_WIDTH, learnopengl::SCR_HEIGHT);
    let frame = tool_frame(&ctx, &mut common::frozen("learnopengl"), width, height);
    // Measured: 148 pixels (0.031%) one level apart, from rounding (the tutorial lights in
    // world space, the renderer in view space); no PCF tap differs where it would show (one
    // tap flipping moves a lit floor pixel by 2 levels or more).
    assert_same_frame("LearnOpenGL 3.1.3", &program.read_colour(), &frame, 0.001);
    let (max, texels) = depth_difference(&program.read_depth(), &frame);
    eprintln!("LearnOpenGL 3.1.3: {texels} depth texels differ, by up to {max:e}");
    // The tutorial composes lightSpaceMatrix x model in single precision, the renderer the
    // light view x model in double: the floor's far corners (25 units out) round to
    // different depths. Measured: 423k of the 1M texels differ, by at most 9.5e-7 (16
    // steps of the 24-bit map), 5000 times less than the smallest bias (0.005), so no
    // comparison changes. A map turned, shifted or scaled would differ by far more.
    assert!(max <= 2e-6, "a depth texel differs by {max:e}");
}

#[test]
fn learnopengl_example_matches_from_above_where_the_bias_shows() {
    // From the tutorial's camera no bias between 0.025 and 0.1 changes a pixel (the floor
    // beside the cubes is hidden). From the steps camera above the cubes the contact
    // shadows and the cubes' lit faces are in view, where the bias and the filter decide.
    let mut scene = common::frozen("learnopengl");
    scene.camera = scene.steps_camera();
    let ctx = common::context();
    let mut program = learnopengl::ShadowMapping::new(ctx.gl()).unwrap();
    program.camera = learnopengl::Camera {
        position: scene.camera.position,
        view: scene.camera.view_matrix(),
    };
    program.render_frame();
    let (width, height) = (learnopengl::SCR_WIDTH, learnopengl::SCR_HEIGHT);
    let frame = tool_frame(&ctx, &mut scene, width, height);
    // Measured: 367 pixels (0.077%) one level apart. A slope bias of 0.045 or 0.06 in
    // place of 0.05 moves pixels by 3 and 7 levels; PCF taps two texels apart, by 42.
    assert_same_frame(
        "LearnOpenGL 3.1.3 from above",
        &program.read_colour(),
        &frame,
        0.001,
    );
}

/// An example's program, built in the profile and target folder this test was built in
/// (`cargo test --release` runs release examples, a plain `cargo test` debug ones), so the
/// program run is the one just built, never a stale one from another profile. This test's
/// cargo has released its lock by the time tests run.
fn example_bin(name: &str) -> std::path::PathBuf {
    // This test runs from <target>/<profile folder>/deps; the examples go beside deps.
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().and_then(|deps| deps.parent()).unwrap();
    let folder = profile_dir.file_name().unwrap().to_str().unwrap();
    // The dev profile's folder is `debug`; every other profile's is its own name.
    let profile = match folder {
        "debug" => "dev",
        other => other,
    };
    let status = std::process::Command::new(env!("CARGO"))
        .args(["build", "--quiet", "--example", name, "--profile", profile])
        .arg("--target-dir")
        .arg(profile_dir.parent().unwrap())
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .status()
        .unwrap();
    assert!(
        status.success(),
        "cargo build --example {name} --profile {profile}"
    );
    let bin = profile_dir
        .join("examples")
        .join(format!("{name}{}", std::env::consts::EXE_SUFFIX));
    assert!(bin.is_file(), "{} was not built", bin.display());
    bin
}

/// Each example answers `--help` with its usage (and writes nothing), and refuses an
/// unknown option or a wrong count of arguments with the usage, exit status 2.
#[test]
fn each_example_has_a_help_and_refuses_bad_arguments() {
    let dir = tempfile::tempdir().unwrap();
    for (name, count) in [
        ("learnopengl_3_1_3", "expected 1 argument, got 0"),
        ("lwjgl_dummygame", "expected 1 argument, got 0"),
        ("render_diff", "expected 2 to 3 arguments, got 0"),
        ("playground_score", "expected 2 to 3 arguments, got 0"),
    ] {
        let bin = example_bin(name);
        let run = |args: &[&str]| {
            let out = std::process::Command::new(&bin)
                .args(args)
                .current_dir(dir.path())
                .output()
                .unwrap();
            let text = |b: &[u8]| String::from_utf8_lossy(b).into_owned();
            (out.status.code(), text(&out.stdout), text(&out.stderr))
        };
        let usage = format!("usage: cargo run --release --example {name} -- ");
        let (code, stdout, stderr) = run(&["--help"]);
        assert_eq!(code, Some(0), "{name} --help: {stderr}");
        assert!(stdout.starts_with(&usage), "{name}: {stdout}");
        assert_eq!(stderr, "", "{name}");
        for (args, problem) in [
            (
                &["--size", "a", "b"][..],
                "error: unknown option '--size'\n\n",
            ),
            (&[][..], &*format!("error: {count}\n\n")),
        ] {
            let (code, stdout, stderr) = run(args);
            assert_eq!(code, Some(2), "{name} {args:?}: {stderr}");
            assert_eq!(stdout, "", "{name}");
            assert!(
                stderr.starts_with(&format!("{problem}{usage}")),
                "{name}: {stderr}"
            );
        }
    }
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}
