//! Kept translucent maps (past the papers, which draw the map every frame): with
//! `shadow_cache` on, a light's translucent map is drawn again only when what it holds
//! could change, as the depth maps are ([`crate::shadows::cache`]). What it holds is summed
//! up in [`content_key`]: the light's camera, the map's own settings, the translucent
//! casters (which, where, how opaque) and the depth fitted to them. No opaque caster is in
//! it: no technique's pass reads the depth map (AVSM's peel compares with its own previous
//! layer).

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use super::{method, translucent_casters, DepthFit};
use crate::scene::Scene;
use crate::settings::{ShadowSettings, Volumetric};
use crate::shadows::cache::hash_placement;
use crate::shadows::ShadowView;

/// Hashes what a light's map is made and drawn for under `settings`: its technique, size
/// and count (slices, terms, nodes), and for AVSM the layers it peels.
pub fn settings_key(settings: &ShadowSettings) -> u64 {
    let mut h = DefaultHasher::new();
    settings.volumetric.hash(&mut h);
    settings.volumetric_size.hash(&mut h);
    method(settings.volumetric)
        .map(|m| m.parameter(settings))
        .hash(&mut h);
    if settings.volumetric == Volumetric::Avsm {
        settings.peel_layers.hash(&mut h);
    }
    h.finish()
}

/// A number that changes whenever drawing the map again could give other texels: the
/// light's camera `view` (its view and projection, bit for bit), the map's `settings`
/// ([`settings_key`]), each translucent caster's index, mesh, placement and opacity, and
/// the depth range `fit` (which follows from them, hashed all the same).
pub fn content_key(scene: &Scene, view: &ShadowView, settings: u64, fit: DepthFit) -> u64 {
    let mut h = DefaultHasher::new();
    settings.hash(&mut h);
    view.view64.to_cols_array().map(f64::to_bits).hash(&mut h);
    view.projection
        .to_cols_array()
        .map(f32::to_bits)
        .hash(&mut h);
    for (k, item) in translucent_casters(scene) {
        k.hash(&mut h);
        hash_placement(item, &mut h);
        item.opacity.to_bits().hash(&mut h);
    }
    [fit.near, fit.far].map(f32::to_bits).hash(&mut h);
    h.finish()
}

/// Translucent maps drawn and kept so far.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct MapDraws {
    pub drawn: u64,
    pub kept: u64,
    /// Resolves for opaque receivers ([`super::resolved`]).
    pub resolved: u64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_follows_the_translucent_casters_the_camera_and_the_settings_alone() {
        let mut scene = Scene::load("smoke").unwrap();
        let s = ShadowSettings {
            volumetric: Volumetric::Avsm,
            ..scene.shadow
        };
        let view = crate::shadows::light_camera(&scene, 0, &s);
        let key = |sc: &Scene, v: &ShadowView, s: &ShadowSettings| {
            let boxes = crate::shadows::camera::fitted::item_world_boxes(sc);
            content_key(sc, v, settings_key(s), DepthFit::of(sc, &boxes, v.view64))
        };
        let k0 = key(&scene, &view, &s);
        assert_eq!(k0, key(&scene, &view, &s));
        // An opaque caster moving, the scene camera and the depth map's own settings: kept.
        let cube = scene.items.iter().position(|i| i.name == "cube").unwrap();
        scene.items[cube].position.x += 0.3;
        scene.camera.position.x += 1.0;
        assert_eq!(k0, key(&scene, &view, &ShadowSettings { bias: 0.02, ..s }));
        // A translucent one moving, or less opaque: drawn again.
        let glass = scene.items.iter().position(|i| i.name == "glass").unwrap();
        let mut moved = scene.clone();
        moved.items[glass].position.y += 0.01;
        assert_ne!(k0, key(&moved, &view, &s));
        let mut thinner = scene.clone();
        thinner.items[glass].opacity = 0.4;
        assert_ne!(k0, key(&thinner, &view, &s));
        // The light's camera and the map's own settings.
        let mut turned = view;
        turned.view64.w_axis.x += 1e-9;
        assert_ne!(k0, key(&scene, &turned, &s));
        for other in [
            ShadowSettings { avsm_nodes: 4, ..s },
            ShadowSettings {
                peel_layers: 8,
                ..s
            },
            ShadowSettings {
                volumetric: Volumetric::Osm,
                ..s
            },
            ShadowSettings {
                volumetric_size: crate::settings::MapSize::square(512),
                ..s
            },
        ] {
            assert_ne!(k0, key(&scene, &view, &other), "{other:?}");
        }
    }
}
