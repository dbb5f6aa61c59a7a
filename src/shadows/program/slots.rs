//! Where each light's shadow lives in the scene shader: its sampler, its slot in the
//! uniform arrays, and the call that adds its light to a fragment (texture units:
//! [`crate::shadows::units`]). ("Shadows"
//! ends with "render a separate depth map for each light"; this is the bookkeeping that
//! takes.)
//!
//! GLSL 3.30 indexes sampler arrays only with constant expressions, and a scene can mix 2D
//! maps, cube maps and cascade arrays, so each light gets its own named sampler and its own
//! call. Those two lists are the only GLSL made in Rust: two small snippets,
//! `generated/samplers.glsl` and `generated/lights.glsl`, included by `shaders/scene.frag`
//! like the library's (so a compile error in them names the generated file and its line).
//! Each technique chooses the library function its light's filter calls and writes the
//! call, the light's settings as literal arguments (its `glsl`, reached through
//! [`ShadowKind::glsl`]); this file names no technique but volumes, which have no test. The
//! compiler inlines the call and folds them, so a light's test costs what a hand-written one
//! would.

use crate::settings::BiasMode;
use crate::shadows::{volumes, ShadowKind, ShadowTest};

/// What the scene program is compiled for about one light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LightSlot {
    pub shadow: ShadowKind,
    /// Shades from a position (per-fragment direction) rather than one direction.
    pub positional: bool,
    /// A spot light's cone limits it.
    pub cone: bool,
    /// Its shadow test (its own settings), when it casts.
    pub test: Option<ShadowTest>,
}

/// Whether translucent items take light `slot`'s test per vertex: its settings ask for it
/// and it can run there.
pub fn per_vertex(slot: &LightSlot) -> bool {
    (slot.test).is_some_and(|t| t.vertex_receivers && t.runs_per_vertex(slot.shadow))
}

/// What a scene program does with the cached shadow mask (`src/renderer/shadow_mask.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum MaskMode {
    /// Each light's test, computed per fragment: the chapters' scene pass.
    #[default]
    Off,
    /// The same tests, written out per light instead of a colour (`SHADOW_MASK_WRITE`).
    Write,
    /// The tests read back from the mask (`SHADOW_MASK_READ`).
    Read,
    /// The translucent items' program: the lights that can take their test per vertex
    /// (`VERTEX_TESTS`, [`super::vertex`]), the others per fragment, each reading
    /// its translucent map's curve (not a resolved map, [`crate::shadows::volumetric::resolved`]).
    Vertex,
}

/// For each light, its slot among the lights with a 2D or cube map (the ones that get a
/// light-space position from the vertex shader), in order; `None` for the others.
pub fn map_slots(kinds: impl IntoIterator<Item = ShadowKind>) -> Vec<Option<usize>> {
    let mut next = 0;
    kinds
        .into_iter()
        .map(|k| {
            next += usize::from(k.map_slot());
            k.map_slot().then(|| next - 1)
        })
        .collect()
}

/// The vertex shader's output components for these lights with `cascades` layers: texture
/// coordinate, view-space normal and position (8), a light-space position per mapped
/// light (4 each), the cascaded light's positions (4 per cascade), and per light a flat
/// diffuse colour and light vector (6 each) besides the ambient colour (4). GL 3.3
/// guarantees 64; the worst case (four lights, one with four cascades) is exactly that.
pub fn vertex_outputs(slots: &[LightSlot], cascades: u32) -> usize {
    let mapped = map_slots(slots.iter().map(|s| s.shadow))
        .iter()
        .flatten()
        .count();
    let cascaded = slots.iter().any(|s| s.shadow.layered());
    8 + 4 * mapped + if cascaded { 4 * cascades as usize } else { 0 } + 4 + 6 * slots.len()
}

/// One light's part of the generated snippets (`shadowmap shaders --light I` prints it).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LightPart {
    /// Its sampler's declaration, when its test reads a map.
    pub sampler: Option<String>,
    /// The defines its test needs (a layered light's filter).
    pub defines: Vec<(&'static str, String)>,
    /// The library files its test calls into.
    pub snippets: Vec<&'static str>,
    /// Its lines in `addLights`.
    pub lines: Vec<String>,
}

