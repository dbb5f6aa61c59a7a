//! The chapters' debug quad: a light's shadow map on the whole target (LearnOpenGL's
//! debug quad, the book's "depth map" picture). Linearised for a perspective light
//! (LearnOpenGL's `LinearizeDepth`), raw for an orthographic one; a cube map as a panorama,
//! cascades side by side.

use crate::engine::mesh::FullScreenTriangle;
use crate::engine::state::NoDepthTest;
use crate::engine::{Gl, Samplers, Sampling, ShaderProgram};
use crate::error::Result;
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
            p.set_i32("linearize", i32::from(v.perspective && !cube));
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
