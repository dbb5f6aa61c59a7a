//! One vec4 a vertex, computed by a pass of its own and kept in a buffer for later draws
//! (the translucent items' per-vertex light, `shadows::volumetric::vertex_light`). The
//! pass is transform feedback: a vertex-only program draws each mesh's vertices as points
//! under `GL_RASTERIZER_DISCARD`, one after the other into the buffer; a draw reads them
//! back as a vertex attribute at the mesh's first vertex there. (glow has no `glTexBuffer`
//! for a buffer texture; an attribute needs no copy and no texture unit.) A draw needs a
//! complete framebuffer even when nothing is rasterised, and a surfaceless context's
//! default one is not: the pass binds a 1 x 1 one of its own.

use glow::HasContext;

use super::{Gl, Mesh, ShaderProgram};
use crate::error::{Error, Result};

/// Bytes a vertex: one vec4.
const STRIDE: usize = 16;

/// The buffer the values are captured into; deleted on drop.
pub struct VertexCapture {
    gl: Gl,
    buffer: glow::Buffer,
    /// The 1 x 1 framebuffer bound while capturing, and its colour renderbuffer.
    target: (glow::Framebuffer, glow::Renderbuffer),
    /// Vertices it has room for.
    capacity: usize,
}

impl VertexCapture {
    pub fn new(gl: &Gl) -> Result<VertexCapture> {
        let create = |what: &str, e: String| Error::Create(format!("vertex capture {what}: {e}"));
        unsafe {
            let buffer = gl.create_buffer().map_err(|e| create("buffer", e))?;
            super::counters::count(|c| c.buffers += 1);
            let capture = |target| VertexCapture {
                gl: gl.clone(),
                buffer,
                target,
                capacity: 0,
            };
            let fbo = match gl.create_framebuffer() {
                Ok(f) => f,
                Err(e) => {
                    gl.delete_buffer(buffer);
                    return Err(create("framebuffer", e));
                }
            };
            let colour = match gl.create_renderbuffer() {
                Ok(r) => r,
                Err(e) => {
                    gl.delete_buffer(buffer);
                    gl.delete_framebuffer(fbo);
                    return Err(create("renderbuffer", e));
                }
            };
            let this = capture((fbo, colour));
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(colour));
            gl.renderbuffer_storage(glow::RENDERBUFFER, glow::RGBA8, 1, 1);
            gl.bind_renderbuffer(glow::RENDERBUFFER, None);
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
            let at = glow::COLOR_ATTACHMENT0;
            gl.framebuffer_renderbuffer(glow::FRAMEBUFFER, at, glow::RENDERBUFFER, Some(colour));
            let status = gl.check_framebuffer_status(glow::FRAMEBUFFER);
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
            if status != glow::FRAMEBUFFER_COMPLETE {
                return Err(create("framebuffer", format!("incomplete ({status:#x})")));
            }
            Ok(this)
        }
    }

    /// Starts capturing `vertices` values with `program` (its varyings recorded,
    /// [`ShaderProgram::capturing`]), which it binds: the buffer grown to fit, bound for
    /// transform feedback, rasterising off. Draw the meshes in order with
    /// [`CapturePass::draw`]; dropping the pass ends it and restores the state.
    pub fn begin<'a>(&'a mut self, program: &ShaderProgram, vertices: usize) -> CapturePass<'a> {
        let gl = &self.gl;
        unsafe {
            if vertices > self.capacity {
                gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, Some(self.buffer));
                let bytes = (vertices * STRIDE) as i32;
                gl.buffer_data_size(glow::TRANSFORM_FEEDBACK_BUFFER, bytes, glow::STATIC_COPY);
                gl.bind_buffer(glow::TRANSFORM_FEEDBACK_BUFFER, None);
                self.capacity = vertices;
            }
            program.bind();
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.target.0));
            gl.set_capability(glow::RASTERIZER_DISCARD, true);
            gl.bind_buffer_base(glow::TRANSFORM_FEEDBACK_BUFFER, 0, Some(self.buffer));
            gl.begin_transform_feedback(glow::POINTS);
        }
        CapturePass { capture: self }
    }

    /// Draws `mesh` reading its vertices' values from vertex `first` of the buffer on
    /// location 3 (scene.vert's `capturedLit`).
    pub fn draw(&self, mesh: &Mesh, first: usize) {
        mesh.render_with_vertex_values(self.buffer, first * STRIDE);
    }
}

impl Drop for VertexCapture {
    fn drop(&mut self) {
        unsafe {
            self.gl.delete_buffer(self.buffer);
            self.gl.delete_framebuffer(self.target.0);
            self.gl.delete_renderbuffer(self.target.1);
        }
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
