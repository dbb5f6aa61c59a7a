//! Cached shadow maps: a light's map is drawn again only when what it sees changed, and a
//! cached frame is the same, pixel for pixel, as one drawn from scratch.

use crate::common;

use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::frame::render_frames;
use shadowmap::renderer::DepthPasses;
use shadowmap::settings::ShadowSettings;
use shadowmap::{Renderer, Scene, Target};

const FRAMES: u32 = 6;

const OUTPUTS: Outputs = Outputs {
    visibility: true,
    gbuffer: false,
};

/// The last of `FRAMES` animated frames with the cache on or off, and the passes drawn.
fn last_frame(
    name: &str,
    cache: bool,
    extra: impl Fn(&mut ShadowSettings),
) -> (Vec<u8>, DepthPasses) {
    let (bytes, passes, _) = last_frame_of(Scene::load(name).unwrap(), cache, extra);
    (bytes, passes)
}

/// A frame's colour, its visibility (as bytes) and the first light's 2D map, if it has one
/// (its depths' bits), as one run of bytes to compare.
fn frame_bytes(colour: &[u8], visibility: &[Option<f32>], depth: Option<&[f32]>) -> Vec<u8> {
    let mut bytes = colour.to_vec();
    bytes.extend(
        visibility
            .iter()
            .map(|v| v.map_or(0, |v| (v * 255.0) as u8)),
    );
    bytes.extend(
        depth
            .unwrap_or_default()
            .iter()
            .flat_map(|d| d.to_bits().to_ne_bytes()),
    );
    bytes
}

/// [`last_frame`] of a scene given, with the frames' use of the shadow mask.
fn last_frame_of(
    mut scene: Scene,
    cache: bool,
    extra: impl Fn(&mut ShadowSettings),
) -> (
    Vec<u8>,
    shadowmap::renderer::DepthPasses,
    shadowmap::renderer::MaskUses,
) {
    let ctx = common::context();
    let name = scene.name.clone();
    let mut s = ShadowSettings {
        shadow_cache: cache,
        ..scene.shadow
    };
    extra(&mut s);
    let frame = render_frames(ctx.gl(), &mut scene, &s, 240, 160, FRAMES, OUTPUTS)
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    let bytes = frame_bytes(
        &frame.colour.rgba,
        &frame.visibility.unwrap(),
        frame.depth_map.as_ref().map(|(_, d)| d.as_slice()),
    );
    (bytes, frame.depth_passes, frame.mask_uses)
}

/// [`last_frame_of`] with `step` run on the scene before each frame after the first (given
/// the frame's number) in place of the scene's own update: a light can move too.
fn last_frame_stepped(
    mut scene: Scene,
    cache: bool,
    step: impl Fn(&mut Scene, u32),
) -> (Vec<u8>, DepthPasses) {
    let ctx = common::context();
    let s = ShadowSettings {
        shadow_cache: cache,
        ..scene.shadow
    };
    scene.size = [240, 160];
    let mut renderer = Renderer::new(ctx.gl(), &scene, &s).unwrap();
    let target = RenderTarget::new(ctx.gl(), 240, 160, OUTPUTS).unwrap();
    for i in 0..FRAMES {
        if i > 0 {
            step(&mut scene, i);
        }
        renderer
            .render(&scene, Target::Offscreen(&target))
            .unwrap_or_else(|e| panic!("frame {i}: {e}"));
    }
    let depth = renderer.shadow_map().map(|m| m.read_depth());
    let visibility = target.read_visibility().unwrap();
    let bytes = frame_bytes(&target.read_colour(), &visibility, depth.as_deref());
    (bytes, renderer.depth_passes())
}

#[test]
fn a_cached_frame_equals_an_uncached_one_on_every_built_in_scene() {
    for name in Scene::builtin_names() {
        let (cached, passes) = last_frame(name, true, |_| {});
        let (fresh, fresh_passes) = last_frame(name, false, |_| {});
        assert!(cached == fresh, "{name}: the cached frame differs");
        let lights = Scene::load(name)
            .unwrap()
            .lights
            .iter()
            .filter(|l| l.casts_shadows())
            .count() as u64;
        assert_eq!(
            fresh_passes,
            DepthPasses {
                drawn: lights * u64::from(FRAMES),
                ..DepthPasses::default()
            },
            "{name}: without the cache every map is drawn whole every frame"
        );
        let p = passes;
        assert_eq!(
            p.drawn + p.patched + p.skipped,
            lights * u64::from(FRAMES),
            "{name}"
        );
        assert!(
            p.drawn >= lights,
            "{name}: each map is drawn whole at least once"
        );
    }
}

