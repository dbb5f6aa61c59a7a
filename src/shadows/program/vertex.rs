//! Translucent receivers tested per vertex (`translucent_receivers = "vertex"`). The smoke's
//! puffs overlap many layers deep, and each of their fragments runs the light's filter and
//! the translucent lookup; engines light particles per vertex instead. The program that draws
//! the translucent items ([`MaskMode::Vertex`]) runs each such light's test, the very lines
//! the fragment shader would run, in the vertex shader (`generated/vertex_tests.glsl`,
//! included by shaders/scene.vert under `VERTEX_TESTS`), and the fragment takes it
//! interpolated (`vertexLit`, light i in component i), as it takes the shadow mask's.
//! Opaque items keep their tests per pixel.

use super::slots::{light_part, map_slots, per_vertex, LightSlot, MaskMode};
use crate::shadows::volumetric::VolumetricKey;
use crate::shadows::ShadowTest;

/// The generated snippet scene.vert includes.
pub const VERTEX_SNIPPET: &str = "generated/vertex_tests.glsl";

/// The vertex shader's snippet for these lights: the samplers and library files of the
/// lights tested per vertex, `toLightOf` and an `addLight` that keeps each light's test,
/// and `vertexTests`, which runs them and writes `vertexLit`.
pub fn vertex_snippet(slots: &[LightSlot]) -> (&'static str, String) {
    // The lines each light's test needs around it, in GLSL: shaders/lib/vertex_lights.glsl.
    let mut head = String::from("#include \"lib/vertex_lights.glsl\"\n");
    let mut body = String::from(
        "\nvoid vertexTests()\n{\n    Fragment f;\n    f.normal = mvVertexNormal;\n    \
         f.lit = vec4(1.0);\n",
    );
    let mut included: Vec<&str> = Vec::new();
    let map_slot = map_slots(slots.iter().map(|s| s.shadow));
    for (i, slot) in slots.iter().enumerate() {
        if !per_vertex(slot) {
            continue;
        }
        // Translucent receivers read the curve, whatever the opaque ones read.
        let curve = |t: ShadowTest| ShadowTest {
            volumetric: t.volumetric.map(|v| VolumetricKey {
                resolved: false,
                ..v
            }),
            ..t
        };
        let slot = &LightSlot {
            test: slot.test.map(curve),
            ..*slot
        };
        let part = light_part(i, map_slot[i].unwrap_or(0), slot, MaskMode::Off);
        head.extend(part.sampler.iter().map(|s| format!("{s}\n")));
        for file in part.snippets {
            if !included.contains(&file) {
                head.push_str(&format!("#include \"{file}\"\n"));
                included.push(file);
            }
        }
        body.extend(part.lines.iter().map(|l| format!("    {l}\n")));
    }
    body.push_str("    vertexLit = f.lit;\n}\n");
    (VERTEX_SNIPPET, head + &body)
}
