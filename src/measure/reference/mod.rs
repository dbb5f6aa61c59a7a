//! Exact CPU reference for hard shadows, for soft ones ([`area`]: a light with a size), and
//! for translucent casters ([`transmittance`]).
//!
//! Shadow maps are approximations: they trade exactness for speed and show
//! acne, peter-panning and aliased edges. To measure those errors we need the
//! true answer, so this module traces one shadow ray per G-buffer pixel
//! through a triangle BVH ([`bvh`]), turns the hits into per-pixel
//! visibility ([`visibility`]), scores a rendered image against it
//! ([`metrics`]) and dumps arrays for offline inspection ([`npy`]).
//! Everything is std plus glam, so the reference builds and runs on machines
//! without a GPU.

pub mod area;
pub mod bvh;
pub mod metrics;
pub mod npy;
pub mod transmittance;
pub mod visibility;

pub use area::{area_visibility, LightExtent};
pub use bvh::{Bvh, Triangle};
pub use metrics::{
    compute_metrics, compute_soft_metrics, error_image, penumbra_profiles, Metrics,
    PenumbraProfile, SoftMetrics,
};
pub use npy::{npy_bytes_f32_hw3, write_npy_f32_hw3};
pub use transmittance::{
    left_after, reference_transmittance, score_transmittance, transmittance_error_image, Crossing,
    Translucent, TransmittanceMetrics,
};
pub use visibility::{
    face_normals, reference_visibility, reference_visibility_supersampled, GBuffer, LightKind,
    RefPixel, RAY_EPSILON,
};
