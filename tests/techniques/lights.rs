//! More light types against the exact reference: a point light inside a room of cubes
//! (omnidirectional shadows in a depth cube map) and a spot light's cone.

use crate::common;

use glam::Vec3;
use shadowmap::compare::{compare, CompareOptions};
use shadowmap::settings::{BiasMode, Filter, MapSize, ShadowSettings};
use shadowmap::Scene;

fn measure(scene: &Scene, s: &ShadowSettings) -> shadowmap::reference::Metrics {
    measure_light(scene, s, 0)
}

/// Light `light`'s shadow test against its own exact visibility.
fn measure_light(scene: &Scene, s: &ShadowSettings, light: usize) -> shadowmap::reference::Metrics {
    let ctx = common::context();
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width: 400,
        height: 300,
        supersample: 2,
        band: 1,
        light,
    };
    compare(ctx.gl(), scene, s, &opts)
        .unwrap_or_else(|e| panic!("{e}"))
        .metrics
}

#[test]
fn point_light_in_a_room_of_cubes_matches_the_reference() {
    let mut scene = Scene::load("point-shadows").unwrap();
    // A view from a corner that sees walls, floor and the cubes' shadows on them.
    scene.camera.position = Vec3::new(3.5, 3.0, 4.5);
    scene.camera.rotation = Vec3::new(30.0, -35.0, 0.0);
    for z in [0.0f32, 2.0, -2.5] {
        let mut sc = scene.clone();
        if let shadowmap::scene::Light::Point(p) = &mut sc.lights[0] {
            p.position = Vec3::new(0.0, 0.0, z);
        }
        let hard = measure(&sc, &sc.shadow.clone());
        let soft = measure(
            &sc,
            &ShadowSettings {
                filter: Filter::Pcf3x3,
                bias: 0.15,
                ..sc.shadow
            },
        );
        eprintln!(
            "light at z = {z}: hard {:.3}% misclassified ({} outside the edge band), soft {:.3}%, MAE hard {:.4} soft {:.4}",
            hard.misclassified_rate * 100.0,
            hard.misclassified_outside_band,
            soft.misclassified_rate * 100.0,
            hard.mae.unwrap(),
            soft.mae.unwrap()
        );
        assert!(hard.receivers > 50_000, "the room must be in view");
        // Shadows exist and land where the rays say: errors only along edges.
        assert!(
            hard.misclassified_rate < 0.005,
            "z = {z}: {}",
            hard.misclassified_rate
        );
        assert!(
            (hard.misclassified_outside_band as f64) < 0.0005 * hard.outside_band_receivers as f64,
            "z = {z}: {} misclassified away from edges",
            hard.misclassified_outside_band
        );
        assert!(
            soft.misclassified_rate < 0.01,
            "z = {z}: soft {}",
            soft.misclassified_rate
        );
    }
    // Shadows are in view: the cubes darken parts of the walls and floor.
    let ctx = common::context();
    let frame = shadowmap::compare::render_visibility(ctx.gl(), &scene, &scene.shadow, 400, 300, 0)
        .unwrap();
    let dark = frame
        .visibility
        .unwrap()
        .iter()
        .flatten()
        .filter(|v| **v < 0.5)
        .count();
    assert!(dark > 1000, "only {dark} shadowed pixels in view");
    // Without a bias the cube map has acne, as the flat maps do.
    let acne = measure(
        &scene,
        &ShadowSettings {
            bias_mode: BiasMode::None,
            ..scene.shadow
        },
    );
    assert!(
        acne.false_shadow_rate > 0.05,
        "no bias should show acne: {}",
        acne.false_shadow_rate
    );
}

#[test]
fn spot_light_shadows_match_the_reference_inside_its_cone() {
    // The blog's bulb over its slab: a perspective shadow map from the light's position.
    let scene = Scene::load("playground").unwrap();
    let m = measure(&scene, &scene.shadow.clone());
    eprintln!(
        "playground spot: {:.3}% misclassified ({} outside the band)",
        m.misclassified_rate * 100.0,
        m.misclassified_outside_band
    );
    // Receivers are inside the bulb's full cone only (18,415 at 400 x 300).
    assert!(m.receivers > 15_000, "{m:?}");
    assert!(
        m.false_shadow_outside_band * 1000 <= m.outside_band_receivers,
        "{m:?}"
    );
}

