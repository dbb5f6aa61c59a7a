//! The scene pass' setup: its program, compiled per what a frame needs (its lights' kinds,
//! the target's outputs, the shadow mask) and kept for the next frames; its inputs; and the
//! choice between the one pass, the shadow mask and the volumes' pass per light.

use super::scene_inputs::Inputs;
use super::shadow_mask::Plan;
use super::{scene_pass, Renderer, Target};
use crate::engine::{Outputs, Samplers, ShaderProgram};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shadows::program::slots::MaskMode;
use crate::shadows::program::ProgramKey;

impl Renderer {
    /// The key of the program this frame draws `outputs` with under `mask`, compiled if the
    /// cache (the last few used, the last first) does not hold it.
    pub(super) fn use_program(
        &mut self,
        scene: &Scene,
        outputs: Outputs,
        mask: MaskMode,
    ) -> Result<ProgramKey> {
        // A bench alternates a timed target and a scored one, each maybe with the mask
        // written and read.
        const KEEP: usize = 6;
        let key = self.program_key(scene, outputs)?.with_mask(mask);
        match self.scene_programs.iter().position(|(k, _)| *k == key) {
            Some(0) => {}
            Some(i) => {
                let entry = self.scene_programs.remove(i);
                self.scene_programs.insert(0, entry);
            }
            None => {
                let program = key.compile(&self.gl)?;
                self.scene_programs.insert(0, (key, program));
                self.scene_programs.truncate(KEEP);
            }
        }
        Ok(key)
    }

    /// The compiled program of `key` (one [`Renderer::use_program`] returned this frame).
    pub(super) fn program(&self, key: ProgramKey) -> Option<&ShaderProgram> {
        let found = self.scene_programs.iter().find(|(k, _)| *k == key);
        found.map(|(_, p)| p)
    }

    /// The scene program's key for this frame's lights and `outputs`, before the mask:
    /// worked out once a frame per outputs, then read back.
    pub(super) fn program_key(&self, scene: &Scene, outputs: Outputs) -> Result<ProgramKey> {
        let known = self
            .frame_keys
            .borrow()
            .iter()
            .find(|(o, _)| *o == outputs)
            .map(|k| k.1);
        if let Some(key) = known {
            return Ok(key);
        }
        let key = ProgramKey::of(scene, &self.plan, self.visibility_light, outputs)?;
        self.frame_keys.borrow_mut().push((outputs, key));
        Ok(key)
    }

    /// The scene pass' inputs: `key`'s program, the lights' techniques and views, the mask
    /// when the program reads it.
    pub(super) fn scene_inputs(&self, key: ProgramKey) -> Result<Inputs<'_>> {
        let mode = key.mask();
        let missing = || Error::Invalid("the scene program was not compiled".into());
        Ok(Inputs {
            program: self.program(key).ok_or_else(missing)?,
            shadows: &self.shadows,
            views: &self.views,
            volumetric: &self.volumetric,
            vertex_light: Some(&self.vertex_light),
            plan: &self.plan,
            meshes: &self.gpu.meshes,
            textures: &self.gpu.textures,
            white: &self.gpu.white,
            instances: &self.gpu.instances,
            pass_light: -1,
            mask: match mode {
                MaskMode::Read => self.mask.texture(),
                MaskMode::Off | MaskMode::Write | MaskMode::Vertex => None,
            },
            translucent: self.translucent_program(key),
        })
    }

    /// The scene pass into `target`, after writing the shadow mask if `plan` says so.
    pub(super) fn draw_scene(
        &mut self,
        scene: &Scene,
        target: Target,
        plan: Plan,
        samplers: &mut Samplers,
    ) -> Result<()> {
        if matches!(plan, Plan::Write(_)) && self.mask.uses.written == 0 {
            // The first mask written (in the first frame, unless that frame could not be
            // cached): draw the frame with every light tested too, as the next frame will if
            // anything moves. llvmpipe compiles a program's shaders for the pipeline's state
            // at its first draw; this puts that here, not in the next frame.
            self.draw_scene(scene, target, Plan::Test, samplers)?;
        }
        let mode = self.apply_mask_plan(scene, target.size(), plan, samplers)?;
        let key = self.use_program(scene, target.outputs(), mode)?;
        self.keep_tests_program(scene, target.outputs(), mode)?;
        target.bind_and_clear(&self.gl, scene.clear_colour.to_array());
        if self.uses_volumes() {
            return self.draw_volumes(scene, target.size(), key, samplers);
        }
        let inputs = self.scene_inputs(key)?;
        scene_pass::draw(&inputs, samplers, &self.gl, scene, target.size())?;
        self.volume_counted.clear();
        Ok(())
    }
}
