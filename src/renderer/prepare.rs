//! Each light's technique made to match the scene's lights and the settings, before a
//! frame's depth pass.

use super::Renderer;
use crate::engine::SamplesQuery;
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shadows::volumes::Volumes;
use crate::shadows::ShadowKind;

impl Renderer {
    /// Makes each light's technique match the scene's lights and the settings: only lights
    /// that cast get one, remade when the settings change its kind or storage.
    pub(super) fn prepare_shadows(&mut self, scene: &Scene) -> Result<()> {
        let kinds = ShadowKind::for_lights(&scene.lights, &self.settings);
        if kinds.contains(&ShadowKind::Volume) {
            if !self.volumes.as_ref().is_some_and(|v| v.fits(scene)) {
                self.volumes = Some(Volumes::new(&self.gl, scene)?);
            }
            while self.volume_queries.len() < kinds.len() {
                self.volume_queries.push(SamplesQuery::new(&self.gl)?);
            }
        }
        self.kinds.clone_from(&kinds);
        self.shadows.resize_with(kinds.len(), || None);
        self.views.resize(kinds.len(), None);
        self.schedule.resize(kinds.len());
        for (i, ((kind, shadow), light)) in kinds
            .into_iter()
            .zip(&mut self.shadows)
            .zip(&scene.lights)
            .enumerate()
        {
            let settings = light.settings(&self.settings);
            // Combinations no technique draws (a moment filter on a cube map) are refused
            // here too, for scenes built in code.
            if let Some(problem) =
                light.settings_problem(&format!("light {i}"), &settings, kind.layered())
            {
                return Err(Error::Invalid(problem));
            }
            if !light.shadow_patch().given().is_empty() {
                settings
                    .validate(self.max_texture_size)
                    .map_err(|e| Error::Invalid(format!("light {i}'s own shadow table: {e}")))?;
            }
            // Checked before any frame by the commands; this guards scenes built in code (a
            // cube map would otherwise take a soft filter as one lookup without a word).
            let (cube, cascaded) = (kind == ShadowKind::Cube, kind.layered());
            if let Some(why) = settings.filter.refused_for(cube, cascaded) {
                return Err(Error::Invalid(format!(
                    "shadow.filter = {}: light {i} cannot use it: {why}",
                    settings.filter.name()
                )));
            }
            let fits = match shadow {
                Some(t) => t.kind() == kind && t.fits(&settings),
                None => matches!(kind, ShadowKind::None | ShadowKind::Volume),
            };
            if !fits {
                *shadow = kind.create(&self.gl, &settings)?;
                self.schedule.forget(i);
            }
        }
        Ok(())
    }
}
