//! A current GL 3.3 core context with no window to show: EGL's device platform where the
//! platform has one (Linux: the tests, on Mesa llvmpipe), else an invisible window's
//! context. Everything is then drawn into a [`RenderTarget`](super::super::RenderTarget), so
//! `render`, `compare`, `steps`, `bench` and `soak` give the same pictures everywhere.

use super::super::Gl;
use crate::error::Result;

#[cfg(all(unix, not(target_vendor = "apple"), not(target_os = "android")))]
use super::egl_device::Backing;
#[cfg(any(windows, target_os = "macos"))]
use super::hidden_window::Backing;
#[cfg(target_family = "wasm")]
use super::web::Backing;

/// A current context. Keep it alive as long as any GL object made with it.
pub struct HeadlessContext {
    gl: Gl,
    // Dropped after `gl`'s users (fields drop in order).
    backing: Backing,
    device_name: String,
}

impl HeadlessContext {
    /// Creates a GL 3.3 core context, a debug context where
    /// [`debug_wanted`](super::super::check::debug_wanted).
    pub fn new() -> Result<HeadlessContext> {
        Self::with_debug(super::super::check::debug_wanted())
    }

    /// [`new`](Self::new) with the driver's debug messages on or off whatever the build.
    pub fn with_debug(debug: bool) -> Result<HeadlessContext> {
        let (backing, gl, device_name) = Backing::new(debug)?;
        Ok(HeadlessContext {
            gl,
            backing,
            device_name,
        })
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
        self.backing.release();
    }

    /// What the context runs on (the EGL device, or the invisible window), for reports.
    pub fn device_name(&self) -> &str {
        &self.device_name
    }
}
