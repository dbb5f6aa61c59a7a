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

    /// What this frame's scene pass draws, decided before it draws: the mask's plan, the
    /// program that takes the tests or reads them (compiled, with those drawn beside it),
    /// and whether a tested pass warms up the first mask written.
    pub(super) fn plan_scene(&mut self, scene: &Scene, target: Target) -> Result<ScenePlan> {
        let mask = self.mask_plan(scene, target.size())?;
        let mode = match mask {
            Plan::Test => MaskMode::Off,
            Plan::Write(_) | Plan::Read => MaskMode::Read,
        };
        let outputs = target.outputs();
        // The first mask written (in the first frame, unless that frame could not be
        // cached): draw the frame with every light tested too, as the next frame will if
        // anything moves. llvmpipe compiles a program's shaders for the pipeline's state
        // at its first draw; this puts that here, not in the next frame.
        let warm_up = matches!(mask, Plan::Write(_)) && self.mask.uses.written == 0;
        let tests = match warm_up {
            true => Some(self.use_program(scene, outputs, MaskMode::Off)?),
            false => None,
        };
        let program = self.use_program(scene, outputs, mode)?;
        self.keep_tests_program(scene, outputs, mode)?;
        Ok(ScenePlan {
            mask,
            warm_up: tests,
            program,
        })
    }

    /// The scene pass into `target` as `plan` says: the warm-up, the mask written, then the
    /// pass itself.
    pub(super) fn draw_scene(
        &mut self,
        scene: &Scene,
        target: Target,
        plan: &ScenePlan,
        samplers: &mut Samplers,
    ) -> Result<()> {
        if let Some(tests) = plan.warm_up {
            self.draw_pass(scene, target, tests, samplers)?;
        }
        if let Plan::Write(key) = plan.mask {
            self.write_mask(scene, target.size(), key, samplers)?;
        }
        self.draw_pass(scene, target, plan.program, samplers)
    }

    /// One scene pass with `program` into `target`: the lights' volumes pass by pass, or the
    /// book's one pass.
    fn draw_pass(
        &mut self,
        scene: &Scene,
        target: Target,
        program: ProgramKey,
        samplers: &mut Samplers,
    ) -> Result<()> {
        target.bind_and_clear(&self.gl, scene.clear_colour.to_array());
        if self.uses_volumes() {
            return self.draw_volumes(scene, target.size(), program, samplers);
        }
        let inputs = self.scene_inputs(program)?;
        scene_pass::draw(&inputs, samplers, &self.gl, scene, target.size())?;
        self.volume_counted.clear();
        Ok(())
    }
}

/// What a frame's scene pass draws ([`Renderer::plan_scene`]).
pub(super) struct ScenePlan {
    /// Whether the mask is written first, read, or not used.
    mask: Plan,
    /// The program of a tested pass before the mask's first write, if this frame has one.
    warm_up: Option<ProgramKey>,
    /// The pass' program.
    program: ProgramKey,
}
