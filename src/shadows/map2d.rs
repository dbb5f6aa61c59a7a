//! The chapters' technique: one 2D depth map per light ("Shadows", sections "Shadow
//! Mapping" and "Improving"; LearnOpenGL "Shadow Mapping").
//!
//! 1. The depth pass (`Map2d::draw`, the book's `renderDepthMap`): bind the map's
//!    framebuffer, viewport to its size, clear depth, draw every caster with the light's
//!    view and its orthographic (or perspective) projection ([`draw_map_casters`]).
//! 2. The test: `calcShadow` in `shaders/lib/shadow_2d.glsl`, called once per fragment with
//!    the fragment's light-space position (`mlightviewVertexPos`, from scene.vert).
//!
//! Beside it: the light's camera ([`camera()`]: the book's box, or past the chapter a
//! perspective, a spot's or a fitted one) and the map behind [`super::Technique`].

mod camera;
mod glsl;
mod kind;
mod technique;

pub use super::casters::draw_map_casters;
pub use crate::settings::Kernel;
pub use camera::{camera, camera_and_casters};
pub use glsl::glsl;
pub use kind::{follows_camera, KIND};

use super::cache::patch::{self, Patch};
use super::casters::depth_state;
use super::{DepthPass, ShadowView, SlotTransform};
use crate::engine::{state, DepthPassGuard, DepthState, Gl, ShadowMap};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::{DepthFormat, Filter, PerspectiveDepth, ShadowSettings};
use glam::Mat4;

/// Its sampler in the scene shader, per light (GLSL 3.30 cannot index sampler arrays).
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["shadowMap0", "shadowMap1", "shadowMap2", "shadowMap3"];

/// Whether its map has a lit border, per light, where the shader draws it
/// (shaders/lib/shadow_border.glsl: OpenGL ES only; the desktop's sampler has the border).
pub const BORDER_LIT: [&str; crate::scene::MAX_LIGHTS] = [
    "shadowBorderLit[0]",
    "shadowBorderLit[1]",
    "shadowBorderLit[2]",
    "shadowBorderLit[3]",
];

/// Whether its map's depths are interpolated, per light, where the shader does it
/// (shaders/lib/shadow_depth.glsl: OpenGL ES only; the desktop's sampler interpolates).
pub const DEPTH_INTERPOLATED: [&str; crate::scene::MAX_LIGHTS] = [
    "shadowDepthInterpolated[0]",
    "shadowDepthInterpolated[1]",
    "shadowDepthInterpolated[2]",
    "shadowDepthInterpolated[3]",
];

/// A light's one 2D map: the book's `ShadowMap` (an FBO and its depth texture).
pub struct Map2d {
    map: ShadowMap,
}

impl Map2d {
    pub fn new(gl: &Gl, settings: &ShadowSettings) -> Result<Map2d> {
        Ok(Map2d {
            map: ShadowMap::new(gl, settings.map_size, settings.depth_format)?,
        })
    }

    /// The depth pass (the book's `renderDepthMap`): the whole map, or past the chapter
    /// with `patch` its region alone (scissored: the clear and the casters touch nothing
    /// else) with its casters.
    fn draw(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
        patch: Option<&Patch>,
    ) -> Result<ShadowView> {
        let (mut view, fitted_casters) = camera_and_casters(scene, index, pass.settings);
        let only = patch::casters_within(fitted_casters, patch);
        view.linear_depth = stores_linear_depth(view.perspective, pass.settings);
        let program = match view.linear_depth {
            true => pass.programs.linear(pass.gl)?,
            false => pass.programs.flat(pass.gl)?,
        };
        let depth = DepthState {
            scissor: patch.map(|p| p.region.pixels()),
            ..depth_state(pass.settings)
        };
        let _state = DepthPassGuard::begin(pass.gl, depth, &program);
        if view.linear_depth {
            program.set_vec2("depthRange", [view.near, view.far]);
            let [factor, units] = pass.settings.polygon_offset;
            let step = least_depth_step(pass.settings.depth_format);
            program.set_vec2("polygonOffset", [factor, units * step]);
        }
        self.map.bind_for_writing();
        state::clear_depth(pass.gl);
        draw_map_casters(pass, scene, index, &view, &program, only.as_deref());
        Ok(view)
    }
}

