//! Opacity shadow maps (Kim and Neumann 2001, "Opacity Shadow Maps"): the light's depth
//! between the nearest and farthest translucent caster cut into K slices; each crossing
//! adds its optical depth, -ln(1 - a), to the slice it falls in (additive blending, so the
//! order of the casters does not matter). A receiver's transmittance is exp(-(the slices
//! before its own, and the part of its own it is past)): exact behind the medium, a ramp
//! across a slice within it. Four slices to an RGBA32F layer (`shaders/osm_map.frag`,
//! `shaders/lib/osm.glsl`).

use super::additive::Additive;
use crate::shaders;

/// The technique (`volumetric = "osm"`, `osm_slices` K): four slices to a layer.
pub static OSM: Additive = Additive {
    count: |s| s.osm_slices,
    settings: &["osm_slices"],
    layers: |slices| slices.div_ceil(4),
    define: "SLICES",
    fragment: shaders::osm_map_frag,
    library: "lib/osm.glsl",
    function: "osmTransmittance",
};
