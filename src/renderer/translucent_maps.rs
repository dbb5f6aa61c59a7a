//! The passes drawn beside the chapter's depth maps, once they are drawn: each light's
//! translucent map (`volumetric`: osm, fom, avsm) from the same light camera, and its
//! resolve.

use super::Renderer;
use crate::error::Result;
use crate::scene::Scene;

impl Renderer {
    /// Each light's translucent map, for the lights whose plan keeps one, drawn from the
    /// camera its depth pass used, and kept while neither map nor its casters change.
    pub(super) fn render_translucent_maps(&mut self, scene: &Scene) -> Result<()> {
        let boxes = self.schedule.boxes();
        let depth: Vec<_> = (self.shadows.iter().zip(self.schedule.keys()))
            .map(|(t, key)| t.as_ref().map(|t| (t.texture(), *key)))
            .collect();
        (self.volumetric).render(
            &self.gl,
            &self.gpu.meshes,
            scene,
            &self.views,
            boxes,
            &depth,
        )
    }
}
