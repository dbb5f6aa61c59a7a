//! What differs between the desktops, named once: which window system a display is, which
//! GL platform APIs it offers, the words of the no-display hint, and the two file-system
//! details the output and input code need (a new file's mode, a special file's kind).

use raw_window_handle::RawDisplayHandle;

use super::window::WindowApi;

/// The window system the event loop is connected to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Platform {
    X11,
    Wayland,
    Windows,
    MacOs,
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

/// The permissions of a file that the output code writes through a temporary file: those
/// of any new file (the umask decides; tempfile's own default is owner-only). `None` where
/// the platform has no Unix modes: there the default is already that of a new file.
pub fn new_file_permissions() -> Option<std::fs::Permissions> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        Some(std::fs::Permissions::from_mode(0o666))
    }
    #[cfg(not(unix))]
    {
        None
    }
}

/// A Unix special file's kind in words (FIFO, device, socket), for "cannot read …" messages;
/// `None` for a plain file or a directory, and everywhere without such files.
pub fn special_file_kind(t: &std::fs::FileType) -> Option<&'static str> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return Some("a FIFO (named pipe)");
        }
        if t.is_char_device() {
            return Some("a character device");
        }
        if t.is_block_device() {
            return Some("a block device");
        }
        if t.is_socket() {
            return Some("a socket");
        }
        None
    }
    #[cfg(not(unix))]
    {
        let _ = t;
        None
    }
}
