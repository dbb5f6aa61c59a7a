//! GL error checks and driver limits, so failures become errors instead of black images.

use glow::HasContext;

use super::Gl;
use crate::error::{Error, Result};

/// The readable name of a glGetError code.
pub fn gl_error_name(code: u32) -> &'static str {
    match code {
        glow::INVALID_ENUM => "GL_INVALID_ENUM",
        glow::INVALID_VALUE => "GL_INVALID_VALUE",
        glow::INVALID_OPERATION => "GL_INVALID_OPERATION",
        glow::INVALID_FRAMEBUFFER_OPERATION => "GL_INVALID_FRAMEBUFFER_OPERATION",
        glow::OUT_OF_MEMORY => "GL_OUT_OF_MEMORY",
        glow::STACK_UNDERFLOW => "GL_STACK_UNDERFLOW",
        glow::STACK_OVERFLOW => "GL_STACK_OVERFLOW",
        _ => "unknown GL error",
    }
}

thread_local! {
    /// Error reports from the driver's KHR_debug output, waiting for the next [`check_gl`]
    /// on this thread (the output is synchronous: the report comes on the calling thread,
    /// so tests drawing in parallel do not read each other's).
    static DEBUG_ERRORS: std::cell::RefCell<Vec<String>> =
        const { std::cell::RefCell::new(Vec::new()) };
}

/// Whether contexts are made as debug contexts with the driver's messages on: in debug
/// builds (and so in tests), or with `SHADOWMAP_GL_DEBUG=1`.
pub(crate) fn debug_wanted() -> bool {
    cfg!(debug_assertions) || std::env::var_os("SHADOWMAP_GL_DEBUG").is_some()
}

/// When `debug` (from [`debug_wanted`]), asks the driver to report errors through KHR_debug where it has
/// it; [`check_gl`] then fails on them too, with the driver's own explanation. Messages flow
/// only with `GL_DEBUG_OUTPUT` on (a debug context starts with it on, others do not).
pub(crate) fn install_debug_output(gl: &mut glow::Context, debug: bool) {
    if !debug || !gl.supported_extensions().contains("GL_KHR_debug") {
        return;
    }
    unsafe {
        gl.enable(glow::DEBUG_OUTPUT);
        gl.enable(glow::DEBUG_OUTPUT_SYNCHRONOUS);
        // The compiler's messages come with the info log, which names files and lines.
        gl.debug_message_callback(|source, kind, _id, severity, message| {
            let error = kind == glow::DEBUG_TYPE_ERROR || severity == glow::DEBUG_SEVERITY_HIGH;
            if error && source != glow::DEBUG_SOURCE_SHADER_COMPILER {
                DEBUG_ERRORS.with(|e| e.borrow_mut().push(message.to_string()));
            }
        });
    }
}

/// Drains glGetError (and the KHR_debug errors) and reports the first error, naming the
/// pass it happened in.
pub fn check_gl(gl: &Gl, during: &str) -> Result<()> {
    let debug: Vec<String> = DEBUG_ERRORS.with(|e| std::mem::take(&mut *e.borrow_mut()));
    let mut first = None;
    // glGetError keeps one flag per error kind; drain them all so the next check starts clean.
    for _ in 0..16 {
        let code = unsafe { gl.get_error() };
        if code == glow::NO_ERROR {
            break;
        }
        first.get_or_insert(code);
    }
    match (first, debug.first()) {
        (None, None) => Ok(()),
        (Some(code), _) => Err(Error::Gl {
            code,
            name: gl_error_name(code),
            during: format!(
                "{during}{}",
                debug
                    .first()
                    .map(|m| format!(" (driver: {m})"))
                    .unwrap_or_default()
            ),
        }),
        (None, Some(m)) => Err(Error::Gl {
            code: 0,
            name: "KHR_debug error",
            during: format!("{during} (driver: {m})"),
        }),
    }
}

