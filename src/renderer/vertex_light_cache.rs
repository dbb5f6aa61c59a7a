//! The translucent items' per-vertex light ([`crate::shadows::program::vertex`]), kept across frames. Each
//! light's test at a vertex (its filter times the translucent lookup) depends on the
//! light's maps and on where the item is, not on the camera. So a pass of its own computes
//! it in world space for every translucent item's vertices (the capture program,
//! `VERTEX_CAPTURE` in shaders/scene.vert, into a [`VertexCapture`] by transform
//! feedback), and the translucent pass reads it back a vertex at a time, whether or not
//! the values were kept: a kept value is the recomputed one, bit for bit. It is captured
//! again only when [`key`] changes: a map drawn again, a translucent item moved, another
//! program; with `shadow_cache` off, every frame.

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use crate::engine::{Gl, Mesh, ShaderProgram, VertexCapture};
use crate::error::Result;
use crate::scene::Scene;
use crate::shadows::cache::hash_placement;
use crate::shadows::program::ProgramKey;

/// The vertex output the capture records: each light's test, light i in component i.
const VARYINGS: [&str; 1] = ["vertexLit"];

/// Captures made and kept so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct VertexLightCounts {
    pub captured: u64,
    pub kept: u64,
}

/// A number that changes whenever a translucent item's per-vertex light could: what each
/// light's maps hold (`maps`: the shadow cache's keys of the depth maps and the translucent
/// maps' keys; `None` for a map drawn every frame, and then this is `None`: capture every
/// frame), the capture `program` (each light's test and its settings), and each
/// translucent item (which, its mesh and placement, its opacity).
pub fn key(program: &ProgramKey, scene: &Scene, maps: &[Option<u64>]) -> Option<u64> {
    let mut h = DefaultHasher::new();
    for map in maps {
        map.ok_or(()).ok()?.hash(&mut h);
    }
    program.hash(&mut h);
    for (k, item) in scene.items.iter().enumerate() {
        if item.is_translucent() {
            k.hash(&mut h);
            hash_placement(item, &mut h);
            item.opacity.to_bits().hash(&mut h);
        }
    }
    Some(h.finish())
}

/// The captured values and what they were captured for.
#[derive(Default)]
pub struct VertexLight {
    capture: Option<VertexCapture>,
    program: Option<(ProgramKey, ShaderProgram)>,
    /// The [`key`] of the values held; `None`: capture again.
    holds: Option<u64>,
    /// Each scene item's first vertex in the buffer, for the items captured.
    first: Vec<Option<usize>>,
    counts: VertexLightCounts,
}

impl VertexLight {
    /// Whether the values must be captured for `key` (`None`: always); counts a kept one.
    pub fn stale(&mut self, key: Option<u64>) -> bool {
        if key.is_some() && key == self.holds && self.capture.is_some() {
            self.counts.kept += 1;
            return false;
        }
        true
    }

    /// Forgets the values: no item reads them until the next capture.
    pub fn clear(&mut self) {
        self.holds = None;
        self.first.clear();
    }

    /// Captures the values of `items` (scene index, mesh) for `key` with the capture
    /// program of `program`, compiled here when it changed: `setup` sets its per-frame
    /// uniforms and binds the maps (what it returns lives through the capture), `each`
    /// sets an item's uniforms (given it) before its vertices are drawn.
    pub fn capture<T>(
        &mut self,
        gl: &Gl,
        (program, key): (&ProgramKey, Option<u64>),
        items: &[(usize, &Mesh)],
        setup: impl FnOnce(&ShaderProgram) -> Result<T>,
        mut each: impl FnMut(&ShaderProgram, &T, usize),
    ) -> Result<()> {
        self.clear();
        if self.program.as_ref().is_none_or(|(k, _)| k != program) {
            self.program = None;
            let stage = [(glow::VERTEX_SHADER, &program.capture_source()?)];
            let compiled = ShaderProgram::capturing(gl, &stage, &[], &VARYINGS)?;
            self.program = Some((*program, compiled));
        }
        if self.capture.is_none() {
            self.capture = Some(VertexCapture::new(gl)?);
        }
        let (Some((_, p)), Some(capture)) = (&self.program, &mut self.capture) else {
            return Ok(());
        };
        let mut first = vec![None; items.iter().map(|(k, _)| k + 1).max().unwrap_or(0)];
        let mut total = 0;
        for (k, mesh) in items {
            first[*k] = Some(total);
            total += mesh.vertex_count();
        }
        p.bind();
        let bound = setup(p)?;
        let pass = capture.begin(p, total);
        for (k, mesh) in items {
            each(p, &bound, *k);
            pass.draw(mesh);
        }
        drop(pass);
        drop(bound);
        p.unbind();
        (self.first, self.holds) = (first, key);
        self.counts.captured += 1;
        Ok(())
    }

    /// Draws scene item `index` with `mesh`, each vertex reading its captured light (on
    /// scene.vert's `capturedLit`); `false` when it has none (not captured).
    pub fn draw(&self, index: usize, mesh: &Mesh) -> bool {
        match (self.first.get(index).copied().flatten(), &self.capture) {
            (Some(first), Some(capture)) => {
                capture.draw(mesh, first);
                true
            }
            _ => false,
        }
    }

    /// Captures made and kept so far.
    pub fn counts(&self) -> VertexLightCounts {
        self.counts
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::Outputs;
    use crate::settings::{ShadowSettings, TranslucentReceivers};
    use crate::shadows::plan::ShadowPlan;
    use crate::shadows::program::slots::MaskMode;

    #[test]
    fn the_key_follows_the_maps_the_program_and_the_translucent_items_not_the_camera() {
        let mut scene = Scene::load("smoke").unwrap();
        let program = |scene: &Scene, s: &ShadowSettings| {
            let plan = ShadowPlan::decide(&scene.lights, s);
            let key = ProgramKey::of(scene, &plan, 0, Outputs::default()).unwrap();
            key.with_mask(MaskMode::Vertex)
        };
        let s = ShadowSettings {
            translucent_receivers: TranslucentReceivers::Vertex,
            ..scene.shadow
        };
        let p = program(&scene, &s);
        let k0 = key(&p, &scene, &[Some(1), Some(2)]);
        assert!(k0.is_some());
        // A map drawn every frame: captured every frame.
        assert_eq!(key(&p, &scene, &[Some(1), None]), None);
        // Either map drawn again, or another program.
        assert_ne!(k0, key(&p, &scene, &[Some(3), Some(2)]));
        assert_ne!(k0, key(&p, &scene, &[Some(1), Some(3)]));
        let biased = ShadowSettings { bias: 0.01, ..s };
        assert_ne!(
            k0,
            key(&program(&scene, &biased), &scene, &[Some(1), Some(2)])
        );
        // The camera and an opaque item change nothing; a translucent item does.
        scene.camera.position.x += 1.0;
        let cube = scene.items.iter().position(|i| i.name == "cube").unwrap();
        scene.items[cube].position.x += 0.3;
        assert_eq!(k0, key(&p, &scene, &[Some(1), Some(2)]));
        let glass = scene.items.iter().position(|i| i.name == "glass").unwrap();
        let mut moved = scene.clone();
        moved.items[glass].rotation.y += 1.0;
        assert_ne!(k0, key(&p, &moved, &[Some(1), Some(2)]));
        let mut thinner = scene.clone();
        thinner.items[glass].opacity = 0.4;
        assert_ne!(k0, key(&p, &thinner, &[Some(1), Some(2)]));
    }
}
