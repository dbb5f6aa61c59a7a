//! The moment maps in the kind table: their HUD words, their storage, their bench family
//! and the settings only a moment filter's test reads.

use super::{glsl, Moments};
use crate::settings::{MomentKnob, ShadowSettings};
use crate::shadows::kind::{self, Family, IdleRules, KindFacts, Storage, TechniqueFacts};
use crate::shadows::{map2d, summed, ShadowKind};

/// The moment maps' row of the kind table.
pub const KIND: KindFacts = KindFacts {
    technique: Some(TechniqueFacts {
        create: |gl, s| Ok(Box::new(Moments::new(gl, s)?)),
        glsl,
        samplers: &map2d::SAMPLERS,
        map_slot: true,
    }),
    words: |s| {
        let blur = match s.blur.taps() {
            0 => "not blurred".to_string(),
            n => format!("blurred {n} x {n}"),
        };
        format!("Shadow: one {} moment map, {blur}", kind::sides(s.map_size))
    },
    storage,
    follows_camera: map2d::follows_camera,
    layers: None,
    // A summed-area table's box is sized by the pixel's screen derivatives.
    per_vertex: |t| t.moments().is_some_and(|m| !m.mode.reads_table()),
    family: |s| match summed::reads_table(s.filter) {
        true => Family::Soft,
        false => Family::OneMap,
    },
    idle: IdleRules {
        no_map: None,
        depth_lookup: |_| Some("a moment map is always read LINEAR (its filtering is the filter)"),
        light: |v, idle| {
            for knob in MomentKnob::ALL {
                if !(v.kind == ShadowKind::Moments && knob.read_by(v.settings.filter)) {
                    let which = knob.readers();
                    for name in knob.settings() {
                        idle.push(name, format!("it is for {which}, on a 2D map"));
                    }
                }
            }
        },
        scene: |v, idle| {
            let filters = (v.lights.iter())
                .filter(|l| l.kind == ShadowKind::Moments)
                .map(|l| l.settings.filter);
            for knob in MomentKnob::ALL {
                if !filters.clone().any(|f| knob.read_by(f)) {
                    let which = knob.readers();
                    for name in knob.settings() {
                        let why =
                            format!("no light's filter reads it (it is for {which}, on a 2D map)");
                        idle.push(name, why);
                    }
                }
            }
        },
    },
};

/// A moment map's storage: two float targets (the map and its blur's), a depth buffer, and
/// for the soft filters a summed-area table of two 32-bit sums a moment.
fn storage(s: &ShadowSettings) -> Option<Storage> {
    let texels = s.map_size.texels();
    let floats = u64::from(s.filter.moment_components()) * 4;
    let table = match summed::reads_table(s.filter) {
        true => texels * 2 * floats,
        false => 0,
    };
    Some(Storage {
        what: format!(
            "shadow.filter = {}'s moment maps of {}",
            s.filter.name(),
            kind::sides(s.map_size)
        ),
        bytes: texels * (2 * floats + kind::DEPTH_TEXEL_BYTES) + table,
    })
}