/// The readable name of a glCheckFramebufferStatus result.
pub fn framebuffer_status_name(status: u32) -> &'static str {
    match status {
        glow::FRAMEBUFFER_COMPLETE => "GL_FRAMEBUFFER_COMPLETE",
        glow::FRAMEBUFFER_UNDEFINED => "GL_FRAMEBUFFER_UNDEFINED",
        glow::FRAMEBUFFER_INCOMPLETE_ATTACHMENT => "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT",
        glow::FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT => {
            "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT"
        }
        glow::FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER => "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER",
        glow::FRAMEBUFFER_INCOMPLETE_READ_BUFFER => "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER",
        glow::FRAMEBUFFER_UNSUPPORTED => "GL_FRAMEBUFFER_UNSUPPORTED",
        glow::FRAMEBUFFER_INCOMPLETE_MULTISAMPLE => "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE",
        _ => "unknown framebuffer status",
    }
}

/// Checks the bound draw framebuffer; the book throws "Could not create FrameBuffer" here.
pub(crate) fn check_framebuffer(gl: &Gl, what: &str) -> Result<()> {
    let status = unsafe { gl.check_framebuffer_status(glow::FRAMEBUFFER) };
    if status == glow::FRAMEBUFFER_COMPLETE {
        Ok(())
    } else {
        Err(Error::IncompleteFramebuffer {
            what: what.to_string(),
            status,
            name: framebuffer_status_name(status),
        })
    }
}

/// Driver facts the settings are validated against.
#[derive(Debug, Clone, Copy)]
pub struct GlLimits {
    pub max_texture_size: u32,
    pub max_renderbuffer_size: u32,
    pub max_viewport: [u32; 2],
    /// Components a vertex shader may output (GL 3.3 guarantees 64).
    pub max_vertex_output_components: u32,
}

/// Reads the limits of the current context.
pub fn gl_limits(gl: &Gl) -> GlLimits {
    let mut viewport = [0i32; 2];
    unsafe {
        gl.get_parameter_i32_slice(glow::MAX_VIEWPORT_DIMS, &mut viewport);
        GlLimits {
            max_texture_size: gl.get_parameter_i32(glow::MAX_TEXTURE_SIZE).max(0) as u32,
            max_renderbuffer_size: gl.get_parameter_i32(glow::MAX_RENDERBUFFER_SIZE).max(0) as u32,
            max_viewport: [viewport[0].max(0) as u32, viewport[1].max(0) as u32],
            max_vertex_output_components: gl
                .get_parameter_i32(glow::MAX_VERTEX_OUTPUT_COMPONENTS)
                .max(0) as u32,
        }
    }
}

/// The renderer string, for reports ("llvmpipe (LLVM 15.0.6, 256 bits)").
pub fn renderer_name(gl: &Gl) -> String {
    unsafe {
        format!(
            "{} / OpenGL {}",
            gl.get_parameter_string(glow::RENDERER),
            gl.get_parameter_string(glow::VERSION)
        )
    }
}

/// Whether a texture name still names a texture (for tests that owners delete theirs).
pub fn object_exists(gl: &Gl, texture: glow::Texture) -> bool {
    unsafe { gl.is_texture(texture) }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A call the driver refuses comes back from `check_gl` with the driver's own words
    /// (Mesa: "GL_INVALID_ENUM in glEnable(...)"), not only the error code. The context asks
    /// for the messages itself, so the test holds in release builds too.
    #[test]
    fn a_bad_call_is_reported_with_the_drivers_message() {
        let context = crate::engine::HeadlessContext::with_debug(true).expect("a headless context");
        let gl = context.gl();
        check_gl(gl, "setup").expect("a clean start");
        unsafe { gl.enable(0x1234) };
        let error = check_gl(gl, "a bad enable").expect_err("the bad call is reported");
        let text = error.to_string();
        assert!(text.contains("GL_INVALID_ENUM"), "{text}");
        assert!(text.contains("(driver: "), "no driver message: {text}");
        assert!(text.contains("glEnable"), "not the driver's words: {text}");
        check_gl(gl, "after the report").expect("the report drained the errors");
    }
}
