//! shadowmap: the classic shadow-mapping chapters (the LWJGL book's "Shadows", LearnOpenGL's
//! "Shadow Mapping", a course's slides, the shadow-playground blog) ported to Rust and
//! OpenGL 3.3 core, built to be read beside them and to measure itself.
//!
//! Layers, each importing only those above it:
//! - data: `settings`, `transformation`, `geometry`, `image_data`, `scene` (the book's
//!   `Camera`, `GameItem`, lights, and the scene files);
//! - `engine`: every GL call (RAII owners, state as values);
//! - `shadows`: one module per technique (the chapter's 2D map, cube maps, cascades, the
//!   fitted box) behind one trait, and the slides' stencil shadow volumes beside them;
//! - `renderer`: the book's two passes;
//! - `measure`: frames read back, the exact reference, compare and bench, attached through
//!   hooks; `steps`: the chapter steps as presets.
//!
//! `tests/layers.rs` checks that no module imports a layer below it.

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
pub use measure::{bench, compare, frame, reference, scale};

pub use error::{Error, Result};
pub use renderer::{Renderer, Target};
pub use scene::Scene;
pub use settings::ShadowSettings;
