//! Bad input gets one clear error naming the file, the line or field, and what was expected.

use crate::common;

use std::path::Path;
use std::process::Command;

use shadowmap::engine::{ShaderProgram, ShaderSource, ShadowMap, Texture};
use shadowmap::settings::DepthFormat;
use shadowmap::{shaders, Error, Scene};

#[test]
fn shader_syntax_error_names_file_and_line() {
    let ctx = common::context();
    let broken = ShaderSource::new(
        "shaders/broken.frag",
        "#version 330 core\nout vec4 c;\nvoid main() {\n    c = vec4(1.0)\n}\n",
    );
    let err = ShaderProgram::new(ctx.gl(), &shaders::depth_vert(), &broken, &[])
        .err()
        .expect("a missing semicolon must not compile");
    let text = err.to_string();
    assert!(matches!(err, Error::Shader { .. }), "{text}");
    // Mesa reports the missing ';' of line 4 where it notices it: the '}' on line 5.
    assert!(
        text.contains("shaders/broken.frag:5:1: error: syntax error, unexpected '}'"),
        "{text}"
    );
    // With defines inserted, line numbers still match the file.
    let err = ShaderProgram::new(
        ctx.gl(),
        &shaders::depth_vert(),
        &broken,
        &[("PCF_RADIUS".into(), "1".into())],
    )
    .err()
    .expect("still broken");
    assert!(
        err.to_string().contains("shaders/broken.frag:5:1:"),
        "{err}"
    );
}

#[test]
fn incomplete_framebuffer_is_an_error_not_a_black_image() {
    let ctx = common::context();
    // A colour texture cannot be a depth attachment.
    let colour = Texture::colour(ctx.gl(), 64, 64).unwrap();
    let err = ShadowMap::from_texture(ctx.gl(), colour, DepthFormat::D24)
        .err()
        .expect("a colour texture as depth must be rejected");
    let text = err.to_string();
    assert!(matches!(err, Error::IncompleteFramebuffer { .. }), "{text}");
    assert!(
        text.contains("GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT"),
        "{text}"
    );
    assert!(
        text.starts_with("could not create framebuffer 'shadow map 64x64'"),
        "{text}"
    );
}

fn load_err(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/bad")
        .join(name);
    let err = Scene::load(path.to_str().unwrap()).expect_err("bad scene must not load");
    let text = err.to_string();
    assert!(
        text.contains(name),
        "the message must name the file: {text}"
    );
    text
}

#[test]
fn scene_file_errors_name_the_line_or_field() {
    let e = load_err("syntax.toml");
    assert!(
        e.contains("line 3, column 26: unclosed array, expected `]`"),
        "{e}"
    );
    let e = load_err("unknown_key.toml");
    assert!(
        e.contains("line 4") && e.contains("shadow_pos_multi"),
        "{e}"
    );
    let e = load_err("negative_scale.toml");
    assert!(
        e.contains("item[0].scale: -0.5: expected a finite number > 0"),
        "{e}"
    );
    let e = load_err("nan_position.toml");
    assert!(
        e.contains("item[0].position: line 6, column 18: NaN is not a finite number"),
        "{e}"
    );
    let e = load_err("near_far.toml");
    // The box as the file writes it, not as Rust's Debug prints it.
    assert!(
        e.ends_with(
            "near_far.toml: light.ortho: { left = -10, right = 10, bottom = -10, top = 10, \
             near = 20, far = -1 }: near = 20 is not below far = -1 (expected left < right, bottom \
             < top and near < far)"
        ),
        "{e}"
    );
    let e = load_err("missing_mesh.toml");
    assert!(
        e.contains("item[0].mesh: ")
            && e.contains("models/does_not_exist.obj: cannot read OBJ model"),
        "{e}"
    );
}

fn run(args: &[&str]) -> (bool, String, String) {
    run_in(Path::new("."), args)
}

