//! The moment filters by name (src/shadows/moments.rs draws their maps,
//! src/shadows/summed.rs reads their summed-area tables): which moments a depth pass
//! stores and which function tests them.

use crate::settings::Filter;

pub use crate::settings::MomentMode;

impl MomentMode {
    /// The moment filter `filter` is, if it is one (a depth map's filters are not).
    pub fn of(filter: Filter) -> Option<MomentMode> {
        filter.facts().moments
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
