//! Translucent casters against the transmittance truth: the translucent maps (osm, fom, avsm),
//! their receivers, the resolved map, self-shadowing, kept maps and the per-vertex light.
//!
//! One test binary per area (docs/architecture.md, "The tests"); each file a module.

#[path = "../common/mod.rs"]
mod common;

mod avsm;
mod ramp;
mod receivers;
mod resolved;
mod self_shadow;
mod sheets;
mod vertex_cache;
