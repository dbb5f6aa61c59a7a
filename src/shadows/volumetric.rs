//! Translucent casters (items with `opacity` below 1). A depth map holds one depth per
//! texel, so it can only cast them all or nothing: `volumetric = "off"` leaves them out of
//! the map (the chapters' depth pass ignores them), `"solid"` draws them into it as if
//! opaque. The truth they are measured against is the product of (1 - opacity) over every
//! crossing of the shadow ray (`crate::reference::transmittance`).

use glam::DMat4;

use super::DepthPass;
use crate::engine::ShaderProgram;
use crate::scene::{GameItem, Scene};
use crate::settings::Volumetric;

/// The translucent items that cast (their own `casts_shadows`).
pub fn translucent_casters(scene: &Scene) -> impl Iterator<Item = (usize, &GameItem)> {
    scene
        .items
        .iter()
        .enumerate()
        .filter(|(_, i)| i.is_translucent() && i.casts_translucent)
}

/// With `volumetric = "solid"`, draws the translucent casters into the bound 2D depth map
/// as opaque ones (`light`: the light's view; depth.vert's uniforms) and counts them among
/// the casters drawn and offered; otherwise nothing.
pub fn draw_solid(pass: &mut DepthPass, scene: &Scene, program: &ShaderProgram, light: DMat4) {
    if pass.settings.volumetric != Volumetric::Solid {
        return;
    }
    let uniform = "modelLightViewMatrix";
    let mut drawn = 0u64;
    for (mesh_id, mesh) in pass.meshes.iter().enumerate() {
        let items = translucent_casters(scene).filter(|(_, i)| i.mesh == mesh_id);
        mesh.render_list(items, |(_, item)| {
            drawn += 1;
            program.set_mat4(uniform, &(light * item.model_matrix64()).as_mat4());
        });
    }
    pass.casters.drawn += drawn;
    pass.casters.total += drawn;
}