#[test]
fn layered_and_six_pass_cube_maps_agree() {
    use shadowmap::settings::PointPass;
    let ctx = common::context();
    let scene = Scene::load("point-shadows").unwrap();
    let render = |pass| {
        let s = ShadowSettings {
            point_pass: pass,
            ..scene.shadow
        };
        shadowmap::compare::render_visibility(ctx.gl(), &scene, &s, 200, 150, 0).unwrap()
    };
    let (a, b) = (render(PointPass::SixPasses), render(PointPass::Layered));
    assert_eq!(
        a.visibility, b.visibility,
        "the two ways of drawing the faces disagree"
    );
    assert_eq!(a.colour, b.colour);
}

/// The three-lights scene with its animation stopped.
fn three_lights() -> Scene {
    let mut scene = Scene::load("three-lights").unwrap();
    scene.items.iter_mut().for_each(|i| i.spin = Vec3::ZERO);
    scene
}

#[test]
fn each_of_several_lights_matches_its_own_reference() {
    // A sun (2D ortho map), a spot (2D perspective map) and a point light (cube map) in one
    // frame: each light's test, read from the one scene program, against rays to that light.
    let scene = three_lights();
    let ctx = common::context();
    let mut shadowed = Vec::new();
    for light in 0..3 {
        let m = measure_light(&scene, &scene.shadow, light);
        eprintln!(
            "three-lights, light {light}: {:.3}% misclassified ({:.3}% outside the band), {} receivers",
            m.misclassified_rate * 100.0,
            m.misclassified_outside_band_rate * 100.0,
            m.receivers
        );
        // The spot (light 1) lights only its cone: fewer receivers (43,538).
        let least = if light == 1 { 35_000 } else { 50_000 };
        assert!(m.receivers > least, "light {light}: {m:?}");
        assert!(m.misclassified_rate < 0.005, "light {light}: {m:?}");
        assert!(
            m.misclassified_outside_band_rate < 0.001,
            "light {light}: {m:?}"
        );
        let frame =
            shadowmap::compare::render_visibility(ctx.gl(), &scene, &scene.shadow, 400, 300, light)
                .unwrap();
        let vis = frame.visibility.unwrap();
        shadowed.push(
            vis.iter()
                .map(|v| v.is_some_and(|v| v < 0.5))
                .collect::<Vec<_>>(),
        );
    }
    // Three different shadows: each light's map is its own.
    for (a, b) in [(0, 1), (0, 2), (1, 2)] {
        let differ = shadowed[a]
            .iter()
            .zip(&shadowed[b])
            .filter(|(x, y)| x != y)
            .count();
        assert!(
            differ > 2000,
            "lights {a} and {b} differ at only {differ} pixels"
        );
    }
}

#[test]
fn only_lights_that_cast_get_a_shadow_map() {
    use shadowmap::engine::RenderTarget;
    use shadowmap::renderer::{Renderer, Target};
    let ctx = common::context();
    let mut scene = three_lights();
    let target = RenderTarget::new(ctx.gl(), 160, 90, Default::default()).unwrap();
    let count = |scene: &Scene| {
        let mut r = Renderer::new(ctx.gl(), scene, &scene.shadow).unwrap();
        r.render(scene, Target::Offscreen(&target)).unwrap();
        r.shadow_memory()
    };
    let (maps, bytes) = count(&scene);
    // Sun and spot 1024^2, the point light's six faces; the fill light none.
    assert_eq!(maps, 3);
    assert_eq!(bytes, (1 + 1 + 6) * 1024 * 1024 * 4);
    for l in &mut scene.lights {
        if let shadowmap::scene::Light::Point(p) = l {
            p.casts_shadows = false;
        }
    }
    assert_eq!(count(&scene), (2, 2 * 1024 * 1024 * 4));
}