#[test]
fn a_still_frame_takes_its_shadow_tests_from_the_mask_and_equals_a_fresh_one() {
    // Every built-in scene held still (nothing spins, no light moves), with its own
    // settings and with the techniques whose tests differ most: the mask is written once
    // (the first frame) and read from then on, and the frame is the uncached one, pixel
    // for pixel. The smoke's translucent items take their own tests over it.
    use shadowmap::settings::{Filter, Fit, ShadowTechnique as Technique};
    type Variant = (&'static str, fn(&mut ShadowSettings));
    let variants: [Variant; 6] = [
        ("its own settings", |_| {}),
        ("pcss", |s| s.filter = Filter::Pcss),
        ("vsm", |s| s.filter = Filter::Vsm),
        ("hw2x2, fitted", |s| {
            s.filter = Filter::Hardware2x2;
            s.fit = Fit::Scene
        }),
        ("3 cascades", |s| s.cascades = 3),
        ("volumes", |s| s.technique = Technique::Volumes),
    ];
    let mut read_somewhere = 0;
    for name in Scene::builtin_names() {
        let mut still = Scene::load(name).unwrap();
        still
            .items
            .iter_mut()
            .for_each(|i| i.spin = glam::Vec3::ZERO);
        for light in &mut still.lights {
            if let shadowmap::scene::Light::Point(p) = light {
                p.oscillate = glam::Vec3::ZERO;
            }
        }
        for (what, variant) in variants {
            let refused = |s: &ShadowSettings| {
                shadowmap::shadows::plan::ShadowPlan::resolve(&still.lights, s, None).is_err()
            };
            let mut probe = still.shadow;
            variant(&mut probe);
            if refused(&probe) {
                continue;
            }
            let (cached, passes, uses) = last_frame_of(still.clone(), true, variant);
            let (fresh, _, fresh_uses) = last_frame_of(still.clone(), false, variant);
            assert!(
                cached == fresh,
                "{name}, {what}: the frame read from the mask differs"
            );
            assert_eq!(fresh_uses.written + fresh_uses.read, 0, "{name}, {what}");
            if probe.technique == Technique::Volumes {
                assert_eq!(uses.read, 0, "{name}, {what}: volumes test by the stencil");
                continue;
            }
            assert_eq!(
                passes.drawn + passes.skipped,
                passes.drawn.max(1) * u64::from(FRAMES),
                "{name}, {what}: each map drawn once, {passes:?}"
            );
            assert_eq!(
                (uses.written, uses.read),
                (1, u64::from(FRAMES)),
                "{name}, {what}"
            );
            read_somewhere += 1;
        }
    }
    assert!(
        read_somewhere >= 20,
        "{read_somewhere} still scenes read the mask"
    );
}

#[test]
fn only_maps_whose_light_sees_a_change_are_drawn_again() {
    // LearnOpenGL's scene does not move: its one map is drawn once.
    let (_, p) = last_frame("learnopengl", true, |_| {});
    assert_eq!(
        (p.drawn, p.patched, p.skipped),
        (1, 0, u64::from(FRAMES) - 1)
    );
    // The DummyGame's cube turns: its map is drawn again every frame (patched where the
    // cube is, see below).
    let (_, p) = last_frame("dummy", true, |_| {});
    assert_eq!((p.drawn + p.patched, p.skipped), (u64::from(FRAMES), 0));
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
    let (_, p) = last_frame("learnopengl", true, |s| {
        s.fit = shadowmap::settings::Fit::Scene
    });
    assert_eq!(p.drawn, 1);
}

#[test]
fn a_point_light_draws_each_caster_only_into_the_cube_faces_it_can_reach() {
    // Casters culled per cube face: counted per face (six offered per caster), and
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
            let (cached, p) = last_frame(name, true, set);
            let (fresh, _) = last_frame(name, false, set);
            assert!(
                cached == fresh,
                "{name}, {filter:?}: the cached frame differs"
            );
            if name == "learnopengl" {
                assert_eq!(
                    (p.drawn, p.skipped),
                    (1, u64::from(FRAMES) - 1),
                    "{filter:?}"
                );
            }
            if name == "dummy" {
                // A moment map is blurred: drawn whole, never patched; PCSS reads a depth map.
                let patched = match filter {
                    Filter::Pcss => u64::from(FRAMES) - 1,
                    _ => 0,
                };
                assert_eq!(p.patched, patched, "{filter:?}");
            }
        }
    }
}

