//! Translucent items (opacity below 1) in the scene pass: drawn after the opaque ones, back
//! to front, each blended over the frame by its opacity ([`TranslucentBlend`]). They take
//! the lights and shadow tests of the opaque items, so they receive shadows too; the frame's
//! measurement outputs keep the opaque receivers under them.
//!
//! The cached shadow mask holds, per pixel, the tests of the opaque surface there (each
//! light's test times the light the translucent casters let through), which is not where a
//! translucent item's fragment is: these items are left out of the mask and, in a frame
//! that reads it, drawn with the program that tests every light (its maps bound here).

use glam::{DMat4, Mat4};

use super::scene_inputs::{bind_maps, Inputs, LightUniforms};
use crate::engine::{BoundSampler, Gl, Samplers, ShaderProgram, TranslucentBlend};
use crate::error::Result;
use crate::scene::{GameItem, Scene};
use crate::shadows::units::MATERIAL_UNIT;
use crate::shadows::ShadowKind;

/// Whether `item` is left to this pass: translucent, and the frame has no shadow volumes
/// (whose additive passes draw every item as the opaque ones).
pub fn drawn_later(inputs: &Inputs, item: &GameItem) -> bool {
    item.is_translucent() && !inputs.plan.has(ShadowKind::Volume)
}

/// The translucent items and their indices, farthest from the camera first: the order
/// blending needs.
fn back_to_front<'a>(inputs: &Inputs, scene: &'a Scene, view: DMat4) -> Vec<(usize, &'a GameItem)> {
    let mut items: Vec<(f64, (usize, &GameItem))> = (scene.items.iter().enumerate())
        .filter(|(_, i)| drawn_later(inputs, i))
        .map(|(k, i)| (view.transform_point3(i.position.as_dvec3()).z, (k, i)))
        .collect();
    // View space looks down -z: the most negative z is the farthest.
    items.sort_by(|a, b| a.0.total_cmp(&b.0));
    items.into_iter().map(|(_, i)| i).collect()
}

/// Draws the translucent items with `inputs.translucent` (none while the mask is written).
/// The scene pass has set the bound program's per-frame uniforms and maps; a program of its
/// own gets them here (`u`: the light uniforms; `camera`: its view, the translation out of
/// world space and the projection).
pub(super) fn draw(
    inputs: &Inputs,
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
    u: &LightUniforms,
    (view64, origin, projection): (DMat4, DMat4, Mat4),
) -> Result<()> {
    let Some(p) = inputs.translucent else {
        return Ok(());
    };
    let items = back_to_front(inputs, scene, view64);
    if items.is_empty() {
        return Ok(());
    }
    let _bound = match std::ptr::eq(p, inputs.program) {
        true => Vec::new(),
        false => own_program(inputs, p, samplers, gl, scene, u, (view64, projection))?,
    };
    (inputs.volumetric).set_matrices(p, inputs.views, view64, true);
    let blend = TranslucentBlend::begin(gl);
    for (k, item) in items {
        super::scene_inputs::set_item_uniforms(p, item, scene, u, view64, origin);
        let m = &item.material;
        m.texture
            .and_then(|t| inputs.textures.get(t))
            .unwrap_or(inputs.white)
            .bind(MATERIAL_UNIT);
        blend.set_opacity(item.opacity);
        // Tested per vertex: each vertex reads the light captured for it.
        let mesh = &inputs.meshes[item.mesh];
        if !inputs.vertex_light.is_some_and(|v| v.draw(k, mesh)) {
            mesh.render_list([()], |_| {});
        }
    }
    Ok(())
}

/// Binds `p` (the program that tests every light) and sets what the scene pass set on its
/// own program: the projection, the light uniforms, the units, each light's map.
fn own_program(
    inputs: &Inputs,
    p: &ShaderProgram,
    samplers: &mut Samplers,
    gl: &Gl,
    scene: &Scene,
    u: &LightUniforms,
    (view64, projection): (DMat4, Mat4),
) -> Result<Vec<BoundSampler>> {
    p.bind();
    p.set_mat4("projectionMatrix", &projection);
    u.set(p, view64.as_mat4());
    p.set_i32("textureSampler", MATERIAL_UNIT as i32);
    p.set_i32("passLight", inputs.pass_light);
    p.set_i32("instanced", 0);
    let tests = Inputs {
        program: p,
        mask: None,
        ..*inputs
    };
    bind_maps(&tests, samplers, gl, scene)
}
