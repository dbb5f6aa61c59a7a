//! Cached shadow maps: a light's map is drawn again only when what it sees changed, and a
//! cached frame is the same, pixel for pixel, as one drawn from scratch.

mod common;

use shadowmap::engine::Outputs;
use shadowmap::frame::render_frames;
use shadowmap::settings::ShadowSettings;
use shadowmap::Scene;

const FRAMES: u32 = 6;

/// The last of `FRAMES` animated frames with the cache on or off, and the passes drawn.
fn last_frame(name: &str, cache: bool, extra: impl Fn(&mut ShadowSettings)) -> (Vec<u8>, u64, u64) {
    let ctx = common::context();
    let mut scene = Scene::load(name).unwrap();
    let mut s = ShadowSettings {
        shadow_cache: cache,
        ..scene.shadow
    };
    extra(&mut s);
    let outputs = Outputs {
        visibility: true,
        gbuffer: false,
    };
    let frame = render_frames(ctx.gl(), &mut scene, &s, 240, 160, FRAMES, outputs)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let mut bytes = frame.colour.rgba.clone();
    bytes.extend(
        frame
            .visibility
            .unwrap()
            .iter()
            .map(|v| v.map_or(0, |v| (v * 255.0) as u8)),
    );
    (bytes, frame.depth_passes.drawn, frame.depth_passes.skipped)
}

#[test]
fn a_cached_frame_equals_an_uncached_one_on_every_built_in_scene() {
    for name in Scene::builtin_names() {
        let (cached, drawn, skipped) = last_frame(name, true, |_| {});
        let (fresh, fresh_drawn, fresh_skipped) = last_frame(name, false, |_| {});
        assert!(cached == fresh, "{name}: the cached frame differs");
        let lights = Scene::load(name)
            .unwrap()
            .lights
            .iter()
            .filter(|l| l.casts_shadows())
            .count() as u64;
        assert_eq!(
            (fresh_drawn, fresh_skipped),
            (lights * u64::from(FRAMES), 0),
            "{name}: without the cache every map is drawn every frame"
        );
        assert_eq!(drawn + skipped, lights * u64::from(FRAMES), "{name}");
        assert!(drawn >= lights, "{name}: each map is drawn at least once");
    }
}

#[test]
fn only_maps_whose_light_sees_a_change_are_drawn_again() {
    // LearnOpenGL's scene does not move: its one map is drawn once.
    let (_, drawn, skipped) = last_frame("learnopengl", true, |_| {});
    assert_eq!((drawn, skipped), (1, u64::from(FRAMES) - 1));
    // The DummyGame's cube turns: its map is drawn every frame.
    let (_, drawn, skipped) = last_frame("dummy", true, |_| {});
    assert_eq!((drawn, skipped), (u64::from(FRAMES), 0));
    // A caster turning outside the light's box does not make it draw again: LearnOpenGL's
    // light with a spinning cube 50 units away, beyond its +-10 box.
    let ctx = common::context();
    let mut scene = Scene::load("learnopengl").unwrap();
    let mut far = scene.items[1].clone();
    far.position = glam::Vec3::new(50.0, 0.0, 0.0);
    far.spin = glam::Vec3::new(0.0, 3.0, 0.0);
    scene.items.push(far);
    let s = scene.shadow;
    let frame = render_frames(
        ctx.gl(),
        &mut scene,
        &s,
        120,
        90,
        FRAMES,
        Outputs::default(),
    )
    .unwrap();
    assert_eq!(frame.depth_passes.drawn, 1);
    // Nor is it drawn into the map: the casters drawn leave it out.
    let mut renderer = shadowmap::Renderer::new(ctx.gl(), &scene, &s).unwrap();
    renderer.render_depth_map(&scene).unwrap();
    let c = renderer.caster_counts();
    assert_eq!((c.drawn, c.total), (4, 5), "{c:?}");
    // A box fitted to the view follows the camera, which stays put: drawn once.
    let (_, drawn, _) = last_frame("learnopengl", true, |s| {
        s.fit = shadowmap::settings::Fit::Scene
    });
    assert_eq!(drawn, 1);
}

#[test]
fn a_point_light_draws_each_caster_only_into_the_cube_faces_it_can_reach() {
    // Issue 16, culled casters per cube face: counted per face (six offered per caster), and
    // a cube straight along +X from the light is drawn into the +X face alone. Both depth
    // passes (one layered pass, six passes) cull alike.
    let ctx = common::context();
    for pass in [
        shadowmap::settings::PointPass::Layered,
        shadowmap::settings::PointPass::SixPasses,
    ] {
        let counts = |scene: &Scene| {
            let s = ShadowSettings {
                point_pass: pass,
                ..scene.shadow
            };
            let mut renderer = shadowmap::Renderer::new(ctx.gl(), scene, &s).unwrap();
            renderer.render_depth_map(scene).unwrap();
            renderer.caster_counts()
        };
        let mut scene = Scene::load("point-shadows").unwrap();
        let casters = scene.items.iter().filter(|i| i.casts_shadows).count() as u64;
        let before = counts(&scene);
        assert_eq!(before.total, 6 * casters, "{pass:?}");
        // The room around the light is in all six faces; the five cubes in fewer.
        assert!(
            before.drawn >= 6 && before.drawn < before.total,
            "{pass:?}: {before:?}"
        );

        let mut along_x = scene.items[1].clone();
        let shadowmap::scene::Light::Point(light) = &scene.lights[0] else {
            panic!("point-shadows' light is a point light");
        };
        along_x.position = light.position + glam::Vec3::new(6.0, 0.0, 0.0);
        along_x.scale = glam::Vec3::splat(0.5);
        scene.items.push(along_x);
        let after = counts(&scene);
        assert_eq!(after.total, before.total + 6, "{pass:?}");
        assert_eq!(
            after.drawn,
            before.drawn + 1,
            "{pass:?}: {before:?} -> {after:?}"
        );
    }
}

#[test]
fn a_cached_moment_map_and_a_soft_filter_give_the_uncached_frame() {
    // The later techniques behind the same cache: a moment map (its blur is part of what is
    // kept) and PCSS, on a scene whose map is reused (learnopengl) and one whose caster
    // turns (dummy). At least one pass must have been skipped where nothing moves.
    use shadowmap::settings::Filter;
    for filter in [Filter::Vsm, Filter::Msm, Filter::Pcss] {
        for name in ["learnopengl", "dummy"] {
            let set = |s: &mut ShadowSettings| s.filter = filter;
            let (cached, drawn, skipped) = last_frame(name, true, set);
            let (fresh, ..) = last_frame(name, false, set);
            assert!(
                cached == fresh,
                "{name}, {filter:?}: the cached frame differs"
            );
            if name == "learnopengl" {
                assert_eq!((drawn, skipped), (1, u64::from(FRAMES) - 1), "{filter:?}");
            }
        }
    }
}