#[test]
fn cached_caster_groups_give_the_uncached_frame() {
    // The layered map behind the same cache: kept where nothing moves (learnopengl), drawn
    // whole every frame where the cube turns (groups follow the camera: never patched).
    for name in ["learnopengl", "dummy"] {
        let set = |s: &mut ShadowSettings| s.caster_groups = 2;
        let (cached, p) = last_frame(name, true, set);
        let (fresh, _) = last_frame(name, false, set);
        assert!(cached == fresh, "{name}: the cached frame differs");
        let expected = match name {
            "learnopengl" => (1, 0, u64::from(FRAMES) - 1),
            _ => (u64::from(FRAMES), 0, 0),
        };
        assert_eq!((p.drawn, p.patched, p.skipped), expected, "{name}");
    }
}

#[test]
fn the_dummy_games_turning_cube_patches_its_map_and_equals_a_full_redraw() {
    // Movers redrawn: only the cube turns under the book's fixed box, so after the
    // first frame its map is patched where the cube was and is; the frame and the map are
    // the uncached ones, bit for bit.
    let (cached, p) = last_frame("dummy", true, |_| {});
    let (fresh, fresh_p) = last_frame("dummy", false, |_| {});
    assert!(cached == fresh, "the patched frame or map differs");
    assert_eq!((fresh_p.drawn, fresh_p.patched), (u64::from(FRAMES), 0));
    assert_eq!(
        (p.drawn, p.patched, p.skipped),
        (1, u64::from(FRAMES) - 1, 0),
        "{p:?}"
    );
    // The cube (1 x 1 in the 20 x 20 box of a 1024 map) and its turn: a small part of it.
    let texels = 1024 * 1024;
    assert!(
        p.patched_texels > 0 && p.patched_texels < p.patched * texels / 50,
        "{p:?}"
    );
}

