//! The moment filters by name (src/shadows/moments.rs draws their maps,
//! src/shadows/summed.rs reads their summed-area tables): which moments a depth pass
//! stores and which function tests them.

use crate::settings::Filter;

/// A moment filter, by name: which moments its depth pass stores and which function tests
/// them. A new one is a compile error at each place that must answer it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MomentMode {
    Vsm,
    Evsm2,
    Evsm4,
    Msm,
    /// VSM's moments read from a summed-area table (src/shadows/summed.rs).
    Vssm,
    /// MSM's moments read from a summed-area table.
    MsmSoft,
}

impl MomentMode {
    /// The moment filter `filter` is, if it is one (a depth map's filters are not).
    pub fn of(filter: Filter) -> Option<MomentMode> {
        match filter {
            Filter::Vsm => Some(MomentMode::Vsm),
            Filter::Evsm2 => Some(MomentMode::Evsm2),
            Filter::Evsm4 => Some(MomentMode::Evsm4),
            Filter::Msm => Some(MomentMode::Msm),
            Filter::Vssm => Some(MomentMode::Vssm),
            Filter::MsmSoft => Some(MomentMode::MsmSoft),
            Filter::Single | Filter::Pcf3x3 | Filter::Pcf5x5 => None,
            Filter::Hardware2x2 | Filter::Hardware3x3 => None,
            Filter::Pcf4x4Weighted | Filter::SoftPcf | Filter::Pcss => None,
        }
    }

    /// The define the depth pass is compiled with (shaders/moments_depth.frag): the
    /// moments it stores (the soft filters store VSM's and MSM's).
    pub fn depth_define(self) -> &'static str {
        match self {
            MomentMode::Vsm | MomentMode::Vssm => "MOMENT_DEPTH_VSM",
            MomentMode::Evsm2 | MomentMode::Evsm4 => "MOMENT_DEPTH_EVSM",
            MomentMode::Msm | MomentMode::MsmSoft => "MOMENT_DEPTH_MSM",
        }
    }

    /// Whether the test reads a summed-area table of the moments (src/shadows/summed.rs).
    pub fn reads_table(self) -> bool {
        match self {
            MomentMode::Vssm | MomentMode::MsmSoft => true,
            MomentMode::Vsm | MomentMode::Evsm2 | MomentMode::Evsm4 | MomentMode::Msm => false,
        }
    }
}
