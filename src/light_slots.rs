//! The one place that decides where each light's shadow lives in the scene shader: its
//! texture unit, its sampler's name and type, its slot in the uniform arrays, and the call
//! that adds its light to a fragment. ("Shadows" ends with "render a separate depth map
//! for each light"; this is the bookkeeping that takes.)
//!
//! GLSL 3.30 indexes sampler arrays only with constant expressions, and a scene can mix
//! 2D maps, cube maps and cascade arrays, so each light gets its own named sampler and its
//! own call, written into the program as `#define`s when it is compiled for the scene.

use crate::scene::Light;
use crate::settings::{LightProjection, ShadowSettings};

/// Lights per scene. Each casting light takes one texture unit besides the material's (GL
/// 3.3 guarantees 16 per stage) and one block of per-pixel work; four keeps the shader's
/// cost within a few of the book's one light.
pub const MAX_LIGHTS: usize = 4;

/// The material's texture unit; light `i`'s shadow map is on unit `1 + i`.
pub const MATERIAL_UNIT: u32 = 0;

/// The texture unit of light `index`'s shadow map.
pub fn texture_unit(index: usize) -> u32 {
    1 + index as u32
}

/// What a light's shadow is stored in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShadowKind {
    /// The light does not cast: no map, no lookup.
    None,
    /// One 2D depth map (directional and spot lights; the chapters' case).
    Map,
    /// A depth cube map of distances (point lights).
    Cube,
    /// A depth texture array, one layer per cascade (directional lights with cascades).
    Cascades,
}

impl ShadowKind {
    /// The kind each of a scene's lights gets: as [`ShadowKind::of`], except that only the
    /// first casting directional light gets cascades (the sun; its cascades' positions are
    /// computed per vertex, and one light's fit among GL 3.3's 64 vertex outputs), the
    /// others one map each.
    pub fn for_lights(lights: &[Light], settings: &ShadowSettings) -> Vec<ShadowKind> {
        let mut cascaded = false;
        lights
            .iter()
            .map(|l| match ShadowKind::of(l, settings) {
                ShadowKind::Cascades if cascaded => ShadowKind::Map,
                ShadowKind::Cascades => {
                    cascaded = true;
                    ShadowKind::Cascades
                }
                kind => kind,
            })
            .collect()
    }

    /// The kind a light gets under `settings`, alone in its scene.
    pub fn of(light: &Light, settings: &ShadowSettings) -> ShadowKind {
        match light {
            l if !l.casts_shadows() => ShadowKind::None,
            Light::Point(_) => ShadowKind::Cube,
            Light::Directional(_)
                if settings.cascades > 1 && settings.light_projection == LightProjection::Ortho =>
            {
                ShadowKind::Cascades
            }
            Light::Directional(_) | Light::Spot(_) => ShadowKind::Map,
        }
    }
}

/// What the scene program is compiled for about one light.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LightSlot {
    pub shadow: ShadowKind,
    /// Shades from a position (per-fragment direction) rather than one direction.
    pub positional: bool,
    /// A spot light's cone limits it.
    pub cone: bool,
}

const SAMPLERS: [[&str; 3]; MAX_LIGHTS] = [
    ["shadowMap0", "shadowCube0", "cascadeMap0"],
    ["shadowMap1", "shadowCube1", "cascadeMap1"],
    ["shadowMap2", "shadowCube2", "cascadeMap2"],
    ["shadowMap3", "shadowCube3", "cascadeMap3"],
];