/// The light-space transform of a 2D map drawn through `view` (the chapter's map and a
/// moment map alike): world to the light's view, its projection, the normal offset in world
/// units. A map tested in linear depth gets it in place of clip z ([`linear_depth_row`]).
pub fn slot_transform(view: &ShadowView, settings: &ShadowSettings) -> SlotTransform {
    let projection = match map_depth(view.perspective, settings) {
        MapDepth::Projected => view.projection,
        MapDepth::Linear | MapDepth::LinearBias => {
            linear_depth_row(view.projection, view.near, view.far)
        }
    };
    SlotTransform {
        from: view.view64,
        projection,
        normal_offset: settings.normal_offset * view.texel_world,
    }
}

/// How a 2D depth map's test reads depth ([`PerspectiveDepth`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MapDepth {
    /// The projection's depth, compared as stored: an orthographic map, or a perspective
    /// one as the chapters draw it.
    Projected,
    /// A perspective map of linear depth.
    Linear,
    /// A perspective map of projected depth, biased in linear depth.
    LinearBias,
}

/// How a 2D depth map seen through a camera (`perspective` or not) stores and tests depth
/// under `settings`: never linear for PCSS, whose penumbra estimate reads the projection's
/// depth, nor in a moment map (its own pass).
pub fn map_depth(perspective: bool, settings: &ShadowSettings) -> MapDepth {
    if !perspective || settings.filter == Filter::Pcss || settings.filter.moments() {
        return MapDepth::Projected;
    }
    match settings.perspective_depth {
        PerspectiveDepth::Linear => MapDepth::Linear,
        PerspectiveDepth::Hyperbolic => MapDepth::Projected,
        PerspectiveDepth::HyperbolicLinearBias => MapDepth::LinearBias,
    }
}

/// Whether the map stores linear depth (its depth pass writes it).
pub fn stores_linear_depth(perspective: bool, settings: &ShadowSettings) -> bool {
    map_depth(perspective, settings) == MapDepth::Linear
}

/// The least depth step GL's polygon offset `units` count in: 2^-bits for a fixed-point
/// format; for 32-bit floats 2^(e - 23) with e the depth's exponent, taken at [0.5, 1).
fn least_depth_step(format: DepthFormat) -> f32 {
    match format {
        DepthFormat::D16 => (-16f32).exp2(),
        DepthFormat::D24 | DepthFormat::D32F => (-24f32).exp2(),
    }
}

/// `projection` with its z row giving the linear depth (w - near) / (far - near), w the
/// distance along the light's axis: linear in the position, so it interpolates exactly as
/// a vertex output. The scene's test (lib/linear_depth.glsl) puts it back as z / w.
pub fn linear_depth_row(projection: Mat4, near: f32, far: f32) -> Mat4 {
    let mut m = projection;
    let range = far - near;
    // Clip w is row 3 (w = -z for GL's perspective); z' = (w - near) / range.
    let w_row = projection.row(3);
    let z_row = (w_row - glam::Vec4::W * near) / range;
    m.x_axis.z = z_row.x;
    m.y_axis.z = z_row.y;
    m.z_axis.z = z_row.z;
    m.w_axis.z = z_row.w;
    m
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec4;

    #[test]
    fn the_linear_row_runs_from_the_near_plane_to_the_far_plane() {
        let (near, far) = (1e-4, 30.0);
        let p = linear_depth_row(Mat4::perspective_rh_gl(1.2, 1.0, near, far), near, far);
        let depth = |z: f32| p * Vec4::new(0.3, -0.2, -z, 1.0);
        assert!(depth(near).z.abs() < 1e-6);
        assert!((depth(far).z - 1.0).abs() < 1e-6);
        assert!((depth(15.00005).z - 0.5).abs() < 1e-6);
        // x, y and w are the projection's own.
        assert_eq!(depth(6.0).w, 6.0);
        let s = ShadowSettings {
            perspective_depth: PerspectiveDepth::Linear,
            ..ShadowSettings::default()
        };
        assert_eq!(map_depth(true, &s), MapDepth::Linear);
        assert_eq!(map_depth(false, &s), MapDepth::Projected);
        let pcss = ShadowSettings {
            filter: Filter::Pcss,
            ..s
        };
        assert_eq!(map_depth(true, &pcss), MapDepth::Projected);
    }
}