/// [`run`] with `cwd` as the working folder (where a wrongly accepted command would write).
fn run_in(cwd: &Path, args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("the binary runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn cli_rejects_bad_values_with_a_clear_message() {
    let (ok, _, err) = run(&["render", "--size", "0x0"]);
    assert!(!ok);
    assert!(err.contains("'0x0': expected WIDTHxHEIGHT"), "{err}");
    let (ok, _, err) = run(&["render", "--size", "abc"]);
    assert!(!ok && err.contains("'abc': expected WIDTHxHEIGHT"), "{err}");
    let (ok, _, err) = run(&["render", "--scene", "nosuch"]);
    assert!(!ok);
    assert!(
        err.contains("unknown scene 'nosuch': expected one of dummy"),
        "{err}"
    );
    let (ok, _, err) = run(&["render", "--filter", "blurry"]);
    assert!(
        !ok && err.contains("pcf3x3"),
        "the valid filters are listed: {err}"
    );
    let (ok, _, err) = run(&["render", "--out", "/nonexistent-dir/x.png"]);
    assert!(!ok);
    assert!(
        err.contains("/nonexistent-dir/x.png: cannot write the image"),
        "{err}"
    );
    let (ok, _, err) = run(&["render", "--map-size", "100000"]);
    assert!(
        !ok && err.contains("shadow.map_size = 100000: expected 1 to"),
        "{err}"
    );
    assert!(!err.contains("panicked"), "{err}");
}

#[test]
fn help_names_every_built_in_scene_and_the_demo_keys() {
    let help = common::stdout_of(common::bin().arg("--help"));
    let demo = common::stdout_of(common::bin().args(["demo", "--help"]));
    for name in shadowmap::Scene::builtin_names() {
        assert!(
            help.contains(name),
            "`shadowmap --help` omits the scene {name}"
        );
        assert!(
            demo.contains(name),
            "`shadowmap demo --help` omits the scene {name}"
        );
    }
    // The key table (the same list the HUD's key panel shows).
    for key in [
        "each casting light's shadow map",
        "tint the cascades",
        "cascades: 1, 2, 3, 4",
        "show / hide these keys",
    ] {
        assert!(demo.contains(key), "`shadowmap demo --help` omits: {key}");
    }
}

#[test]
fn an_error_in_an_included_snippet_names_the_snippet_and_its_line() {
    let ctx = common::context();
    // The real scene shader with every library snippet, and a generated light snippet
    // whose second line calls a function that does not exist.
    let samplers = ("generated/samplers.glsl", String::new());
    let lights = (
        "generated/lights.glsl",
        "void addLights(inout Fragment f)\n{\n    addLightNowhere(0, f);\n}\n".to_string(),
    );
    let fragment = shaders::scene_frag(&[samplers, lights]).unwrap();
    let defines: Vec<(String, String)> = [
        ("LIGHT_COUNT", "1"),
        ("MAP_COUNT", "0"),
        ("MAP_SLOTS", "1"),
        ("VISIBILITY_LIGHT", "0"),
        ("BLINN", "0"),
        ("SPECULAR_POWER", "10.0"),
        ("OUTPUT_VISIBILITY", "0"),
        ("OUTPUT_GBUFFER", "0"),
    ]
    .iter()
    .map(|(k, v)| (k.to_string(), v.to_string()))
    .collect();
    let err = ShaderProgram::new(ctx.gl(), &shaders::scene_vert(), &fragment, &defines)
        .err()
        .expect("an unknown function must not compile");
    let text = err.to_string();
    // Line 3 of the generated snippet, not a line of scene.frag.
    assert!(text.contains("shaders/generated/lights.glsl:3:"), "{text}");
    assert!(text.contains("addLightNowhere"), "{text}");
}

#[test]
fn numeric_flags_take_negative_numbers_after_a_space() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("errors-negative");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("x.png");
    let out = out.to_str().unwrap();
    // Values that are valid when negative: the frame is rendered.
    for (flag, value) in [
        ("--camera-position", "-1,2,5"),
        ("--camera-rotation", "-10,-20,0"),
        ("--polygon-offset", "-1,-4"),
    ] {
        let (ok, stdout, err) = run(&["render", "--size", "16x16", "--out", out, flag, value]);
        assert!(ok && stdout.starts_with("wrote "), "{flag} {value}: {err}");
    }
    // Values that are not: the message names the flag and what it expected, never
    // "unexpected argument".
    let cases: &[(&[&str], &str)] = &[
        (
            &["render", "--bias", "-0.5"],
            "--bias: shadow.bias = -0.5: expected 0 to 1",
        ),
        (
            &["render", "--bias-min", "-1"],
            "--bias-min: shadow.bias_min = -1: expected 0 to 1",
        ),
        (
            &["render", "--normal-offset", "-2"],
            "--normal-offset: shadow.normal_offset = -2: expected 0 (off) to 16 (texels)",
        ),
        (
            &["render", "--perspective-fov", "-45"],
            "--perspective-fov: shadow.perspective_fov = -45: expected degrees between 0 and 180",
        ),
        (
            &["render", "--cascade-lambda", "-0.5"],
            "--cascade-lambda: shadow.cascade_lambda = -0.5: expected 0 to 1",
        ),
        (
            &["render", "--cascade-blend", "-0.1"],
            "--cascade-blend: shadow.cascade_blend = -0.1: expected 0 to 0.5",
        ),
        (
            &["render", "--shadow-distance", "-5"],
            "--shadow-distance: shadow.shadow_distance = -5: expected a finite number >= 0",
        ),
        (
            &["render", "--light-angle", "-10"],
            "--light-angle -10: expected degrees from 0 to 180",
        ),
        (
            &["render", "--light-angle", "180.5"],
            "--light-angle 180.5: expected degrees from 0 to 180",
        ),
        (
            &["render", "--map-size", "-1"],
            "invalid value '-1' for '--map-size <SIZE>': '-1': expected a side in texels like \
             1024, or WIDTHxHEIGHT like 400x300",
        ),
        (
            &["render", "--map-size", "400x"],
            "invalid value '400x' for '--map-size <SIZE>'",
        ),
        (
            &[
                "render",
                "--scene",
                "point-shadows",
                "--map-size",
                "400x300",
            ],
            "--map-size: shadow.map_size = 400x300: light 0 has a point light's cube map, which \
             needs a square map; expected one number, like 400",
        ),
        (
            &["render", "--cascades", "-2"],
            "invalid value '-2' for '--cascades <N>'",
        ),
        (
            &["render", "--frames", "-1"],
            "invalid value '-1' for '--frames <N>'",
        ),
        (
            &["render", "--bias", "nan"],
            "invalid value 'nan' for '--bias <B>': 'nan': expected a finite number",
        ),
        (
            &["compare", "--out-dir", "d", "--supersample", "-1"],
            "invalid value '-1' for '--supersample <N>'",
        ),
        (
            &["compare", "--out-dir", "d", "--band", "-1"],
            "invalid value '-1' for '--band <K>'",
        ),
        (
            &["compare", "--out-dir", "d", "--light", "-1"],
            "invalid value '-1' for '--light <N>'",
        ),
        (
            &["bench", "--out-dir", "d", "--frames", "-3"],
            "invalid value '-3' for '--frames <N>'",
        ),
        (
            &["bench", "--out-dir", "d", "--warmup", "-3"],
            "invalid value '-3' for '--warmup <N>'",
        ),
        (
            &["bench", "--out-dir", "d", "--target-error", "-0.1"],
            "'-0.1': expected a fraction from 0 to 1",
        ),
        (
            &["steps", "--out-dir", "d", "--supersample", "-2"],
            "invalid value '-2' for '--supersample <N>'",
        ),
        (
            &["demo", "--exit-after-frames", "-1"],
            "invalid value '-1' for '--exit-after-frames <N>'",
        ),
        (
            &["soak", "--frames", "-1"],
            "invalid value '-1' for '--frames <N>'",
        ),
        // Zero frames would open nothing and exit 0 without a word.
        (
            &["demo", "--exit-after-frames", "0"],
            "error: invalid value '0' for '--exit-after-frames <N>': '0': expected a whole \
             number of frames from 1 to 18446744073709551615",
        ),
        (
            &["soak", "--frames", "0"],
            "error: invalid value '0' for '--frames <N>': '0': expected a whole number of \
             frames from 1 to 18446744073709551615",
        ),
        (
            &["render", "--frames", "0"],
            "error: invalid value '0' for '--frames <N>': '0': expected a whole number of \
             frames from 1 to 4294967295",
        ),
    ];
    // Run in an empty folder of their own: a refused command writes nothing there.
    let refused = dir.join("refused");
    std::fs::create_dir_all(&refused).unwrap();
    let mut wrong = Vec::new();
    for (args, needle) in cases {
        let (ok, _, err) = run_in(&refused, args);
        if ok
            || !err.contains(needle)
            || err.contains("unexpected argument")
            || !err.starts_with("error: ")
        {
            wrong.push(format!("{args:?}: {err}"));
        }
    }
    assert!(wrong.is_empty(), "\n{}", wrong.join("\n"));
    let left: Vec<_> = std::fs::read_dir(&refused).unwrap().flatten().collect();
    assert!(left.is_empty(), "refused commands left {left:?}");
}

