//! Where each light's shadow lives in the scene shader: its texture unit, its sampler, its
//! slot in the uniform arrays, and the call that adds its light to a fragment. ("Shadows"
//! ends with "render a separate depth map for each light"; this is the bookkeeping that
//! takes.)
//!
//! GLSL 3.30 indexes sampler arrays only with constant expressions, and a scene can mix 2D
//! maps, cube maps and cascade arrays, so each light gets its own named sampler and its own
//! call. Those two lists are the only GLSL made in Rust: two small snippets,
//! `generated/samplers.glsl` and `generated/lights.glsl`, included by `shaders/scene.frag`
//! like the library's (so a compile error in them names the generated file and its line).
//! Each technique writes its own two lines ([`super::map2d::glsl`], [`super::cube::glsl`],
//! [`super::cascades::glsl`]).

use super::{cascades, cube, map2d, ShadowKind};
use crate::scene::MAX_LIGHTS;

/// The material's texture unit; light `i`'s shadow map is on unit `1 + i`.
pub const MATERIAL_UNIT: u32 = 0;

/// The texture unit of light `index`'s shadow map.
pub fn texture_unit(index: usize) -> u32 {
    1 + index as u32
}

/// What the scene program is compiled for about one light.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct LightSlot {
    pub shadow: ShadowKind,
    /// Shades from a position (per-fragment direction) rather than one direction.
    pub positional: bool,
    /// A spot light's cone limits it.
    pub cone: bool,
}

/// The sampler uniform of light `index`'s shadow, if it has one.
pub fn sampler_name(index: usize, kind: ShadowKind) -> Option<&'static str> {
    match kind {
        _ if index >= MAX_LIGHTS => None,
        ShadowKind::None => None,
        ShadowKind::Map => Some(map2d::SAMPLERS[index]),
        ShadowKind::Cube => Some(cube::SAMPLERS[index]),
        ShadowKind::Cascades => Some(cascades::SAMPLERS[index]),
    }
}

