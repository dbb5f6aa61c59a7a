//! The program around the library: command line, demo window, headless commands.

pub mod bench;
pub mod cli;
pub mod compare;
pub mod compare_setup;
pub mod demo;
pub mod gallery;
pub mod hud;
pub mod keys;
pub mod map_memory;
pub mod motion;
pub mod motion_args;
pub mod motion_plot;
pub mod plot;
pub mod quality;
pub mod render;
pub mod shaders;
pub mod soak;

#[cfg(test)]
mod tests;
