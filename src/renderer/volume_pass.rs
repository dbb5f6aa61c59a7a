//! The frame with stencil shadow volumes (`crate::shadows::volumes`): an ambient pass that
//! lays down depth, then per light: clear the stencil, count that light's volumes (z-fail),
//! and add its light where the count is 0. Lights with a map take part too (their pass
//! tests their map and ignores the stencil), so techniques mix within a scene; every pass
//! shades with the same `shaders/lib/lighting.glsl`, so an unshadowed pixel is the one
//! pass' colour up to the rounding of each addition.

use glam::Vec4;

use super::scene_inputs::Inputs;
use super::scene_pass;
use super::Renderer;
use crate::engine::volume::clear_stencil;
use crate::engine::{Gl, LightPass, LightPassGuard, Samplers, SamplesQuery};
use crate::engine::{VolumeDraw, VolumePassGuard};
use crate::error::{Error, Result};
use crate::scene::Scene;
use crate::shadows::plan::ShadowPlan;
use crate::shadows::program::ProgramKey;
use crate::shadows::volumes::Volumes;
use crate::shadows::ShadowKind;

/// The debug view's colours, one per light (translucent, so overlaps show).
const COLOURS: [Vec4; 4] = [
    Vec4::new(1.0, 0.85, 0.1, 0.18),
    Vec4::new(0.2, 0.6, 1.0, 0.18),
    Vec4::new(1.0, 0.3, 0.3, 0.18),
    Vec4::new(0.3, 1.0, 0.4, 0.18),
];

impl Renderer {
    /// Whether a light has shadow volumes (and their meshes are made): the scene pass is
    /// then one pass per light.
    pub(super) fn uses_volumes(&self) -> bool {
        self.volumes.is_some() && self.plan.has(ShadowKind::Volume)
    }

    /// The frame with volumes into the bound, cleared target of `size`, with the volumes'
    /// debug view over it when asked; keeps which queries counted volume pixels.
    pub(super) fn draw_volumes(
        &mut self,
        scene: &Scene,
        size: (u32, u32),
        program: ProgramKey,
        samplers: &mut Samplers,
    ) -> Result<()> {
        let Some(volumes) = &self.volumes else {
            return Err(Error::Invalid("the shadow volumes are missing".into()));
        };
        let (inputs, gl) = (self.scene_inputs(program)?, &self.gl);
        let queries = &self.volume_queries;
        let light = self.visibility_light;
        let counted = draw(&inputs, volumes, light, queries, samplers, gl, scene, size)?;
        if self.settings.show_volumes {
            draw_debug(volumes, &self.plan, gl, scene, size);
        }
        self.volume_counted = counted;
        Ok(())
    }
}

/// Draws the frame into the bound, cleared target. `queries` (one per light) count the
/// volume pixels that passed the depth test; returns their sum.
#[allow(clippy::too_many_arguments)]
pub fn draw(
    inputs: &Inputs,
    volumes: &Volumes,
    visibility_light: usize,
    queries: &[SamplesQuery],
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
    size: (u32, u32),
) -> Result<Vec<usize>> {
    // Ambient (and depth, and the extra outputs: the measured light is 0 here).
    scene_pass::draw(
        &Inputs {
            pass_light: -1,
            ..*inputs
        },
        samplers,
        gl,
        scene,
        size,
    )?;
    let mut counted = Vec::new();
    for (i, own) in inputs.plan.lights.iter().enumerate() {
        let stencil_lit = own.kind == ShadowKind::Volume;
        if stencil_lit {
            clear_stencil(gl);
            let _pass = VolumePassGuard::begin(gl, VolumeDraw::Stencil);
            let query = queries.get(i);
            query.inspect(|q| q.begin());
            volumes.draw(scene, &own.settings, i, size, Vec4::ZERO);
            if let Some(q) = query {
                q.end();
                counted.push(i);
            }
        }
        let _pass = LightPassGuard::begin(
            gl,
            LightPass {
                stencil_lit,
                extra_outputs: i == visibility_light,
            },
        );
        scene_pass::draw(
            &Inputs {
                pass_light: i as i32,
                ..*inputs
            },
            samplers,
            gl,
            scene,
            size,
        )?;
    }
    Ok(counted)
}

/// The debug view: every volume light's faces, translucent, over the finished frame.
pub fn draw_debug(volumes: &Volumes, plan: &ShadowPlan, gl: &Gl, scene: &Scene, size: (u32, u32)) {
    let _pass = VolumePassGuard::begin(gl, VolumeDraw::Debug);
    for (i, own) in plan.lights.iter().enumerate() {
        if own.kind == ShadowKind::Volume {
            volumes.draw(scene, &own.settings, i, size, COLOURS[i % COLOURS.len()]);
        }
    }
}
