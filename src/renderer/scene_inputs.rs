//! What the scene pass ([`super::scene_pass`]) reads: its inputs, the per-light uniforms
//! (view space), and each light's map bound on its texture unit with its sampler.

use glam::{DMat4, Mat3, Mat4, Vec3, Vec4};

use crate::engine::{BoundSampler, Gl, InstanceBuffer, Mesh, Samplers, ShaderProgram, Texture};
use crate::error::Result;
use crate::image_data::ImageData;
use crate::scene::{GameItem, Light, Scene, Shading};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::program::slots;
use crate::shadows::{ShadowView, Technique};

/// The scene's meshes and textures on the GPU (the book's `Mesh` and `Texture`).
pub(super) struct SceneGpu {
    pub meshes: Vec<Mesh>,
    pub textures: Vec<Texture>,
    /// 1 x 1 white, for items without a texture.
    pub white: Texture,
    /// The per-instance values of the instanced draws, every pass' in turn.
    pub instances: InstanceBuffer,
}

impl SceneGpu {
    pub(super) fn upload(gl: &Gl, scene: &Scene) -> Result<SceneGpu> {
        let meshes = scene
            .meshes
            .iter()
            .map(|m| Mesh::new(gl, m))
            .collect::<Result<Vec<_>>>()?;
        let textures = scene
            .textures
            .iter()
            .map(|t| Texture::from_image(gl, t))
            .collect::<Result<Vec<_>>>()?;
        let white = ImageData {
            width: 1,
            height: 1,
            rgba: vec![255; 4],
        };
        Ok(SceneGpu {
            meshes,
            textures,
            white: Texture::from_image(gl, &white)?,
            instances: InstanceBuffer::new(gl)?,
        })
    }
}

/// What the pass reads.
pub struct Inputs<'a> {
    pub program: &'a ShaderProgram,
    pub shadows: &'a [Option<Box<dyn Technique>>],
    pub views: &'a [Option<ShadowView>],
    /// Each light's translucent map, if it keeps one.
    pub volumetric: &'a crate::shadows::volumetric::Maps,
    /// The translucent items' per-vertex light, where it is tested per vertex.
    pub vertex_light: Option<&'a super::vertex_light_cache::VertexLight>,
    /// Each light's kind and settings.
    pub plan: &'a ShadowPlan,
    pub meshes: &'a [Mesh],
    pub textures: &'a [Texture],
    pub white: &'a Texture,
    pub instances: &'a InstanceBuffer,
    /// With shadow volumes, the light this pass adds (-1: the ambient pass); unused
    /// otherwise.
    pub pass_light: i32,
    /// The cached shadow mask, for a program that reads it.
    pub mask: Option<&'a Texture>,
    /// The program the translucent items are drawn with: `program`, or beside a program
    /// that reads the mask, the one that tests ([`super::translucent_pass`]); `None`
    /// while the mask is written (it holds the opaque receivers' tests alone).
    pub translucent: Option<&'a ShaderProgram>,
}

/// The per-light uniform arrays of the scene pass (view space), and the per-slot ones of
/// the lights with a 2D or cube map ([`slots::map_slots`]).
pub(super) struct LightUniforms {
    /// Each light's colour times its intensity.
    pub colour: Vec<Vec3>,
    /// A positional light's position, or the direction towards a directional one.
    position_or_direction: Vec<Vec3>,
    cone_cos: Vec<f32>,
    cone_axis: Vec<Vec3>,
    far: Vec<f32>,
    /// PCSS's (S.x, S.y, near, far) per light: see [`penumbra`].
    penumbra: Vec<Vec4>,
    /// Each 2D map's (near, far, 0, 0), for a test biased in linear depth
    /// (shaders/lib/linear_depth.glsl).
    depth_range: Vec<Vec4>,
    /// World to the light's view (a point light: to the light's position), per map slot.
    pub light_from: Vec<DMat4>,
    /// Per map slot.
    normal_offset: Vec<f32>,
    projection: Vec<Mat4>,
    /// Its rotation (for normal offsets), per map slot.
    rotation: Vec<Mat3>,
}

