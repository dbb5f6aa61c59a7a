//! Where the main pass draws: the window's framebuffer or an offscreen target.

use crate::engine::{state, Gl, Outputs, RenderTarget};

/// Where the main pass draws: the window's framebuffer (size in physical pixels) or an
/// offscreen [`RenderTarget`].
#[derive(Clone, Copy)]
pub enum Target<'a> {
    Window { width: u32, height: u32 },
    Offscreen(&'a RenderTarget),
}

impl Target<'_> {
    pub fn size(&self) -> (u32, u32) {
        match self {
            Target::Window { width, height } => (*width, *height),
            Target::Offscreen(t) => (t.width(), t.height()),
        }
    }

    /// The outputs besides colour (a window has none).
    pub fn outputs(&self) -> Outputs {
        match self {
            Target::Window { .. } => Outputs::default(),
            Target::Offscreen(t) => t.outputs(),
        }
    }

    /// Binds the target and sets the viewport to its size, keeping what is drawn there (to
    /// draw over a frame).
    pub(super) fn bind(&self, gl: &Gl) {
        match self {
            Target::Offscreen(t) => t.bind(),
            Target::Window { width, height } => state::bind_window(gl, *width, *height),
        }
    }

    /// Binds the target, sets the viewport to its size in pixels (not the window's logical
    /// size) and clears it.
    pub(super) fn bind_and_clear(&self, gl: &Gl, colour: [f32; 4]) {
        match self {
            Target::Offscreen(t) => t.bind_and_clear(colour),
            Target::Window { width, height } => {
                state::bind_window_and_clear(gl, *width, *height, colour)
            }
        }
    }
}
