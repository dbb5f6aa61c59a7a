//! Each light's technique made to match the shadow plan (the one place that decides each
//! light's kind and settings, [`crate::shadows::plan`]), before a frame's depth pass.

use super::{Renderer, Target};
use crate::engine::SamplesQuery;
use crate::error::Result;
use crate::scene::Scene;
use crate::shadows::plan::ShadowPlan;
use crate::shadows::volumes::Volumes;
use crate::shadows::ShadowKind;

impl Renderer {
    /// Makes what frames into `target` need before the first of them: each light's
    /// technique, the scene program and, when the shadow mask may serve, its programs and
    /// target (else the frame that first writes the mask would stall on two shader
    /// compiles). Each frame asks again, which costs a key comparison when nothing changed.
    pub fn prepare_frame(&mut self, scene: &Scene, target: Target) -> Result<()> {
        self.prepare_shadows(scene)?;
        let program = self.program_key(scene, target.outputs())?;
        let key = (program, target.size(), self.settings.shadow_cache);
        if self.prepared != Some(key) {
            self.prepare_mask(scene, target.size(), target.outputs())?;
            self.prepared = Some(key);
        }
        Ok(())
    }

    /// Makes each light's technique match the plan (resolved again when the settings or the
    /// lights changed): only lights that cast get one, remade when its kind or storage
    /// changes.
    pub(super) fn prepare_shadows(&mut self, scene: &Scene) -> Result<()> {
        if !self.plan.fits(&scene.lights, &self.settings) {
            let max = Some(self.max_texture_size);
            self.plan = ShadowPlan::resolve(&scene.lights, &self.settings, max)?;
            self.frame_keys.get_mut().clear();
        }
        let plan = &self.plan;
        if plan.has(ShadowKind::Volume) {
            if !self.volumes.as_ref().is_some_and(|v| v.fits(scene)) {
                self.volumes = Some(Volumes::new(&self.gl, scene)?);
            }
            while self.volume_queries.len() < plan.lights.len() {
                self.volume_queries.push(SamplesQuery::new(&self.gl)?);
            }
        }
        let n = plan.lights.len();
        self.shadows.resize_with(n, || None);
        self.views.resize(n, None);
        self.schedule.resize(n);
        for (i, (own, shadow)) in plan.lights.iter().zip(&mut self.shadows).enumerate() {
            let (kind, settings) = (own.kind, &own.settings);
            let fits = match shadow {
                Some(t) => t.kind() == kind && t.fits(settings),
                None => !kind.has_map(),
            };
            if !fits {
                *shadow = kind.create(&self.gl, settings)?;
                self.schedule.forget(i);
            }
        }
        let lights = (self.plan.lights.iter()).map(|own| (own.settings, own.volumetric));
        self.volumetric.prepare(&self.gl, lights)
    }
}
