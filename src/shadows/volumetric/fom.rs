//! Fourier opacity maps (Jansen and Bavoil 2010, "Fourier Opacity Mapping"): the optical
//! depth's density along the light's depth t (0 to 1 over the translucent casters), a sum
//! of spikes -ln(1 - a) at the crossings, kept as the first terms of its Fourier series:
//! the mean and, for k = 1 to N, a cosine and a sine coefficient, each crossing adding
//! its share (additive blending, any order). A receiver at t integrates the series from 0
//! to t, each term damped by Lanczos' sigma factor against ringing, and takes exp(-it),
//! clamped to [0, 1]. At t = 1 every term but the mean integrates to 0: exact behind the
//! medium. `shaders/fom_map.frag`, `shaders/lib/fom.glsl`; 1 + 2N floats in RGBA32F layers.

use super::additive::Additive;
use crate::shaders;

/// The technique (`volumetric = "fom"`, `fom_coefficients` N): the mean and N cosine and
/// sine pairs, four to a layer.
pub static FOM: Additive = Additive {
    count: |s| s.fom_coefficients,
    settings: &["fom_coefficients"],
    layers: |terms| (1 + 2 * terms).div_ceil(4),
    define: "TERMS",
    fragment: shaders::fom_map_frag,
    library: "lib/fom.glsl",
    function: "fomTransmittance",
};