#[test]
fn a_light_that_does_not_cast_lights_what_another_shadows() {
    // The DummyGame with a second, non-casting light from the same direction: the cube's
    // shadow on the plane gets that light's diffuse term (lit areas are already at full
    // blue, so there it clamps).
    let ctx = common::context();
    let one = common::dummy(90.0);
    let mut two = one.clone();
    let mut fill = one.lights[0];
    if let shadowmap::scene::Light::Directional(l) = &mut fill {
        l.casts_shadows = false;
        l.intensity = 0.5;
    }
    two.lights.push(fill);
    let a = common::render(&ctx, &mut one.clone(), &one.shadow, 320, 180);
    let b = common::render(&ctx, &mut two.clone(), &two.shadow, 320, 180);
    let plane_a = common::plane_pixels(&a);
    let (shadow_px, lit_px): (Vec<usize>, Vec<usize>) = {
        let pos = a.world_positions().unwrap();
        let vis = a.visibility.as_ref().unwrap();
        let on_plane = |i: usize| (pos[i][1] + 1.0).abs() < 1e-3;
        let shadow = (0..pos.len())
            .filter(|&i| on_plane(i) && vis[i] == Some(0.0))
            .collect();
        let lit = (0..pos.len())
            .filter(|&i| on_plane(i) && vis[i] == Some(1.0))
            .collect();
        (shadow, lit)
    };
    assert!(
        plane_a.len() > 10_000 && shadow_px.len() > 500,
        "{}",
        shadow_px.len()
    );
    // In light 0's shadow, only ambient in `one`; ambient plus the fill in `two`.
    let blue = |f: &shadowmap::frame::Frame, i: usize| f32::from(f.colour.rgba[i * 4 + 2]);
    let gain =
        |px: &[usize]| px.iter().map(|&i| blue(&b, i) - blue(&a, i)).sum::<f32>() / px.len() as f32;
    let (in_shadow, in_light) = (gain(&shadow_px), gain(&lit_px));
    eprintln!("fill light adds {in_shadow:.1} in the shadow, {in_light:.1} in the light (of 255)");
    assert!(in_shadow > 50.0, "{in_shadow}");
    // The visibility output is still light 0's: the fill light does not change the test.
    assert_eq!(a.visibility, b.visibility);
}

#[test]
fn the_depth_view_shows_each_lights_own_map() {
    use shadowmap::engine::RenderTarget;
    use shadowmap::renderer::{Renderer, Target};
    let ctx = common::context();
    let scene = three_lights();
    let s = ShadowSettings {
        show_depth_map: true,
        ..scene.shadow
    };
    let target = RenderTarget::new(ctx.gl(), 160, 90, Default::default()).unwrap();
    let mut renderer = Renderer::new(ctx.gl(), &scene, &s).unwrap();
    let mut views = Vec::new();
    for light in 0..3 {
        renderer.set_depth_view_light(light);
        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
        let grey: Vec<u8> = target.read_colour().chunks_exact(4).map(|p| p[0]).collect();
        let (lo, hi) = (grey.iter().min().unwrap(), grey.iter().max().unwrap());
        // A map with something in it: near casters and far receivers.
        assert!(hi - lo > 40, "light {light}: depth view {lo}..{hi}");
        views.push(grey);
    }
    assert_ne!(views[0], views[1]);
    assert_ne!(views[1], views[2]);
}

