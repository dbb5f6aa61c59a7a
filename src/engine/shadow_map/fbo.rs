//! The depth-only framebuffer every kind of shadow map draws into.

use glow::HasContext;

use crate::engine::check::check_framebuffer;
use crate::engine::Gl;
use crate::error::{Error, Result};
use crate::settings::MapSize;

/// A framebuffer with only a depth attachment (draw and read buffers NONE), shared by the
/// three kinds of shadow map; deleted on drop.
pub(super) struct DepthFbo {
    gl: Gl,
    fbo: glow::Framebuffer,
}

impl DepthFbo {
    pub(super) fn new(gl: &Gl, what: &str) -> Result<DepthFbo> {
        let fbo = unsafe { gl.create_framebuffer() }
            .map_err(|e| Error::Create(format!("{what}: {e}")))?;
        crate::engine::counters::count(|c| c.framebuffers += 1);
        Ok(DepthFbo {
            gl: gl.clone(),
            fbo,
        })
    }

    pub(super) fn bind(&self) {
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.fbo)) };
    }

    /// Once the depth attachment is bound: no colour buffers, then the completeness check
    /// (an error naming `what`, never a silently black map).
    pub(super) fn finish(&self, what: &str) -> Result<()> {
        self.bind();
        unsafe {
            self.gl.draw_buffer(glow::NONE);
            self.gl.read_buffer(glow::NONE);
        }
        let status = check_framebuffer(&self.gl, what);
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
        status
    }

    /// Clears one texel's depth under a scissor. Mesa clears part of a buffer by drawing a
    /// quad with shaders of its own, compiled at their first use for the buffer's format:
    /// here, when the first map of a format is made, rather than in the first frame that
    /// patches a map (a scissored clear).
    pub(super) fn warm_scissored_clear(&self) {
        self.bind();
        self.gl.set_capability(glow::SCISSOR_TEST, true);
        unsafe {
            self.gl.scissor(0, 0, 1, 1);
            self.gl.clear(glow::DEPTH_BUFFER_BIT);
        }
        self.gl.set_capability(glow::SCISSOR_TEST, false);
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
    }

    /// Reads the attached depth of `size` back (row 0 at the bottom, as GL stores them).
    pub(super) fn read_depth(&self, size: MapSize) -> Vec<f32> {
        let n = size.texels() as usize;
        let mut bytes = vec![0u8; n * 4];
        self.bind();
        unsafe {
            self.gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
            self.gl.read_pixels(
                0,
                0,
                size.width as i32,
                size.height as i32,
                glow::DEPTH_COMPONENT,
                glow::FLOAT,
                glow::PixelPackData::Slice(Some(&mut bytes)),
            );
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
        bytes
            .chunks_exact(4)
            .map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
            .collect()
    }
}

impl Drop for DepthFbo {
    fn drop(&mut self) {
        unsafe { self.gl.delete_framebuffer(self.fbo) };
    }
}
