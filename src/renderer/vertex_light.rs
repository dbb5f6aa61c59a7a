//! The translucent items' per-vertex light captured after the maps are drawn
//! ([`super::vertex_light_cache`]): the capture program takes the scene
//! pass' uniforms and maps with the world as its "view space" (the identity), so what it
//! computes does not depend on the camera and a kept value is a recomputed one.

use glam::{DMat4, Mat4};

use super::scene_inputs::{bind_maps_from, set_item_uniforms, Inputs, LightUniforms};
use super::vertex_light_cache as vertex_light;
use super::Renderer;
use crate::engine::{Mesh, Outputs, ShaderProgram};
use crate::error::Result;
use crate::scene::Scene;
use crate::shadows::program::slots::MaskMode;
use crate::shadows::ShadowKind;

impl Renderer {
    /// Captures the translucent items' per-vertex light when a light tests them per vertex
    /// and what it depends on changed ([`vertex_light::key`]); keeps it otherwise.
    pub(super) fn capture_vertex_light(&mut self, scene: &Scene) -> Result<()> {
        let program = self
            .program_key(scene, Outputs::default())?
            .with_mask(MaskMode::Vertex);
        let meshes = &self.gpu.meshes;
        let items: Vec<(usize, &Mesh)> = (scene.items.iter().enumerate())
            .filter(|(_, i)| i.is_translucent() && i.mesh < meshes.len())
            .map(|(k, i)| (k, &meshes[i.mesh]))
            .collect();
        let wanted = program.tests_per_vertex() && !self.plan.has(ShadowKind::Volume);
        if !wanted || items.is_empty() {
            self.vertex_light.clear();
            return Ok(());
        }
        let key = vertex_light::key(&program, scene, &self.map_keys());
        if !self.vertex_light.stale(key) {
            return Ok(());
        }
        let world = DMat4::IDENTITY;
        let (gl, samplers) = (&self.gl, &mut self.samplers);
        let (shadows, views, volumetric, plan) =
            (&self.shadows, &self.views, &self.volumetric, &self.plan);
        let gpu = (&self.gpu.textures, &self.gpu.white, &self.gpu.instances);
        let setup = |p: &ShaderProgram| {
            let inputs = Inputs {
                program: p,
                shadows,
                views,
                volumetric,
                vertex_light: None,
                plan,
                meshes,
                textures: gpu.0,
                white: gpu.1,
                instances: gpu.2,
                pass_light: -1,
                mask: None,
                translucent: None,
            };
            let u = LightUniforms::of(scene, &inputs, world);
            p.set_mat4("projectionMatrix", &Mat4::IDENTITY);
            u.set(p, Mat4::IDENTITY);
            p.set_i32("instanced", 0);
            let bound = bind_maps_from(&inputs, samplers, gl, scene, world)?;
            // Translucent items read their maps a little nearer the light.
            volumetric.set_matrices(p, views, world, true);
            Ok((bound, u))
        };
        let each = |p: &ShaderProgram, (_, u): &(_, LightUniforms), k: usize| {
            set_item_uniforms(p, &scene.items[k], scene, u, world, world);
        };
        (self.vertex_light).capture(gl, (&program, key), &items, setup, each)
    }

    /// What each light's maps hold: the depth maps' shadow cache keys, then the translucent
    /// maps' keys (`None`: drawn every frame).
    fn map_keys(&self) -> Vec<Option<u64>> {
        let depth = (self.shadows.iter().zip(self.schedule.keys()))
            .filter(|(t, _)| t.is_some())
            .map(|(_, key)| *key);
        let translucent = (self.volumetric.keys().iter().enumerate())
            .filter(|(i, _)| self.volumetric.get(*i).is_some())
            .map(|(_, key)| *key);
        depth.chain(translucent).collect()
    }
}
