//! The renderer seen from outside: its settings and switches, what it counts, and the
//! hooks measurement attaches (the renderer does not know who measures).

use std::rc::Rc;

use super::shadow_mask::MaskUses;
use super::Renderer;
use crate::engine::{state, ShadowMap};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::settings::ShadowSettings;
use crate::shadows::cache::schedule::DepthPasses;
use crate::shadows::plan::ShadowPlan;
use crate::shadows::{CasterCounts, ShadowView};

/// The passes of a frame, for [`PassHooks`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    Depth,
    Scene,
}

/// Measurement attached from outside (the bench's GPU timers): told when a pass begins and
/// ends.
pub trait PassHooks {
    fn begin(&self, pass: Pass);
    fn end(&self, pass: Pass);
}

impl Renderer {
    pub fn settings(&self) -> &ShadowSettings {
        &self.settings
    }

    /// Each light's shadow as the last frame drew it.
    pub fn plan(&self) -> &ShadowPlan {
        &self.plan
    }

    /// Switches settings; what they change (programs, maps) is rebuilt on the next frame.
    pub fn set_settings(&mut self, settings: &ShadowSettings) -> Result<()> {
        settings.validate(self.max_texture_size)?;
        self.settings = *settings;
        self.frame_keys.get_mut().clear();
        Ok(())
    }

    /// Which light's shadow test the visibility output carries (`compare` measures one
    /// light at a time).
    pub fn set_visibility_light(&mut self, index: usize) {
        self.visibility_light = index;
        self.frame_keys.get_mut().clear();
    }

    /// Which light's map the depth view shows.
    pub fn set_depth_view_light(&mut self, index: usize) {
        self.depth_view_light = index;
    }

    /// Attaches measurement: `hooks` is told when each pass begins and ends.
    pub fn set_hooks(&mut self, hooks: Rc<dyn PassHooks>) {
        self.hooks = Some(hooks);
    }

    /// Tells the hooks, if any, that `pass` begins (or ends).
    pub(super) fn hook(&self, pass: Pass, begin: bool) {
        if let Some(h) = &self.hooks {
            match begin {
                true => h.begin(pass),
                false => h.end(pass),
            }
        }
    }

    /// The first light's 2D shadow map, if it has one (the chapters' one map).
    pub fn shadow_map(&self) -> Option<&ShadowMap> {
        self.shadows.first()?.as_deref()?.depth_map()
    }

    /// The first light's camera of the last depth pass.
    pub fn shadow_view(&self) -> Option<&ShadowView> {
        self.views.first()?.as_ref()
    }

    /// Depth passes drawn, skipped and patched so far ([`DepthPasses`]).
    pub fn depth_passes(&self) -> DepthPasses {
        self.schedule.passes()
    }

    /// Frames that wrote the cached shadow mask and frames that read it, so far.
    pub fn mask_uses(&self) -> MaskUses {
        self.mask.uses
    }

    /// The translucent items' per-vertex light captured and kept, so far.
    pub fn vertex_light_counts(&self) -> super::vertex_light_cache::VertexLightCounts {
        self.vertex_light.counts()
    }

    /// Casters drawn into maps against casters offered so far (culled per light volume;
    /// cascades cull per cascade and count only in the passes).
    pub fn caster_counts(&self) -> CasterCounts {
        self.casters
    }

    /// The pixels of shadow-volume faces that passed the depth test in the last frame
    /// (what z-fail counts: the fill the volumes cost); 0 without volumes.
    pub fn volume_pixels(&self) -> u64 {
        self.volume_counted
            .iter()
            .map(|&i| self.volume_queries[i].read())
            .sum()
    }

    /// Shadow maps in use and the bytes they take (translucent maps' bytes included).
    pub fn shadow_memory(&self) -> (usize, u64) {
        let techniques = self.shadows.iter().flatten();
        (
            techniques.clone().count(),
            techniques.map(|t| t.bytes()).sum::<u64>() + self.volumetric.bytes(),
        )
    }

    /// Each light's translucent map as the last frame drew it.
    pub fn volumetric_maps(&self) -> &crate::shadows::volumetric::Maps {
        &self.volumetric
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        state::finish(&self.gl);
    }

    /// An error unless the depth pass has made a technique slot for each of the scene's
    /// lights (`what` must come after [`Renderer::render_depth_map`]).
    pub(super) fn after_depth_map(&self, scene: &Scene, what: &str) -> Result<()> {
        match self.shadows.len() == scene.lights.len() {
            true => Ok(()),
            false => Err(Error::Invalid(format!(
                "{what} before render_depth_map: there are no shadow maps yet"
            ))),
        }
    }
}
