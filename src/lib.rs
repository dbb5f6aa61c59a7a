//! shadowmap: the classic shadow-mapping chapters (the LWJGL book's "Shadows", LearnOpenGL's
//! "Shadow Mapping", a course's slides, the shadow-playground blog) ported to Rust and
//! OpenGL 3.3 core, built to be read beside them and to measure itself.
//!
//! The engine (`engine`) holds every GL call; the scene side (`scene`, `transformation`,
//! `settings`) is plain data; `renderer` is the book's two-pass frame; `frame` renders
//! headless frames and reads them back.

pub mod bench;
pub mod compare;
pub mod engine;
pub mod error;
pub mod frame;
pub mod geometry;
pub mod image_data;
pub mod input;
pub mod light_slots;
pub mod reference;
pub mod renderer;
pub mod scene;
pub mod settings;
pub mod shaders;
pub mod steps;
pub mod transformation;

pub use error::{Error, Result};
pub use renderer::{Renderer, Target};
pub use scene::Scene;
pub use settings::ShadowSettings;