impl LightUniforms {
    pub(super) fn of(scene: &Scene, inputs: &Inputs, view64: DMat4) -> LightUniforms {
        let view = view64.as_mat4();
        let n = scene.lights.len();
        let kinds = inputs.shadows.iter().map(|s| {
            s.as_ref()
                .map_or(crate::shadows::ShadowKind::None, |t| t.kind())
        });
        let slot_of = slots::map_slots(kinds);
        let mapped = slot_of.iter().flatten().count().max(1);
        let mut u = LightUniforms {
            colour: Vec::with_capacity(n),
            position_or_direction: vec![Vec3::Z; n],
            cone_cos: vec![-2.0; n],
            cone_axis: vec![Vec3::Z; n],
            far: vec![1.0; n],
            penumbra: vec![Vec4::ZERO; n],
            depth_range: vec![Vec4::ZERO; n],
            normal_offset: vec![0.0; mapped],
            projection: vec![Mat4::IDENTITY; mapped],
            light_from: vec![DMat4::IDENTITY; mapped],
            rotation: vec![Mat3::IDENTITY; mapped],
        };
        for (i, light) in scene.lights.iter().enumerate() {
            u.colour.push(light.colour() * light.intensity());
            match light.shading() {
                Shading::Direction(d) => u.position_or_direction[i] = view.transform_vector3(d),
                Shading::Position { position, cone } => {
                    u.position_or_direction[i] =
                        view64.transform_point3(position.as_dvec3()).as_vec3();
                    if let Some((cos, axis)) = cone {
                        u.cone_cos[i] = cos;
                        u.cone_axis[i] = view.transform_vector3(axis);
                    }
                }
            }
            if let Light::Point(l) = light {
                u.far[i] = l.far;
            }
            let (Some(p), Some(Some(t)), Some(Some(v))) =
                (slot_of[i], inputs.shadows.get(i), inputs.views.get(i))
            else {
                continue;
            };
            u.penumbra[i] = penumbra(light, v);
            u.depth_range[i] = Vec4::new(v.near, v.far, 0.0, 0.0);
            if let Some(s) = t.slot_transform(light, v, &inputs.plan.lights[i].settings) {
                u.normal_offset[p] = s.normal_offset;
                u.projection[p] = s.projection;
                u.light_from[p] = s.from;
                u.rotation[p] = Mat3::from_mat4(s.from.as_mat4());
            }
        }
        u
    }

    /// Sets the per-light arrays, and the matrices from view space back to world space
    /// (`view` is rigid: the transpose of its rotation undoes it; G-buffer outputs) and to
    /// each map.
    pub(super) fn set(&self, p: &ShaderProgram, view: Mat4) {
        p.set_vec3_array("lightPositionOrDirection", &self.position_or_direction);
        p.set_f32_array("lightConeCos", &self.cone_cos);
        p.set_vec3_array("lightConeAxis", &self.cone_axis);
        p.set_f32_array("lightFar", &self.far);
        p.set_vec4_array("lightPenumbra", &self.penumbra);
        p.set_vec4_array("lightDepthRange", &self.depth_range);
        p.set_f32_array("normalOffset", &self.normal_offset);
        p.set_mat3_array("lightRotation", &self.rotation);
        p.set_mat3("viewToWorld", &Mat3::from_mat4(view).transpose());
        p.set_mat4_array("orthoProjectionMatrix", &self.projection);
    }
}

/// Binds each light's map and sampler on its unit for `p` (none when `p` reads the shadow
/// mask: it has no test) and sets the techniques' own uniforms; the samplers unbind when
/// the returned list drops.
pub(super) fn bind_maps(
    inputs: &Inputs,
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
) -> Result<Vec<BoundSampler>> {
    bind_maps_from(inputs, samplers, gl, scene, scene.camera.view_matrix64())
}