#[test]
fn a_light_with_its_own_shadow_table_gets_its_own_map_and_test() {
    use shadowmap::engine::{Outputs, RenderTarget};
    use shadowmap::frame::render_frames_of_light;
    use shadowmap::renderer::{Renderer, Target};
    use shadowmap::settings::ShadowPatch;
    let text = r#"
        [camera]
        position = [0.0, 6.0, 8.0]
        rotation = [35.0, 0.0, 0.0]
        [[lights]]
        direction = [0.3, 1.0, 0.4]
        shadow = { filter = "single", map_size = 256, bias_mode = "none" }
        [[lights]]
        kind = "spot"
        position = [0.0, 4.0, 3.0]
        target = [0.0, 0.0, 0.0]
        fov = 60.0
        near = 1.0
        far = 20.0
        [[item]]
        mesh = "cube"
        position = [0.0, 1.0, 0.0]
        [[item]]
        mesh = "plane"
        scale = 10.0
    "#;
    let scene =
        shadowmap::scene::file::parse(text, std::path::Path::new("own.toml"), None).unwrap();
    assert_eq!(
        *scene.lights[0].shadow_patch(),
        ShadowPatch {
            filter: Some(Filter::Single),
            map_size: Some(MapSize::square(256)),
            bias_mode: Some(BiasMode::None),
            ..ShadowPatch::default()
        }
    );
    let global = scene.shadow;
    assert_eq!(global.map_size, MapSize::square(1024));
    // Light 0's map is 256^2 and light 1's the scene's 1024^2.
    let ctx = common::context();
    let mut renderer = Renderer::new(ctx.gl(), &scene, &global).unwrap();
    let target = RenderTarget::new(ctx.gl(), 64, 48, Outputs::default()).unwrap();
    renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    assert_eq!(renderer.shadow_memory(), (2, (256 * 256 + 1024 * 1024) * 4));
    // Light 0's test with its own table equals light 0's test with those settings for the
    // whole scene; and differs from the scene's own (3 x 3 PCF at 1024^2 with a bias: no
    // acne).
    let visibility = |sc: &Scene, s: &ShadowSettings| {
        let mut sc = sc.clone();
        let outputs = Outputs {
            visibility: true,
            gbuffer: false,
        };
        render_frames_of_light(ctx.gl(), &mut sc, s, 320, 240, 1, outputs, 0)
            .unwrap()
            .visibility
            .unwrap()
    };
    let own = visibility(&scene, &global);
    let mut plain = scene.clone();
    *plain.lights[0].shadow_patch_mut() = ShadowPatch::default();
    let as_global = ShadowSettings {
        filter: Filter::Single,
        map_size: MapSize::square(256),
        bias_mode: BiasMode::None,
        ..global
    };
    assert_eq!(own, visibility(&plain, &as_global));
    let differ = own
        .iter()
        .zip(visibility(&plain, &global))
        .filter(|(a, b)| **a != *b)
        .count();
    assert!(
        differ > 1000,
        "only {differ} pixels differ from the scene's settings"
    );
    // A bad value in a light's table names the light's table and the setting.
    let bad = text.replace("map_size = 256", "bias = -1.0");
    let err = shadowmap::scene::file::parse(&bad, std::path::Path::new("own.toml"), None)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("lights[0].shadow") && err.contains("shadow.bias = -1"),
        "{err}"
    );
    // Flags win over a light's own table: the fields a flag gives leave the table.
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("own-table");
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("own.toml");
    std::fs::write(&file, text).unwrap();
    let dark_pixels = |extra: &[&str]| -> usize {
        let out = dir.join("v.png");
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_shadowmap"))
            .args([
                "render",
                "--scene",
                file.to_str().unwrap(),
                "--size",
                "320x240",
            ])
            .args(["--out", dir.join("c.png").to_str().unwrap()])
            .args(["--shadow-out", out.to_str().unwrap()])
            .args(extra)
            .status()
            .unwrap();
        assert!(status.success());
        let image = image::open(&out).unwrap().to_rgba8();
        image.pixels().filter(|p| p[3] > 0 && p[0] < 128).count()
    };
    // The table's `bias_mode = "none"` covers the floor in acne; `--bias-mode constant`
    // takes the bias back for that light too.
    let (acne, cured) = (dark_pixels(&[]), dark_pixels(&["--bias-mode", "constant"]));
    assert!(
        acne > 3 * cured && cured > 0,
        "dark pixels: {acne} with the table's bias mode, {cured} with the flag's"
    );
    // An unknown setting in a light's table names it.
    let bad = text.replace("map_size = 256", "map_sise = 256");
    let err = shadowmap::scene::file::parse(&bad, std::path::Path::new("own.toml"), None)
        .unwrap_err()
        .to_string();
    assert!(err.contains("map_sise"), "{err}");
}