/// For each light, its slot among the lights with a 2D or cube map (the ones that get a
/// light-space position from the vertex shader), in order; `None` for the others.
pub fn map_slots(kinds: impl IntoIterator<Item = ShadowKind>) -> Vec<Option<usize>> {
    let mut next = 0;
    kinds
        .into_iter()
        .map(|k| match k {
            ShadowKind::Map | ShadowKind::Cube => {
                next += 1;
                Some(next - 1)
            }
            ShadowKind::None | ShadowKind::Cascades => None,
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
    let cascaded = slots.iter().any(|s| s.shadow == ShadowKind::Cascades);
    8 + 4 * mapped + if cascaded { 4 * cascades as usize } else { 0 } + 4 + 6 * slots.len()
}

/// The two generated snippets for these lights: `generated/samplers.glsl` (one sampler
/// declaration per casting light) and `generated/lights.glsl` (`addLights`, one add... call
/// per light in order, with its map slot).
pub fn snippets(slots: &[LightSlot]) -> [(&'static str, String); 2] {
    let mut samplers =
        String::from("// Made by src/shadows/slots.rs: one sampler per casting light.\n");
    let mut calls = String::from(
        "// Made by src/shadows/slots.rs: each light's call, in the scene's order.\n\
         void addLights(inout Fragment f)\n{\n",
    );
    let map_slot = map_slots(slots.iter().map(|s| s.shadow));
    for (i, slot) in slots.iter().enumerate() {
        let p = map_slot[i].unwrap_or(0);
        let (positional, cone) = (slot.positional, slot.cone);
        let (sampler, call) = match slot.shadow {
            ShadowKind::None => (
                None,
                format!("addLightUnshadowed({i}, {positional}, {cone}, f);"),
            ),
            ShadowKind::Map => {
                let (s, c) = map2d::glsl(i, p, positional, cone);
                (Some(s), c)
            }
            ShadowKind::Cube => {
                let (s, c) = cube::glsl(i, p, positional, cone);
                (Some(s), c)
            }
            ShadowKind::Cascades => {
                let (s, c) = cascades::glsl(i, positional, cone);
                (Some(s), c)
            }
        };
        if let Some(s) = sampler {
            samplers.push_str(&s);
            samplers.push('\n');
        }
        calls.push_str("    ");
        calls.push_str(&call);
        calls.push('\n');
    }
    calls.push_str("}\n");
    [
        ("generated/samplers.glsl", samplers),
        ("generated/lights.glsl", calls),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Light;
    use crate::settings::ShadowSettings;
    use crate::Scene;

    #[test]
    fn only_the_first_casting_directional_light_gets_cascades() {
        let mut scene = Scene::load("three-lights").unwrap();
        let sun = scene.lights[0];
        let mut quiet_sun = sun;
        if let Light::Directional(l) = &mut quiet_sun {
            l.casts_shadows = false;
        }
        // A sun that does not cast, then two that do, then the spot, point and fill lights.
        scene.lights = vec![quiet_sun, sun, sun, scene.lights[1], scene.lights[2]];
        let settings = ShadowSettings {
            cascades: 4,
            ..scene.shadow
        };
        use ShadowKind::*;
        assert_eq!(
            ShadowKind::for_lights(&scene.lights, &settings),
            [None, Cascades, Map, Map, Cube]
        );
        let one = ShadowSettings {
            cascades: 1,
            ..settings
        };
        assert_eq!(
            ShadowKind::for_lights(&scene.lights, &one),
            [None, Map, Map, Map, Cube]
        );
    }

    #[test]
    fn every_light_has_its_own_texture_unit_and_call() {
        let slot = |shadow, positional| LightSlot {
            shadow,
            positional,
            cone: false,
        };
        let slots = [
            slot(ShadowKind::Map, false),
            slot(ShadowKind::None, true),
            slot(ShadowKind::Cube, true),
            slot(ShadowKind::Cascades, false),
        ];
        let [(samplers_name, samplers), (lights_name, lights)] = snippets(&slots);
        assert_eq!(samplers_name, "generated/samplers.glsl");
        assert_eq!(lights_name, "generated/lights.glsl");
        let lines = |t: &str| -> Vec<String> {
            t.lines()
                .filter(|l| !l.starts_with("//"))
                .map(|l| l.trim().to_string())
                .collect()
        };
        assert_eq!(
            lines(&samplers),
            [
                "uniform SHADOW_SAMPLER_2D shadowMap0;",
                "uniform samplerCube shadowCube2;",
                "uniform SHADOW_SAMPLER_ARRAY cascadeMap3;"
            ]
        );
        assert_eq!(
            lines(&lights),
            [
                "void addLights(inout Fragment f)",
                "{",
                "addLight2D(0, 0, shadowMap0, false, false, f);",
                "addLightUnshadowed(1, true, false, f);",
                "addLightCube(2, 1, shadowCube2, true, false, f);",
                "addLightCascades(3, cascadeMap3, false, false, f);",
                "}"
            ]
        );
        let units: Vec<u32> = (0..MAX_LIGHTS).map(texture_unit).collect();
        assert_eq!(units, [1, 2, 3, 4]);
        assert!(!units.contains(&MATERIAL_UNIT));
    }

    #[test]
    fn the_worst_case_fits_gl_3_3s_vertex_outputs() {
        let slot = |shadow| LightSlot {
            shadow,
            positional: true,
            cone: false,
        };
        use ShadowKind::*;
        let worst = [slot(Cascades), slot(Map), slot(Cube), slot(Map)];
        assert_eq!(vertex_outputs(&worst, 4), 64);
        let maps = [slot(Map), slot(Map), slot(Cube), slot(Map)];
        assert_eq!(vertex_outputs(&maps, 4), 52);
        assert_eq!(vertex_outputs(&[slot(Map)], 1), 22);
        assert_eq!(
            map_slots([Cascades, Map, None, Cube]),
            [Option::None, Some(0), Option::None, Some(1)]
        );
    }
}
