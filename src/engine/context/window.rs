//! A window with a GL 3.3 core context, through winit 0.30 and glutin-winit's display
//! builder, which picks the platform's API: WGL on Windows, CGL on macOS, EGL on Wayland,
//! GLX (then EGL) on X11. The demo drives it; the renderer only sees the shared [`Gl`].

use std::num::NonZeroU32;
use std::rc::Rc;

use glutin::config::{Config, ConfigTemplateBuilder, GlConfig};
use glutin::context::{
    ContextApi, ContextAttributesBuilder, GlProfile, NotCurrentGlContext, PossiblyCurrentContext,
    Version,
};
use glutin::display::{GetGlDisplay, GlDisplay};
use glutin::surface::{GlSurface, Surface, SwapInterval, WindowSurface};
use glutin_winit::{ApiPreference, DisplayBuilder, GlWindow};
use raw_window_handle::{HasDisplayHandle, HasWindowHandle};
use winit::event_loop::ActiveEventLoop;
use winit::window::{Window, WindowAttributes};

use super::super::render_target::read_rgba8;
use super::super::Gl;
use super::platform::{Platform, WindowApi};
use crate::error::{Error, Result};

/// The API a glutin display is, from its version string ("GLX 1.4", "EGL 1.5", "WGL",
/// "Apple CGL"): the one thing every backend's display says of itself.
fn api_of(display: &glutin::display::Display) -> WindowApi {
    let version = display.version_string();
    [WindowApi::Glx, WindowApi::Wgl, WindowApi::Cgl]
        .into_iter()
        .find(|api| version.contains(&api.flag().to_uppercase()))
        .unwrap_or(WindowApi::Egl)
}

/// glutin-winit's preference for a choice on `platform`, or the refusal that lists what the
/// platform has.
fn preference(api: WindowApi, platform: Platform) -> Result<ApiPreference> {
    api.check(platform)?;
    Ok(match api {
        WindowApi::Egl => ApiPreference::PreferEgl,
        WindowApi::Auto | WindowApi::Glx | WindowApi::Wgl | WindowApi::Cgl => {
            ApiPreference::FallbackEgl
        }
    })
}

/// A window, its GL surface and its current context.
pub struct WindowContext {
    gl: Gl,
    api: WindowApi,
    platform: Platform,
    // Field order is drop order: surface and context go before the window they draw into.
    surface: Surface<WindowSurface>,
    context: PossiblyCurrentContext,
    window: Window,
}

/// The config the window draws with: single-sampled, a stencil, the deepest depth buffer.
fn pick_config(configs: Box<dyn Iterator<Item = Config> + '_>) -> Config {
    configs
        .max_by_key(|c| {
            (
                c.num_samples() == 0,
                c.stencil_size() >= 8,
                c.depth_size(),
                c.alpha_size(),
            )
        })
        // glutin's find_configs answers an error, never an empty list.
        .expect("glutin returns at least one config or an error")
}

impl WindowContext {
    /// Opens a window and makes a GL 3.3 core context current on it, a debug context where
    /// [`debug_wanted`](super::super::check::debug_wanted).
    pub fn new(
        event_loop: &ActiveEventLoop,
        attributes: WindowAttributes,
        api: WindowApi,
    ) -> Result<WindowContext> {
        Self::with_debug(
            event_loop,
            attributes,
            api,
            super::super::check::debug_wanted(),
        )
    }

    /// [`new`](Self::new) with the driver's debug messages on or off whatever the build.
    pub fn with_debug(
        event_loop: &ActiveEventLoop,
        attributes: WindowAttributes,
        api: WindowApi,
        debug: bool,
    ) -> Result<WindowContext> {
        let no_gl = |e: &dyn std::fmt::Display| {
            Error::Context(format!("could not open a window with OpenGL: {e}"))
        };
        let platform = Platform::of(event_loop.display_handle().map_err(|e| no_gl(&e))?.as_raw());
        let template = ConfigTemplateBuilder::new()
            .with_depth_size(24)
            .with_stencil_size(8);
        let (window, config) = DisplayBuilder::new()
            .with_preference(preference(api, platform)?)
            .with_window_attributes(Some(attributes))
            .build(event_loop, template, pick_config)
            .map_err(|e| no_gl(&e))?;
        let window = window.ok_or_else(|| no_gl(&"the display builder made no window"))?;
        let display = config.display();
        let got = api_of(&display);
        if api != WindowApi::Auto && got != api {
            return Err(Error::Context(format!(
                "--gl-api {}: the {} display could not give one; it gave {} (try --gl-api auto)",
                api.flag(),
                platform.name(),
                got.flag().to_uppercase()
            )));
        }
        let (surface, context) = Self::make_current(&display, &config, &window, debug)?;
        // Measure frames, not the monitor: do not wait for vertical sync.
        let _ = surface.set_swap_interval(&context, SwapInterval::DontWait);
        // SAFETY: the context is current on this thread.
        let mut gl =
            unsafe { glow::Context::from_loader_function_cstr(|s| display.get_proc_address(s)) };
        super::super::check::install_debug_output(&mut gl, debug);
        Ok(WindowContext {
            gl: Rc::new(super::super::bindings::GlContext::new(gl)),
            api: got,
            platform,
            surface,
            context,
            window,
        })
    }

    /// A 3.3 core context on the window's surface, made current.
    fn make_current(
        display: &glutin::display::Display,
        config: &Config,
        window: &Window,
        debug: bool,
    ) -> Result<(Surface<WindowSurface>, PossiblyCurrentContext)> {
        let raw = window
            .window_handle()
            .map_err(|e| Error::Context(format!("window handle: {e}")))?
            .as_raw();
        let attributes = ContextAttributesBuilder::new()
            .with_context_api(ContextApi::OpenGl(Some(Version::new(3, 3))))
            .with_profile(GlProfile::Core)
            .with_debug(debug)
            .build(Some(raw));
        // SAFETY: the config and the window handle come from the same display and live on.
        let not_current = unsafe { display.create_context(config, &attributes) }.map_err(|e| {
            Error::Context(format!("could not create an OpenGL 3.3 core context: {e}"))
        })?;
        let surface_attributes = window
            .build_surface_attributes(Default::default())
            .map_err(|e| Error::Context(format!("window surface: {e}")))?;
        // SAFETY: the window outlives the surface (field order of WindowContext).
        let surface = unsafe { display.create_window_surface(config, &surface_attributes) }
            .map_err(|e| Error::Context(format!("window surface: {e}")))?;
        let context = not_current
            .make_current(&surface)
            .map_err(|e| Error::Context(format!("make context current: {e}")))?;
        Ok((surface, context))
    }

    pub fn gl(&self) -> &Gl {
        &self.gl
    }

    /// The platform API the context came from and the window system, for reports:
    /// "GLX on X11", "EGL on Wayland", "WGL on Windows", "CGL on macOS".
    pub fn api(&self) -> String {
        format!(
            "{} on {}",
            self.api.flag().to_uppercase(),
            self.platform.name()
        )
    }

    /// Releases the context from this thread (an invisible window used headless hands the
    /// thread over to the next context this way).
    #[cfg_attr(
        all(unix, not(target_vendor = "apple"), not(target_os = "android")),
        allow(dead_code)
    )]
    pub(super) fn release(&self) {
        use glutin::context::PossiblyCurrentGlContext;
        if self.context.is_current() {
            let _ = self.context.make_not_current_in_place();
        }
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
