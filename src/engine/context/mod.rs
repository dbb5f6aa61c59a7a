//! Where a GL context comes from, on every platform: the only module of the crate that
//! knows which operating system it runs on (every `#[cfg(target_os …)]` is here).
//!
//! - [`WindowContext`]: a window with a GL 3.3 core context, through winit and glutin-winit's
//!   display builder: WGL on Windows, CGL on macOS (its 4.1 core profile holds every 3.3
//!   feature used), EGL on Wayland, GLX or EGL on X11; in the browser, the page's canvas
//!   with WebGL2.
//! - [`HeadlessContext`]: no window. EGL's device platform (surfaceless) where the platform
//!   has it (Linux and the other free Unixes), else an invisible window's context; either way
//!   everything is drawn into the project's own framebuffer, a
//!   [`RenderTarget`](super::RenderTarget), so the pictures are the same.
//! - The process's one event loop ([`run_app`]): winit allows one per process, and both the
//!   demo's window and (off Linux) a headless context need it.
//! - The command line ([`args`], [`report_error`]): the process's own on the desktop, the
//!   page's address and title in the browser.

#[cfg(all(unix, not(target_vendor = "apple"), not(target_os = "android")))]
mod egl_device;
mod event_loop;
mod headless;
#[cfg(any(windows, target_os = "macos"))]
mod hidden_window;
mod platform;
#[cfg(target_family = "wasm")]
mod web;
#[cfg(not(target_family = "wasm"))]
mod window;

pub use event_loop::{no_display_reason, run_app, window_system};
pub use headless::HeadlessContext;
pub use platform::{no_display_hint, Platform, WindowApi, DEBIAN_PACKAGES};
#[cfg(target_family = "wasm")]
pub use web::{args, report_error, report_note, start, WindowContext};
#[cfg(not(target_family = "wasm"))]
pub use window::WindowContext;

/// Whether errors reach a terminal (and a bad command line exits as a command does); in the
/// browser they go to the page ([`report_error`]).
pub const HAS_TERMINAL: bool = cfg!(not(target_family = "wasm"));

/// Whether the context can say what is bound (`glGet*` of a binding): glow's WebGL backend
/// panics on an empty one.
pub const CAN_QUERY_BINDINGS: bool = cfg!(not(target_family = "wasm"));

/// Sets up what the platform needs before anything runs (the browser: errors on the page).
#[cfg(not(target_family = "wasm"))]
pub fn start() {}

/// The command line, the program's name first.
#[cfg(not(target_family = "wasm"))]
pub fn args() -> Vec<String> {
    std::env::args().collect()
}

/// Says what went wrong, where the user will read it.
#[cfg(not(target_family = "wasm"))]
pub fn report_error(message: &str) {
    eprintln!("error: {message}");
}

/// Says what a key could not do while the program goes on, where the user will read it.
#[cfg(not(target_family = "wasm"))]
pub fn report_note(message: &str) {
    eprintln!("note: {message}");
}

/// Makes `font` the plots' `name` where the program draws a plot's text itself. In the
/// browser plotters draws with the page's fonts and has no registry: nothing to do.
pub fn register_plot_font(name: &str, font: &'static [u8]) -> Result<(), String> {
    #[cfg(not(target_family = "wasm"))]
    plotters::style::register_font(name, plotters::style::FontStyle::Normal, font)
        .map_err(|_| "the embedded font is not readable".to_string())?;
    #[cfg(target_family = "wasm")]
    let _ = (name, font);
    Ok(())
}
