//! The GLSL sources, embedded at build time so the binary runs from any directory, and the
//! small `#include` resolver the scene shader's snippets need.
//!
//! GLSL has no `#include`. A line `#include "lib/name.glsl"` is replaced by that file's
//! text between two `#line` directives: one before it, starting file K's lines, and one
//! after it, back to the includer's next line. GLSL's `#line` takes a "source string
//! number" for K, but Mesa reports every message as source 0, so K also goes into the line
//! number: file K's line L is numbered `K * LINE_BLOCK + L`.
//! [`crate::engine::shader_program::annotate_log`] decodes both, so a mistake in a snippet
//! names the snippet and its own line. Files under `generated/` are
//! not on disk: the renderer makes them for the scene's lights
//! ([`crate::shadows::program::slots`]) and passes them in.

use crate::engine::shader_program::LINE_BLOCK;
use crate::engine::ShaderSource;
use crate::error::{Error, Result};

macro_rules! shader {
    ($name:ident, $file:literal) => {
        /// The embedded text of `shaders/` + the file name.
        pub fn $name() -> ShaderSource {
            ShaderSource::new(
                concat!("shaders/", $file),
                include_str!(concat!("../shaders/", $file)),
            )
        }
    };
}

shader!(depth_vert, "depth.vert");
shader!(depth_frag, "depth.frag");
shader!(scene_vert, "scene.vert");
shader!(depth_view_vert, "depth_view.vert");
shader!(depth_view_frag, "depth_view.frag");
shader!(depth_point_vert, "depth_point.vert");
shader!(depth_point_frag, "depth_point.frag");
shader!(depth_point_layered_vert, "depth_point_layered.vert");
shader!(depth_point_layered_geom, "depth_point_layered.geom");
shader!(volume_vert, "volume.vert");
shader!(volume_geom, "volume.geom");
shader!(volume_frag, "volume.frag");
shader!(avsm_peel_frag, "avsm_peel.frag");
shader!(avsm_build_frag, "avsm_build.frag");
shader!(moments_depth_frag, "moments_depth.frag");
shader!(moments_blur_frag, "moments_blur.frag");
shader!(summed_area_frag, "summed_area.frag");
shader!(text_vert, "text.vert");
shader!(text_frag, "text.frag");
shader!(translucent_map_vert, "translucent_map.vert");
shader!(osm_map_frag, "osm_map.frag");
shader!(fom_map_frag, "fom_map.frag");

/// The snippets a shader may `#include`, by the name it includes them with.
const LIBRARY: &[(&str, &str)] = &[
    (
        "lib/lighting.glsl",
        include_str!("../shaders/lib/lighting.glsl"),
    ),
    ("lib/bias.glsl", include_str!("../shaders/lib/bias.glsl")),
    (
        "lib/shadow_border.glsl",
        include_str!("../shaders/lib/shadow_border.glsl"),
    ),
    (
        "lib/shadow_depth.glsl",
        include_str!("../shaders/lib/shadow_depth.glsl"),
    ),
    ("lib/avsm.glsl", include_str!("../shaders/lib/avsm.glsl")),
    (
        "lib/linear_depth.glsl",
        include_str!("../shaders/lib/linear_depth.glsl"),
    ),
    (
        "lib/shadow_2d.glsl",
        include_str!("../shaders/lib/shadow_2d.glsl"),
    ),
    (
        "lib/hardware_pcf.glsl",
        include_str!("../shaders/lib/hardware_pcf.glsl"),
    ),
    (
        "lib/soft_filters.glsl",
        include_str!("../shaders/lib/soft_filters.glsl"),
    ),
    ("lib/pcss.glsl", include_str!("../shaders/lib/pcss.glsl")),
    (
        "lib/shadow_cube.glsl",
        include_str!("../shaders/lib/shadow_cube.glsl"),
    ),
    (
        "lib/shadow_layers.glsl",
        include_str!("../shaders/lib/shadow_layers.glsl"),
    ),
    (
        "lib/shadow_cascades.glsl",
        include_str!("../shaders/lib/shadow_cascades.glsl"),
    ),
    (
        "lib/shadow_groups.glsl",
        include_str!("../shaders/lib/shadow_groups.glsl"),
    ),
    (
        "lib/shadow_moments.glsl",
        include_str!("../shaders/lib/shadow_moments.glsl"),
    ),
    (
        "lib/soft_moments.glsl",
        include_str!("../shaders/lib/soft_moments.glsl"),
    ),
    (
        "lib/volumetric.glsl",
        include_str!("../shaders/lib/volumetric.glsl"),
    ),
    ("lib/osm.glsl", include_str!("../shaders/lib/osm.glsl")),
    (
        "lib/vertex_lights.glsl",
        include_str!("../shaders/lib/vertex_lights.glsl"),
    ),
    ("lib/fom.glsl", include_str!("../shaders/lib/fom.glsl")),
    (
        "lib/outputs.glsl",
        include_str!("../shaders/lib/outputs.glsl"),
    ),
];

