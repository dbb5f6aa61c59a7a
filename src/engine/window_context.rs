//! A window with a GL 3.3 core context, through winit 0.30 and glutin's EGL platform
//! (the same Mesa EGL as the headless path). The demo drives it; the renderer only sees the shared [`Gl`].

use std::num::NonZeroU32;
use std::rc::Rc;

use glutin::config::{ConfigTemplateBuilder, GlConfig};
use glutin::context::{
    ContextApi, ContextAttributesBuilder, GlProfile, NotCurrentGlContext, PossiblyCurrentContext,
    Version,
};
use glutin::display::{Display, DisplayApiPreference, GlDisplay};
use glutin::surface::{GlSurface, Surface, SwapInterval, WindowSurface};
use glutin_winit::{finalize_window, GlWindow};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use winit::event_loop::ActiveEventLoop;
use winit::window::{Window, WindowAttributes};

use super::render_target::read_rgba8;
use super::Gl;
use crate::error::{Error, Result};

/// Which platform API the window's context comes from. On X11 with a software driver the
/// two swap differently: GLX hands the frame to the X server through shared memory
/// (MIT-SHM), while Mesa's EGL (22.x) sends it down the socket, which made the window 1.2 to
/// 1.35 times slower than headless. Headless rendering always uses EGL.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum WindowApi {
    /// GLX where the X server has it, else EGL.
    #[default]
    Auto,
    Glx,
    Egl,
}

/// A window, its GL surface and its current context.
pub struct WindowContext {
    gl: Gl,
    api: &'static str,
    // Field order is drop order: surface and context go before the window they draw into.
    surface: Surface<WindowSurface>,
    context: PossiblyCurrentContext,
    window: Window,
}

impl WindowContext {
    /// Opens a window and makes a GL 3.3 core context current on it.
    pub fn new(
        event_loop: &ActiveEventLoop,
        attributes: WindowAttributes,
        api: WindowApi,
    ) -> Result<WindowContext> {
        let no_gl = |e: &dyn std::fmt::Display| {
            Error::Context(format!("could not open a window with OpenGL: {e}"))
        };
        let display_handle = event_loop.display_handle().map_err(|e| no_gl(&e))?.as_raw();
        // SAFETY: the event loop (and so its display connection) outlives the window.
        let hook = || Box::new(winit::platform::x11::register_xlib_error_hook);
        let preference = match api {
            WindowApi::Auto => DisplayApiPreference::GlxThenEgl(hook()),
            WindowApi::Glx => DisplayApiPreference::Glx(hook()),
            WindowApi::Egl => DisplayApiPreference::Egl,
        };
        let display = unsafe { Display::new(display_handle, preference) }.map_err(|e| no_gl(&e))?;
        let template = ConfigTemplateBuilder::new()
            .with_depth_size(24)
            .with_stencil_size(8)
            .build();
        // SAFETY: the template holds no native window.
        let config = unsafe { display.find_configs(template) }
            .map_err(|e| no_gl(&e))?
            .max_by_key(|c| {
                (
                    c.num_samples() == 0,
                    c.stencil_size() >= 8,
                    c.depth_size(),
                    c.alpha_size(),
                )
            })
            .ok_or_else(|| no_gl(&"the display offers no OpenGL config with a depth buffer"))?;
        let window = finalize_window(event_loop, attributes, &config).map_err(|e| no_gl(&e))?;
        let raw = window
            .window_handle()
            .map_err(|e| Error::Context(format!("window handle: {e}")))?
            .as_raw();
        let attributes = ContextAttributesBuilder::new()
            .with_context_api(ContextApi::OpenGl(Some(Version::new(3, 3))))
            .with_profile(GlProfile::Core)
            .with_debug(super::check::debug_wanted())
            .build(Some(raw));
        // SAFETY: the config and the window handle come from the same display and live on.
        let not_current = unsafe { display.create_context(&config, &attributes) }.map_err(|e| {
            Error::Context(format!("could not create an OpenGL 3.3 core context: {e}"))
        })?;
        let surface_attributes = window
            .build_surface_attributes(Default::default())
            .map_err(|e| Error::Context(format!("window surface: {e}")))?;
        // SAFETY: the window outlives the surface (field order above).
        let surface = unsafe { display.create_window_surface(&config, &surface_attributes) }
            .map_err(|e| Error::Context(format!("window surface: {e}")))?;
        let context = not_current
            .make_current(&surface)
            .map_err(|e| Error::Context(format!("make context current: {e}")))?;
        // Measure frames, not the monitor: do not wait for vertical sync.
        let _ = surface.set_swap_interval(&context, SwapInterval::DontWait);
        // SAFETY: the context is current on this thread.
        let mut gl =
            unsafe { glow::Context::from_loader_function_cstr(|s| display.get_proc_address(s)) };
        super::check::install_debug_output(&mut gl, super::check::debug_wanted());
        let api = match display {
            Display::Glx(_) => "GLX",
            _ => "EGL",
        };
        Ok(WindowContext {
            gl: Rc::new(super::bindings::GlContext::new(gl)),
            api,
            surface,
            context,
            window,
        })
    }

    pub fn gl(&self) -> &Gl {
        &self.gl
    }

    /// The platform API the context came from ("GLX" or "EGL").
    pub fn api(&self) -> &'static str {
        self.api
    }

    pub fn window(&self) -> &Window {
        &self.window
    }

    /// The framebuffer size in physical pixels (what glViewport needs, not the logical size).
    pub fn framebuffer_size(&self) -> (u32, u32) {
        let s = self.window.inner_size();
        (s.width, s.height)
    }

    /// Resizes the GL surface; ignored for a 0 x 0 (minimised) window.
    pub fn resize(&self, width: u32, height: u32) {
        if let (Some(w), Some(h)) = (NonZeroU32::new(width), NonZeroU32::new(height)) {
            self.surface.resize(&self.context, w, h);
        }
    }

    /// Reads the back buffer (call before `swap_buffers`), rows top to bottom.
    pub fn read_back_buffer(&self) -> Vec<u8> {
        let (w, h) = self.framebuffer_size();
        read_rgba8(&self.gl, None, 0, w, h)
    }

    pub fn swap_buffers(&self) -> Result<()> {
        self.surface
            .swap_buffers(&self.context)
            .map_err(|e| Error::Context(format!("swap buffers: {e}")))
    }

    /// Binds the window's framebuffer for the main pass.
    pub fn bind_default_framebuffer(&self) {
        use glow::HasContext;
        unsafe { self.gl.bind_framebuffer(glow::FRAMEBUFFER, None) };
    }
}
