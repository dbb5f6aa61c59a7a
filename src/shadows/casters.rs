//! What every depth pass shares: its programs, its fixed-function state and the loop that
//! draws the shadow casters ("Shadows": the depth pass draws every game item with the
//! light's matrices).

use std::rc::Rc;

use glam::{DMat4, Vec4};

use crate::engine::instances;
use crate::engine::{DepthState, Gl, InstanceBuffer, Mesh, ShaderProgram};
use crate::error::Result;
use crate::scene::{GameItem, Scene};
use crate::settings::{PointPass, ShadowSettings, Volumetric};
use crate::shaders;

use super::camera::culling::may_land;
use super::{DepthPass, ShadowView};

/// The depth programs, each compiled when a technique first needs it.
#[derive(Default)]
pub struct DepthPrograms {
    /// Shared, so a pass can hold it while it hands its [`super::DepthPass`] on.
    flat: Option<Rc<ShaderProgram>>,
    /// The same with `LINEAR_DEPTH`: a perspective map's linear depth.
    linear: Option<Rc<ShaderProgram>>,
    /// A point light's program and whether it is the layered one.
    point: Option<(ShaderProgram, PointPass)>,
}

impl DepthPrograms {
    /// The book's depth shaders (depth.vert / depth.frag): 2D maps and cascades.
    pub fn flat(&mut self, gl: &Gl) -> Result<Rc<ShaderProgram>> {
        Self::get(&mut self.flat, gl, &[])
    }

    /// The same shaders writing linear depth (`LINEAR_DEPTH`): a perspective 2D map that
    /// [`super::map2d::stores_linear_depth`].
    pub fn linear(&mut self, gl: &Gl) -> Result<Rc<ShaderProgram>> {
        Self::get(&mut self.linear, gl, &[("LINEAR_DEPTH".into(), "1".into())])
    }

    fn get(
        slot: &mut Option<Rc<ShaderProgram>>,
        gl: &Gl,
        defines: &[(String, String)],
    ) -> Result<Rc<ShaderProgram>> {
        if slot.is_none() {
            *slot = Some(Rc::new(ShaderProgram::new(
                gl,
                &shaders::depth_vert(),
                &shaders::depth_frag(),
                defines,
            )?));
        }
        match slot {
            Some(p) => Ok(Rc::clone(p)),
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

/// The scene's shadow casters.
pub fn casters(scene: &Scene) -> u64 {
    scene.items.iter().filter(|i| i.casts_shadows).count() as u64
}

/// The depth pass' state under `settings`: culling and polygon offset, the whole map.
pub fn depth_state(settings: &ShadowSettings) -> DepthState {
    DepthState {
        cull: settings.cull,
        polygon_offset: settings.polygon_offset,
        scissor: None,
    }
}

/// Draws light `index`'s casters into the bound 2D map with `program` (depth.vert's
/// uniforms), seen through `view`, and counts them: only casters that can land in the map,
/// the rest would be clipped anyway, and of those only the ones in `only` when given (the
/// casters a fitted box was fitted to). With `volumetric = "solid"` the translucent casters
/// are drawn too, as opaque ones, every one of them.
pub fn draw_map_casters(
    pass: &mut DepthPass,
    scene: &Scene,
    index: usize,
    view: &ShadowView,
    program: &ShaderProgram,
    only: Option<&[usize]>,
) {
    program.set_mat4("orthoProjectionMatrix", &view.projection);
    let light = &scene.lights[index];
    let boxes = pass.boxes;
    let solid = pass.settings.volumetric == Volumetric::Solid;
    let keep = |k: usize| {
        if scene.items[k].casts_translucent {
            return true; // drawn only when solid, every one of them
        }
        only.is_none_or(|o| o.contains(&k)) && may_land(light, view, boxes[k].0, boxes[k].1)
    };
    let drawn = draw_casters_with(pass.gpu(), scene, program, view.view64, keep, None, solid);
    let solid_casters = match solid {
        true => scene.items.iter().filter(|i| i.casts_translucent).count() as u64,
        false => 0,
    };
    pass.casters.drawn += drawn as u64;
    pass.casters.total += casters(scene) + solid_casters;
}

/// Draws every shadow caster that `keep` (by item index) lets through with `light * model`
/// (composed in double precision) as its matrix (`modelLightViewMatrix` or
/// `modelLightMatrix`); returns how many it drew. The book draws them one at a time; here
/// the pass' casters are instanced, one draw per mesh ([`draw_casters_with`]).
pub fn draw_casters(
    (meshes, instances): (&[Mesh], &InstanceBuffer),
    scene: &Scene,
    program: &ShaderProgram,
    light: DMat4,
    keep: impl Fn(usize) -> bool,
) -> usize {
    draw_casters_with(
        (meshes, instances),
        scene,
        program,
        light,
        keep,
        None,
        false,
    )
}

/// [`draw_casters`], with `faces` giving each drawn item (by index) a texel of its own after
/// its matrix (a cube map's faces to draw it into), and with `translucent` the translucent
/// casters drawn as opaque ones (`volumetric = "solid"`). The casters are gathered mesh by mesh in
/// scene order (the book's order), their matrices uploaded at once, and each mesh's drawn
/// with one instanced call.
pub fn draw_casters_with(
    (meshes, instances): (&[Mesh], &InstanceBuffer),
    scene: &Scene,
    program: &ShaderProgram,
    light: DMat4,
    keep: impl Fn(usize) -> bool,
    faces: Option<&dyn Fn(usize) -> Vec4>,
    translucent: bool,
) -> usize {
    let mut kept: Vec<(usize, &GameItem)> = (scene.items.iter().enumerate())
        .filter(|(k, i)| {
            let casts = i.casts_shadows || (translucent && i.casts_translucent);
            i.mesh < meshes.len() && casts && keep(*k)
        })
        .collect();
    kept.sort_by_key(|(_, i)| i.mesh);
    let stride = if faces.is_some() { 5 } else { 4 };
    let instanced = instances.fill(program, stride, |t| {
        for (k, item) in &kept {
            t.mat4(&(light * item.model_matrix64()).as_mat4());
            if let Some(f) = faces {
                t.vec4(f(*k));
            }
        }
    });
    // The per-item uniforms of the depth programs, for runs of one.
    let uniform = match program.uses("modelLightViewMatrix") {
        true => "modelLightViewMatrix",
        false => "modelLightMatrix",
    };
    for b in instances::batches(kept.iter().map(|(_, i)| i.mesh)) {
        if b.count > 1 {
            instanced.draw(&meshes[b.key], &b);
            continue;
        }
        let (k, item) = kept[b.first];
        instanced.draw_one(&meshes[b.key], |p| {
            p.set_mat4(uniform, &(light * item.model_matrix64()).as_mat4());
            if let Some(f) = faces {
                p.set_i32("faceMask", f(k).x as i32);
            }
        });
    }
    kept.len()
}
