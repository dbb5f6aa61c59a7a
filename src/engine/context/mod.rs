//! Where a GL context comes from, on every platform: the only module of the crate that
//! knows which operating system it runs on (every `#[cfg(target_os …)]` is here).
//!
//! - [`WindowContext`]: a window with a GL 3.3 core context, through winit and glutin-winit's
//!   display builder: WGL on Windows, CGL on macOS (its 4.1 core profile holds every 3.3
//!   feature used), EGL on Wayland, GLX or EGL on X11.
//! - [`HeadlessContext`]: no window. EGL's device platform (surfaceless) where the platform
//!   has it (Linux and the other free Unixes), else an invisible window's context; either way
//!   everything is drawn into the project's own framebuffer, a
//!   [`RenderTarget`](super::RenderTarget), so the pictures are the same.
//! - The process's one event loop ([`run_app`]): winit allows one per process, and both the
//!   demo's window and (off Linux) a headless context need it.

#[cfg(all(unix, not(target_vendor = "apple"), not(target_os = "android")))]
mod egl_device;
mod event_loop;
mod headless;
#[cfg(not(all(unix, not(target_vendor = "apple"), not(target_os = "android"))))]
mod hidden_window;
mod platform;
mod window;

pub use event_loop::{no_display_reason, run_app, window_system};
pub use headless::HeadlessContext;
pub use platform::{no_display_hint, Platform, WindowApi, DEBIAN_PACKAGES};
pub use window::WindowContext;
