//! The project's own rules: the docs against the program, and the library's layers against
//! the architecture page.
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod docs;
mod layers;
