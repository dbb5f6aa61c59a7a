//! The scene pass' inputs: per-light uniforms (view space), each light's map on its texture
//! unit with its sampler, and the per-item matrices and colours ("Shadows": the scene
//! shader gets `modelLightViewMatrix` and `orthoProjectionMatrix` besides the camera's).

use glam::{DMat4, Mat3, Mat4, Vec3, Vec4};

use crate::engine::{BoundSampler, Gl, Mesh, Samplers, ShaderProgram, Texture};
use crate::error::Result;
use crate::scene::{Light, Scene, Shading};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::slots::{self, MASK_UNIT, MATERIAL_UNIT};
use crate::shadows::{ShadowView, Technique};

/// What the pass reads.
pub struct Inputs<'a> {
    pub program: &'a ShaderProgram,
    pub shadows: &'a [Option<Box<dyn Technique>>],
    pub views: &'a [Option<ShadowView>],
    /// Each light's kind and settings.
    pub plan: &'a ShadowPlan,
    pub meshes: &'a [Mesh],
    pub textures: &'a [Texture],
    pub white: &'a Texture,
    /// With shadow volumes, the light this pass adds (-1: the ambient pass); unused
    /// otherwise.
    pub pass_light: i32,
    /// The cached shadow mask, for a program that reads it.
    pub mask: Option<&'a Texture>,
}

/// Draws every item with `inputs.program` (bound here) into the bound target.
pub fn draw(
    inputs: &Inputs,
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
    (width, height): (u32, u32),
) -> Result<()> {
    let p = inputs.program;
    // View x model in double precision: far from the origin the two translations cancel,
    // and in single precision their difference would lose its digits.
    let view64 = scene.camera.view_matrix64();
    let view = view64.as_mat4();
    // World outputs are written relative to the camera for the same reason.
    let origin = DMat4::from_translation(-scene.camera.position.as_dvec3());
    p.bind();
    p.set_mat4(
        "projectionMatrix",
        &scene.camera.projection_matrix(width, height),
    );
    let u = LightUniforms::of(scene, inputs, view64);
    p.set_vec3_array("lightPositionOrDirection", &u.position_or_direction);
    p.set_f32_array("lightConeCos", &u.cone_cos);
    p.set_vec3_array("lightConeAxis", &u.cone_axis);
    p.set_f32_array("lightFar", &u.far);
    p.set_vec4_array("lightPenumbra", &u.penumbra);
    p.set_f32_array("normalOffset", &u.normal_offset);
    p.set_mat3_array("lightRotation", &u.rotation);
    // The view is rigid: the transpose of its rotation undoes it (G-buffer outputs).
    p.set_mat3("viewToWorld", &Mat3::from_mat4(view).transpose());
    p.set_mat4_array("orthoProjectionMatrix", &u.projection);
    p.set_i32("textureSampler", MATERIAL_UNIT as i32);
    p.set_i32("passLight", inputs.pass_light);
    if let Some(mask) = inputs.mask {
        p.set_i32("shadowMask", MASK_UNIT as i32);
        mask.bind(MASK_UNIT);
    }
    // Each light's map and sampler on its unit, for the pass; the samplers unbind when
    // `bound` drops.
    let mut bound: Vec<BoundSampler> = Vec::with_capacity(inputs.shadows.len());
    // A program reading the mask has no test: nothing to bind for the maps.
    let tested = match inputs.mask {
        Some(_) => &[][..],
        None => inputs.shadows,
    };
    for (i, (shadow, own)) in tested.iter().zip(&inputs.plan.lights).enumerate() {
        let Some(t) = shadow else { continue };
        let settings = &own.settings;
        t.set_scene_uniforms(p, scene, settings);
        if let Some(name) = slots::sampler_name(i, t.kind()) {
            let unit = slots::texture_unit(i);
            p.set_i32(name, unit as i32);
            t.texture().bind(unit);
            bound.push(samplers.get(gl, t.sampling(settings))?.bind(unit));
        }
    }
    let mut light_matrices = vec![Mat4::IDENTITY; u.light_from.len()];
    let mut diffuse = vec![Vec3::ZERO; u.colour.len()];
    for (mesh_id, mesh) in inputs.meshes.iter().enumerate() {
        let items = scene.items.iter().filter(|i| i.mesh == mesh_id);
        mesh.render_list(items, |item| {
            let model = item.model_matrix64();
            let model_view = (view64 * model).as_mat4();
            p.set_mat4("modelOriginMatrix", &(origin * model).as_mat4());
            p.set_mat4("modelViewMatrix", &model_view);
            p.set_mat3("normalMatrix", &normal_matrix(&model_view));
            p.set_mat3("worldNormalMatrix", &normal_matrix(&model.as_mat4()));
            for (m, from) in light_matrices.iter_mut().zip(&u.light_from) {
                *m = (*from * model).as_mat4();
            }
            p.set_mat4_array("modelLightViewMatrix", &light_matrices);
            let m = &item.material;
            let colour = m.colour.truncate();
            p.set_vec4(
                "material.ambient",
                (scene.ambient * colour).extend(m.reflectance),
            );
            for (d, light) in diffuse.iter_mut().zip(&u.colour) {
                *d = *light * colour;
            }
            p.set_vec3_array("material.diffuse", &diffuse);
            m.texture
                .and_then(|t| inputs.textures.get(t))
                .unwrap_or(inputs.white)
                .bind(MATERIAL_UNIT);
        });
    }
    p.unbind();
    drop(bound);
    Ok(())
}

/// The per-light uniform arrays of the scene pass (view space), and the per-slot ones of
/// the lights with a 2D or cube map ([`slots::map_slots`]).
struct LightUniforms {
    colour: Vec<Vec3>,
    /// A positional light's position, or the direction towards a directional one.
    position_or_direction: Vec<Vec3>,
    cone_cos: Vec<f32>,
    cone_axis: Vec<Vec3>,
    far: Vec<f32>,
    /// PCSS's (S.x, S.y, near, far) per light: see [`penumbra`].
    penumbra: Vec<Vec4>,
    /// Per map slot.
    normal_offset: Vec<f32>,
    projection: Vec<Mat4>,
    /// World to the light's view (a point light: to the light's position), per map slot.
    light_from: Vec<DMat4>,
    /// Its rotation (for normal offsets), per map slot.
    rotation: Vec<Mat3>,
}

impl LightUniforms {
    fn of(scene: &Scene, inputs: &Inputs, view64: DMat4) -> LightUniforms {
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
            if let Some(s) = t.slot_transform(light, v, &inputs.plan.lights[i].settings) {
                u.normal_offset[p] = s.normal_offset;
                u.projection[p] = s.projection;
                u.light_from[p] = s.from;
                u.rotation[p] = Mat3::from_mat4(s.from.as_mat4());
            }
        }
        u
    }
}

/// PCSS's constants for a light's 2D map (shaders/lib/soft_filters.glsl): its size in the
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
fn normal_matrix(m: &Mat4) -> Mat3 {
    Mat3::from_mat4(*m).inverse().transpose()
}
