//! Translucent casters (items with `opacity` below 1). A depth map holds one depth per
//! texel, so it can only cast them all or nothing: `volumetric = "off"` leaves them out of
//! the map (the chapters' depth pass ignores them), `"solid"` draws them into it as if
//! opaque. The truth they are measured against is the product of (1 - opacity) over every
//! crossing of the shadow ray (`crate::reference::transmittance`).
//!
//! The other choices keep a translucent map beside the light's depth map: drawn from the
//! light's camera (its view and projection, so a texel is the depth map's texel) before
//! the scene pass, its depth fitted to the translucent casters alone ([`DepthFit`]), and
//! read in the scene pass as `lit *= transmittance` (`shaders/lib/volumetric.glsl` finds
//! the fragment in it). Each technique is a [`Method`] ([`osm`], [`fom`]) named by
//! [`method`], the one match over them: its map, its lookup's snippet and call, its cost.

mod additive;
pub mod avsm;
pub mod cache;
pub mod fom;
pub mod idle;
pub mod maps;
pub mod osm;
pub mod resolved;

use glam::{DMat4, DVec3, Mat4};

use super::ShadowView;
use crate::engine::{Gl, Mesh, PixelRect, ShaderProgram, TranslucentMap};
use crate::error::Result;
use crate::scene::{GameItem, Scene};
use crate::settings::{MapSize, ShadowSettings, Volumetric};

pub use maps::Maps;

/// The most floats a texel can hold: four to a layer of the translucent map.
pub const MAX_CHANNELS: u32 = crate::settings::MAX_TRANSLUCENT_CHANNELS;
const _: () = assert!(MAX_CHANNELS == 4 * crate::engine::translucent_map::MAX_LAYERS);

pub use crate::settings::MAX_FOURIER_TERMS;

/// Each light's sampler of its translucent map in the scene shader.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] = [
    "volumetricMap0",
    "volumetricMap1",
    "volumetricMap2",
    "volumetricMap3",
];

/// The translucent items that cast (their own `casts_shadows`).
pub fn translucent_casters(scene: &Scene) -> impl Iterator<Item = (usize, &GameItem)> {
    scene
        .items
        .iter()
        .enumerate()
        .filter(|(_, i)| i.is_translucent() && i.casts_translucent)
}

/// A technique that keeps a translucent map: what the plan, the renderer, the scene
/// shader and the bench ask of it.
pub trait Method: Sync {
    /// Its map for a light under `settings`.
    fn create(&self, gl: &Gl, settings: &ShadowSettings) -> Result<Box<dyn VolumetricMap>>;
    /// The number its lookup is compiled for (slices, terms, nodes).
    fn parameter(&self, settings: &ShadowSettings) -> u32;
    /// Its lookup's library file and call for light `i`, compiled for `parameter`: a
    /// transmittance, 1 = nothing in the way.
    fn lookup(&self, i: usize, parameter: u32) -> (&'static str, String);
    /// Its library file and the curve at one texel of the map, for the resolve
    /// (shaders/volumetric_resolve.frag: `translucentMap`, `texel`, its centre `uv` and the
    /// fitted `depth`).
    fn texel_call(&self, parameter: u32) -> (&'static str, String);
    /// Bytes a texel and passes over the map a frame, without GL (the bench's rows).
    fn cost(&self, settings: &ShadowSettings) -> (u32, u32);
    /// The settings only it reads, as the scene file names them (idle without it).
    fn settings(&self) -> &'static [&'static str];
}

/// The technique behind `volumetric`, if it keeps a map: the one match over them.
pub fn method(volumetric: Volumetric) -> Option<&'static dyn Method> {
    match volumetric {
        Volumetric::Off | Volumetric::Solid => None,
        Volumetric::Osm => Some(&osm::OSM),
        Volumetric::Fom => Some(&fom::FOM),
        Volumetric::Avsm => Some(&avsm::Avsm),
    }
}

/// What the scene program is compiled for about a light's translucent map.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct VolumetricKey {
    pub technique: Volumetric,
    pub parameter: u32,
    /// `opaque_receivers = "resolved"`: opaque receivers read the resolved map
    /// ([`resolved`]); translucent ones keep the curve.
    pub resolved: bool,
}

impl VolumetricKey {
    /// The key under `settings`, when its technique keeps a map.
    pub fn of(settings: &ShadowSettings) -> Option<VolumetricKey> {
        method(settings.volumetric).map(|m| VolumetricKey {
            technique: settings.volumetric,
            parameter: m.parameter(settings),
            resolved: resolved::wanted(settings),
        })
    }

    /// Light `i`'s lookup (its light-space position in map slot `p`): its library files
    /// and its call; for an opaque receiver (`opaque`) under `resolved`, the resolved map's
    /// one fetch.
    pub fn lookup(&self, i: usize, p: usize, opaque: bool) -> Option<(&'static str, String)> {
        if opaque && self.resolved {
            let map = resolved::SAMPLERS[i];
            let call = format!("resolvedTransmittance({map}, mlightviewVertexPos[{p}])");
            return Some(("lib/volumetric.glsl", call));
        }
        method(self.technique).map(|m| m.lookup(i, self.parameter))
    }

    /// Light `i`'s sampler declaration for that lookup.
    pub fn sampler(&self, i: usize, opaque: bool) -> String {
        match opaque && self.resolved {
            true => format!("uniform sampler2D {};", resolved::SAMPLERS[i]),
            false => format!("uniform sampler2DArray {};", SAMPLERS[i]),
        }
    }
}

