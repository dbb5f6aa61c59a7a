//! Adaptive volumetric shadow maps against the transmittance truth: the curves the GPU
//! builds equal the CPU AVSM built from the truth's crossings (read back, to 1e-4), hold
//! every crossing exactly when they fit, keep the K nearest crossings of K peeled layers
//! (and fold the rest into one), stop peeling at the first empty layer, leave 1 - a behind one sheet of opacity a, and
//! do not depend on the order the casters are drawn in (depth peeling sorts them).

use crate::common;

use std::path::Path;

use glam::{DMat4, DVec3, Mat4, Vec3};
use shadowmap::compare::{compare, translucent_casters};
use shadowmap::engine::{Mesh, PixelRect};
use shadowmap::scene::file::parse;
use shadowmap::settings::{MapSize, ShadowSettings, Volumetric};
use shadowmap::shadows::volumetric::avsm::curve::{Curve, Node};
use shadowmap::shadows::volumetric::avsm::AvsmMap;
use shadowmap::shadows::volumetric::{DepthFit, Draw, VolumetricMap};
use shadowmap::shadows::{Rays, ShadowView};
use shadowmap::Scene;

/// A translucent sheet: position, scale, rotation in degrees, opacity.
type Sheet = ([f32; 3], [f32; 3], [f32; 3], f32);

/// Sheets tilted and offset, so texels see 0 to 6 crossings at depths that vary across
/// the map.
const SHEETS: [Sheet; 6] = [
    ([0.0, 1.5, 0.0], [1.2, 1.0, 1.2], [0.0, 0.0, 10.0], 0.3),
    ([0.3, 1.0, -0.2], [1.0, 1.0, 1.0], [8.0, 0.0, 0.0], 0.5),
    ([-0.2, 0.5, 0.1], [1.4, 1.0, 0.8], [0.0, 0.0, -15.0], 0.2),
    ([0.0, 0.0, 0.0], [1.5, 1.0, 1.5], [0.0, 0.0, 0.0], 0.4),
    ([0.2, -0.5, 0.3], [0.9, 1.0, 0.9], [5.0, 0.0, 5.0], 0.6),
    ([-0.3, -1.0, 0.0], [1.1, 1.0, 1.1], [0.0, 0.0, 0.0], 0.25),
];

/// A floor at y = -2 and `sheets` over it, lit from straight above.
fn scene_of(sheets: &[Sheet]) -> Scene {
    let mut text = String::from(
        "size = [320, 240]\n\
         [camera]\nposition = [0.0, 4.0, 4.0]\ntarget = [0.0, -1.0, 0.0]\n\
         [light]\ndirection = [0.0, 1.0, 0.0001]\n\
         ortho = { left = -3.0, right = 3.0, bottom = -3.0, top = 3.0, near = -1.0, far = 12.0 }\n\
         [shadow]\nlight_view = \"look-at\"\nbias = 0.005\n\
         [[item]]\nname = \"floor\"\nmesh = \"plane\"\nposition = [0.0, -2.0, 0.0]\nscale = 3.0\n",
    );
    for (k, (p, s, r, a)) in sheets.iter().enumerate() {
        text += &format!(
            "[[item]]\nname = \"sheet{k}\"\nmesh = \"plane\"\nposition = {p:?}\nscale = {s:?}\n\
             rotation = {r:?}\ncolour = [1.0, 0.5, 0.0, 1.0]\nopacity = {a}\n"
        );
    }
    parse(&text, Path::new("sheets.toml"), None).unwrap_or_else(|e| panic!("{e}"))
}

/// The map's side, and the light's box: looking down from y = 5 over x, z in [-2, 2].
const SIDE: u32 = 96;
const HALF: f32 = 2.0;
const FIT: DepthFit = DepthFit {
    near: 3.0,
    far: 7.0,
};

fn light_view() -> ShadowView {
    let view = DMat4::look_at_rh(DVec3::new(0.0, 5.0, 0.0), DVec3::ZERO, DVec3::Z);
    ShadowView {
        view: view.as_mat4(),
        view64: view,
        projection: Mat4::orthographic_rh_gl(-HALF, HALF, -HALF, HALF, -1.0, 12.0),
        perspective: false,
        linear_depth: false,
        near: -1.0,
        far: 12.0,
        texel_world: 2.0 * HALF / SIDE as f32,
        rays: Rays::Parallel { to_light: Vec3::Y },
    }
}

