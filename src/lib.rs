//! shadowmap: the classic shadow-mapping chapters (the LWJGL book's "Shadows", LearnOpenGL's
//! "Shadow Mapping", a course's slides, the shadow-playground blog) ported to Rust and
//! OpenGL 3.3 core, built to be read beside them and to measure itself against an exact
//! ray-traced reference.
//!
//! The modules are layers, each using only those below it: `docs/architecture.md` describes
//! them (and `tests/project/layers.rs` checks the source against its table); `docs/reading-guide.md`
//! names the module and function that ports each section of the chapters.

pub mod engine;
pub mod error;
pub mod geometry;
pub mod image_data;
pub mod input;
pub mod measure;
pub mod output;
pub mod renderer;
pub mod scene;
pub mod settings;
pub mod shaders;
pub mod shadows;
pub mod steps;
pub mod transformation;

// The measurement modules keep their old paths for the program and the tests.
pub use measure::{bench, compare, frame, motion, reference, scale};

pub use error::{Error, Result};
pub use renderer::{Renderer, Target};
pub use scene::Scene;
pub use settings::ShadowSettings;