/// The names of the library's snippets.
pub fn library() -> impl Iterator<Item = &'static str> {
    LIBRARY.iter().map(|(name, _)| *name)
}

/// A library snippet's text, with the snippets it includes resolved.
pub fn snippet(name: &str) -> Result<ShaderSource> {
    let (_, text) = LIBRARY
        .iter()
        .find(|(f, _)| *f == name)
        .ok_or_else(|| Error::Invalid(format!("no library snippet {name}")))?;
    resolve(&format!("shaders/{name}"), text, &[])
}

/// The scene pass' fragment shader with its snippets included; `generated` are the
/// `generated/...` files made for the scene's lights.
pub fn scene_frag(generated: &[(&str, String)]) -> Result<ShaderSource> {
    resolve(
        "shaders/scene.frag",
        include_str!("../shaders/scene.frag"),
        generated,
    )
}

/// Replaces every `#include "name"` line of `text` (and of what it includes) with the named
/// file: a library snippet or one of `generated`. Each file is included at most once per
/// shader; a file that includes itself, directly or not, is an error.
pub fn resolve(name: &str, text: &str, generated: &[(&str, String)]) -> Result<ShaderSource> {
    let mut out = ShaderSource::new(name, String::with_capacity(text.len() * 4));
    out.text.clear();
    let mut stack = vec![name.to_string()];
    include_into(&mut out, text, 0, generated, &mut stack)?;
    Ok(out)
}

fn include_into(
    out: &mut ShaderSource,
    text: &str,
    index: usize,
    generated: &[(&str, String)],
    stack: &mut Vec<String>,
) -> Result<()> {
    for (n, line) in text.lines().enumerate() {
        let Some(target) = include_target(line) else {
            out.text.push_str(line);
            out.text.push('\n');
            continue;
        };
        let here = || format!("{}:{}", out.files[index], n + 1);
        if stack.iter().any(|f| f == target) {
            return Err(Error::Invalid(format!(
                "{}: #include \"{target}\" includes itself",
                here()
            )));
        }
        let body = LIBRARY
            .iter()
            .find(|(f, _)| *f == target)
            .map(|(_, t)| *t)
            .or_else(|| {
                generated
                    .iter()
                    .find(|(f, _)| *f == target)
                    .map(|(_, t)| t.as_str())
            })
            .ok_or_else(|| {
                Error::Invalid(format!(
                    "{}: #include \"{target}\": no such snippet (the library has {})",
                    here(),
                    LIBRARY
                        .iter()
                        .map(|(f, _)| *f)
                        .collect::<Vec<_>>()
                        .join(", ")
                ))
            })?;
        let child = out.files.len();
        out.files.push(format!("shaders/{target}"));
        out.text
            .push_str(&format!("#line {} {child}\n", first_line(child, 1)));
        stack.push(target.to_string());
        include_into(out, body, child, generated, stack)?;
        stack.pop();
        // Back in the includer: its next line keeps its own number.
        out.text
            .push_str(&format!("#line {} {index}\n", first_line(index, n + 2)));
    }
    Ok(())
}

/// The number `#line` gives line `line` of file `file`.
fn first_line(file: usize, line: usize) -> usize {
    file * LINE_BLOCK as usize + line
}

/// The file named by an `#include "..."` line, if the line is one.
fn include_target(line: &str) -> Option<&str> {
    let rest = line.trim_start().strip_prefix('#')?.trim_start();
    let rest = rest.strip_prefix("include")?.trim();
    rest.strip_prefix('"')?.strip_suffix('"')
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn includes_keep_each_files_own_line_numbers() {
        let gen = [("generated/a.glsl", "float a;\nfloat b;".to_string())];
        let s = resolve(
            "main.frag",
            "#version 330 core\n#include \"generated/a.glsl\"\nvoid main() {}\n",
            &gen,
        )
        .unwrap();
        assert_eq!(
            s.text,
            "#version 330 core\n#line 100001 1\nfloat a;\nfloat b;\n#line 3 0\nvoid main() {}\n"
        );
        assert_eq!(s.files, ["main.frag", "shaders/generated/a.glsl"]);
    }

    #[test]
    fn a_missing_or_circular_include_names_where_it_is() {
        let e = resolve("m.frag", "x\n#include \"lib/nope.glsl\"\n", &[]).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("m.frag:2: #include \"lib/nope.glsl\": no such snippet"),
            "{e}"
        );
        let gen = [(
            "generated/loop.glsl",
            "#include \"generated/loop.glsl\"".into(),
        )];
        let e = resolve("m.frag", "#include \"generated/loop.glsl\"\n", &gen).unwrap_err();
        assert!(e.to_string().contains("includes itself"), "{e}");
    }
}
