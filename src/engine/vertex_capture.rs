//! One vec4 a vertex, computed by a pass of its own and kept in a buffer for later draws
//! (the translucent items' per-vertex light, `renderer::vertex_light`). The
//! pass is transform feedback: a vertex-only program draws each mesh's vertices as points
//! under `GL_RASTERIZER_DISCARD`, one after the other into the buffer; a draw reads them
//! back as a vertex attribute at the mesh's first vertex there. (glow has no `glTexBuffer`
//! for a buffer texture; an attribute needs no copy and no texture unit.) A draw needs a
//! complete framebuffer even when nothing is rasterised, and a surfaceless context's
//! default one is not: the pass binds a 1 x 1 one of its own.

use glow::HasContext;

use super::framebuffer::{Attachment, Framebuffer};
use super::owned::OwnedBuffer;
use super::{Gl, Mesh, ShaderProgram};
use crate::error::Result;

/// Bytes a vertex: one vec4.
const STRIDE: usize = 16;

/// The buffer the values are captured into, and the framebuffer bound meanwhile; both
/// deleted on drop.
pub struct VertexCapture {
    gl: Gl,
    buffer: OwnedBuffer,
    /// The 1 x 1 framebuffer (a colour renderbuffer) bound while capturing.
    target: Framebuffer,
    /// Vertices it has room for.
    capacity: usize,
}

impl VertexCapture {
    pub fn new(gl: &Gl) -> Result<VertexCapture> {
        let buffer = OwnedBuffer::new(gl, "vertex capture buffer")?;
        let target = Framebuffer::build(gl, "vertex capture")?
            .renderbuffer(
                Attachment::Colour(0),
                glow::RGBA8,
                (1, 1),
                "vertex capture renderbuffer",
            )?
            .finish("vertex capture 1x1")?;
        Ok(VertexCapture {
            gl: gl.clone(),
            buffer,
            target,
            capacity: 0,
        })
    }

    /// Starts capturing `vertices` values with `program` (its varyings recorded,
    /// [`ShaderProgram::capturing`]), which it binds: the buffer grown to fit, bound for
    /// transform feedback, rasterising off. Draw the meshes in order with
    /// [`CapturePass::draw`]; dropping the pass ends it and restores the state.
    pub fn begin<'a>(&'a mut self, program: &ShaderProgram, vertices: usize) -> CapturePass<'a> {
        let gl = &self.gl;
        unsafe {
            if vertices > self.capacity {
                gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, Some(self.buffer.raw()));
                let bytes = (vertices * STRIDE) as i32;
                gl.buffer_data_size(glow::TRANSFORM_FEEDBACK_BUFFER, bytes, glow::STATIC_COPY);
                gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, None);
                self.capacity = vertices;
            }
            program.bind();
            self.target.bind();
            gl.set_capability(glow::RASTERIZER_DISCARD, true);
            gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, Some(self.buffer.raw()));
            gl.begin_transform_feedback(glow::POINTS);
        }
        CapturePass { capture: self }
    }

    /// Draws `mesh` reading its vertices' values from vertex `first` of the buffer on
    /// location 3 (scene.vert's `capturedLit`).
    pub fn draw(&self, mesh: &Mesh, first: usize) {
        mesh.render_with_vertex_values(self.buffer.raw(), first * STRIDE);
    }
}

/// A capture in progress ([`VertexCapture::begin`]).
pub struct CapturePass<'a> {
    capture: &'a VertexCapture,
}

impl CapturePass<'_> {
    /// Captures `mesh`'s vertices after those drawn before, with the uniforms set now.
    pub fn draw(&self, mesh: &Mesh) {
        mesh.render_points();
    }
}

impl Drop for CapturePass<'_> {
    fn drop(&mut self) {
        let gl = &self.capture.gl;
        unsafe {
            gl.end_transform_feedback();
            gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, None);
            gl.set_capability(glow::RASTERIZER_DISCARD, false);
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }
}
