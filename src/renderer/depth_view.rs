//! The chapters' debug quad: a light's shadow map on the whole target (LearnOpenGL's
//! debug quad, the book's "depth map" picture). Linearised for a perspective light
//! (LearnOpenGL's `LinearizeDepth`), raw for an orthographic one; a cube map as a panorama,
//! cascades side by side. A 2D map's greys are stretched over the depths its casters can
//! reach ([`DepthRange`]): the book's 20 x 20 box around a 5-unit scene otherwise shows a
//! white square with a small grey blob where the cube is.

use super::{Renderer, Target};
use crate::engine::mesh::FullScreenTriangle;
use crate::engine::state::{self, NoDepthTest};
use crate::engine::{check_gl, Gl, Samplers, Sampling, ShaderProgram};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shaders;
use crate::shadows::camera::fitted::corners;
use crate::shadows::{DepthViewKind, ShadowView, Technique};

/// The view's programs (one per kind of texture, compiled on first use) and its triangle.
pub struct DepthView {
    flat: Option<ShaderProgram>,
    cube: Option<ShaderProgram>,
    array: Option<ShaderProgram>,
    full_screen: FullScreenTriangle,
    /// The grey range of the last 2D map drawn.
    last_range: Option<DepthRange>,
}

/// Where a 2D map's greys run: black at `black`, white at `white`, distances along the
/// light's view from the light, between its `near` and `far` planes. They are the nearest
/// and farthest depths of the casters' boxes (each mesh's box turned with its item: exact
/// for the chapters' cubes and planes), so the view shows the depths the map holds; texels
/// no caster reached (the cleared far plane) stay white.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthRange {
    pub near: f32,
    pub far: f32,
    pub black: f32,
    pub white: f32,
}

impl DepthRange {
    /// The casters' span of `view`'s depths, or `None` with no caster in front of the far
    /// plane or a span too thin to stretch.
    pub fn of_casters(scene: &Scene, view: &ShadowView) -> Option<DepthRange> {
        let view64 = view.view64;
        let (mut black, mut white) = (f64::INFINITY, f64::NEG_INFINITY);
        for item in scene.items.iter().filter(|i| i.casts_shadows) {
            let (lo, hi) = scene.meshes.get(item.mesh)?.bounds();
            let to_view = view64 * item.model_matrix64();
            for c in corners(lo.as_dvec3(), hi.as_dvec3()) {
                let depth = -to_view.transform_point3(c).z;
                black = black.min(depth);
                white = white.max(depth);
            }
        }
        let (near, far) = (f64::from(view.near), f64::from(view.far));
        let (black, white) = (black.max(near), white.min(far));
        (white - black > 1e-4 * (far - near)).then_some(DepthRange {
            near: view.near,
            far: view.far,
            black: black as f32,
            white: white as f32,
        })
    }

    /// The range as the shader's fractions of near..far (what an orthographic map stores and
    /// a perspective one is linearised to).
    fn fractions(&self) -> (f32, f32) {
        let span = self.far - self.near;
        (
            (self.black - self.near) / span,
            (self.white - self.near) / span,
        )
    }

    /// The range in words, for the view's caption.
    pub fn words(&self) -> String {
        format!(
            "greys stretched over the casters' depths: black {:.2}, white {:.2} units from \
             the light (its map spans {:.2} to {:.2})",
            self.black, self.white, self.near, self.far
        )
    }
}

impl DepthView {
    pub fn new(gl: &Gl) -> Result<DepthView> {
        Ok(DepthView {
            flat: None,
            cube: None,
            array: None,
            full_screen: FullScreenTriangle::new(gl)?,
            last_range: None,
        })
    }

