//! The scene pass (the book's `renderScene`): every item from the camera, with the lights'
//! uniforms ([`super::scene_inputs`]) and each light's map on its texture unit; per item
//! its matrices and colours ("Shadows": the scene shader gets `modelLightViewMatrix` and
//! `orthoProjectionMatrix` besides the camera's, for `calcShadow`). Where the book sets
//! them and draws item by item, the items here are batched by mesh ([`draw_opaque`]).

use glam::DMat4;

use super::scene_inputs::{bind_maps, normal_matrix, set_item_uniforms, Inputs, LightUniforms};
use super::translucent_pass;
use crate::engine::instances::{self, Values};
use crate::engine::{Gl, Samplers};
use crate::error::Result;
use crate::scene::{GameItem, Scene};
use crate::shadows::units::{MASK_UNIT, MATERIAL_UNIT};

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
    // The book's loop sets each item's matrices and draws it; here the items are batched by
    // mesh and texture (`draw_opaque`), their values in the instance buffer.
    draw_opaque(inputs, scene, &u, view64, origin);
    let camera = (view64, origin, projection);
    let translucent = translucent_pass::draw(inputs, samplers, gl, scene, &u, camera);
    p.unbind();
    drop(bound);
    translucent
}

/// The opaque items, one instanced draw per run of items sharing a mesh and a texture, in
/// the book's order (mesh by mesh, items in scene order): each item's matrices and colours
/// computed as the book's per-item uniforms (double precision, then f32) and uploaded at once.
fn draw_opaque(inputs: &Inputs, scene: &Scene, u: &LightUniforms, view64: DMat4, origin: DMat4) {
    let p = inputs.program;
    let mut items: Vec<&GameItem> = (scene.items.iter())
        .filter(|i| i.mesh < inputs.meshes.len() && !translucent_pass::drawn_later(inputs, i))
        .collect();
    items.sort_by_key(|i| i.mesh);
    // Only a target with world outputs reads these: no matrices per item for nothing.
    let world_outputs = p.uses("modelOriginMatrix") || p.uses("worldNormalMatrix");
    let stride = 15 + 4 * u.light_from.len() + u.colour.len().max(1);
    let instanced = inputs.instances.fill(p, stride, |t| {
        for item in &items {
            push_instance(t, item, scene, u, view64, origin, world_outputs);
        }
    });
    let texture = |i: &GameItem| i.material.texture.filter(|&t| t < inputs.textures.len());
    for b in instances::batches(items.iter().map(|i| (i.mesh, texture(i)))) {
        let (mesh, tex) = b.key;
        tex.map_or(inputs.white, |t| &inputs.textures[t])
            .bind(MATERIAL_UNIT);
        match b.count {
            1 => instanced.draw_one(&inputs.meshes[mesh], |p| {
                set_item_uniforms(p, items[b.first], scene, u, view64, origin)
            }),
            _ => instanced.draw(&inputs.meshes[mesh], &b),
        }
    }
}

/// One item's values in scene.vert's layout: the values its uniforms had.
fn push_instance(
    t: &mut Values,
    item: &GameItem,
    scene: &Scene,
    u: &LightUniforms,
    view64: DMat4,
    origin: DMat4,
    world_outputs: bool,
) {
    let model = item.model_matrix64();
    let model_view = (view64 * model).as_mat4();
    t.mat4(&model_view);
    t.mat3(&normal_matrix(&model_view));
    if world_outputs {
        t.mat4(&(origin * model).as_mat4());
        t.mat3(&normal_matrix(&model.as_mat4()));
    } else {
        t.zeros(7);
    }
    let m = &item.material;
    let colour = m.colour.truncate();
    t.vec4((scene.ambient * colour).extend(m.reflectance));
    for from in &u.light_from {
        t.mat4(&(*from * model).as_mat4());
    }
    for light in &u.colour {
        t.vec4((*light * colour).extend(0.0));
    }
    if u.colour.is_empty() {
        t.zeros(1);
    }
}
