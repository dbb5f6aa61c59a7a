//! Fixed-function state as values: a pass says what it needs, a guard applies it and puts
//! the renderer's resting state back when it drops, on an error's early return too. The
//! resting state between passes: depth test on, no culling, no polygon offset, no scissor
//! test, the default framebuffer and no program bound.

use glow::HasContext;

use super::{Gl, ShaderProgram};
use crate::settings::Cull;

/// What a depth pass changes ("Shadows": the depth pass; LearnOpenGL's front-face culling
/// against peter panning; glPolygonOffset as the slides' alternative to a bias).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DepthState {
    pub cull: Cull,
    /// `glPolygonOffset(factor, units)`; [0, 0] leaves it off.
    pub polygon_offset: [f32; 2],
    /// The only texels the pass may clear and draw (a patched map); `None`: all of them.
    pub scissor: Option<PixelRect>,
}

/// A depth pass in progress: culling, polygon offset, scissor and its program applied;
/// dropping it restores the resting state (and unbinds the shadow map's framebuffer).
pub struct DepthPassGuard {
    gl: Gl,
}

impl DepthPassGuard {
    pub fn begin(gl: &Gl, state: DepthState, program: &ShaderProgram) -> DepthPassGuard {
        let [factor, units] = state.polygon_offset;
        unsafe {
            gl.depth_mask(true);
            if factor != 0.0 || units != 0.0 {
                gl.set_capability(glow::POLYGON_OFFSET_FILL, true);
                gl.polygon_offset(factor, units);
            }
            match state.cull {
                Cull::None => gl.set_capability(glow::CULL_FACE, false),
                Cull::Back => {
                    gl.set_capability(glow::CULL_FACE, true);
                    gl.cull_face(glow::BACK);
                }
                Cull::Front => {
                    gl.set_capability(glow::CULL_FACE, true);
                    gl.cull_face(glow::FRONT);
                }
            }
            if let Some(r) = state.scissor {
                gl.set_capability(glow::SCISSOR_TEST, true);
                gl.scissor(r.x as i32, r.y as i32, r.width as i32, r.height as i32);
            }
        }
        program.bind();
        DepthPassGuard { gl: gl.clone() }
    }
}

impl Drop for DepthPassGuard {
    fn drop(&mut self) {
        unsafe {
            self.gl.use_program_once(None);
            self.gl.set_capability(glow::CULL_FACE, false);
            self.gl.set_capability(glow::POLYGON_OFFSET_FILL, false);
            self.gl.set_capability(glow::SCISSOR_TEST, false);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }
}

/// Clears the bound framebuffer's depth (a shadow map, before its casters are drawn); only
/// the scissor's texels while a [`DepthPassGuard`] with one lives.
pub fn clear_depth(gl: &Gl) {
    unsafe { gl.clear(glow::DEPTH_BUFFER_BIT) };
}

/// The resting state's depth test, set once when a renderer is made.
pub fn enable_depth_test(gl: &Gl) {
    gl.set_capability(glow::DEPTH_TEST, true);
}

/// Binds the window's framebuffer, sets the viewport to its size in pixels and clears it.
pub fn bind_window_and_clear(gl: &Gl, width: u32, height: u32, colour: [f32; 4]) {
    unsafe {
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        gl.viewport(0, 0, width as i32, height as i32);
        gl.clear_color(colour[0], colour[1], colour[2], colour[3]);
        gl.stencil_mask(0xff);
        gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT | glow::STENCIL_BUFFER_BIT);
    }
}

/// Depth testing off while it lives (a full-screen quad), back on when it drops.
pub struct NoDepthTest {
    gl: Gl,
}

impl NoDepthTest {
    pub fn begin(gl: &Gl) -> NoDepthTest {
        gl.set_capability(glow::DEPTH_TEST, false);
        NoDepthTest { gl: gl.clone() }
    }
}

impl Drop for NoDepthTest {
    fn drop(&mut self) {
        self.gl.set_capability(glow::DEPTH_TEST, true);
    }
}

/// A rectangle of the bound framebuffer in pixels, GL's way: `x`, `y` from the bottom-left
/// corner.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PixelRect {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
}

/// Drawing into part of the bound framebuffer (the shadow-map inset): while it lives the
/// viewport is `rect` and only the first colour output is written, so a headless target's
/// extra outputs (visibility, positions) keep the scene's values under the picture. Dropping
/// it puts back the viewport and draw buffers it found.
pub struct OverlayViewport {
    gl: Gl,
    viewport: [i32; 4],
    /// The draw buffers it found, trailing NONEs left out; restored only if it cut them.
    draw_buffers: Vec<u32>,
}

impl OverlayViewport {
    pub fn begin(gl: &Gl, rect: PixelRect) -> OverlayViewport {
        let mut viewport = [0i32; 4];
        let mut draw_buffers = Vec::new();
        unsafe {
            gl.get_parameter_i32_slice(glow::VIEWPORT, &mut viewport);
            let max = gl.get_parameter_i32(glow::MAX_DRAW_BUFFERS).clamp(1, 16) as u32;
            draw_buffers
                .extend((0..max).map(|i| gl.get_parameter_i32(glow::DRAW_BUFFER0 + i) as u32));
            while draw_buffers.last() == Some(&glow::NONE) {
                draw_buffers.pop();
            }
            if draw_buffers.len() > 1 {
                gl.draw_buffers(&draw_buffers[..1]);
            }
            gl.viewport(
                rect.x as i32,
                rect.y as i32,
                rect.width as i32,
                rect.height as i32,
            );
        }
        OverlayViewport {
            gl: gl.clone(),
            viewport,
            draw_buffers,
        }
    }
}

impl Drop for OverlayViewport {
    fn drop(&mut self) {
        let [x, y, w, h] = self.viewport;
        unsafe {
            self.gl.viewport(x, y, w, h);
            if self.draw_buffers.len() > 1 {
                self.gl.draw_buffers(&self.draw_buffers);
            }
        }
    }
}

/// Binds the window's framebuffer and sets the viewport to its size, without clearing (to
/// draw over a frame already there).
pub fn bind_window(gl: &Gl, width: u32, height: u32) {
    unsafe {
        gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        gl.viewport(0, 0, width as i32, height as i32);
    }
}

/// Blocks until the GPU has finished (wall-time measurements).
pub fn finish(gl: &Gl) {
    unsafe { gl.finish() };
}
