//! What differs between the desktops, named once: which window system a display is, which
//! GL platform APIs it offers (`--gl-api`), and the words of the no-display hint.

use raw_window_handle::RawDisplayHandle;

use crate::error::{Error, Result};

/// Which platform API the window's context comes from (`--gl-api`). On X11 with a software
/// driver GLX and EGL swap differently: GLX hands the frame to the X server through shared
/// memory (MIT-SHM), while Mesa's EGL (22.x) sends it down the socket, which made the window
/// 1.2 to 1.35 times slower than headless.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum WindowApi {
    /// The platform's own (GLX, WGL, CGL; EGL on Wayland), else EGL.
    #[default]
    Auto,
    Glx,
    Egl,
    Wgl,
    Cgl,
}

impl WindowApi {
    /// The name `--gl-api` takes, lower case.
    pub fn flag(self) -> &'static str {
        match self {
            WindowApi::Auto => "auto",
            WindowApi::Glx => "glx",
            WindowApi::Egl => "egl",
            WindowApi::Wgl => "wgl",
            WindowApi::Cgl => "cgl",
        }
    }

    /// Refuses a choice `platform` lacks, with the list of what it has.
    pub(super) fn check(self, platform: Platform) -> Result<()> {
        let apis = platform.apis();
        if self != WindowApi::Auto && !apis.contains(&self) {
            let mut names = vec!["auto"];
            names.extend(apis.iter().map(|a| a.flag()));
            return Err(Error::Invalid(format!(
                "--gl-api {}: a window on {} gets its OpenGL context through {}; expected \
                 one of: {}",
                self.flag(),
                platform.name(),
                match apis {
                    [] if platform == Platform::Web => "WebGL2".to_string(),
                    [] => "none of the APIs this program knows".to_string(),
                    _ => apis
                        .iter()
                        .map(|a| a.flag().to_uppercase())
                        .collect::<Vec<_>>()
                        .join(" or "),
                },
                names.join(", ")
            )));
        }
        Ok(())
    }
}

/// The window system the event loop is connected to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Platform {
    X11,
    Wayland,
    Windows,
    MacOs,
    /// A browser's page (WebGL2 only).
    Web,
    /// A window system the project has not been built for (named by winit's handle).
    Other(&'static str),
}

impl Platform {
    /// The window system behind a display handle.
    pub fn of(handle: RawDisplayHandle) -> Platform {
        match handle {
            RawDisplayHandle::Xlib(_) | RawDisplayHandle::Xcb(_) => Platform::X11,
            RawDisplayHandle::Wayland(_) => Platform::Wayland,
            RawDisplayHandle::Windows(_) => Platform::Windows,
            RawDisplayHandle::AppKit(_) => Platform::MacOs,
            RawDisplayHandle::Web(_) => Platform::Web,
            // raw-window-handle's enum is non-exhaustive: what is not listed has no GL here.
            _ => Platform::Other("an unsupported window system"),
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Platform::X11 => "X11",
            Platform::Wayland => "Wayland",
            Platform::Windows => "Windows",
            Platform::MacOs => "macOS",
            Platform::Web => "the web",
            Platform::Other(name) => name,
        }
    }

    /// The GL platform APIs a window can get its context from here, the first the one
    /// `--gl-api auto` tries first.
    pub fn apis(self) -> &'static [WindowApi] {
        match self {
            Platform::X11 => &[WindowApi::Glx, WindowApi::Egl],
            Platform::Wayland => &[WindowApi::Egl],
            Platform::Windows => &[WindowApi::Wgl, WindowApi::Egl],
            Platform::MacOs => &[WindowApi::Cgl],
            Platform::Web => &[],
            Platform::Other(_) => &[],
        }
    }
}

/// The packages that provide EGL and a software GL driver on Debian and Ubuntu.
pub const DEBIAN_PACKAGES: &str = "libegl1 libegl-mesa0 libgl1-mesa-dri";

/// How to get a window when there is none, said the same way on every platform.
pub fn no_display_hint() -> &'static str {
    #[cfg(all(unix, not(target_vendor = "apple"), not(target_os = "android")))]
    {
        "For a window, run under X11: `apt-get install xvfb`, `Xvfb :99 &`, then \
         `DISPLAY=:99 shadowmap`."
    }
    #[cfg(not(all(unix, not(target_vendor = "apple"), not(target_os = "android"))))]
    {
        "For a window, run it from the desktop session (not a service or a remote shell)."
    }
}
