//! A GL 3.3 core context with no window and no display, through EGL's device platform
//! (Mesa llvmpipe on a machine without a GPU): query the EGL devices, open a display on one,
//! pick a config with no surface type and make the context current without a surface.
//! Everything is then drawn into a [`RenderTarget`](super::RenderTarget).

use std::rc::Rc;

use glutin::api::egl::context::PossiblyCurrentContext;
use glutin::api::egl::device::Device;
use glutin::api::egl::display::Display;
use glutin::config::{Api, ConfigSurfaceTypes, ConfigTemplateBuilder};
use glutin::context::{ContextApi, ContextAttributesBuilder, GlProfile, Version};
use glutin::display::GlDisplay;

use super::Gl;
use crate::error::{Error, Result};

/// The packages that provide EGL and a software GL driver on Debian and Ubuntu.
pub const DEBIAN_PACKAGES: &str = "libegl1 libegl-mesa0 libgl1-mesa-dri";

/// A current, surfaceless GL context. Keep it alive as long as any GL object made with it.
pub struct HeadlessContext {
    gl: Gl,
    // Dropped after `gl`'s users (fields drop in order): the context, then the display.
    _context: PossiblyCurrentContext,
    _display: Display,
    device_name: String,
}

impl HeadlessContext {
    /// Creates a GL 3.3 core context on the first EGL device that can make one, a debug
    /// context where [`debug_wanted`](super::check::debug_wanted).
    pub fn new() -> Result<HeadlessContext> {
        Self::with_debug(super::check::debug_wanted())
    }

    /// [`new`](Self::new) with the driver's debug messages on or off whatever the build.
    pub fn with_debug(debug: bool) -> Result<HeadlessContext> {
        let devices = Device::query_devices().map_err(|e| {
            Error::Context(format!(
                "cannot use EGL to render without a display: {e}.\n\
                 On Debian or Ubuntu install the EGL loader and Mesa's drivers: \
                 apt-get install {DEBIAN_PACKAGES}"
            ))
        })?;
        let mut failures = Vec::new();
        for device in devices {
            let name = device
                .name()
                .or(device.vendor())
                .unwrap_or("unnamed EGL device")
                .to_string();
            match Self::on_device(&device, debug) {
                Ok((display, context)) => {
                    // SAFETY: the context is current on this thread; the loader returns its
                    // function pointers.
                    let mut gl = unsafe {
                        glow::Context::from_loader_function_cstr(|s| display.get_proc_address(s))
                    };
                    super::check::install_debug_output(&mut gl, debug);
                    return Ok(HeadlessContext {
                        gl: Rc::new(super::bindings::GlContext::new(gl)),
                        _context: context,
                        _display: display,
                        device_name: name,
                    });
                }
                Err(e) => failures.push(format!("{name}: {e}")),
            }
        }
        Err(Error::Context(if failures.is_empty() {
            format!(
                "EGL found no device to render on (no GPU driver and no software renderer).\n\
                 On Debian or Ubuntu install Mesa's drivers: apt-get install {DEBIAN_PACKAGES}"
            )
        } else {
            format!(
                "no EGL device could create an OpenGL 3.3 core context:\n  {}\n\
                 On Debian or Ubuntu install Mesa's drivers: apt-get install {DEBIAN_PACKAGES}",
                failures.join("\n  ")
            )
        }))
    }

    fn on_device(
        device: &Device,
        debug: bool,
    ) -> std::result::Result<(Display, PossiblyCurrentContext), glutin::error::Error> {
        // SAFETY: no raw display handle is passed, so there is nothing to keep valid.
        let display = unsafe { Display::with_device(device, None) }?;
        let template = ConfigTemplateBuilder::new()
            .with_surface_type(ConfigSurfaceTypes::empty())
            .with_api(Api::OPENGL)
            .build();
        // SAFETY: the template holds no native window.
        let config = unsafe { display.find_configs(template) }?
            .next()
            .ok_or(glutin::error::ErrorKind::BadConfig)?;
        let attributes = ContextAttributesBuilder::new()
            .with_context_api(ContextApi::OpenGl(Some(Version::new(3, 3))))
            .with_profile(GlProfile::Core)
            .with_debug(debug)
            .build(None);
        // SAFETY: the config came from this display.
        let context = unsafe { display.create_context(&config, &attributes) }?;
        let context = context.make_current_surfaceless()?;
        Ok((display, context))
    }

    pub fn gl(&self) -> &Gl {
        &self.gl
    }

    /// Releases the context from this thread and frees it. A window's GLX context made
    /// current afterwards on the same thread fails with BadAccess while an EGL context is
    /// still current there (`demo --target-error` renders headless first, then opens its
    /// window). Dropping without this leaves the context current until another is made so,
    /// which nested contexts (tests) rely on.
    pub fn release(self) {
        use glutin::context::PossiblyCurrentGlContext;
        if self._context.is_current() {
            let _ = self._context.make_not_current_in_place();
        }
    }

    /// The EGL device the context runs on, for reports.
    pub fn device_name(&self) -> &str {
        &self.device_name
    }
}
