//! The scene pass (the book's `renderScene`): every item from the camera, with the lights'
//! uniforms ([`super::scene_inputs`]) and each light's map on its texture unit; per item
//! its matrices and colours ("Shadows": the scene shader gets `modelLightViewMatrix` and
//! `orthoProjectionMatrix` besides the camera's, for `calcShadow`).

use glam::{DMat4, Mat4, Vec3};

use super::scene_inputs::{bind_maps, normal_matrix, Inputs, LightUniforms};
use super::translucent_pass;
use crate::engine::{Gl, Samplers};
use crate::error::Result;
use crate::scene::Scene;
use crate::shadows::slots::{MASK_UNIT, MATERIAL_UNIT};

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
    let projection = scene.camera.projection_matrix(width, height);
    p.set_mat4("projectionMatrix", &projection);
    let u = LightUniforms::of(scene, inputs, view64);
    u.set(p, view);
    p.set_i32("textureSampler", MATERIAL_UNIT as i32);
    p.set_i32("passLight", inputs.pass_light);
    if let Some(mask) = inputs.mask {
        p.set_i32("shadowMask", MASK_UNIT as i32);
        mask.bind(MASK_UNIT);
    }
    // Each light's map and sampler on its unit, for the pass.
    let bound = bind_maps(inputs, samplers, gl, scene)?;
    let mut light_matrices = vec![Mat4::IDENTITY; u.light_from.len()];
    let mut diffuse = vec![Vec3::ZERO; u.colour.len()];
    // Only a target with world outputs reads these: no matrices per item for nothing.
    let world_outputs = p.uses("modelOriginMatrix") || p.uses("worldNormalMatrix");
    for (mesh_id, mesh) in inputs.meshes.iter().enumerate() {
        let items = (scene.items.iter())
            .filter(|i| i.mesh == mesh_id && !translucent_pass::drawn_later(inputs, i));
        mesh.render_list(items, |item| {
            let model = item.model_matrix64();
            let model_view = (view64 * model).as_mat4();
            p.set_mat4("modelViewMatrix", &model_view);
            p.set_mat3("normalMatrix", &normal_matrix(&model_view));
            if world_outputs {
                p.set_mat4("modelOriginMatrix", &(origin * model).as_mat4());
                p.set_mat3("worldNormalMatrix", &normal_matrix(&model.as_mat4()));
            }
            for (m, from) in light_matrices.iter_mut().zip(&u.light_from) {
                *m = (*from * model).as_mat4();
            }
            p.set_mat4_array("modelLightViewMatrix", &light_matrices);
            let m = &item.material;
            let colour = m.colour.truncate();
            let ambient = (scene.ambient * colour).extend(m.reflectance);
            p.set_vec4("material.ambient", ambient);
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
    translucent_pass::draw(inputs, gl, scene, view64, origin, &u);
    p.unbind();
    drop(bound);
    Ok(())
}
