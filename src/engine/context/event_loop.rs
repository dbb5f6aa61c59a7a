//! The process's one winit event loop. winit refuses a second `EventLoop::new()` in a
//! process (even after the first failed), and both the demo's window and, where there is no
//! EGL device platform, a headless context's invisible window need one: so on the desktop it
//! is made once, on first use, kept for the thread, and lent to each user in turn. In the
//! browser the loop is handed to the page (`requestAnimationFrame`) and runs after `main`.

#[cfg(any(windows, target_os = "macos"))]
pub(super) use desktop::with_event_loop;
#[cfg(not(target_family = "wasm"))]
pub use desktop::{run_app, window_system};
#[cfg(target_family = "wasm")]
pub use web::{run_app, window_system};

#[cfg(not(target_family = "wasm"))]
mod desktop {
    use std::cell::RefCell;

    use winit::application::ApplicationHandler;
    use winit::event_loop::EventLoop;
    use winit::platform::run_on_demand::EventLoopExtRunOnDemand;

    use crate::error::{Error, Result};

    thread_local! {
        /// The loop, or why it could not be made (kept: winit would refuse a second try).
        static EVENT_LOOP: RefCell<Option<std::result::Result<EventLoop<()>, String>>> =
            const { RefCell::new(None) };
    }

    /// Lends the event loop to `f`; `Err(reason)` when there is none (no display), the
    /// reason in the user's words (see [`no_display_reason`](super::no_display_reason)).
    pub(in super::super) fn with_event_loop<R>(
        f: impl FnOnce(&mut EventLoop<()>) -> R,
    ) -> std::result::Result<R, String> {
        EVENT_LOOP.with(|cell| {
            let mut slot = cell.borrow_mut();
            let made = slot.get_or_insert_with(|| {
                EventLoop::new().map_err(|e| super::no_display_reason(&e.to_string()))
            });
            match made {
                Ok(event_loop) => Ok(f(event_loop)),
                Err(reason) => Err(reason.clone()),
            }
        })
    }

    /// Whether there is a window system to open windows on: `Err(reason)` when there is no
    /// display, so that the caller can fall back to rendering headless before it builds
    /// anything.
    pub fn window_system() -> std::result::Result<(), String> {
        with_event_loop(|_| ())
    }

    /// Runs `app` on the event loop until it calls `exit()`, and hands it back.
    pub fn run_app<A: ApplicationHandler + 'static>(mut app: A) -> Result<Option<A>> {
        match with_event_loop(|event_loop| event_loop.run_app_on_demand(&mut app)) {
            Ok(Ok(())) => Ok(Some(app)),
            Ok(Err(e)) => Err(Error::Context(format!("window event loop: {e}"))),
            Err(reason) => Err(Error::Context(format!("no window ({reason})"))),
        }
    }
}

#[cfg(target_family = "wasm")]
mod web {
    use winit::application::ApplicationHandler;
    use winit::event_loop::EventLoop;
    use winit::platform::web::EventLoopExtWebSys;

    use crate::error::{Error, Result};

    /// The page always has its canvas.
    pub fn window_system() -> std::result::Result<(), String> {
        Ok(())
    }

    /// Hands `app` to the page's event loop, which runs it after `main` returns: `None`,
    /// there is nothing to hand back (errors are shown on the page).
    pub fn run_app<A: ApplicationHandler + 'static>(app: A) -> Result<Option<A>> {
        let event_loop =
            EventLoop::new().map_err(|e| Error::Context(format!("the page's event loop: {e}")))?;
        event_loop.spawn_app(app);
        Ok(None)
    }
}

/// Why there is no window, in the user's words. winit's own error names one of winit's
/// source files, not the cause: on the free Unixes the cause is read from the environment
/// winit read; elsewhere winit's message is all there is.
pub fn no_display_reason(winit_error: &str) -> String {
    #[cfg(all(unix, not(target_vendor = "apple"), not(target_os = "android")))]
    {
        let _ = winit_error;
        let var = |name| std::env::var(name).ok().filter(|v| !v.is_empty());
        match (var("DISPLAY"), var("WAYLAND_DISPLAY")) {
            (None, None) => "DISPLAY and WAYLAND_DISPLAY are not set".to_string(),
            (Some(d), _) => format!("the X server at DISPLAY={d} refused the connection"),
            (None, Some(w)) => format!("the Wayland compositor at WAYLAND_DISPLAY={w} refused"),
        }
    }
    #[cfg(not(all(unix, not(target_vendor = "apple"), not(target_os = "android"))))]
    {
        format!("the window system refused: {winit_error}")
    }
}