/// One light's translucent map.
pub trait VolumetricMap {
    /// Whether the storage still matches `settings`.
    fn fits(&self, settings: &ShadowSettings) -> bool;
    /// Draws the translucent casters into the map, seen through `draw.view`.
    fn render(&mut self, draw: &Draw) -> Result<()>;
    /// The map the lookup reads.
    fn map(&self) -> &TranslucentMap;
    /// Passes over the map a frame.
    fn passes(&self) -> u32 {
        1
    }
}

/// What a translucent map is drawn with: the scene's meshes, the light's camera and the
/// depth range fitted to the translucent casters.
pub struct Draw<'a> {
    pub gl: &'a Gl,
    pub meshes: &'a [Mesh],
    pub scene: &'a Scene,
    pub view: &'a ShadowView,
    pub fit: DepthFit,
    /// The texels to clear and draw: those the casters cover, and those they covered when
    /// the map was last drawn.
    pub region: PixelRect,
}

impl Draw<'_> {
    /// Draws every translucent caster with `program` (shaders/translucent_map.vert's
    /// uniforms): its light view, the light's projection, the fitted depth range and its
    /// optical depth -ln(1 - opacity), the opacity clamped below 1 (an opaque item would
    /// take the depth map's part; here it stays finite).
    pub fn casters(&self, program: &ShaderProgram) {
        program.set_mat4("orthoProjectionMatrix", &self.view.projection);
        program.set_vec2("depthFit", [self.fit.near, 1.0 / self.fit.depth()]);
        for (mesh_id, mesh) in self.meshes.iter().enumerate() {
            let items = translucent_casters(self.scene).filter(|(_, i)| i.mesh == mesh_id);
            mesh.render_list(items, |(_, item)| {
                let model_light = self.view.view64 * item.model_matrix64();
                program.set_mat4("modelLightViewMatrix", &model_light.as_mat4());
                program.set_f32("opticalDepth", optical_depth(item.opacity));
            });
        }
    }
}

/// The most opacity a crossing takes: -ln(1 - a) stays finite (about 9.2).
pub const OPACITY_MAX: f32 = 0.9999;

/// A crossing's optical depth, -ln(1 - a), with a clamped to [0, [`OPACITY_MAX`]].
pub fn optical_depth(opacity: f32) -> f32 {
    -(1.0 - opacity.clamp(0.0, OPACITY_MAX)).ln()
}

/// The light's depth (distance along its view axis) between the nearest and the
/// farthest translucent caster: the map's depth runs 0 to 1 over it, so slices and
/// frequencies spend nothing on empty depth, and a receiver past every caster reads 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthFit {
    pub near: f32,
    pub far: f32,
}

impl DepthFit {
    /// The range of the translucent casters' world boxes (`boxes`, by item) in the light's
    /// view `view`; 0 to 1 when there are none.
    pub fn of(scene: &Scene, boxes: &[(DVec3, DVec3)], view: DMat4) -> DepthFit {
        let (mut near, mut far) = (f64::INFINITY, f64::NEG_INFINITY);
        for (k, _) in translucent_casters(scene) {
            let Some(&(lo, hi)) = boxes.get(k) else {
                continue;
            };
            for c in super::camera::fitted::corners(lo, hi) {
                let depth = -view.transform_point3(c).z;
                near = near.min(depth);
                far = far.max(depth);
            }
        }
        if near > far {
            return DepthFit {
                near: 0.0,
                far: 1.0,
            };
        }
        // A sliver either side, so the nearest and farthest crossings fall inside.
        let margin = 1e-4 * (far - near) + 1e-5;
        DepthFit {
            near: (near - margin) as f32,
            far: (far + margin) as f32,
        }
    }

    pub fn depth(&self) -> f32 {
        self.far - self.near
    }
}

/// The matrix that takes a fragment's camera-view position to light `view`'s
/// translucent map: x, y and w as the light's projection gives them (its texel), z the
/// fitted depth, 0 at `fit.near` to 1 at `fit.far`, undivided (shaders/lib/volumetric.glsl),
/// read `lift` world units nearer the light ([`self_shadow_lift`]).
pub fn lookup_matrix(view: &ShadowView, fit: DepthFit, lift: f32, camera_view: DMat4) -> Mat4 {
    let mut projection = view.projection.as_dmat4();
    let inv = 1.0 / f64::from(fit.depth());
    // Row z: -z_view (the distance along the light's axis), moved and scaled.
    projection.x_axis.z = 0.0;
    projection.y_axis.z = 0.0;
    projection.z_axis.z = -inv;
    projection.w_axis.z = -(f64::from(fit.near) + f64::from(lift)) * inv;
    (projection * view.view64 * camera_view.inverse()).as_mat4()
}

/// How much nearer the light a receiver reads the translucent map, in world units: two of
/// the map's texels (`texel_world`: one of the depth map's, of `map_size`, for a
/// translucent map of `volumetric_size`). A translucent item is itself one of the crossings
/// its map holds, at its own depth; read there, the lookup's 2 x 2 texels split on its own
/// step and it shades itself in specks, the acne of the depth test. Two texels clear a
/// surface tilted up to 45 degrees from the light's view plane across them.
pub fn self_shadow_lift(texel_world: f32, map_size: MapSize, volumetric_size: MapSize) -> f32 {
    2.0 * texel_world * map_size.min_side() as f32 / volumetric_size.min_side().max(1) as f32
}

#[cfg(test)]
mod tests;
