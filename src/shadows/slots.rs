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
//! [`super::layers::Snippet::glsl`]).

use super::moments::MomentTest;
use super::{cascades, cube, groups, map2d, moments, volumes, ShadowKind};
use crate::scene::Light;
use crate::scene::MAX_LIGHTS;
use crate::settings::{
    glsl_float, BeyondFar, BiasMode, Filter, LightProjection, MapSize, ShadowSettings,
};

/// The material's texture unit; light `i`'s shadow map is on unit `1 + i`.
pub const MATERIAL_UNIT: u32 = 0;

/// The texture unit of the cached shadow mask (after every light's map).
pub const MASK_UNIT: u32 = 1 + crate::scene::MAX_LIGHTS as u32;

/// The texture unit of light `index`'s shadow map.
pub fn texture_unit(index: usize) -> u32 {
    1 + index as u32
}

/// The shadow test's constants (shaders/lib/bias.glsl and the technique snippets).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ShadowTest {
    pub pcf_radius: u32,
    pub hardware: bool,
    pub bias_mode: BiasMode,
    pub bias_bits: u32,
    pub bias_min_bits: u32,
    pub beyond_far_lit: bool,
    pub normal_offset: bool,
    /// The map's size: the PCF grid steps one texel, 1 / width across and 1 / height up.
    pub map_size: MapSize,
    /// [`Filter::kernel`]: the grid, or a soft filter (shaders/lib/soft_filters.glsl).
    pub kernel: u32,
    /// PCSS's taps (0 for the other filters, so their key ignores them).
    pub pcss_blocker_taps: u32,
    pub pcss_filter_taps: u32,
    /// PCSS: the light's map is a perspective one (its depth is not linear).
    pub pcss_perspective: bool,
    /// A moment filter's own constants.
    pub moments: Option<MomentTest>,
}

impl ShadowTest {
    /// The test as the settings apply it ([`ShadowSettings::effective`]).
    pub fn of(settings: &ShadowSettings) -> ShadowTest {
        let s = settings.effective();
        let pcss = s.filter == Filter::Pcss;
        ShadowTest {
            pcf_radius: s.filter.radius(),
            hardware: s.filter.hardware(),
            bias_mode: s.bias_mode,
            bias_bits: s.bias.to_bits(),
            bias_min_bits: s.bias_min.to_bits(),
            beyond_far_lit: s.beyond_far == BeyondFar::Lit,
            normal_offset: s.normal_offset != 0.0,
            map_size: s.map_size,
            moments: MomentTest::of(&s),
            kernel: s.filter.kernel(),
            pcss_blocker_taps: if pcss { s.pcss_blocker_taps } else { 0 },
            pcss_filter_taps: if pcss { s.pcss_filter_taps } else { 0 },
            pcss_perspective: false,
        }
    }

    /// The test of `light` under its own settings: as [`ShadowTest::of`], knowing whether
    /// PCSS reads a perspective map (a spot's, or a directional light's perspective one).
    pub fn for_light(light: &Light, settings: &ShadowSettings) -> ShadowTest {
        let perspective = match light {
            Light::Spot(_) => true,
            Light::Directional(_) => settings.light_projection == LightProjection::Perspective,
            Light::Point(_) => false,
        };
        ShadowTest {
            pcss_perspective: perspective && settings.filter == Filter::Pcss,
            ..ShadowTest::of(settings)
        }
    }
}

impl ShadowTest {
    /// The constants of shaders/lib/bias.glsl and the technique snippets, for one light.
    /// How many constants [`ShadowTest::defines`] makes for every light (a moment map's
    /// add their own after them).
    pub const DEFINES: usize = 11;

    fn defines(&self) -> Vec<(&'static str, String)> {
        let bit = |b: bool| u32::from(b).to_string();
        let mode = match self.bias_mode {
            BiasMode::None => 0,
            BiasMode::Constant => 1,
            BiasMode::Slope => 2,
        };
        let mut d = vec![
            ("PCF_RADIUS", self.pcf_radius.to_string()),
            ("HW_PCF", bit(self.hardware)),
            ("BIAS_MODE", mode.to_string()),
            ("BIAS", glsl_float(f32::from_bits(self.bias_bits))),
            ("BIAS_MIN", glsl_float(f32::from_bits(self.bias_min_bits))),
            ("BEYOND_FAR_LIT", bit(self.beyond_far_lit)),
            (
                "SHADOW_TEXEL",
                format!(
                    "vec2({}, {})",
                    glsl_float(1.0 / self.map_size.width as f32),
                    glsl_float(1.0 / self.map_size.height as f32)
                ),
            ),
            ("FILTER_KERNEL", self.kernel.to_string()),
            ("PCSS_BLOCKER_TAPS", self.pcss_blocker_taps.to_string()),
            ("PCSS_FILTER_TAPS", self.pcss_filter_taps.to_string()),
            ("PCSS_PERSPECTIVE", bit(self.pcss_perspective)),
        ];
        if let Some(m) = &self.moments {
            d.extend(m.defines());
        }
        d
    }
}

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
}

