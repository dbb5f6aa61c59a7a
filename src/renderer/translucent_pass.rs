//! Translucent items (opacity below 1) in the scene pass: drawn after the opaque ones, back
//! to front, each blended over the frame by its opacity ([`TranslucentBlend`]). They take
//! the lights and shadow tests of the opaque items, so they receive shadows too; the frame's
//! measurement outputs keep the opaque receivers under them.

use glam::{DMat4, Mat4, Vec3};

use super::scene_inputs::{normal_matrix, Inputs, LightUniforms};
use crate::engine::{Gl, TranslucentBlend};
use crate::scene::{GameItem, Scene};
use crate::shadows::slots::MATERIAL_UNIT;
use crate::shadows::ShadowKind;

/// Whether `item` is left to this pass: translucent, and the frame has no shadow volumes
/// (whose additive passes draw every item as the opaque ones).
pub fn drawn_later(inputs: &Inputs, item: &GameItem) -> bool {
    item.is_translucent() && !inputs.plan.has(ShadowKind::Volume)
}

/// The translucent items, farthest from the camera first: the order blending needs.
fn back_to_front<'a>(inputs: &Inputs, scene: &'a Scene, view: DMat4) -> Vec<&'a GameItem> {
    let mut items: Vec<(f64, &GameItem)> = scene
        .items
        .iter()
        .filter(|i| drawn_later(inputs, i))
        .map(|i| (view.transform_point3(i.position.as_dvec3()).z, i))
        .collect();
    // View space looks down -z: the most negative z is the farthest.
    items.sort_by(|a, b| a.0.total_cmp(&b.0));
    items.into_iter().map(|(_, i)| i).collect()
}

/// Draws the translucent items with the bound scene program, whose per-frame uniforms and
/// maps the scene pass has set (`u`: its light uniforms; `origin`: the camera's translation
/// out of world space).
pub(super) fn draw(
    inputs: &Inputs,
    gl: &Gl,
    scene: &Scene,
    view64: DMat4,
    origin: DMat4,
    u: &LightUniforms,
) {
    let items = back_to_front(inputs, scene, view64);
    if items.is_empty() {
        return;
    }
    let p = inputs.program;
    let blend = TranslucentBlend::begin(gl);
    let mut light_matrices = vec![Mat4::IDENTITY; u.light_from.len()];
    let mut diffuse = vec![Vec3::ZERO; u.colour.len()];
    for item in items {
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
        blend.set_opacity(item.opacity);
        inputs.meshes[item.mesh].render_list([()], |_| {});
    }
}
