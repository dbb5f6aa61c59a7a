//! The translucent items' per-vertex light kept across frames
//! (`shadows::volumetric::vertex_light`): with `translucent_receivers = "vertex"` it is
//! captured at the first frame and again only when a map or a translucent item changed,
//! and every frame is the one drawn capturing it every frame (`shadow_cache` off), pixel
//! for pixel.

use crate::common;

use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::renderer::VertexLightCounts;
use shadowmap::scene::Light;
use shadowmap::settings::{ShadowSettings, TranslucentReceivers, Volumetric};
use shadowmap::{Renderer, Scene, Target};

const OUTPUTS: Outputs = Outputs {
    visibility: true,
    gbuffer: false,
};

/// What changes before a frame.
#[derive(Debug, Clone, Copy)]
enum Move {
    Nothing,
    /// The camera: no map and no item moves.
    Camera,
    /// The glass, a translucent caster: its translucent map changes.
    Glass,
    /// The cube, an opaque caster: the depth map changes.
    Cube,
    /// The light turns a little: every map changes.
    Light,
    /// A translucent ball that casts nothing: no map changes, only where its vertices are.
    Ball,
}

/// The smoke scene with one more puff, translucent and casting nothing, across the far
/// edge of the cube's shadow: its vertices' light changes as it moves, and no map does.
fn smoke_with_ball() -> Scene {
    let mut scene = common::frozen("smoke");
    scene.size = [240, 160];
    let puff = scene
        .items
        .iter()
        .position(|i| i.name.starts_with("smoke"))
        .unwrap();
    let mut ball = scene.items[puff].clone();
    ball.name = "ball".into();
    ball.position = glam::Vec3::new(-0.6, -0.75, 0.1);
    ball.scale = glam::Vec3::splat(0.25);
    ball.opacity = 0.5;
    (ball.casts_shadows, ball.casts_translucent) = (false, false);
    scene.items.push(ball);
    scene
}

fn frame_bytes(target: &RenderTarget) -> Vec<u8> {
    let mut bytes = target.read_colour();
    let visibility = target.read_visibility().unwrap();
    bytes.extend(
        visibility
            .iter()
            .map(|v| v.map_or(0, |v| (v * 255.0) as u8)),
    );
    bytes
}

/// The scene under `volumetric` with per-vertex translucent receivers, frame by frame with
/// the cache on and off side by side (`moves[i]` before frame i): every frame must be the
/// same. Returns the captures each renderer made and kept.
fn side_by_side(volumetric: Volumetric, moves: &[Move]) -> [VertexLightCounts; 2] {
    let ctx = common::context();
    let mut scene = smoke_with_ball();
    let find = |name: &str| scene.items.iter().position(|i| i.name == name).unwrap();
    let (glass, cube, ball) = (find("glass"), find("cube"), find("ball"));
    let mut renderers = [true, false].map(|cache| {
        let s = ShadowSettings {
            shadow_cache: cache,
            volumetric,
            translucent_receivers: TranslucentReceivers::Vertex,
            ..scene.shadow
        };
        let renderer = Renderer::new(ctx.gl(), &scene, &s).unwrap();
        let target = RenderTarget::new(ctx.gl(), 240, 160, OUTPUTS).unwrap();
        (renderer, target)
    });
    for (i, m) in moves.iter().enumerate() {
        match m {
            Move::Nothing => {}
            Move::Camera => scene.camera.position.x += 0.2,
            Move::Glass => scene.items[glass].position.x += 0.05,
            Move::Cube => scene.items[cube].position.z += 0.2,
            Move::Ball => scene.items[ball].position.z -= 0.1,
            Move::Light => match &mut scene.lights[0] {
                Light::Directional(l) => l.direction.x += 0.05,
                _ => unreachable!("the smoke's light is directional"),
            },
        }
        let [cached, fresh] = renderers.each_mut().map(|(renderer, target)| {
            renderer
                .render(&scene, Target::Offscreen(target))
                .unwrap_or_else(|e| panic!("{volumetric:?}, frame {i}: {e}"));
            frame_bytes(target)
        });
        let differ = cached.iter().zip(&fresh).filter(|(a, b)| a != b).count();
        assert!(
            differ == 0,
            "{volumetric:?}, frame {i} ({m:?} moved): {differ} bytes of the kept frame differ"
        );
    }
    renderers.each_ref().map(|(r, _)| r.vertex_light_counts())
}

#[test]
fn kept_vertex_light_gives_the_frames_captured_every_frame() {
    use Move::*;
    let moves = [
        Nothing, Nothing, Camera, Glass, Nothing, Cube, Camera, Ball, Light, Nothing,
    ];
    for volumetric in [
        Volumetric::Osm,
        Volumetric::Fom,
        Volumetric::Avsm,
        Volumetric::Off,
    ] {
        let [cached, fresh] = side_by_side(volumetric, &moves);
        // Captured at the first frame and where the glass, the cube, the ball or the light
        // moved; kept where nothing or only the camera did.
        assert_eq!(
            (cached.captured, cached.kept),
            (5, 5),
            "{volumetric:?}: {cached:?}"
        );
        assert_eq!(
            (fresh.captured, fresh.kept),
            (moves.len() as u64, 0),
            "{volumetric:?}: without the cache, every frame"
        );
    }
}

#[test]
fn per_pixel_receivers_capture_nothing() {
    let ctx = common::context();
    let scene = smoke_with_ball();
    let s = ShadowSettings {
        volumetric: Volumetric::Osm,
        ..scene.shadow
    };
    let mut renderer = Renderer::new(ctx.gl(), &scene, &s).unwrap();
    let target = RenderTarget::new(ctx.gl(), 240, 160, OUTPUTS).unwrap();
    for _ in 0..2 {
        renderer.render(&scene, Target::Offscreen(&target)).unwrap();
    }
    assert_eq!(renderer.vertex_light_counts(), VertexLightCounts::default());
}

#[test]
fn render_counts_the_captures_in_its_summary() {
    let out = std::env::temp_dir().join("shadowmap-vertex-light-summary.png");
    let stdout = common::stdout_of(common::bin().args([
        "render",
        "--scene",
        "smoke",
        "--size",
        "160x90",
        "--frames",
        "4",
        "--volumetric",
        "osm",
        "--translucent-receivers",
        "vertex",
        "--out",
        out.to_str().unwrap(),
    ]));
    assert!(
        stdout.contains("vertex light over 4 frames: 1 captured, 3 kept"),
        "{stdout}"
    );
}