#[test]
fn camera_target_aims_the_camera_and_refuses_rotation_beside_it() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("errors-camera-target");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (a, b) = (path("target.png"), path("angles.png"));
    // Negative numbers after a space; the same frame as the angles it stands for.
    let camera = shadowmap::scene::Camera::look_at(
        glam::Vec3::new(-3.0, 2.0, 4.0),
        glam::Vec3::new(0.5, -1.0, -0.5),
    )
    .unwrap();
    let r = camera.rotation;
    let angles = format!("{},{},{}", r.x, r.y, r.z);
    let common = ["render", "--size", "64x36", "--camera-position", "-3,2,4"];
    let (ok, _, err) = run(&[
        &common[..],
        &["--out", &a, "--camera-target", "0.5,-1,-0.5"],
    ]
    .concat());
    assert!(ok, "{err}");
    let (ok, _, err) = run(&[&common[..], &["--out", &b, "--camera-rotation", &angles]].concat());
    assert!(ok, "{err}");
    let (fa, fb) = (std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());
    assert_eq!(fa, fb, "--camera-target and its angles render differently");
    // The default view would differ: the target did something.
    let (ok, _, err) = run(&[&common[..], &["--out", &b]].concat());
    assert!(ok, "{err}");
    assert_ne!(fa, std::fs::read(&b).unwrap());
    for (args, expected) in [
        (
            &["--camera-rotation", "0,0,0", "--camera-target", "0,0,0"][..],
            "--camera-rotation and --camera-target are both given",
        ),
        (
            &["--camera-target", "-3,2,4"][..],
            "--camera-target -3,2,4: the camera's own position",
        ),
        (&["--camera-target", "1,2"][..], "expected three numbers"),
    ] {
        let (ok, _, err) = run(&[&common[..], &["--out", &a], args].concat());
        assert!(!ok && err.contains(expected), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
    }
}