/// What the GPU built: the nodes of every texel (row 0 at the bottom), the layers peeled
/// that caught a crossing, and the passes.
struct Built {
    nodes: Vec<Vec<Node>>,
    peeled: u32,
    passes: u32,
}

fn build(scene: &Scene, nodes: u32, layers: u32) -> Built {
    build_frames(&[scene], nodes, layers)
}

/// What one map holds after drawing `scenes` in turn (each over the whole map's region).
fn build_frames(scenes: &[&Scene], nodes: u32, layers: u32) -> Built {
    let ctx = common::context();
    let gl = ctx.gl();
    let size = MapSize {
        width: SIDE,
        height: SIDE,
    };
    let mut map = AvsmMap::new(gl, size, nodes, layers).unwrap_or_else(|e| panic!("{e}"));
    let view = light_view();
    for scene in scenes {
        let meshes: Vec<Mesh> = (scene.meshes.iter())
            .map(|m| Mesh::new(gl, m).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        let draw = Draw {
            gl,
            meshes: &meshes,
            scene,
            view: &view,
            fit: FIT,
            region: PixelRect {
                x: 0,
                y: 0,
                width: SIDE,
                height: SIDE,
            },
        };
        map.render(&draw).unwrap_or_else(|e| panic!("{e}"));
    }
    Built {
        nodes: map.read_nodes(),
        peeled: map.peeled(),
        passes: map.passes(),
    }
}

/// The truth's crossings through every texel's centre, as (fitted depth, opacity),
/// nearest first (row 0 at the bottom).
fn truth_crossings(scene: &Scene) -> Vec<Vec<(f32, f32)>> {
    let truth = translucent_casters(scene, DVec3::ZERO);
    let to_world = light_view().view64.inverse();
    let depth = FIT.far - FIT.near;
    let dir = to_world.transform_vector3(-DVec3::Z).as_vec3();
    let centre = |i: u32| -HALF + 2.0 * HALF * (i as f32 + 0.5) / SIDE as f32;
    (0..SIDE * SIDE)
        .map(|t| {
            let (x, y) = (centre(t % SIDE), centre(t / SIDE));
            let start = DVec3::new(f64::from(x), f64::from(y), -f64::from(FIT.near));
            let origin = to_world.transform_point3(start).as_vec3();
            let crossings = truth.crossings(origin, dir, 0.0, depth);
            crossings.iter().map(|c| (c.t / depth, c.opacity)).collect()
        })
        .collect()
}

/// The crossings `layers` peeled layers give: the nearest `layers`, then the rest as one
/// at the farthest of them, letting through what they all do.
fn peeled(crossings: &[(f32, f32)], layers: usize) -> Vec<(f32, f32)> {
    let mut kept = crossings[..layers.min(crossings.len())].to_vec();
    if let Some(last) = crossings.get(layers..).and_then(|r| r.last()) {
        let through: f32 = crossings[layers..].iter().map(|(_, a)| 1.0 - a).product();
        kept.push((last.0, 1.0 - through));
    }
    kept
}

/// The largest difference between the GPU's nodes and the CPU's curves (`nodes` nodes,
/// from what `layers` layers peel); node counts must agree.
fn against_cpu(built: &Built, truth: &[Vec<(f32, f32)>], nodes: usize, layers: usize) -> f32 {
    let mut worst = 0.0f32;
    for (t, (gpu, crossings)) in built.nodes.iter().zip(truth).enumerate() {
        let cpu = Curve::from_crossings(nodes, peeled(crossings, layers));
        assert_eq!(gpu.len(), cpu.nodes().len(), "texel {t}: {gpu:?} {cpu:?}");
        for (g, c) in gpu.iter().zip(cpu.nodes()) {
            worst = worst
                .max((g.depth - c.depth).abs())
                .max((g.transmittance - c.transmittance).abs());
        }
    }
    worst
}

#[test]
fn the_gpu_curve_equals_the_cpu_avsm_of_the_truths_crossings() {
    let scene = scene_of(&SHEETS);
    let truth = truth_crossings(&scene);
    let most = truth.iter().map(Vec::len).max().unwrap();
    assert_eq!(most, 6, "the sheets overlap six deep somewhere");
    let over_four = truth.iter().filter(|c| c.len() > 4).count();
    assert!(
        over_four > 100,
        "{over_four} texels need compressing at 4 nodes"
    );
    for (nodes, layers) in [(8, 16), (4, 16), (3, 16), (2, 16), (3, 4)] {
        let built = build(&scene, nodes, layers);
        let worst = against_cpu(&built, &truth, nodes as usize, layers as usize);
        println!(
            "AVSM-{nodes}, {layers} layers: largest difference from the CPU curve {worst:.2e}"
        );
        assert!(worst < 1e-4, "AVSM-{nodes}: {worst}");
    }
}

#[test]
fn a_curve_that_fits_holds_every_crossing_exactly() {
    let scene = scene_of(&SHEETS);
    let truth = truth_crossings(&scene);
    let built = build(&scene, 8, 16);
    for (gpu, crossings) in built.nodes.iter().zip(&truth) {
        assert_eq!(gpu.len(), crossings.len());
        let mut left = 1.0;
        for (node, (depth, opacity)) in gpu.iter().zip(crossings) {
            left *= 1.0 - opacity;
            assert!((node.depth - depth).abs() < 1e-5, "{gpu:?} {crossings:?}");
            assert!(
                (node.transmittance - left).abs() < 1e-5,
                "{gpu:?} {crossings:?}"
            );
        }
    }
}

#[test]
fn k_layers_keep_the_k_nearest_crossings_and_peeling_stops_at_an_empty_layer() {
    let scene = scene_of(&SHEETS);
    let truth = truth_crossings(&scene);
    let three = build(&scene, 8, 3);
    // Three layers, the rest, and one build.
    assert_eq!((three.peeled, three.passes), (3, 5));
    // Every texel holds exactly its three nearest crossings, and the rest as one.
    assert!(against_cpu(&three, &truth, 8, 3) < 1e-5);
    for (gpu, crossings) in three.nodes.iter().zip(&truth) {
        let behind: f32 = crossings.iter().map(|(_, a)| 1.0 - a).product();
        let last = gpu.last().map_or(1.0, |n| n.transmittance);
        assert!((last - behind).abs() < 1e-5, "{gpu:?} {crossings:?}");
        assert_eq!(gpu.len(), crossings.len().min(4));
    }
    let all = build(&scene, 8, 16);
    // Six layers catch something, the seventh nothing: seven peels, one build.
    assert_eq!((all.peeled, all.passes), (6, 8));
    // Nothing translucent: no pass, empty curves.
    let none = build(&scene_of(&[]), 8, 16);
    assert_eq!((none.peeled, none.passes), (0, 0));
    assert!(none.nodes.iter().all(Vec::is_empty));
}

#[test]
fn curves_the_casters_left_are_emptied() {
    let (sheets, moved) = (scene_of(&SHEETS), scene_of(&SHEETS[..1]));
    let direct = build(&moved, 8, 16);
    let after = build_frames(&[&sheets, &moved], 8, 16);
    assert!(after.nodes.iter().filter(|n| n.len() == 1).count() > 1000);
    assert_eq!(after.nodes, direct.nodes);
    let gone = build_frames(&[&sheets, &scene_of(&[])], 8, 16);
    assert!(gone.nodes.iter().all(Vec::is_empty));
}

#[test]
fn the_draw_order_changes_nothing_as_the_layers_come_sorted() {
    let scene = scene_of(&SHEETS);
    let mut reversed = scene.clone();
    reversed.items.reverse();
    let (a, b) = (build(&scene, 4, 16), build(&reversed, 4, 16));
    let mut worst = 0.0f32;
    for (x, y) in a.nodes.iter().zip(&b.nodes) {
        assert_eq!(x.len(), y.len());
        for (p, q) in x.iter().zip(y) {
            worst = worst
                .max((p.depth - q.depth).abs())
                .max((p.transmittance - q.transmittance).abs());
        }
    }
    println!("AVSM-4, casters drawn in reverse: largest node difference {worst:e}");
    assert_eq!(worst, 0.0);
}

#[test]
fn one_sheet_of_opacity_a_leaves_one_minus_a_behind_it() {
    let scene = scene_of(&[([0.0, 0.0, 0.0], [1.0, 1.0, 1.0], [0.0; 3], 0.4)]);
    let settings = ShadowSettings {
        volumetric: Volumetric::Avsm,
        ..scene.shadow
    };
    let ctx = common::context();
    let opts = common::frame_options(scene.size[0], scene.size[1]);
    let c = compare(ctx.gl(), &scene, &settings, &opts).unwrap_or_else(|e| panic!("{e}"));
    let t = c.transmittance.expect("scored");
    assert!(t.in_shadow > 2000, "{t:?}");
    // Within 1% but at the sheet's edge, where a texel straddles it.
    assert!(t.mae_in_shadow < 0.01, "{t:?}");
    assert!(t.mae_outside < 0.005, "{t:?}");
}
