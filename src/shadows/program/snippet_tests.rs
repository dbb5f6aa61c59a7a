//! The scene program's layout and its generated snippets.

use super::slots::*;
use super::vertex::vertex_snippet;
use crate::scene::{Light, MAX_LIGHTS};
use crate::settings::{Filter, ShadowSettings, Volumetric};
use crate::shadows::map2d::MapDepth;
use crate::shadows::units::{texture_unit, MATERIAL_UNIT};
use crate::shadows::volumetric::VolumetricKey;
use crate::shadows::{OwnTest, ShadowKind, ShadowTest};
use crate::Scene;

/// `t` with its depth map storing depth as `map_depth`.
fn with_depth(mut t: ShadowTest, map_depth: MapDepth) -> ShadowTest {
    if let OwnTest::Depth(d) = &mut t.own {
        d.map_depth = map_depth;
    }
    t
}

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
            "#include \"lib/shadow_border.glsl\"",
            "#include \"lib/shadow_depth.glsl\"",
            "#include \"lib/shadow_2d.glsl\"",
            "#include \"lib/shadow_cube.glsl\"",
            "#define LAYER_SAMPLER sampler2DArrayShadow",
            "#define LAYER_TEXEL vec2(0.0009765625, 0.0009765625)",
            "#define LAYER_RADIUS 0",
            "#define LAYER_TAPS_GRID 1",
            "#include \"lib/shadow_cascades.glsl\"",
            "void addLights(inout Fragment f)",
            "{",
            "vec3 toLight0 = toLightOf(0, false);",
            "float lit0 = SHADOW_DEPTH_OF(0, SHADOW_BORDER(0, mlightviewVertexPos[0], false, \
             calcShadow(shadowMap0, mlightviewVertexPos[0], 0.05, \
             vec2(0.0009765625, 0.0009765625), 1, false)));",
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
        volumetric: beside(crate::settings::Volumetric::Osm, 16),
        ..with_depth(t, MapDepth::Linear)
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
    let soft = snippets(
        &[slot(ShadowKind::Map, with(Filter::Pcf4x4Weighted))],
        MaskMode::Off,
    );
    let resolved_soft = crate::shaders::scene_frag(&soft).unwrap();
    // The translucent items' tests per vertex, in the vertex shader.
    let vert = crate::shaders::scene_vert();
    let vertex = crate::shaders::resolve(&vert.files[0], &vert.text, &[vertex_snippet(&[])]);
    let vertex = vertex.unwrap();
    for name in crate::shaders::library() {
        let file = format!("shaders/{name}");
        let programs = [&resolved, &resolved_others, &resolved_soft, &vertex];
        assert!(
            programs.iter().any(|p| p.files.contains(&file)),
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
        // A 2D map's test inside its lit border's and its depths' (lib/shadow_border.glsl,
        // lib/shadow_depth.glsl).
        let line = call(shadow, filter)
            .replace("SHADOW_DEPTH_OF(0, ", "")
            .replace("SHADOW_BORDER(0, mlightviewVertexPos[0], false, ", "");
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
            test: Some(with_depth(
                ShadowTest::of(&ShadowSettings::default()),
                map_depth,
            )),
        };
        light_part(1, 0, &slot, MaskMode::Off)
    };
    let linear = depth(MapDepth::Linear);
    assert!(linear.snippets.contains(&"lib/linear_depth.glsl"));
    assert_eq!(
        linear.lines[1],
        "float lit1 = SHADOW_DEPTH_OF(1, SHADOW_BORDER(1, mlightviewVertexPos[0], false, \
         calcShadow(shadowMap1, linearDepthPosition(mlightviewVertexPos[0]), 0.05, \
         vec2(0.0009765625, 0.0009765625), 1, false)));"
    );
    assert_eq!(
        depth(MapDepth::LinearBias).lines[1],
        "float lit1 = SHADOW_DEPTH_OF(1, SHADOW_BORDER(1, mlightviewVertexPos[0], false, \
         calcShadow(shadowMap1, projectedBiasedPosition(mlightviewVertexPos[0], 0.05, \
         lightDepthRange[1]), 0.0, vec2(0.0009765625, 0.0009765625), 1, false)));"
    );
    assert!(!depth(MapDepth::Projected)
        .snippets
        .contains(&"lib/linear_depth.glsl"));
    // The grid's radius is the filter's.
    assert!(call(Map, Filter::Single).ends_with(", 0, false)));"));
    assert!(call(Map, Filter::Pcf5x5).ends_with(", 2, false)));"));
}

