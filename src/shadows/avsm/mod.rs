//! Adaptive volumetric shadow maps (Salvi et al., EGSR 2010; the slides' last "Advanced
//! techniques" link): per texel a short curve of transmittance against depth, built from the
//! light's translucent fragments peeled layer by layer, looked up between its nodes.

pub mod curve;