    /// Draws `technique`'s map over the bound target; `view` is its light camera.
    pub fn draw(
        &mut self,
        gl: &Gl,
        samplers: &mut Samplers,
        technique: &dyn Technique,
        (scene, view): (&Scene, Option<&ShadowView>),
    ) -> Result<()> {
        let kind = technique.depth_view();
        // A cube map and layers keep their own scales (each layer has its own box).
        let flat = matches!(
            kind,
            DepthViewKind::Flat | DepthViewKind::Exponential { .. }
        );
        self.last_range = view
            .filter(|_| flat)
            .and_then(|v| DepthRange::of_casters(scene, v));
        let shown = self.last_range.map_or((0.0, 1.0), |r| r.fractions());
        let (slot, cube, array) = match kind {
            DepthViewKind::Flat | DepthViewKind::Exponential { .. } => {
                (&mut self.flat, false, false)
            }
            DepthViewKind::Cube => (&mut self.cube, true, false),
            DepthViewKind::Array { .. } => (&mut self.array, false, true),
        };
        if slot.is_none() {
            *slot = Some(ShaderProgram::new(
                gl,
                &shaders::depth_view_vert(),
                &shaders::depth_view_frag(),
                &[
                    ("CUBE".into(), u32::from(cube).to_string()),
                    ("ARRAY".into(), u32::from(array).to_string()),
                ],
            )?);
        }
        let Some(p) = slot.as_ref() else {
            return Ok(());
        };
        p.bind();
        p.set_i32("depthMap", 0);
        if let Some(v) = view {
            // A map of linear depth is shown as stored, as an orthographic one.
            let linearize = v.perspective && !v.linear_depth && !cube;
            p.set_i32("linearize", i32::from(linearize));
            p.set_f32("nearPlane", v.near);
            p.set_f32("farPlane", v.far);
        }
        if let DepthViewKind::Array { layers } = kind {
            p.set_i32("layers", layers as i32);
        }
        let (warp, warped) = match kind {
            DepthViewKind::Exponential {
                exponent_bits,
                warped,
            } => (f32::from_bits(exponent_bits), warped),
            DepthViewKind::Flat | DepthViewKind::Cube | DepthViewKind::Array { .. } => (0.0, false),
        };
        p.set_f32("warp", warp);
        p.set_i32("warped", i32::from(warped));
        p.set_f32("shownFrom", shown.0);
        p.set_f32("shownTo", shown.1);
        technique.view_texture().bind(0);
        // A plain sampler: the map may be read in compare mode by the scene pass.
        let _sampler = samplers.get(gl, Sampling::PLAIN)?.bind(0);
        let _no_depth = NoDepthTest::begin(gl);
        self.full_screen.draw();
        p.unbind();
        Ok(())
    }
}

impl Renderer {
    /// The chapters' debug quad: a light's shadow map on the whole target (see
    /// [`DepthView`]).
    pub fn render_depth_view(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let index = self
            .depth_view_light
            .min(self.shadows.len().saturating_sub(1));
        if self.shadows.is_empty() {
            return Err(Error::Invalid(
                "render_depth_view before render_depth_map: there is no shadow map yet".into(),
            ));
        }
        target.bind_and_clear(&self.gl, scene.clear_colour.to_array());
        // A light without a map: the cleared target says so.
        self.draw_depth_view(scene, index)?;
        check_gl(&self.gl, "the depth-map view")
    }

    /// The shadow-map inset: the depth view (LearnOpenGL's debug quad, [`DepthView`]) drawn
    /// into `rect` of `target` over the frame already there, so the map and the shadows it
    /// makes are seen together. Shows the light the depth view is set to
    /// ([`Renderer::set_depth_view_light`]) or, if that one has no map, the first light
    /// with one; with no map at all it draws nothing. Writes colour only; call after
    /// [`Renderer::render`] (it needs this frame's maps).
    pub fn render_depth_inset(
        &mut self,
        scene: &Scene,
        target: Target,
        rect: state::PixelRect,
    ) -> Result<()> {
        self.after_depth_map(scene, "render_depth_inset")?;
        let (width, height) = target.size();
        let inside = rect.width > 0
            && rect.height > 0
            && u64::from(rect.x) + u64::from(rect.width) <= u64::from(width)
            && u64::from(rect.y) + u64::from(rect.height) <= u64::from(height);
        if !inside {
            return Err(Error::Invalid(format!(
                "shadow-map inset {rect:?}: expected a non-empty rectangle inside the \
                 {width}x{height} frame"
            )));
        }
        let has_map = |i: &usize| self.shadows.get(*i).is_some_and(Option::is_some);
        let Some(index) = std::iter::once(self.depth_view_light)
            .chain(0..self.shadows.len())
            .find(has_map)
        else {
            return Ok(());
        };
        target.bind(&self.gl);
        let _overlay = state::OverlayViewport::begin(&self.gl, rect);
        self.draw_depth_view(scene, index)?;
        check_gl(&self.gl, "the shadow-map inset")
    }

    /// Light `index`'s map drawn by the depth view over the bound viewport; nothing for a
    /// light without a map.
    fn draw_depth_view(&mut self, scene: &Scene, index: usize) -> Result<()> {
        let Some(technique) = self.shadows[index].as_deref() else {
            return Ok(());
        };
        let view = self.views[index].as_ref();
        self.depth_view
            .draw(&self.gl, &mut self.samplers, technique, (scene, view))
    }

    /// The grey range of the 2D map the depth view or the inset drew last; `None` after a
    /// cube map, layers, or no map.
    pub fn depth_view_range(&self) -> Option<DepthRange> {
        self.depth_view.last_range
    }
}
