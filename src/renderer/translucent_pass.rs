//! Translucent items (opacity below 1) in the scene pass: drawn after the opaque ones, back
//! to front, each blended over the frame by its opacity ([`TranslucentBlend`]). They take
//! the lights and shadow tests of the opaque items, so they receive shadows too; the frame's
//! measurement outputs keep the opaque receivers under them.

use glam::DMat4;

use super::scene_inputs::{Inputs, LightUniforms};
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
    for item in items {
        super::scene_inputs::set_item_uniforms(p, item, scene, u, view64, origin);
        let m = &item.material;
        m.texture
            .and_then(|t| inputs.textures.get(t))
            .unwrap_or(inputs.white)
            .bind(MATERIAL_UNIT);
        blend.set_opacity(item.opacity);
        inputs.meshes[item.mesh].render_list([()], |_| {});
    }
}
