//! The frame as the renderer draws it: kept maps and the shadow mask against frames drawn
//! from scratch, the hot path, instancing, GL objects' owners, the shader programs, the debug
//! views, the HUD and the inset, and our LearnOpenGL frame against a plain one.
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod baseline;
mod cache;
mod debug_views;
mod hot_path;
mod hud;
mod inset;
mod instanced;
mod lifetimes;
mod shaders;
mod step_views;