#[test]
fn a_frame_size_too_large_names_where_it_came_from() {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("errors-size");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let scene = dir.join("wide.toml");
    std::fs::write(
        &scene,
        "size = [200000, 100]\n[light]\nangle = 45.0\n[[item]]\nmesh = \"cube\"\n",
    )
    .unwrap();
    let out = dir.join("x.png");
    let run = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_shadowmap"))
            .args(["render", "--scene", scene.to_str().unwrap()])
            .args(["--out", out.to_str().unwrap()])
            .args(extra)
            .output()
            .unwrap()
    };
    let from_file = run(&[]);
    let text = String::from_utf8_lossy(&from_file.stderr);
    assert!(!from_file.status.success());
    assert!(
        text.contains("wide.toml: size: [200000, 100]: expected each side from 1 to"),
        "{text}"
    );
    let from_flag = run(&["--size", "100x300000"]);
    let text = String::from_utf8_lossy(&from_flag.stderr);
    assert!(!from_flag.status.success());
    assert!(
        text.contains("--size 100x300000: expected each side from 1 to"),
        "{text}"
    );
    assert!(!out.exists(), "nothing is written");
}

/// A name one slip away from a known one is answered with that name (edit distance, a swap
/// of neighbours counting as one): scenes, steps, flags' values and flags, and a scene
/// file's keys and values, where the message keeps its line and column and leaves out the
/// list of every field.
#[test]
fn a_near_miss_gets_a_did_you_mean() {
    let dir = tempfile::tempdir().unwrap();
    let file = |name: &str, text: &str| {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        path.to_str().unwrap().to_string()
    };
    let key = file(
        "key.toml",
        "[light]\nangle = 45.0\n[shadow]\nmapsize = 1024\n",
    );
    let value = file(
        "value.toml",
        "[light]\nangle = 45.0\n[shadow]\nfilter = \"pfc3x3\"\n",
    );
    let light = file("light.toml", "[light]\nangel = 45.0\n");
    let cases: [(&[&str], String); 6] = [
        (
            &["render", "--scene", "dumy"],
            "error: unknown scene 'dumy' (did you mean 'dummy'?): expected one of dummy, \
             learnopengl, slides, playground, point-shadows, large, three-lights, overlap, \
             penumbra, smoke, ramp or a path to a .toml scene file\n"
                .into(),
        ),
        (
            &["render", "--scene", &key],
            format!(
                "error: {key}: shadow.mapsize: line 4, column 1: unknown field `mapsize`: did \
                 you mean `map_size`?\n"
            ),
        ),
        (
            &["render", "--scene", &value],
            format!(
                "error: {value}: shadow.filter: line 4, column 10: unknown value `pfc3x3`: did \
                 you mean `pcf3x3`?\n"
            ),
        ),
        (
            &["render", "--scene", &light],
            format!(
                "error: {light}: light.angel: line 2, column 1: unknown field `angel`: did you \
                 mean `angle`?\n"
            ),
        ),
        // clap's own measure would offer `pcss` here.
        (
            &["render", "--step", "pfc"],
            "tip: a similar value exists: 'pcf'".into(),
        ),
        (
            &["render", "--map-szie", "512"],
            "tip: a similar argument exists: '--map-size'".into(),
        ),
    ];
    for (args, expected) in cases {
        let (ok, stdout, stderr) = run_in(dir.path(), args);
        assert!(!ok && stdout.is_empty(), "{args:?}: {stdout}");
        match expected.starts_with("error:") {
            true => assert_eq!(stderr, expected, "{args:?}"),
            false => assert!(stderr.contains(&expected), "{args:?}: {stderr}"),
        }
    }
    // Nothing near: the full list, as before.
    let (_, _, stderr) = run(&["render", "--scene", "castle"]);
    assert!(
        stderr.starts_with("error: unknown scene 'castle': expected one of dummy"),
        "{stderr}"
    );
}
