//! The program as a user meets it: first runs and `--help`, warnings for settings that do
//! nothing, errors and their messages, outputs written whole, the parsers under generated
//! input, scene files and the examples.
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod errors;
mod examples;
mod first_run;
mod first_use;
mod fuzz;
mod io;
mod scene_file;
