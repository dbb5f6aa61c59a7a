//! What every depth pass shares: its programs, its fixed-function state and the loop that
//! draws the shadow casters ("Shadows": the depth pass draws every game item with the
//! light's matrices).

use glam::DMat4;

use crate::engine::{DepthState, Gl, Mesh, ShaderProgram};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::{PointPass, ShadowSettings};
use crate::shaders;

/// The depth programs, each compiled when a technique first needs it.
#[derive(Default)]
pub struct DepthPrograms {
    flat: Option<ShaderProgram>,
    /// A point light's program and whether it is the layered one.
    point: Option<(ShaderProgram, PointPass)>,
}

impl DepthPrograms {
    /// The book's depth shaders (depth.vert / depth.frag): 2D maps and cascades.
    pub fn flat(&mut self, gl: &Gl) -> Result<&ShaderProgram> {
        if self.flat.is_none() {
            self.flat = Some(ShaderProgram::new(
                gl,
                &shaders::depth_vert(),
                &shaders::depth_frag(),
                &[],
            )?);
        }
        match &self.flat {
            Some(p) => Ok(p),
            None => Err(crate::Error::Invalid("the depth program is missing".into())),
        }
    }

    /// A point light's program: six passes, or one layered pass through a geometry shader.
    pub fn point(&mut self, gl: &Gl, pass: PointPass) -> Result<&ShaderProgram> {
        if self.point.as_ref().map(|(_, p)| *p) != Some(pass) {
            let program = match pass {
                PointPass::Layered => ShaderProgram::from_stages(
                    gl,
                    &[
                        (glow::VERTEX_SHADER, &shaders::depth_point_layered_vert()),
                        (glow::GEOMETRY_SHADER, &shaders::depth_point_layered_geom()),
                        (glow::FRAGMENT_SHADER, &shaders::depth_point_frag()),
                    ],
                    &[],
                )?,
                PointPass::SixPasses => ShaderProgram::new(
                    gl,
                    &shaders::depth_point_vert(),
                    &shaders::depth_point_frag(),
                    &[],
                )?,
            };
            self.point = Some((program, pass));
        }
        match &self.point {
            Some((p, _)) => Ok(p),
            None => Err(crate::Error::Invalid(
                "the point depth program is missing".into(),
            )),
        }
    }
}

/// The depth pass' state under `settings`: culling and polygon offset.
pub fn depth_state(settings: &ShadowSettings) -> DepthState {
    DepthState {
        cull: settings.cull,
        polygon_offset: settings.polygon_offset,
    }
}

/// Draws every shadow caster that `keep` (by item index) lets through, one mesh's items at a
/// time, with `uniform` set to `light * model` (composed in double precision).
pub fn draw_casters(
    meshes: &[Mesh],
    scene: &Scene,
    program: &ShaderProgram,
    uniform: &'static str,
    light: DMat4,
    keep: impl Fn(usize) -> bool,
) {
    for (mesh_id, mesh) in meshes.iter().enumerate() {
        let items = scene
            .items
            .iter()
            .enumerate()
            .filter(|(k, i)| i.mesh == mesh_id && i.casts_shadows && keep(*k))
            .map(|(_, i)| i);
        mesh.render_list(items, |item| {
            program.set_mat4(uniform, &(light * item.model_matrix64()).as_mat4());
        });
    }
}
