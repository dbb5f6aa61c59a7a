//! The chapters' debug quad: a light's shadow map on the whole target (LearnOpenGL's
//! debug quad, the book's "depth map" picture). Linearised for a perspective light
//! (LearnOpenGL's `LinearizeDepth`), raw for an orthographic one; a cube map as a panorama,
//! cascades side by side.

use super::{Renderer, Target};
use crate::engine::mesh::FullScreenTriangle;
use crate::engine::state::{self, NoDepthTest};
use crate::engine::{check_gl, Gl, Samplers, Sampling, ShaderProgram};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shaders;
use crate::shadows::{DepthViewKind, ShadowView, Technique};

/// The view's programs (one per kind of texture, compiled on first use) and its triangle.
pub struct DepthView {
    flat: Option<ShaderProgram>,
    cube: Option<ShaderProgram>,
    array: Option<ShaderProgram>,
    full_screen: FullScreenTriangle,
}

impl DepthView {
    pub fn new(gl: &Gl) -> Result<DepthView> {
        Ok(DepthView {
            flat: None,
            cube: None,
            array: None,
            full_screen: FullScreenTriangle::new(gl)?,
        })
    }

    /// Draws `technique`'s map over the bound target; `view` is its light camera.
    pub fn draw(
        &mut self,
        gl: &Gl,
        samplers: &mut Samplers,
        technique: &dyn Technique,
        view: Option<&ShadowView>,
    ) -> Result<()> {
        let kind = technique.depth_view();
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
        let warp = match kind {
            DepthViewKind::Exponential { exponent_bits } => f32::from_bits(exponent_bits),
            _ => 0.0,
        };
        p.set_f32("warp", warp);
        technique.texture().bind(0);
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
        self.draw_depth_view(index)?;
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
        self.draw_depth_view(index)?;
        check_gl(&self.gl, "the shadow-map inset")
    }

    /// Light `index`'s map drawn by the depth view over the bound viewport; nothing for a
    /// light without a map.
    fn draw_depth_view(&mut self, index: usize) -> Result<()> {
        let Some(technique) = self.shadows[index].as_deref() else {
            return Ok(());
        };
        let view = self.views[index].as_ref();
        self.depth_view
            .draw(&self.gl, &mut self.samplers, technique, view)
    }
}