/// Light `i`'s part, its light-space position (if any) in map slot `p`: its test's
/// function, chosen by its technique and filter, called with its own settings, and the
/// light added to the fragment times that test.
pub fn light_part(i: usize, p: usize, slot: &LightSlot, mask: MaskMode) -> LightPart {
    let (positional, cone) = (slot.positional, slot.cone);
    let glsl = slot.test.and_then(|test| slot.shadow.glsl(i, p, &test));
    let mut part = LightPart::default();
    if slot.shadow == ShadowKind::Volume {
        part.lines.push(volumes::call(i, positional, cone));
        return part;
    }
    let (Some(glsl), Some(name)) = (glsl, slot.shadow.sampler(i)) else {
        part.lines
            .push(format!("addLightUnshadowed({i}, {positional}, {cone}, f);"));
        return part;
    };
    if mask == MaskMode::Read {
        part.lines.push(format!(
            "addLight({i}, toLightOf({i}, {positional}), {cone}, maskedLit[{i}], f);"
        ));
        return part;
    }
    if mask == MaskMode::Vertex && per_vertex(slot) {
        part.lines.push(format!(
            "addLight({i}, toLightOf({i}, {positional}), {cone}, vertexLit[{i}], f);"
        ));
        return part;
    }
    part.sampler = Some(format!("uniform {} {name};", glsl.sampler_type));
    part.defines = glsl.defines;
    if slot.test.is_some_and(|t| t.bias_mode == BiasMode::Slope) {
        part.snippets.push("lib/bias.glsl");
    }
    part.snippets.extend(glsl.snippets);
    part.lines = vec![
        format!("vec3 toLight{i} = toLightOf({i}, {positional});"),
        format!("float lit{i} = {};", glsl.test),
        format!("addLight({i}, toLight{i}, {cone}, lit{i}, f);"),
    ];
    // The light that passes the opaque test times what the translucent casters let
    // through; the translucent items' own program (`Vertex`) reads the curve.
    let opaque = mask != MaskMode::Vertex;
    let key = slot.test.and_then(|t| t.volumetric);
    if let Some(((file, call), key)) = key.and_then(|k| Some((k.lookup(i, p, opaque)?, k))) {
        part.snippets.push("lib/volumetric.glsl");
        if !part.snippets.contains(&file) {
            part.snippets.push(file);
        }
        let declared = part.sampler.take().unwrap_or_default();
        part.sampler = Some(format!("{declared}\n{}", key.sampler(i, opaque)));
        part.lines.insert(2, format!("lit{i} *= {call};"));
    }
    part
}

/// Every light's part, in the scene's order.
pub fn light_parts(slots: &[LightSlot], mask: MaskMode) -> Vec<LightPart> {
    let map_slot = map_slots(slots.iter().map(|s| s.shadow));
    slots
        .iter()
        .enumerate()
        .map(|(i, slot)| light_part(i, map_slot[i].unwrap_or(0), slot, mask))
        .collect()
}

/// The two generated snippets for these lights: `generated/samplers.glsl` (one sampler
/// declaration per casting light) and `generated/lights.glsl`: the library files the
/// lights' tests call, each included once, then `addLights`, each light's lines in order.
///
/// With `mask` = [`MaskMode::Read`] no test is compiled in: each casting light takes its
/// test from the cached shadow mask (`maskedLit`, read once per fragment in scene.frag).
pub fn snippets(slots: &[LightSlot], mask: MaskMode) -> [(&'static str, String); 2] {
    let parts = light_parts(slots, mask);
    let mut samplers =
        String::from("// Made by src/shadows/program/slots.rs: one sampler per casting light.\n");
    let mut lights = String::from(
        "// Made by src/shadows/program/slots.rs: the library's tests these lights use, then each\n\
         // light's test, called with its own settings, and its light.\n",
    );
    let mut included: Vec<&str> = Vec::new();
    for part in &parts {
        for (k, v) in &part.defines {
            lights.push_str(&format!("#define {k} {v}\n"));
        }
        for &file in &part.snippets {
            if !included.contains(&file) {
                lights.push_str(&format!("#include \"{file}\"\n"));
                included.push(file);
            }
        }
        samplers.extend(part.sampler.iter().map(|s| format!("{s}\n")));
    }
    lights.push_str("\nvoid addLights(inout Fragment f)\n{\n");
    for part in &parts {
        for line in &part.lines {
            lights.push_str(&format!("    {line}\n"));
        }
    }
    lights.push_str("}\n");
    [
        ("generated/samplers.glsl", samplers),
        ("generated/lights.glsl", lights),
    ]
}