/// The sampler uniform of light `index`'s shadow, if it has one.
pub fn sampler_name(index: usize, kind: ShadowKind) -> Option<&'static str> {
    match kind {
        _ if index >= MAX_LIGHTS => None,
        ShadowKind::None | ShadowKind::Volume => None,
        ShadowKind::Map | ShadowKind::Moments => Some(map2d::SAMPLERS[index]),
        ShadowKind::Cube => Some(cube::SAMPLERS[index]),
        ShadowKind::Cascades => Some(cascades::SAMPLERS[index]),
        ShadowKind::Groups => Some(groups::SAMPLERS[index]),
    }
}

/// For each light, its slot among the lights with a 2D or cube map (the ones that get a
/// light-space position from the vertex shader), in order; `None` for the others.
pub fn map_slots(kinds: impl IntoIterator<Item = ShadowKind>) -> Vec<Option<usize>> {
    let mut next = 0;
    kinds
        .into_iter()
        .map(|k| match k {
            ShadowKind::Map | ShadowKind::Cube | ShadowKind::Moments => {
                next += 1;
                Some(next - 1)
            }
            ShadowKind::None | ShadowKind::Cascades | ShadowKind::Groups | ShadowKind::Volume => {
                None
            }
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

/// The two generated snippets for these lights: `generated/samplers.glsl` (one sampler
/// declaration per casting light) and `generated/lights.glsl`: for each casting light its
/// test's constants as `#define`s and its technique's library snippet, with the snippet's
/// functions renamed after the light (`calcShadow` becomes `calcShadow_0`); then
/// `addLights`, one add... call per light in order.
///
/// With `mask` = [`MaskMode::Read`] no test is compiled in: each casting light takes its
/// test from the cached shadow mask (`maskedLit`, read once per fragment in scene.frag).
pub fn snippets(slots: &[LightSlot], mask: MaskMode) -> [(&'static str, String); 2] {
    let mut samplers =
        String::from("// Made by src/shadows/slots.rs: one sampler per casting light.\n");
    let mut lights = String::from(
        "// Made by src/shadows/slots.rs: each casting light's shadow test with its own\n\
         // constants, then each light's call in the scene's order.\n",
    );
    let mut calls = String::from("void addLights(inout Fragment f)\n{\n");
    let map_slot = map_slots(slots.iter().map(|s| s.shadow));
    for (i, slot) in slots.iter().enumerate() {
        let p = map_slot[i].unwrap_or(0);
        let (positional, cone) = (slot.positional, slot.cone);
        let hardware = slot.test.is_some_and(|t| t.hardware);
        let glsl = match slot.shadow {
            ShadowKind::Volume => {
                calls.push_str(&format!("    {}\n", volumes::call(i, positional, cone)));
                continue;
            }
            ShadowKind::None => None,
            ShadowKind::Map => Some(map2d::glsl(i, p, positional, cone, hardware)),
            ShadowKind::Cube => Some(cube::glsl(i, p, positional, cone)),
            ShadowKind::Cascades => Some(cascades::SNIPPET.glsl(i, positional, cone, hardware)),
            ShadowKind::Groups => Some(groups::SNIPPET.glsl(i, positional, cone, hardware)),
            ShadowKind::Moments => Some(moments::glsl(i, p, positional, cone)),
        };
        let (Some(glsl), Some(test), Some(name)) = (glsl, slot.test, sampler_name(i, slot.shadow))
        else {
            calls.push_str(&format!(
                "    addLightUnshadowed({i}, {positional}, {cone}, f);\n"
            ));
            continue;
        };
        if mask == MaskMode::Read {
            calls.push_str(&format!(
                "    addLight({i}, toLightOf({i}, {positional}), {cone}, maskedLit[{i}], f);\n"
            ));
            continue;
        }
        samplers.push_str(&format!("uniform {} {name};\n", glsl.sampler_type));
        let defines: Vec<(String, String)> = test
            .defines()
            .into_iter()
            .map(|(k, v)| (k.to_string(), v))
            .chain(std::iter::once(("LIGHT_INDEX".to_string(), i.to_string())))
            .chain(
                std::iter::once("depthBias")
                    .chain(glsl.functions.iter().copied())
                    .map(|f| (f.to_string(), format!("{f}_{i}"))),
            )
            .collect();
        lights.push_str(&format!("\n// Light {i}\n"));
        for (k, v) in &defines {
            lights.push_str(&format!("#define {k} {v}\n"));
        }
        lights.push_str("#include \"lib/bias.glsl\"\n");
        lights.push_str(&format!("#include \"{}\"\n", glsl.snippet));
        for (k, _) in &defines {
            lights.push_str(&format!("#undef {k}\n"));
        }
        calls.push_str(&format!("    {}\n", glsl.call));
    }
    calls.push_str("}\n");
    lights.push('\n');
    lights.push_str(&calls);
    [
        ("generated/samplers.glsl", samplers),
        ("generated/lights.glsl", lights),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
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
            crate::shadows::plan::ShadowPlan::decide(&scene.lights, &settings).kinds(),
            [None, Cascades, Map, Map, Cube]
        );
        let one = ShadowSettings {
            cascades: 1,
            ..settings
        };
        assert_eq!(
            crate::shadows::plan::ShadowPlan::decide(&scene.lights, &one).kinds(),
            [None, Map, Map, Map, Cube]
        );
    }

    #[test]
    fn every_light_has_its_own_texture_unit_sampler_test_and_call() {
        let hw = ShadowSettings {
            filter: crate::settings::Filter::Hardware2x2,
            bias: 0.25,
            ..ShadowSettings::default()
        };
        let slot = |shadow, positional, s: &ShadowSettings| LightSlot {
            shadow,
            positional,
            cone: false,
            test: (shadow != ShadowKind::None).then(|| ShadowTest::of(s)),
        };
        let book = ShadowSettings::default();
        let slots = [
            slot(ShadowKind::Map, false, &book),
            slot(ShadowKind::None, true, &book),
            slot(ShadowKind::Cube, true, &book),
            slot(ShadowKind::Cascades, false, &hw),
        ];
        let [(samplers_name, samplers), (lights_name, lights)] = snippets(&slots, MaskMode::Off);
        assert_eq!(samplers_name, "generated/samplers.glsl");
        assert_eq!(lights_name, "generated/lights.glsl");
        let lines = |t: &str| -> Vec<String> {
            t.lines()
                .filter(|l| !l.starts_with("//") && !l.trim().is_empty())
                .map(|l| l.trim().to_string())
                .collect()
        };
        // Each sampler's type follows its own light's filter.
        assert_eq!(
            lines(&samplers),
            [
                "uniform sampler2D shadowMap0;",
                "uniform samplerCube shadowCube2;",
                "uniform sampler2DArrayShadow cascadeMap3;"
            ]
        );
        let lights = lines(&lights);
        let calls = lights
            .iter()
            .position(|l| l == "void addLights(inout Fragment f)")
            .unwrap();
        assert_eq!(
            lights[calls..],
            [
                "void addLights(inout Fragment f)",
                "{",
                "addLight2D_0(0, 0, shadowMap0, false, false, f);",
                "addLightUnshadowed(1, true, false, f);",
                "addLightCube_2(2, 1, shadowCube2, true, false, f);",
                "addLightCascades_3(3, cascadeMap3, false, false, f);",
                "}"
            ]
        );
        // Light 0's test is the book's, light 3's its own; each snippet's functions are
        // renamed after its light, and every constant is undone after it.
        let block = |i: usize| -> Vec<String> {
            let from = lights
                .iter()
                .position(|l| l.starts_with(&format!("#define depthBias depthBias_{i}")))
                .unwrap();
            lights[from - ShadowTest::DEFINES - 1..from + 1].to_vec()
        };
        assert!(
            block(0).contains(&"#define BIAS 0.05".to_string()),
            "{:?}",
            block(0)
        );
        assert!(
            block(3).contains(&"#define BIAS 0.25".to_string()),
            "{:?}",
            block(3)
        );
        assert!(
            block(3).contains(&"#define HW_PCF 1".to_string()),
            "{:?}",
            block(3)
        );
        assert!(lights.contains(&"#define calcShadow calcShadow_0".to_string()));
        assert!(lights.contains(&"#define calcShadowCube calcShadowCube_2".to_string()));
        let defined = lights.iter().filter(|l| l.starts_with("#define")).count();
        let undone = lights.iter().filter(|l| l.starts_with("#undef")).count();
        assert_eq!(defined, undone);
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
            test: Option::None,
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

    #[test]
    fn every_library_snippet_is_reachable_from_the_scene_shader() {
        // Four lights of four kinds, one with cascades, one with a moment map: every
        // snippet is included but caster groups' (only one light is layered), which a
        // second set of lights includes.
        let test = ShadowTest::of(&crate::settings::ShadowSettings::default());
        let slot = |shadow| LightSlot {
            shadow,
            positional: false,
            cone: false,
            test: Some(test),
        };
        let generated = snippets(
            &[
                slot(ShadowKind::Map),
                slot(ShadowKind::Cube),
                slot(ShadowKind::Cascades),
                slot(ShadowKind::Moments),
            ],
            MaskMode::Off,
        );
        // Included directly or by another snippet (the soft filters by the 2D test's).
        let resolved = crate::shaders::scene_frag(&generated).unwrap();
        let groups = snippets(&[slot(ShadowKind::Groups)], MaskMode::Off);
        let resolved_groups = crate::shaders::scene_frag(&groups).unwrap();
        for name in crate::shaders::library() {
            let file = format!("shaders/{name}");
            assert!(
                resolved.files.contains(&file) || resolved_groups.files.contains(&file),
                "{name} is never included"
            );
        }
    }
}
