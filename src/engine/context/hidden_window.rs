//! A GL 3.3 core context where there is no EGL device platform (Windows, macOS): the
//! context of an invisible window, opened on the process's event loop. Nothing is drawn to
//! the window itself; the renderer draws into its own framebuffer, as on the EGL path.

use std::time::Duration;

use winit::application::ApplicationHandler;
use winit::event::WindowEvent;
use winit::event_loop::ActiveEventLoop;
use winit::platform::pump_events::EventLoopExtPumpEvents;
use winit::window::{Window, WindowId};

use super::super::Gl;
use super::event_loop::with_event_loop;
use super::platform::WindowApi;
use super::window::WindowContext;
use crate::error::{Error, Result};

/// The invisible window whose context is current.
pub(super) struct Backing {
    window: WindowContext,
}

/// Runs `open` once the event loop hands out an [`ActiveEventLoop`] (after its start-up
/// events), then leaves the loop.
struct Opener<F: FnOnce(&ActiveEventLoop) -> Result<WindowContext>> {
    open: Option<F>,
    opened: Option<Result<WindowContext>>,
}

impl<F: FnOnce(&ActiveEventLoop) -> Result<WindowContext>> ApplicationHandler for Opener<F> {
    fn resumed(&mut self, _: &ActiveEventLoop) {}

    fn window_event(&mut self, _: &ActiveEventLoop, _: WindowId, _: WindowEvent) {}

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(open) = self.open.take() {
            self.opened = Some(open(event_loop));
        }
    }
}

impl Backing {
    /// An invisible window's context, current: the backing, its GL and its name for reports.
    pub(super) fn new(debug: bool) -> Result<(Backing, Gl, String)> {
        let attributes = Window::default_attributes()
            .with_title("shadowmap (headless)")
            .with_visible(false)
            .with_inner_size(winit::dpi::PhysicalSize::new(64, 64));
        let mut opener = Opener {
            open: Some(|event_loop: &ActiveEventLoop| {
                WindowContext::with_debug(event_loop, attributes, WindowApi::Auto, debug)
            }),
            opened: None,
        };
        with_event_loop(|event_loop| {
            // The first pump delivers the start-up events; a few more at most.
            for _ in 0..100 {
                let _ = event_loop.pump_app_events(Some(Duration::ZERO), &mut opener);
                if opener.opened.is_some() {
                    break;
                }
            }
        })
        .map_err(|reason| {
            Error::Context(format!(
                "cannot render headless: no window system for an invisible window ({reason})"
            ))
        })?;
        let window = opener.opened.unwrap_or_else(|| {
            Err(Error::Context(
                "cannot render headless: the event loop never became active".into(),
            ))
        })?;
        let name = format!("an invisible window ({})", window.api());
        let gl = window.gl().clone();
        Ok((Backing { window }, gl, name))
    }

    /// Releases the context from this thread.
    pub(super) fn release(&self) {
        self.window.release();
    }
}
