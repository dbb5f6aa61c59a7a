//! Bad input gets one clear error naming the file, the line or field, and what was expected.

mod common;

use std::path::Path;
use std::process::Command;

use shadowmap::engine::{DepthFormat, ShaderProgram, ShaderSource, ShadowMap, Texture};
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
    assert!(e.contains("line 4, column 1: invalid array"), "{e}");
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
        e.contains("item[0].position: NaN is not a finite number"),
        "{e}"
    );
    let e = load_err("near_far.toml");
    assert!(e.contains("light.ortho") && e.contains("near < far"), "{e}");
    let e = load_err("missing_mesh.toml");
    assert!(
        e.contains("item[0].mesh: ")
            && e.contains("models/does_not_exist.obj: cannot read OBJ model"),
        "{e}"
    );
}

fn run(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_shadowmap"))
        .args(args)
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
