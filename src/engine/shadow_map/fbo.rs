//! What every kind of shadow map does with its depth-only framebuffer besides drawing.

use glow::HasContext;

use crate::engine::framebuffer::{Attachment, Framebuffer, Part};
use crate::engine::texture::Texture;
use crate::engine::Gl;
use crate::error::Result;
use crate::settings::MapSize;

/// A framebuffer with `part` of `depth` as its only attachment (draw and read buffers
/// NONE), checked complete under the name `what`.
pub(super) fn depth_only(gl: &Gl, depth: &Texture, part: Part, what: &str) -> Result<Framebuffer> {
    Framebuffer::build(gl, what)?
        .texture(Attachment::Depth, depth, part)
        .finish(what)
}

/// Clears one texel's depth under a scissor. Mesa clears part of a buffer by drawing a
/// quad with shaders of its own, compiled at their first use for the buffer's format:
/// here, when the first map of a format is made, rather than in the first frame that
/// patches a map (a scissored clear).
pub(super) fn warm_scissored_clear(gl: &Gl, fbo: &Framebuffer) {
    fbo.bind();
    gl.set_capability(glow::SCISSOR_TEST, true);
    unsafe {
        gl.scissor(0, 0, 1, 1);
        gl.clear(glow::DEPTH_BUFFER_BIT);
    }
    gl.set_capability(glow::SCISSOR_TEST, false);
    unsafe { gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
}

/// Reads the attached depth of `size` back (row 0 at the bottom, as GL stores them).
pub(super) fn read_depth(gl: &Gl, fbo: &Framebuffer, size: MapSize) -> Vec<f32> {
    let n = size.texels() as usize;
    let mut bytes = vec![0u8; n * 4];
    fbo.bind();
    unsafe {
        gl.pixel_store_i32(glow::PACK_ALIGNMENT, 4);
        gl.read_pixels(
            0,
            0,
            size.width as i32,
            size.height as i32,
            glow::DEPTH_COMPONENT,
            glow::FLOAT,
            glow::PixelPackData::Slice(Some(&mut bytes)),
        );
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
    }
    bytes
        .chunks_exact(4)
        .map(|c| f32::from_ne_bytes([c[0], c[1], c[2], c[3]]))
        .collect()
}
