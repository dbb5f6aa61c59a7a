//! Blending translucent items over the frame (`renderer::translucent_pass`): each item's
//! colour weighs its opacity, through GL's constant blend colour, so the scene shader is the
//! opaque items' own, unchanged.

use glow::HasContext;

use super::Gl;

/// The colour outputs a scene target can have besides colour (visibility, positions,
/// normals): the blend leaves them as the opaque surfaces wrote them, so measurements see
/// the receivers under the translucent items.
const OUTPUTS_KEPT: u32 = 3;

/// Translucent drawing in progress: depth tested but not written, colour output 0 blended
/// as `opacity * fragment + (1 - opacity) * frame` (its alpha kept), the other outputs
/// masked. Dropping it restores the resting state (depth writes, no blending, every output
/// written).
pub struct TranslucentBlend {
    gl: Gl,
}

impl TranslucentBlend {
    pub fn begin(gl: &Gl) -> TranslucentBlend {
        unsafe {
            gl.depth_mask(false);
            gl.enable_draw_buffer(glow::BLEND, 0);
            gl.blend_equation(glow::FUNC_ADD);
            gl.blend_func_separate(
                glow::CONSTANT_ALPHA,
                glow::ONE_MINUS_CONSTANT_ALPHA,
                glow::ZERO,
                glow::ONE,
            );
            for i in 1..=OUTPUTS_KEPT {
                gl.color_mask_draw_buffer(i, false, false, false, false);
            }
        }
        TranslucentBlend { gl: gl.clone() }
    }

    /// The next item's opacity: the weight of its colour.
    pub fn set_opacity(&self, opacity: f32) {
        unsafe { self.gl.blend_color(0.0, 0.0, 0.0, opacity) };
    }
}

impl Drop for TranslucentBlend {
    fn drop(&mut self) {
        unsafe {
            for i in 1..=OUTPUTS_KEPT {
                self.gl.color_mask_draw_buffer(i, true, true, true, true);
            }
            self.gl.blend_func(glow::ONE, glow::ZERO);
            self.gl.blend_color(0.0, 0.0, 0.0, 0.0);
            self.gl.disable_draw_buffer(glow::BLEND, 0);
            self.gl.depth_mask(true);
        }
    }
}
