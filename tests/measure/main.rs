//! Measurement: the exact reference on closed forms, `compare`, `bench` and `--scale`, motion
//! and flicker, the scenes against their originals, and the figures the docs cite.
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod gpu_figures;
mod motion;
mod originals;
mod reference;
mod results_figures;
mod scale;
