//! One error type for the library, so every failure names what went wrong and where.

use std::path::PathBuf;

/// Everything the engine and the scene loaders can report.
///
/// Messages are written for the person at the keyboard: they name the file, the line or
/// field when there is one, and what was expected.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// No usable OpenGL context could be created (EGL, drivers, display).
    #[error("{0}")]
    Context(String),

    /// A shader failed to compile or link; the message carries `file:line: text` lines.
    #[error("shader error in {file}:\n{log}")]
    Shader { file: String, log: String },

    /// glGetError reported an error after a pass.
    #[error("OpenGL error {code:#06x} ({name}) during {during}")]
    Gl {
        code: u32,
        name: &'static str,
        during: String,
    },

    /// glCheckFramebufferStatus did not report GL_FRAMEBUFFER_COMPLETE.
    #[error("could not create framebuffer '{what}': status {status:#06x} ({name})")]
    IncompleteFramebuffer {
        what: String,
        status: u32,
        name: &'static str,
    },

    /// A GL object could not be created (out of names or memory).
    #[error("could not create {0}")]
    Create(String),

    /// A file (scene, model, texture, output) could not be read or written.
    #[error("{path}: {message}")]
    File { path: PathBuf, message: String },

    /// A value in a file is wrong: `field` is its dotted name as the file spells it
    /// (`camera.far`, `item[2] ("cube").scale`), so callers and tests can ask which field
    /// failed without reading the message.
    /// (`path`, not `source`: thiserror would take a field named `source` for the cause.)
    #[error("{path}: {field}: {message}")]
    Field {
        path: PathBuf,
        field: String,
        message: String,
    },

    /// A scene or setting is invalid; the message names the field.
    #[error("{0}")]
    Invalid(String),

    /// Something the program itself should have made impossible (a bug, not bad input).
    #[error("internal error: {0} (please report this)")]
    Internal(String),
}

pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// A file error with a path and a message.
    pub fn file(path: impl Into<PathBuf>, message: impl Into<String>) -> Self {
        Error::File {
            path: path.into(),
            message: message.into(),
        }
    }

    /// An error about one field of a file; renders as `{path}: {field}: {message}`, the
    /// text `Error::file(path, format!("{field}: {message}"))` gives.
    pub fn in_field(
        path: impl Into<PathBuf>,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Error::Field {
            path: path.into(),
            field: field.into(),
            message: message.into(),
        }
    }

    /// The field the error is about, when it is about one.
    pub fn field(&self) -> Option<&str> {
        match self {
            Error::Field { field, .. } => Some(field),
            _ => None,
        }
    }
}
