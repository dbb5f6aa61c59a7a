//! Adaptive volumetric shadow maps (Salvi, Vidimce, Lauritzen and Lefohn, EGSR 2010; the
//! slides' last "Advanced techniques" link): per texel a short curve of transmittance
//! against the light's depth, `avsm_nodes` nodes, built from every translucent fragment the
//! light sees and, when full, compressed by dropping the node whose removal changes the
//! area under the curve least ([`curve`] on the CPU, `shaders/avsm_build.frag` on the GPU).
//!
//! GL 3.3 has no atomics or image stores to insert fragments as they come, so the light's
//! translucent fragments are captured by depth peeling, up to `peel_layers` layers
//! ([`DepthPeel`]; it stops at the first empty layer), each into its own layer of an array.
//! When the last layer allowed still caught something, one more pass folds all the
//! fragments behind it into one crossing at the farthest of them (what they let through,
//! multiplied by blending): the curve stays exact behind the medium, whatever its depth.
//! Then one full-screen pass builds every texel's curve in locals, inserting the layers'
//! crossings nearest first (depth order, as the paper asks), and writes its nodes once:
//! (depth, transmittance) pairs at 32-bit, two to an RGBA32F layer of a
//! [`TranslucentMap`], 8 bytes a node. `shaders/lib/avsm.glsl` looks the curve up in the
//! four texels around a receiver.

pub mod curve;

use glam::DVec2;

use super::{translucent_casters, Draw, Method, VolumetricMap, SAMPLERS};
use crate::engine::{DepthPeel, FullScreenTriangle, Gl, PixelRect, ShaderProgram, TranslucentMap};
use crate::error::Result;
use crate::settings::{MapSize, ShadowSettings};
use crate::shaders;
use crate::shadows::camera::fitted;

/// The technique (`volumetric = "avsm"`, `avsm_nodes` N, `peel_layers` K).
pub struct Avsm;

/// The unit the peel reads the previous layer's depth from, and the build its two inputs
/// from (none of them the scene pass' units: these passes come before it).
const PEEL_UNIT: u32 = 0;
const BUILD_LAYERS_UNIT: u32 = 0;
const BUILD_REST_UNIT: u32 = 1;

/// Bytes a node: a 32-bit depth and a 32-bit transmittance.
pub const NODE_BYTES: u32 = 8;

/// The most nodes: two to a layer of the translucent map.
pub const MAX_NODES: u32 = crate::settings::MAX_AVSM_NODES;
const _: () = assert!(MAX_NODES == 2 * crate::engine::translucent_map::MAX_LAYERS);

pub use crate::settings::MAX_PEEL_LAYERS;

/// RGBA layers for `nodes`.
fn layers(nodes: u32) -> u32 {
    nodes.div_ceil(2)
}

impl Method for Avsm {
    fn create(&self, gl: &Gl, settings: &ShadowSettings) -> Result<Box<dyn VolumetricMap>> {
        let (nodes, layers) = (settings.avsm_nodes, settings.peel_layers);
        Ok(Box::new(AvsmMap::new(
            gl,
            settings.volumetric_size,
            nodes,
            layers,
        )?))
    }

    fn parameter(&self, settings: &ShadowSettings) -> u32 {
        settings.avsm_nodes
    }

    fn lookup(&self, i: usize, nodes: u32) -> (&'static str, String) {
        (
            "lib/avsm.glsl",
            format!(
                "avsmTransmittance({}, volumetricCoords({i}), {nodes})",
                SAMPLERS[i]
            ),
        )
    }

    fn texel_call(&self, nodes: u32) -> (&'static str, String) {
        let call = format!("avsmTexel(translucentMap, texel, depth, {nodes})");
        ("lib/avsm.glsl", call)
    }

    /// At most: a peel per layer and for the rest, and one build.
    fn cost(&self, settings: &ShadowSettings) -> (u32, u32) {
        (16 * layers(settings.avsm_nodes), settings.peel_layers + 2)
    }

    fn settings(&self) -> &'static [&'static str] {
        &["avsm_nodes", "peel_layers"]
    }
}