/// The sampler uniform of light `index`'s shadow, if it has one.
pub fn sampler_name(index: usize, kind: ShadowKind) -> Option<&'static str> {
    let names = SAMPLERS.get(index)?;
    match kind {
        ShadowKind::None => None,
        ShadowKind::Map => Some(names[0]),
        ShadowKind::Cube => Some(names[1]),
        ShadowKind::Cascades => Some(names[2]),
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

/// The `#define`s that lay the lights out in `shaders/scene.{vert,frag}`:
/// `LIGHT_COUNT` (the per-light arrays' length), `MAP_COUNT` and `MAP_SLOTS` (lights with
/// a light-space position, and their arrays' length, at least 1), `LIGHT_SAMPLERS` (one
/// declaration per casting light), `LIGHT_CALLS` (one `add...` call per light, in order,
/// with its map slot) and `VISIBILITY_LIGHT` (whose shadow test goes to the visibility
/// output that `compare` reads).
pub fn defines(slots: &[LightSlot], visibility_light: usize) -> Vec<(String, String)> {
    let mut samplers = String::new();
    let mut calls = String::new();
    let map_slot = map_slots(slots.iter().map(|s| s.shadow));
    let mapped = map_slot.iter().flatten().count();
    for (i, slot) in slots.iter().enumerate() {
        let p = map_slot[i].unwrap_or(0);
        let (positional, c) = (slot.positional, slot.cone);
        let sampler = sampler_name(i, slot.shadow);
        let (ty, call) = match slot.shadow {
            ShadowKind::None => (
                None,
                format!("addLightUnshadowed({i}, {positional}, {c}, f);"),
            ),
            ShadowKind::Map => (
                Some("SHADOW_SAMPLER_2D"),
                format!("addLight2D({i}, {p}, shadowMap{i}, {positional}, {c}, f);"),
            ),
            ShadowKind::Cube => (
                Some("samplerCube"),
                format!("addLightCube({i}, {p}, shadowCube{i}, {positional}, {c}, f);"),
            ),
            ShadowKind::Cascades => (
                Some("SHADOW_SAMPLER_ARRAY"),
                format!("addLightCascades({i}, cascadeMap{i}, {positional}, {c}, f);"),
            ),
        };
        if let (Some(ty), Some(name)) = (ty, sampler) {
            samplers.push_str(&format!("uniform {ty} {name}; "));
        }
        calls.push_str(&call);
        calls.push(' ');
    }
    vec![
        ("LIGHT_COUNT".into(), slots.len().max(1).to_string()),
        ("MAP_COUNT".into(), mapped.to_string()),
        ("MAP_SLOTS".into(), mapped.max(1).to_string()),
        ("LIGHT_SAMPLERS".into(), samplers),
        ("LIGHT_CALLS".into(), calls),
        ("VISIBILITY_LIGHT".into(), visibility_light.to_string()),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
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
        let slots = [
            LightSlot {
                shadow: ShadowKind::Map,
                positional: false,
                cone: false,
            },
            LightSlot {
                shadow: ShadowKind::None,
                positional: true,
                cone: false,
            },
            LightSlot {
                shadow: ShadowKind::Cube,
                positional: true,
                cone: false,
            },
            LightSlot {
                shadow: ShadowKind::Cascades,
                positional: false,
                cone: false,
            },
        ];
        let d: std::collections::HashMap<String, String> = defines(&slots, 2).into_iter().collect();
        assert_eq!(d["LIGHT_COUNT"], "4");
        assert_eq!(d["VISIBILITY_LIGHT"], "2");
        assert_eq!(
            (d["MAP_COUNT"].as_str(), d["MAP_SLOTS"].as_str()),
            ("2", "2")
        );
        assert_eq!(
            d["LIGHT_SAMPLERS"].trim(),
            "uniform SHADOW_SAMPLER_2D shadowMap0; uniform samplerCube shadowCube2; \
             uniform SHADOW_SAMPLER_ARRAY cascadeMap3;"
        );
        assert_eq!(
            d["LIGHT_CALLS"].trim(),
            "addLight2D(0, 0, shadowMap0, false, false, f); addLightUnshadowed(1, true, false, f); \
             addLightCube(2, 1, shadowCube2, true, false, f); \
             addLightCascades(3, cascadeMap3, false, false, f);"
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
