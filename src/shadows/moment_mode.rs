//! The moment filters by name (src/shadows/moments/mod.rs draws their maps,
//! src/shadows/summed.rs reads their summed-area tables): which moments a depth pass
//! stores and which function tests them, from their rows of [`MomentMode::facts`].

use crate::settings::{Filter, MomentDepth};

pub use crate::settings::MomentMode;

impl MomentMode {
    /// The moment filter `filter` is, if it is one (a depth map's filters are not).
    pub fn of(filter: Filter) -> Option<MomentMode> {
        filter.facts().moments
    }

    /// The define the depth pass is compiled with (shaders/moments_depth.frag): the
    /// moments it stores (the soft filters store VSM's and MSM's).
    pub fn depth_define(self) -> &'static str {
        match self.facts().depth {
            MomentDepth::Vsm => "MOMENT_DEPTH_VSM",
            MomentDepth::Evsm => "MOMENT_DEPTH_EVSM",
            MomentDepth::Msm => "MOMENT_DEPTH_MSM",
            MomentDepth::Esm => "MOMENT_DEPTH_ESM",
        }
    }

    /// Whether the test reads a summed-area table of the moments (src/shadows/summed.rs).
    pub fn reads_table(self) -> bool {
        self.facts().table
    }
}