/// A light's curves, its peeling and the programs.
pub struct AvsmMap {
    curves: TranslucentMap,
    peel: DepthPeel,
    peel_program: ShaderProgram,
    /// The peel compiled with `REMAINDER`: the rest past the last layer.
    rest_program: ShaderProgram,
    build_program: ShaderProgram,
    triangle: FullScreenTriangle,
    nodes: u32,
    /// The layers the last render peeled that caught a crossing, and its passes.
    peeled: u32,
    passes: u32,
}

impl AvsmMap {
    /// A `size` map of `nodes` nodes (2 to [`MAX_NODES`]) a texel, peeling at most
    /// `max_layers`.
    pub fn new(gl: &Gl, size: MapSize, nodes: u32, max_layers: u32) -> Result<AvsmMap> {
        if !(2..=MAX_NODES).contains(&nodes) {
            return Err(crate::Error::Invalid(format!(
                "AVSM with {nodes} nodes: expected 2 to {MAX_NODES}"
            )));
        }
        let layers = layers(nodes);
        let defines = [
            ("AVSM_NODES".to_string(), nodes.to_string()),
            ("AVSM_LAYERS".to_string(), layers.to_string()),
        ];
        let curves = TranslucentMap::new(gl, size, layers)?;
        curves.clear([EMPTY_DEPTH, 1.0, EMPTY_DEPTH, 1.0]);
        Ok(AvsmMap {
            curves,
            peel: DepthPeel::new(gl, size, max_layers)?,
            peel_program: ShaderProgram::new(
                gl,
                &shaders::translucent_map_vert(),
                &shaders::avsm_peel_frag(),
                &[],
            )?,
            rest_program: ShaderProgram::new(
                gl,
                &shaders::translucent_map_vert(),
                &shaders::avsm_peel_frag(),
                &[("REMAINDER".to_string(), "1".to_string())],
            )?,
            build_program: ShaderProgram::new(
                gl,
                &shaders::depth_view_vert(),
                &shaders::avsm_build_frag(),
                &defines,
            )?,
            triangle: FullScreenTriangle::new(gl)?,
            nodes,
            peeled: 0,
            passes: 0,
        })
    }

    /// Layers that caught a crossing in the last render (peeling stops at the first
    /// empty one, or at the most it may peel).
    pub fn peeled(&self) -> u32 {
        self.peeled
    }

    /// Peels layer `k` of the translucent casters (with `rest`, all behind layer k - 1):
    /// whether it caught anything.
    fn peel_layer(&self, draw: &Draw, k: u32, rest: bool, rect: PixelRect) -> bool {
        let (pass, p) = match rest {
            false => (self.peel.begin(k, PEEL_UNIT, rect), &self.peel_program),
            true => (self.peel.begin_rest(k, PEEL_UNIT, rect), &self.rest_program),
        };
        p.bind();
        p.set_i32("previousDepth", PEEL_UNIT as i32);
        p.set_i32("firstLayer", i32::from(k == 0));
        draw.casters(p);
        pass.finish()
    }

    /// Builds every texel's curve within `rect` (outside it the map holds empty curves)
    /// from the first `count` peeled layers, then the rest if `rest`.
    fn build(&self, count: u32, rest: bool, rect: PixelRect) {
        let _pass = self.curves.begin_write(rect);
        let p = &self.build_program;
        p.bind();
        self.peel.bind_layers(BUILD_LAYERS_UNIT);
        self.peel.bind_rest(BUILD_REST_UNIT);
        p.set_i32("layers", BUILD_LAYERS_UNIT as i32);
        p.set_i32("rest", BUILD_REST_UNIT as i32);
        p.set_i32("layerCount", count as i32);
        p.set_i32("hasRest", i32::from(rest));
        self.triangle.draw();
    }