#[test]
fn a_map_whose_light_moves_or_whose_mover_covers_most_of_it_is_drawn_whole() {
    // The patch is not taken, and the frame is still the uncached one: the light turns
    // every frame; the light turns once (the frames after it patch again); the cube grown
    // to cover most of the map.
    let dummy = || Scene::load("dummy").unwrap();
    type Case = (&'static str, Scene, fn(&mut Scene, u32), (u64, u64));
    let mut big = dummy();
    big.items[0].scale = glam::Vec3::splat(8.0);
    let frames = u64::from(FRAMES);
    let cases: [Case; 3] = [
        (
            "the light turns each frame",
            dummy(),
            |s, i| {
                s.update();
                assert!(s.set_light_angle(45.0 + i as f32));
            },
            (frames, 0),
        ),
        (
            "the light turns at frame 3",
            dummy(),
            |s, i| {
                s.update();
                if i == 3 {
                    assert!(s.set_light_angle(50.0));
                }
            },
            (2, frames - 2),
        ),
        (
            "a cube over most of the map",
            big,
            |s, _| s.update(),
            (frames, 0),
        ),
    ];
    for (what, scene, step, (drawn, patched)) in cases {
        let (cached, p) = last_frame_stepped(scene.clone(), true, step);
        let (fresh, fresh_p) = last_frame_stepped(scene, false, step);
        assert!(cached == fresh, "{what}: the cached frame or map differs");
        assert_eq!(fresh_p.drawn, frames, "{what}");
        assert_eq!(
            (p.drawn, p.patched, p.skipped),
            (drawn, patched, 0),
            "{what}: {p:?}"
        );
    }
}

/// What moves before a frame of [`smoke_side_by_side`].
#[derive(Clone, Copy, Debug, PartialEq)]
enum Move {
    Nothing,
    /// The glass, a translucent caster.
    Translucent,
    /// The cube, an opaque caster.
    Opaque,
}

/// The smoke scene under `volumetric`, frame by frame with the cache on and off side by
/// side (`moves[i]` before frame i): each frame's colour and visibility, and after the last
/// the translucent map, must be the same. Returns the cached renderer's translucent maps
/// drawn and kept, and its frames that wrote and read the shadow mask.
fn smoke_side_by_side(
    volumetric: shadowmap::settings::Volumetric,
    moves: &[Move],
) -> (
    shadowmap::shadows::volumetric::cache::MapDraws,
    shadowmap::renderer::MaskUses,
) {
    let ctx = common::context();
    let mut scene = common::frozen("smoke");
    scene.size = [240, 160];
    let find = |name: &str| scene.items.iter().position(|i| i.name == name).unwrap();
    let (glass, cube) = (find("glass"), find("cube"));
    let mut renderers = [true, false].map(|cache| {
        let s = ShadowSettings {
            shadow_cache: cache,
            volumetric,
            ..scene.shadow
        };
        let renderer = Renderer::new(ctx.gl(), &scene, &s).unwrap();
        (
            renderer,
            RenderTarget::new(ctx.gl(), 240, 160, OUTPUTS).unwrap(),
        )
    });
    for (i, m) in moves.iter().enumerate() {
        match m {
            Move::Nothing => {}
            Move::Translucent => scene.items[glass].position.x += 0.05,
            Move::Opaque => scene.items[cube].position.z += 0.05,
        }
        let [cached, fresh] = renderers.each_mut().map(|(renderer, target)| {
            renderer
                .render(&scene, Target::Offscreen(target))
                .unwrap_or_else(|e| panic!("{volumetric:?}, frame {i}: {e}"));
            let visibility = target.read_visibility().unwrap();
            frame_bytes(&target.read_colour(), &visibility, None)
        });
        assert!(
            cached == fresh,
            "{volumetric:?}, frame {i} ({m:?} moved): the cached frame differs"
        );
    }
    let [cached, fresh] = renderers.each_ref().map(|(renderer, _)| {
        let map = renderer
            .volumetric_maps()
            .get(0)
            .expect("a translucent map");
        let map = map.map();
        (0..map.layers())
            .map(|l| map.read_layer(l))
            .collect::<Vec<_>>()
    });
    assert!(
        cached == fresh,
        "{volumetric:?}: the kept translucent map differs"
    );
    let fresh_draws = renderers[1].0.volumetric_maps().draws();
    assert_eq!(
        (fresh_draws.drawn, fresh_draws.kept),
        (moves.len() as u64, 0),
        "{volumetric:?}: without the cache every frame draws the map"
    );
    let (renderer, _) = &renderers[0];
    (renderer.volumetric_maps().draws(), renderer.mask_uses())
}

#[test]
fn a_kept_translucent_map_gives_the_frames_drawn_without_the_cache() {
    // The smoke's translucent map is drawn again only when the glass moves (and the first
    // frame): an opaque caster moving, or nothing, keeps it. Every frame is the one the
    // uncached renderer draws, pixel for pixel.
    use shadowmap::settings::Volumetric;
    use Move::*;
    let moves = [
        Nothing,
        Nothing,
        Translucent,
        Nothing,
        Opaque,
        Nothing,
        Translucent,
    ];
    for volumetric in [Volumetric::Osm, Volumetric::Fom, Volumetric::Avsm] {
        let (draws, _) = smoke_side_by_side(volumetric, &moves);
        assert_eq!(
            (draws.drawn, draws.kept),
            (3, 4),
            "{volumetric:?}: drawn at the first frame and where the glass moved"
        );
    }
}

#[test]
fn a_still_frame_with_translucent_maps_reads_the_mask_and_equals_a_fresh_one() {
    // The smoke held still, then the glass moved once, under every technique that keeps a
    // translucent map: the mask (each light's test times the light the translucent casters
    // leave, for the opaque surfaces) is written at the first frame and read while nothing
    // moves, written again once the glass has moved and stayed, and every frame is the
    // uncached one, pixel for pixel, the translucent items drawn over it taking their own
    // tests.
    use shadowmap::settings::Volumetric;
    use Move::*;
    let moves = [Nothing, Nothing, Nothing, Translucent, Nothing, Nothing];
    for volumetric in [Volumetric::Osm, Volumetric::Fom, Volumetric::Avsm] {
        let (draws, uses) = smoke_side_by_side(volumetric, &moves);
        assert_eq!((draws.drawn, draws.kept), (2, 4), "{volumetric:?}");
        // Frames 0 (written) to 2 read it; 3 moved: tested; 4 written, 5 read.
        assert_eq!((uses.written, uses.read), (2, 5), "{volumetric:?}");
    }
}
