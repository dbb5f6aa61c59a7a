//! A GL 3.3 core context with no window and no display, through EGL's device platform
//! (Mesa llvmpipe on a machine without a GPU): query the EGL devices, open a display on one,
//! pick a config with no surface type and make the context current without a surface.

use std::rc::Rc;

use glutin::api::egl::context::PossiblyCurrentContext;
use glutin::api::egl::device::Device;
use glutin::api::egl::display::Display;
use glutin::config::{Api, ConfigSurfaceTypes, ConfigTemplateBuilder};
use glutin::context::{ContextApi, ContextAttributesBuilder, GlProfile, Version};
use glutin::display::GlDisplay;

use super::super::Gl;
use super::platform::DEBIAN_PACKAGES;
use crate::error::{Error, Result};

/// What keeps the context alive: the context, then its display (fields drop in order).
pub(super) struct Backing {
    context: PossiblyCurrentContext,
    _display: Display,
}

impl Backing {
    /// The first EGL device that can make a 3.3 core context: the backing, a GL loaded
    /// from it and the device's name.
    pub(super) fn new(debug: bool) -> Result<(Backing, Gl, String)> {
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
            match on_device(&device, debug) {
                Ok((display, context)) => {
                    // SAFETY: the context is current on this thread; the loader returns its
                    // function pointers.
                    let mut gl = unsafe {
                        glow::Context::from_loader_function_cstr(|s| display.get_proc_address(s))
                    };
                    super::super::check::install_debug_output(&mut gl, debug);
                    let gl = Rc::new(super::super::bindings::GlContext::new(gl));
                    let backing = Backing {
                        context,
                        _display: display,
                    };
                    return Ok((backing, gl, name));
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

    /// Releases the context from this thread.
    pub(super) fn release(&self) {
        use glutin::context::PossiblyCurrentGlContext;
        if self.context.is_current() {
            let _ = self.context.make_not_current_in_place();
        }
    }
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