    /// The nodes read back, texel by texel (row 0 at the bottom), nearest first; unused
    /// nodes left out.
    pub fn read_nodes(&self) -> Vec<Vec<curve::Node>> {
        let map = &self.curves;
        let layers: Vec<Vec<[f32; 4]>> = (0..map.layers()).map(|l| map.read_layer(l)).collect();
        (0..layers[0].len())
            .map(|t| {
                let pairs = layers
                    .iter()
                    .flat_map(|l| [[l[t][0], l[t][1]], [l[t][2], l[t][3]]]);
                pairs
                    .take_while(|[d, _]| *d < EMPTY_DEPTH)
                    .map(|[depth, transmittance]| curve::Node {
                        depth,
                        transmittance,
                    })
                    .collect()
            })
            .collect()
    }
}

/// The texels of a `size` map the translucent casters' world boxes cover through the
/// light's camera, grown by a texel; `None` when they cover none.
fn footprint(draw: &Draw, size: MapSize) -> Option<PixelRect> {
    let whole = PixelRect {
        x: 0,
        y: 0,
        width: size.width,
        height: size.height,
    };
    let boxes = fitted::item_world_boxes(draw.scene);
    let clip = draw.view.projection.as_dmat4() * draw.view.view64;
    let (mut lo, mut hi) = (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY));
    for (k, _) in translucent_casters(draw.scene) {
        let Some(&(a, b)) = boxes.get(k) else {
            continue;
        };
        for c in fitted::corners(a, b) {
            let p = clip * c.extend(1.0);
            if p.w <= 0.0 {
                // Behind a perspective light's eye: the whole map.
                return Some(whole);
            }
            let ndc = DVec2::new(p.x, p.y) / p.w;
            (lo, hi) = (lo.min(ndc), hi.max(ndc));
        }
    }
    let side = DVec2::new(f64::from(size.width), f64::from(size.height));
    let to_texel = |v: DVec2| (v * 0.5 + 0.5) * side;
    let (a, b) = (to_texel(lo).floor() - 1.0, to_texel(hi).ceil() + 1.0);
    let (a, b) = (a.max(DVec2::ZERO).min(side), b.max(DVec2::ZERO).min(side));
    (b.x > a.x && b.y > a.y).then_some(PixelRect {
        x: a.x as u32,
        y: a.y as u32,
        width: (b.x - a.x) as u32,
        height: (b.y - a.y) as u32,
    })
}

/// Whether `outer` holds every texel of `inner`.
fn within(inner: PixelRect, outer: PixelRect) -> bool {
    inner.x >= outer.x
        && inner.y >= outer.y
        && inner.x + inner.width <= outer.x + outer.width
        && inner.y + inner.height <= outer.y + outer.height
}

/// The depth of an unused node (the fitted depths run 0 to 1).
pub const EMPTY_DEPTH: f32 = 2.0;

impl VolumetricMap for AvsmMap {
    fn fits(&self, settings: &ShadowSettings) -> bool {
        self.nodes == settings.avsm_nodes
            && self.peel.count() == settings.peel_layers.max(1)
            && self.curves.size() == settings.volumetric_size
    }

    /// Peels layer after layer until a layer is empty or `peel_layers` are in, then the
    /// rest if there may be one, and builds the curves in one pass over the texels the
    /// translucent casters can cover. Outside them the curves are empty: set when the map
    /// is made, and again within `draw.region` (what the casters covered before).
    fn render(&mut self, draw: &Draw) -> Result<()> {
        self.peeled = 0;
        self.passes = 0;
        let footprint = footprint(draw, self.curves.size());
        // The texels the casters covered before and cover no longer: emptied.
        let region = draw.region;
        if region.width > 0 && region.height > 0 && !footprint.is_some_and(|r| within(region, r)) {
            self.build(0, false, region);
        }
        let Some(rect) = footprint else {
            return Ok(());
        };
        let most = self.peel.count();
        let mut rest = false;
        for k in 0..=most {
            let any = self.peel_layer(draw, k, k == most, rect);
            self.passes += 1;
            if !any {
                break;
            }
            if k == most {
                rest = true;
            } else {
                self.peeled += 1;
            }
        }
        if self.peeled > 0 {
            self.build(self.peeled, rest, rect);
            self.passes += 1;
        }
        Ok(())
    }

    fn map(&self) -> &TranslucentMap {
        &self.curves
    }

    fn passes(&self) -> u32 {
        self.passes
    }
}
