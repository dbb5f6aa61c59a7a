//! Cached shadow maps (past the chapters, which redraw every map every frame): a light's
//! map is drawn again only when what it sees changed. What it sees is summed up in a
//! [`content_key`]: the light, its settings, every caster's mesh and placement, and, for a
//! map that follows the camera (a fitted box, cascades), the camera and the frame's shape.
//! An unchanged key means the depth pass would write the same texels, so it is skipped; a
//! changed one where only casters moved may redraw just the part they dirtied
//! ([`patch`]).

pub mod patch;
pub mod schedule;

use std::cell::RefCell;
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use glam::DVec3;

use super::{ShadowKind, ShadowView};
use crate::scene::{Light, Scene};
use crate::settings::ShadowSettings;

/// What light `index`'s map depends on this frame besides its casters, worked out once a
/// frame for both the cache key and the patch record ([`patch::MapRecord`]).
pub struct LightFacts {
    /// The light and its settings ([`hash_light`]).
    pub hash: u64,
    /// The light's own camera; `None` for a map that follows the viewer (its box depends on
    /// the camera and the casters, so every caster counts).
    pub camera: Option<ShadowView>,
}

impl LightFacts {
    pub fn of(
        scene: &Scene,
        index: usize,
        settings: &ShadowSettings,
        follows_camera: bool,
    ) -> LightFacts {
        let mut h = DefaultHasher::new();
        hash_light(&scene.lights[index], settings, &mut h);
        LightFacts {
            hash: h.finish(),
            camera: (!follows_camera).then(|| super::light_camera(scene, index, settings)),
        }
    }
}

/// Each item's [`hash_placement`], once a frame for every light's key and record.
pub fn placements(scene: &Scene) -> Vec<u64> {
    scene
        .items
        .iter()
        .map(|item| {
            let mut h = DefaultHasher::new();
            hash_placement(item, &mut h);
            h.finish()
        })
        .collect()
}

/// A number that changes whenever light `index`'s depth pass could draw something else:
/// `facts`, and the placements of the casters that can land in its map (all casters for a
/// map that follows the viewer, with the camera and the frame's shape), so a caster
/// turning out of a fixed camera's sight does not make it draw again.
pub fn content_key(
    scene: &Scene,
    boxes: &[(DVec3, DVec3)],
    placements: &[u64],
    index: usize,
    facts: &LightFacts,
) -> u64 {
    let light = &scene.lights[index];
    let mut h = DefaultHasher::new();
    facts.hash.hash(&mut h);
    for ((item, (lo, hi)), placement) in scene.items.iter().zip(boxes).zip(placements) {
        let seen = match &facts.camera {
            Some(c) => crate::shadows::camera::culling::may_land(light, c, *lo, *hi),
            None => true,
        };
        if item.casts_shadows && seen {
            placement.hash(&mut h);
        }
    }
    if facts.camera.is_none() {
        scene.fitting_camera().hash_bits(&mut h);
        scene.size.hash(&mut h);
    }
    h.finish()
}

/// Hashes a light and its shadow settings, every field.
pub fn hash_light(light: &Light, settings: &ShadowSettings, h: &mut impl Hasher) {
    light_hash(light, settings).hash(h);
}

/// How many (light, settings) pairs [`light_hash`] remembers.
const REMEMBERED: usize = 16;

thread_local! {
    /// The pairs hashed lately and their hashes: a frame whose lights and settings are
    /// unchanged compares them as values instead of formatting them again.
    static HASHED: RefCell<Vec<(Light, ShadowSettings, u64)>> = const { RefCell::new(Vec::new()) };
}

/// The hash of a light and its settings: their `Debug` text (every field, floats bit for
/// bit in their shortest exact form, without a Hash impl on each type), made once per pair;
/// a pair equal to a remembered one (compared as values, so a NaN never is) reuses it.
fn light_hash(light: &Light, settings: &ShadowSettings) -> u64 {
    HASHED.with(|memo| {
        let mut memo = memo.borrow_mut();
        let same = |(l, s, _): &&(Light, ShadowSettings, u64)| l == light && s == settings;
        if let Some((_, _, hash)) = memo.iter().find(same) {
            return *hash;
        }
        let mut h = DefaultHasher::new();
        format!("{light:?}").hash(&mut h);
        format!("{settings:?}").hash(&mut h);
        let hash = h.finish();
        if memo.len() == REMEMBERED {
            memo.remove(0);
        }
        memo.push((*light, *settings, hash));
        hash
    })
}

/// Hashes what an item is and where: its mesh, position, rotation and scale, bit for bit.
pub fn hash_placement(item: &crate::scene::GameItem, h: &mut impl Hasher) {
    item.mesh.hash(h);
    for v in [item.position, item.rotation, item.scale] {
        v.to_array().map(f32::to_bits).hash(h);
    }
}

/// Whether `light`'s map of kind `kind` under `settings` follows the camera (its box is
/// fitted to what the camera sees).
pub fn follows_camera(light: &Light, kind: ShadowKind, settings: &ShadowSettings) -> bool {
    (kind.facts().follows_camera)(light, settings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_key_changes_with_what_the_light_sees_and_only_then() {
        let mut scene = Scene::load("dummy").unwrap();
        let s = scene.shadow;
        let key = |sc: &Scene, s: &ShadowSettings| {
            let boxes = crate::shadows::camera::fitted::item_world_boxes(sc);
            let follows = follows_camera(&sc.lights[0], ShadowKind::Map, s);
            let facts = LightFacts::of(sc, 0, s, follows);
            content_key(sc, &boxes, &placements(sc), 0, &facts)
        };
        let k0 = key(&scene, &s);
        assert_eq!(k0, key(&scene, &s));
        // The camera does not matter to the book's hand-set box ...
        scene.camera.position.x += 1.0;
        assert_eq!(k0, key(&scene, &s));
        // ... but does to a fitted one.
        let fitted = ShadowSettings {
            fit: crate::settings::Fit::Scene,
            ..s
        };
        let f0 = key(&scene, &fitted);
        scene.camera.position.x += 1.0;
        assert_ne!(f0, key(&scene, &fitted));
        // A turning caster, a setting and the light all change it.
        let k1 = key(&scene, &s);
        scene.update();
        assert_ne!(k1, key(&scene, &s));
        let k2 = key(&scene, &s);
        assert_ne!(k2, key(&scene, &ShadowSettings { bias: 0.01, ..s }));
        scene.set_light_angle(60.0);
        assert_ne!(k2, key(&scene, &s));
    }

    #[test]
    fn a_remembered_light_hash_follows_every_setting_change() {
        let scene = Scene::load("dummy").unwrap();
        let light = &scene.lights[0];
        let s = scene.shadow;
        let hash = |s: &ShadowSettings| light_hash(light, s);
        let h0 = hash(&s);
        assert_eq!(h0, hash(&s));
        let changed = [
            ShadowSettings {
                bias: s.bias * 2.0,
                ..s
            },
            ShadowSettings {
                shadow_cache: !s.shadow_cache,
                ..s
            },
            ShadowSettings {
                cascades: s.cascades + 1,
                ..s
            },
        ];
        for c in &changed {
            assert_ne!(h0, hash(c), "{c:?}");
        }
        // Back to the first settings after the memo has seen others: the first hash.
        assert_eq!(h0, hash(&s));
        // Past what it remembers, a pair is hashed again, to the same value.
        for k in 0..2 * REMEMBERED {
            hash(&ShadowSettings {
                bias: k as f32,
                ..s
            });
        }
        assert_eq!(h0, hash(&s));
    }
}
