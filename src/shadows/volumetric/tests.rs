use glam::{DMat4, DVec3, Mat4, Vec3};

use super::*;
use crate::shadows::program::slots::{light_part, LightSlot, MaskMode, ShadowTest};
use crate::shadows::{Rays, ShadowKind};

fn view(projection: Mat4, view: DMat4) -> ShadowView {
    ShadowView {
        view: view.as_mat4(),
        view64: view,
        projection,
        perspective: false,
        linear_depth: false,
        near: -1.0,
        far: 12.0,
        texel_world: 0.01,
        rays: Rays::Parallel { to_light: Vec3::Y },
    }
}

#[test]
fn the_lookup_matrix_gives_the_lights_texel_and_the_fitted_depth() {
    let light = DMat4::look_at_rh(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, DVec3::Z);
    let projection = Mat4::orthographic_rh_gl(-4.0, 4.0, -4.0, 4.0, -1.0, 12.0);
    let v = view(projection, light);
    let camera = DMat4::look_at_rh(DVec3::new(1.0, 2.0, 6.0), DVec3::ZERO, DVec3::Y);
    // The light looks down from y = 5: depth 5 - y; fitted over y in [-1, 1].
    let fit = DepthFit {
        near: 4.0,
        far: 6.0,
    };
    let m = lookup_matrix(&v, fit, 0.0, camera);
    for (world, depth) in [
        (DVec3::new(1.0, 1.0, 2.0), 0.0),
        (DVec3::new(-2.0, -1.0, 0.5), 1.0),
    ] {
        let c = m * camera.transform_point3(world).as_vec3().extend(1.0);
        let clip = projection * light.transform_point3(world).as_vec3().extend(1.0);
        assert!((c.truncate().truncate() - clip.truncate().truncate()).length() < 1e-5);
        assert!((c.z - depth).abs() < 1e-5, "{c} for {world}");
        assert_eq!(c.w, 1.0);
    }
}

#[test]
fn optical_depth_is_minus_ln_of_what_passes_clamped_below_one() {
    assert!((optical_depth(0.5) - std::f32::consts::LN_2).abs() < 1e-6);
    assert_eq!(optical_depth(0.0), 0.0);
    let most = optical_depth(1.0);
    assert!(most.is_finite() && (most - optical_depth(OPACITY_MAX)).abs() < 1e-6);
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
    let (_, snippet) = super::receivers::vertex_snippet(&[vertex]);
    assert!(
        snippet.contains("lit0 *= fomTransmittance(volumetricMap0, volumetricCoords(0), 7);"),
        "{snippet}"
    );
    assert!(!snippet.contains("resolved"), "{snippet}");
    // Without one, the chapters' three lines.
    assert_eq!(light_part(0, 0, &slot(None), MaskMode::Off).lines.len(), 3);
}

#[test]
fn the_plan_gives_a_translucent_map_to_a_2d_depth_map_only() {
    let scene = Scene::load("smoke").unwrap();
    let with = |volumetric| ShadowSettings {
        volumetric,
        ..scene.shadow
    };
    let plan = |v| crate::shadows::plan::ShadowPlan::decide(&scene.lights, &with(v));
    assert_eq!(
        plan(Volumetric::Osm).lights[0].volumetric,
        Some(Volumetric::Osm)
    );
    assert_eq!(
        plan(Volumetric::Fom).lights[0].volumetric,
        Some(Volumetric::Fom)
    );
    assert_eq!(plan(Volumetric::Solid).lights[0].volumetric, None);
    assert_eq!(plan(Volumetric::Off).lights[0].volumetric, None);
    let cost = |v| method(v).unwrap().cost(&with(v));
    // 16 slices and 1 + 2 x 7 coefficients: four RGBA32F layers each, 64 bytes.
    assert_eq!(cost(Volumetric::Osm), (64, 1));
    assert_eq!(cost(Volumetric::Fom), (64, 1));
}
