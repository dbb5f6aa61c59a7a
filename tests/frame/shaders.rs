//! `shadowmap shaders` prints the scene program the renderer compiles, and it compiles.

use crate::common;

use shadowmap::engine::{Outputs, ShaderProgram, ShaderSource};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::shadows::program::ProgramKey;
use shadowmap::{Scene, ShadowSettings};

const VERTEX: &str = "// ==== vertex shader: shaders/scene.vert ====\n";
const FRAGMENT: &str = "// ==== fragment shader: shaders/scene.frag ====\n";

/// The printed vertex and fragment shaders of `shadowmap shaders ARGS`.
fn printed(args: &[&str]) -> (String, String) {
    let out = common::stdout_of(common::bin().arg("shaders").args(args));
    let rest = out.strip_prefix(VERTEX).expect("the vertex shader first");
    let (vertex, fragment) = rest.split_once(FRAGMENT).expect("then the fragment shader");
    (vertex.to_string(), fragment.to_string())
}

/// The texts the renderer's program key hands the driver for `scene` under `settings`.
fn compiled(scene: &Scene, settings: &ShadowSettings) -> [String; 2] {
    let plan = ShadowPlan::resolve(&scene.lights, settings, None).unwrap();
    let key = ProgramKey::of(scene, &plan, 0, Outputs::default()).unwrap();
    key.sources().unwrap().map(|s| s.text)
}

#[test]
fn the_printed_program_is_the_compiled_one_and_compiles() {
    let ctx = common::context();
    let dummy = Scene::load("dummy").unwrap();
    let (vertex, fragment) = printed(&["--scene", "dummy"]);
    assert_eq!(
        [vertex.clone(), fragment.clone()],
        compiled(&dummy, &dummy.shadow)
    );
    // The book's test, called with the DummyGame's settings; the defines shown.
    assert!(fragment.starts_with("#version 330 core\n#define LIGHT_COUNT 1\n"));
    assert!(fragment.contains("\nfloat calcShadow(sampler2D shadowMap, vec4 position,"));
    assert!(fragment.contains(
        "    float lit0 = SHADOW_DEPTH_OF(0, SHADOW_BORDER(0, mlightviewVertexPos[0], false, \
         calcShadow(shadowMap0, mlightviewVertexPos[0], 0.05, \
         vec2(0.0009765625, 0.0009765625), 1, false)));\n"
    ));
    assert!(
        !fragment.contains("pcss("),
        "only the tests the lights call"
    );
    let program = |v: &str, f: &str| {
        ShaderProgram::new(
            ctx.gl(),
            &ShaderSource::new("printed.vert", v),
            &ShaderSource::new("printed.frag", f),
            &[],
        )
    };
    program(&vertex, &fragment).unwrap_or_else(|e| panic!("{e}"));
    // Three kinds of light, each with its own test, and the flags applied.
    let (vertex, fragment) = printed(&["--scene", "three-lights", "--filter", "hw3x3"]);
    assert!(
        fragment.contains("calcShadowHardware(shadowMap0,"),
        "{fragment}"
    );
    assert!(
        fragment.contains("calcShadowCubeSoft(shadowCube2,"),
        "{fragment}"
    );
    program(&vertex, &fragment).unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn the_printed_program_has_every_include_resolved() {
    // What the driver gets has no `#include` line: not in either stage, for any scene, nor
    // with the translucent items tested per vertex.
    for scene in Scene::builtin_names() {
        let (vertex, fragment) = printed(&["--scene", scene]);
        for (stage, text) in [("vertex", &vertex), ("fragment", &fragment)] {
            let line = text
                .lines()
                .find(|l| l.trim_start().starts_with("#include"));
            assert_eq!(line, None, "{scene}: the {stage} shader keeps an include");
        }
    }
    let (vertex, _) = printed(&["--scene", "smoke", "--translucent-receivers", "vertex"]);
    assert!(!vertex.contains("#include"), "{vertex}");
}

#[test]
fn one_lights_part_is_its_sampler_its_library_and_its_call() {
    let out = common::stdout_of(common::bin().args([
        "shaders",
        "--scene",
        "playground",
        "--filter",
        "pcss",
        "--light",
        "0",
    ]));
    assert!(out.contains("\nuniform sampler2D shadowMap0;\n"), "{out}");
    assert!(out.contains("// ==== shaders/lib/pcss.glsl ====\n"));
    assert!(out.contains("\nfloat pcss(sampler2D shadowMap, vec4 position,"));
    assert!(out.contains(
        "    float lit0 = SHADOW_DEPTH_OF(0, SHADOW_BORDER(0, mlightviewVertexPos[0], false, \
         pcss(shadowMap0, mlightviewVertexPos[0], "
    ));
    assert!(!out.contains("void main()"), "its part, not the program");
}

#[test]
fn a_light_the_scene_lacks_is_refused() {
    let out = common::bin()
        .args(["shaders", "--scene", "dummy", "--light", "1"])
        .output()
        .unwrap();
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "error: --light 1: the scene <built-in dummy> has 1 light(s), numbered from 0\n"
    );
}

#[test]
fn the_depth_pass_reads_positions_alone_and_the_scene_pass_does_not() {
    let ctx = common::context();
    let depth = ShaderProgram::new(
        ctx.gl(),
        &shadowmap::shaders::depth_vert(),
        &shadowmap::shaders::depth_frag(),
        &[],
    )
    .unwrap();
    assert!(depth.reads_positions_only());
    let dummy = Scene::load("dummy").unwrap();
    let [vertex, fragment] = compiled(&dummy, &dummy.shadow);
    let scene = ShaderProgram::new(
        ctx.gl(),
        &ShaderSource::new("scene.vert", vertex),
        &ShaderSource::new("scene.frag", fragment),
        &[],
    )
    .unwrap();
    assert!(!scene.reads_positions_only());
}

#[test]
fn the_es_dialect_is_the_same_program_under_its_version_and_precision() {
    let desktop = common::stdout_of(common::bin().args(["shaders", "--scene", "learnopengl"]));
    let es = common::stdout_of(common::bin().args([
        "shaders",
        "--scene",
        "learnopengl",
        "--dialect",
        "es",
    ]));
    assert_eq!(es.matches("#version 300 es\n").count(), 2, "{es}");
    assert!(!es.contains("#version 330"));
    assert!(es.contains("precision highp sampler2DShadow;\n"));
    assert!(es.contains("#define SHADOW_BORDER_IN_SHADER 1\n"));
    // Past each shader's prelude (up to its `#line 2`), the desktop's text line for line.
    let mut back = Vec::new();
    let mut lines = es.lines();
    while let Some(line) = lines.next() {
        if line == "#version 300 es" {
            back.push("#version 330 core");
            for l in lines.by_ref() {
                if l == "#line 2" {
                    break;
                }
            }
        } else {
            back.push(line);
        }
    }
    assert_eq!(back.join("\n"), desktop.trim_end_matches('\n'));
}
