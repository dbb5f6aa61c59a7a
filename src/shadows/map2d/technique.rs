//! The chapter's map behind [`Technique`]: its kind, whether its storage still fits, how
//! the scene pass samples it, and a patch drawn into it ([`crate::shadows::cache::patch`]).

use super::{slot_transform, Map2d};
use crate::engine::{Sampling, ShadowMap, Texture};
use crate::error::Result;
use crate::scene::{Light, Scene};
use crate::settings::{DepthLookup, ShadowSettings};
use crate::shadows::cache::patch::Patch;
use crate::shadows::{DepthPass, DepthViewKind, ShadowKind, ShadowView, SlotTransform, Technique};

impl Technique for Map2d {
    fn kind(&self) -> ShadowKind {
        ShadowKind::Map
    }

    fn fits(&self, s: &ShadowSettings) -> bool {
        self.map.size() == s.map_size && self.map.format() == s.depth_format
    }

    /// The book's `renderDepthMap`.
    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView> {
        self.draw(pass, scene, index, None)
    }

    fn patches(&self) -> bool {
        true
    }

    fn render_depth_patch(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
        patch: &Patch,
    ) -> Result<ShadowView> {
        self.draw(pass, scene, index, Some(patch))
    }

    fn texture(&self) -> &Texture {
        self.map.depth_map_texture()
    }

    /// LINEAR for the hardware's 2 x 2 comparison, or for `depth_lookup = "linear"` (each
    /// lookup an interpolated depth, the shadow-playground's colour map). A lit border and
    /// interpolated depths can be the shader's (lib/shadow_border.glsl,
    /// lib/shadow_depth.glsl) where the sampler has neither.
    fn sampling(&self, settings: &ShadowSettings) -> Sampling {
        let s = settings.effective();
        Sampling {
            compare: s.filter.hardware(),
            linear: s.filter.hardware() || s.depth_lookup == DepthLookup::Linear,
            wrap: s.wrap,
            border_in_shader: s.wrap == crate::settings::Wrap::ClampToBorder,
            interpolate_in_shader: !s.filter.hardware() && s.depth_lookup == DepthLookup::Linear,
        }
    }

    fn slot_transform(
        &self,
        _light: &Light,
        view: &ShadowView,
        settings: &ShadowSettings,
    ) -> Option<SlotTransform> {
        Some(slot_transform(view, settings))
    }

    fn bytes(&self) -> u64 {
        self.map.size().texels() * 4
    }

    fn depth_view(&self) -> DepthViewKind {
        DepthViewKind::Flat
    }

    fn depth_map(&self) -> Option<&ShadowMap> {
        Some(&self.map)
    }
}