#[test]
fn each_soft_moment_filter_calls_its_function_with_its_constants() {
    let vssm = ShadowSettings {
        filter: Filter::Vssm,
        ..ShadowSettings::default()
    };
    let test = ShadowTest::of(&vssm);
    assert!(test.moments().is_some(), "vssm is a moment filter");
    let g = crate::shadows::summed::glsl(1, 0, &test).unwrap();
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
    let g = crate::shadows::summed::glsl(1, 0, &cheap).unwrap();
    assert!(g.test.contains(", lightPenumbra[1], 2, 3, "), "{}", g.test);
    let msm = ShadowSettings {
        filter: Filter::MsmSoft,
        ..vssm
    };
    let test = ShadowTest::of(&msm);
    let g = crate::shadows::summed::glsl(0, 0, &test).unwrap();
    assert!(g.test.starts_with("msmSoft("), "{}", g.test);
}

#[test]
fn a_light_with_a_translucent_map_multiplies_its_test_by_the_lookup() {
    let test = |volumetric| ShadowTest {
        volumetric,
        ..ShadowTest::of(&ShadowSettings::default())
    };
    let slot = |volumetric| LightSlot {
        shadow: ShadowKind::Map,
        positional: false,
        cone: false,
        test: Some(test(volumetric)),
    };
    let osm = VolumetricKey {
        technique: Volumetric::Osm,
        parameter: 16,
        resolved: false,
    };
    let part = light_part(2, 0, &slot(Some(osm)), MaskMode::Off);
    assert_eq!(
        part.lines[2],
        "lit2 *= osmTransmittance(volumetricMap2, volumetricCoords(2), 16);"
    );
    assert!(part.lines[3].starts_with("addLight(2, toLight2, false, lit2, f);"));
    assert!(part
        .snippets
        .ends_with(&["lib/volumetric.glsl", "lib/osm.glsl"]));
    let samplers = part.sampler.unwrap();
    assert!(
        samplers.ends_with("\nuniform sampler2DArray volumetricMap2;"),
        "{samplers}"
    );
    let fom = VolumetricKey {
        technique: Volumetric::Fom,
        parameter: 7,
        resolved: false,
    };
    let part = light_part(0, 0, &slot(Some(fom)), MaskMode::Off);
    assert_eq!(
        part.lines[2],
        "lit0 *= fomTransmittance(volumetricMap0, volumetricCoords(0), 7);"
    );
    // Resolved: the opaque items' programs fetch the resolved map once, at the light's
    // map slot position; the translucent items' own program keeps the curve.
    let resolved = Some(VolumetricKey {
        resolved: true,
        ..fom
    });
    for mask in [MaskMode::Off, MaskMode::Write] {
        let part = light_part(1, 0, &slot(resolved), mask);
        assert_eq!(
            part.lines[2],
            "lit1 *= resolvedTransmittance(resolvedMap1, mlightviewVertexPos[0]);"
        );
        let samplers = part.sampler.unwrap();
        assert!(
            samplers.ends_with("\nuniform sampler2D resolvedMap1;"),
            "{samplers}"
        );
    }
    let part = light_part(1, 0, &slot(resolved), MaskMode::Vertex);
    assert_eq!(
        part.lines[2],
        "lit1 *= fomTransmittance(volumetricMap1, volumetricCoords(1), 7);"
    );
    // And so do their tests per vertex.
    let mut vertex = slot(resolved);
    vertex.test = vertex.test.map(|t| ShadowTest {
        vertex_receivers: true,
        ..t
    });
    let (_, snippet) = vertex_snippet(&[vertex]);
    assert!(
        snippet.contains("lit0 *= fomTransmittance(volumetricMap0, volumetricCoords(0), 7);"),
        "{snippet}"
    );
    assert!(!snippet.contains("resolved"), "{snippet}");
    // Without one, the chapters' three lines.
    assert_eq!(light_part(0, 0, &slot(None), MaskMode::Off).lines.len(), 3);
}