/// [`bind_maps`] for a program whose "view space" is `camera_view`'s (the per-vertex
/// capture's: world space, the identity).
pub(super) fn bind_maps_from(
    inputs: &Inputs,
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
    camera_view: DMat4,
) -> Result<Vec<BoundSampler>> {
    let p = inputs.program;
    let mut bound: Vec<BoundSampler> = Vec::with_capacity(inputs.shadows.len());
    let tested = match inputs.mask {
        Some(_) => &[][..],
        None => inputs.shadows,
    };
    for (i, (shadow, own)) in tested.iter().zip(&inputs.plan.lights).enumerate() {
        let Some(t) = shadow else { continue };
        let settings = &own.settings;
        t.set_scene_uniforms(p, scene, settings);
        if let Some(name) = t.kind().sampler(i) {
            let unit = crate::shadows::units::texture_unit(i);
            p.set_i32(name, unit as i32);
            let sampling = t.sampling(settings);
            crate::engine::sampler::check_readable(gl, t.texture(), sampling)?;
            // Only an ES program declares them (lib/shadow_border.glsl,
            // lib/shadow_depth.glsl): nothing to do on the desktop's hot path.
            if crate::engine::Dialect::of(gl) == crate::engine::Dialect::Es {
                let border = i32::from(sampling.border_in_shader);
                p.set_i32(crate::shadows::map2d::BORDER_LIT[i], border);
                let interpolated = i32::from(sampling.interpolate_in_shader);
                p.set_i32(crate::shadows::map2d::DEPTH_INTERPOLATED[i], interpolated);
            }
            t.texture().bind(unit);
            bound.push(samplers.get(gl, sampling)?.bind(unit));
        }
    }
    if inputs.mask.is_none() {
        (inputs.volumetric).bind(p, inputs.views, camera_view);
    }
    Ok(bound)
}

/// PCSS's constants for a light's 2D map (shaders/lib/pcss.glsl): its size in the
/// map's units per distance, S = (size term) x (P[0][0], P[1][1]) / 2 with P the light's
/// projection, and its near and far planes. The size term is a perspective map's light
/// radius (a directional light's angular radius seen from its shadow position), or an
/// orthographic map's tan of the angular radius.
fn penumbra(light: &Light, view: &ShadowView) -> Vec4 {
    let half_angle = || (light.size().to_radians() * 0.5).tan();
    let size = match (light, view.perspective) {
        (Light::Directional(l), true) => l.shadow_pos_mult.abs() * half_angle(),
        (Light::Directional(_), false) => half_angle(),
        (Light::Spot(_) | Light::Point(_), _) => light.size(),
    };
    let scale = glam::Vec2::new(view.projection.x_axis.x, view.projection.y_axis.y) * 0.5;
    (scale.abs() * size).extend(view.near).extend(view.far)
}

/// The matrix that carries normals: the inverse transpose of the upper 3 x 3, so normals
/// stay perpendicular under non-uniform scale.
pub(super) fn normal_matrix(m: &Mat4) -> Mat3 {
    Mat3::from_mat4(*m).inverse().transpose()
}

/// One item's per-item uniforms (the book's loop: "set the model matrix, draw"), for the
/// items drawn one at a time: translucent ones, and a run of one.
pub(super) fn set_item_uniforms(
    p: &ShaderProgram,
    item: &GameItem,
    scene: &Scene,
    u: &LightUniforms,
    view64: DMat4,
    origin: DMat4,
) {
    let model = item.model_matrix64();
    let model_view = (view64 * model).as_mat4();
    p.set_mat4("modelOriginMatrix", &(origin * model).as_mat4());
    p.set_mat4("modelViewMatrix", &model_view);
    p.set_mat3("normalMatrix", &normal_matrix(&model_view));
    p.set_mat3("worldNormalMatrix", &normal_matrix(&model.as_mat4()));
    let light_matrices: Vec<Mat4> = (u.light_from.iter())
        .map(|from| (*from * model).as_mat4())
        .collect();
    p.set_mat4_array("modelLightViewMatrix", &light_matrices);
    let m = &item.material;
    let colour = m.colour.truncate();
    p.set_vec4(
        "material.ambient",
        (scene.ambient * colour).extend(m.reflectance),
    );
    let diffuse: Vec<Vec3> = u.colour.iter().map(|light| *light * colour).collect();
    p.set_vec3_array("material.diffuse", &diffuse);
}
