//! `shadowmap shaders`: the scene program's source as the driver gets it, so a reader sees
//! the code the GPU runs for a scene and its settings (the lights' tests and their
//! arguments included). No GL: the text is made as the renderer makes it.

use shadowmap::compare::check_light;
use shadowmap::engine::{Dialect, Outputs};
use shadowmap::shaders;
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::shadows::program::slots::{self, LightPart, MaskMode};
use shadowmap::shadows::program::ProgramKey;
use shadowmap::{Result, Scene, ShadowSettings};

use super::cli::ShadersArgs;

/// The line before each printed shader: `// ==== <stage> shader: <file> ====`.
pub const HEADER: &str = "// ==== ";

pub fn run(args: &ShadersArgs) -> Result<()> {
    let mut scene = args.scene.load()?;
    let settings = args.settings.apply(&mut scene)?;
    args.settings.check_values(&scene, &settings)?;
    if let Some(light) = args.light {
        check_light(&scene, light, "--light", false)?;
    }
    let dialect = shadowmap::engine::Dialect::from(args.dialect);
    print!("{}", text(&scene, &settings, args.light, dialect)?);
    Ok(())
}

/// The printed text: the whole program in `dialect`, or with `light` that light's part of
/// it (snippets, which have no `#version` of their own).
pub fn text(
    scene: &Scene,
    settings: &ShadowSettings,
    light: Option<usize>,
    dialect: Dialect,
) -> Result<String> {
    let key = key(scene, settings)?;
    let Some(i) = light else {
        let [vertex, fragment] = key.sources()?;
        return Ok(format!(
            "{HEADER}vertex shader: {} ====\n{}{HEADER}fragment shader: {} ====\n{}",
            vertex.name,
            dialect.apply(&vertex.text),
            fragment.name,
            dialect.apply(&fragment.text)
        ));
    };
    let part = &slots::light_parts(&key.slots(), MaskMode::Off)[i];
    light_text(scene, i, part)
}

/// The program a plain frame of this scene compiles (the renderer's key with no extra
/// outputs, the first light's visibility, no shadow mask).
pub fn key(scene: &Scene, settings: &ShadowSettings) -> Result<ProgramKey> {
    let plan = ShadowPlan::resolve(&scene.lights, settings, None)?;
    ProgramKey::of(scene, &plan, 0, Outputs::default())
}

/// Light `i`'s part: its sampler, its defines, the library files it calls into (each
/// whole), and its lines in `addLights`.
fn light_text(scene: &Scene, i: usize, part: &LightPart) -> Result<String> {
    let mut out = format!(
        "// Light {i} of the {} scene ({}): its part of the scene program's fragment shader.\n",
        scene.name,
        scene.lights[i].kind_name()
    );
    if let Some(sampler) = &part.sampler {
        out.push_str(&format!("\n// In generated/samplers.glsl:\n{sampler}\n"));
    }
    if !part.defines.is_empty() || !part.snippets.is_empty() {
        out.push_str("\n// In generated/lights.glsl, before addLights:\n");
    }
    for (k, v) in &part.defines {
        out.push_str(&format!("#define {k} {v}\n"));
    }
    for file in &part.snippets {
        out.push_str(&format!("#include \"{file}\"\n"));
    }
    for file in &part.snippets {
        let s = shaders::snippet(file)?;
        out.push_str(&format!("\n{HEADER}{} ====\n{}", s.name, s.text));
    }
    out.push_str("\n// In addLights (generated/lights.glsl):\n");
    for line in &part.lines {
        out.push_str(&format!("    {line}\n"));
    }
    Ok(out)
}
