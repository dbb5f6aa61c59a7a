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
//! Each technique chooses the library function its light's filter calls and writes the
//! call, the light's settings as literal arguments ([`map2d_glsl`],
//! [`cube_glsl`], [`moments_glsl`], [`layered_glsl`]); the
//! compiler inlines it and folds them, so a light's test costs what a hand-written one
//! would.

use super::vertex::per_vertex;
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
    /// (`VERTEX_TESTS`, [`volumetric::receivers`]), the others per fragment, each reading
    /// its translucent map's curve (not a resolved map, [`volumetric::resolved`]).
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
        String::from("// Made by src/shadows/slots.rs: one sampler per casting light.\n");
    let mut lights = String::from(
        "// Made by src/shadows/slots.rs: the library's tests these lights use, then each\n\
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
        // Each library file once, the layered light's filter as defines; then each light's
        // test, chosen by its technique and filter, called with its own settings.
        assert_eq!(
            lines(&lights),
            [
                "#include \"lib/shadow_2d.glsl\"",
                "#include \"lib/shadow_cube.glsl\"",
                "#define LAYER_SAMPLER sampler2DArrayShadow",
                "#define LAYER_TEXEL vec2(0.0009765625, 0.0009765625)",
                "#define LAYER_RADIUS 0",
                "#define LAYER_TAPS 0",
                "#include \"lib/shadow_cascades.glsl\"",
                "void addLights(inout Fragment f)",
                "{",
                "vec3 toLight0 = toLightOf(0, false);",
                "float lit0 = calcShadow(shadowMap0, mlightviewVertexPos[0], 0.05, \
                 vec2(0.0009765625, 0.0009765625), 1, false);",
                "addLight(0, toLight0, false, lit0, f);",
                "addLightUnshadowed(1, true, false, f);",
                "vec3 toLight2 = toLightOf(2, true);",
                "float lit2 = calcShadowCubeSoft(shadowCube2, mlightviewVertexPos[1].xyz, \
                 lightFar[2], 0.05, false);",
                "addLight(2, toLight2, false, lit2, f);",
                "vec3 toLight3 = toLightOf(3, false);",
                "float lit3 = calcShadowCascades(cascadeMap3, 0.25, f);",
                "addLight(3, toLight3, false, lit3, f);",
                "}"
            ]
        );
        // Read from the cached mask, no test is compiled in.
        let [(_, none), (_, masked)] = snippets(&slots, MaskMode::Read);
        assert!(lines(&none).is_empty(), "{none}");
        assert!(!masked.contains("#include"), "{masked}");
        assert!(masked.contains("addLight(0, toLightOf(0, false), false, maskedLit[0], f);"));
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
        // Four lights of four kinds, one with cascades, one with a moment map, the others
        // with a filter of their own: every snippet is included but caster groups' (only
        // one light is layered), which a second set of lights includes.
        use crate::settings::{BiasMode, Filter};
        let with = |filter| ShadowSettings {
            filter,
            ..ShadowSettings::default()
        };
        let slot = |shadow, s: ShadowSettings| LightSlot {
            shadow,
            positional: false,
            cone: false,
            test: Some(ShadowTest::of(&s)),
        };
        let slope = ShadowSettings {
            bias_mode: BiasMode::Slope,
            ..with(Filter::Hardware2x2)
        };
        // Translucent maps beside three of the 2D maps.
        let beside = |technique, parameter| {
            Some(VolumetricKey {
                technique,
                parameter,
                resolved: false,
            })
        };
        let mut slope = slot(ShadowKind::Map, slope);
        slope.test = slope.test.map(|t| ShadowTest {
            volumetric: beside(crate::settings::Volumetric::Avsm, 8),
            ..t
        });
        let generated = snippets(
            &[
                slope,
                slot(ShadowKind::Cube, with(Filter::Pcf3x3)),
                slot(ShadowKind::Cascades, with(Filter::Pcf3x3)),
                slot(ShadowKind::Moments, with(Filter::Vsm)),
            ],
            MaskMode::Off,
        );
        let resolved = crate::shaders::scene_frag(&generated).unwrap();
        let mut linear = slot(ShadowKind::Map, with(Filter::Pcf3x3));
        linear.test = linear.test.map(|t| ShadowTest {
            map_depth: MapDepth::Linear,
            volumetric: beside(crate::settings::Volumetric::Osm, 16),
            ..t
        });
        let mut pcss = slot(ShadowKind::Map, with(Filter::Pcss));
        pcss.test = pcss.test.map(|t| ShadowTest {
            volumetric: beside(crate::settings::Volumetric::Fom, 7),
            ..t
        });
        let others = snippets(
            &[
                slot(ShadowKind::Groups, with(Filter::Pcf3x3)),
                pcss,
                linear,
                slot(ShadowKind::Moments, with(Filter::Vssm)),
            ],
            MaskMode::Off,
        );
        let resolved_others = crate::shaders::scene_frag(&others).unwrap();
        for name in crate::shaders::library() {
            let file = format!("shaders/{name}");
            assert!(
                resolved.files.contains(&file) || resolved_others.files.contains(&file),
                "{name} is never included"
            );
        }
    }

    #[test]
    fn each_filter_calls_its_own_function() {
        use crate::settings::Filter;
        let call = |shadow, filter| {
            let s = ShadowSettings {
                filter,
                ..ShadowSettings::default()
            };
            let slot = LightSlot {
                shadow,
                positional: false,
                cone: false,
                test: Some(ShadowTest::of(&s)),
            };
            light_part(0, 0, &slot, MaskMode::Off).lines[1].clone()
        };
        use ShadowKind::{Cube, Map, Moments};
        for (shadow, filter, function) in [
            (
                Map,
                Filter::Single,
                "calcShadow(shadowMap0, mlightviewVertexPos[0], 0.05, ",
            ),
            (Map, Filter::Pcf5x5, "calcShadow("),
            (Map, Filter::Hardware3x3, "calcShadowHardware("),
            (Map, Filter::Pcf4x4Weighted, "pcf4x4Weighted("),
            (Map, Filter::SoftPcf, "softPcf("),
            (Map, Filter::Pcss, "pcss("),
            (Moments, Filter::Vsm, "calcShadowVsm("),
            (Moments, Filter::Evsm2, "calcShadowEvsm("),
            (Moments, Filter::Msm, "calcShadowMsm("),
            (Moments, Filter::Vssm, "vssm("),
            (Moments, Filter::MsmSoft, "msmSoft("),
            (Cube, Filter::Single, "calcShadowCube("),
            (Cube, Filter::Pcf3x3, "calcShadowCubeSoft("),
        ] {
            let line = call(shadow, filter);
            assert!(
                line.starts_with(&format!("float lit0 = {function}")),
                "{filter:?}: {line}"
            );
        }
        // A perspective map tested in linear depth: its position through the library's
        // helper, the bias in it or in the call.
        let depth = |map_depth| {
            let slot = LightSlot {
                shadow: Map,
                positional: true,
                cone: true,
                test: Some(ShadowTest {
                    map_depth,
                    ..ShadowTest::of(&ShadowSettings::default())
                }),
            };
            light_part(1, 0, &slot, MaskMode::Off)
        };
        let linear = depth(MapDepth::Linear);
        assert!(linear.snippets.contains(&"lib/linear_depth.glsl"));
        assert_eq!(
            linear.lines[1],
            "float lit1 = calcShadow(shadowMap1, linearDepthPosition(mlightviewVertexPos[0]), \
             0.05, vec2(0.0009765625, 0.0009765625), 1, false);"
        );
        assert_eq!(
            depth(MapDepth::LinearBias).lines[1],
            "float lit1 = calcShadow(shadowMap1, projectedBiasedPosition(mlightviewVertexPos[0], \
             0.05, lightDepthRange[1]), 0.0, vec2(0.0009765625, 0.0009765625), 1, false);"
        );
        assert!(!depth(MapDepth::Projected)
            .snippets
            .contains(&"lib/linear_depth.glsl"));
        // The grid's radius is the filter's.
        assert!(call(Map, Filter::Single).ends_with(", 0, false);"));
        assert!(call(Map, Filter::Pcf5x5).ends_with(", 2, false);"));
    }

    #[test]
    fn each_soft_moment_filter_calls_its_function_with_its_constants() {
        let vssm = ShadowSettings {
            filter: Filter::Vssm,
            ..ShadowSettings::default()
        };
        let test = ShadowTest::of(&vssm);
        let m = test.moments.expect("vssm is a moment filter");
        let g = soft_moments_glsl(1, 0, &test, &m);
        assert_eq!(g.sampler_type, "usampler2D");
        assert!(
            g.test
                .starts_with("vssm(shadowMap1, mlightviewVertexPos[0], "),
            "{}",
            g.test
        );
        assert!(g.test.contains(", lightPenumbra[1], 4, 4, "), "{}", g.test);
        // Each stage's cells, the search's first.
        let cheap = ShadowTest::of(&ShadowSettings {
            soft_search_cells: 2,
            soft_filter_cells: 3,
            ..vssm
        });
        let g = soft_moments_glsl(1, 0, &cheap, &m);
        assert!(g.test.contains(", lightPenumbra[1], 2, 3, "), "{}", g.test);
        let msm = ShadowSettings {
            filter: Filter::MsmSoft,
            ..vssm
        };
        let test = ShadowTest::of(&msm);
        let g = soft_moments_glsl(0, 0, &test, &test.moments.unwrap());
        assert!(g.test.starts_with("msmSoft("), "{}", g.test);
    }
}
