//! Each shadow technique against the exact reference: the chapter's map, its matrices, the light's
//! angle and camera, cascades, caster groups, moment maps, the soft filters, point and spot
//! lights, shadow volumes, and the extremes (map sizes, depth formats, far from the origin).
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod behind_light;
mod cascades;
mod esm;
mod extremes;
mod groups;
mod light_angle;
mod lights;
mod moments;
mod shadows;
mod soft;
mod soft_moments;
mod transformation;
mod volumes;
