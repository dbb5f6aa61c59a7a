//! Patching a cached 2D depth map (the movers' light-space rectangles redrawn):
//! when the light's camera, the light, its settings, the map and the set of casters are the
//! ones the map was drawn with and only some casters moved, only the texels those movers
//! covered before and cover now are cleared and drawn again, by the casters that can reach
//! them. A texel's depth is the nearest of the fragments drawn into it whatever their order,
//! and the scissor only drops fragments, so the patched map is the full redraw's, bit for bit.
//!
//! Only the chapter's depth map ([`crate::shadows::map2d`]) is patched. A box fitted to the scene
//! and cascades follow the camera and the casters, so their view changes and they are drawn
//! whole; a moment map is blurred (a texel depends on its neighbours) and a cube map has six
//! faces: both are drawn whole too.

use glam::DVec3;

use crate::scene::Scene;
use crate::settings::MapSize;
use crate::shadows::cache::LightFacts;
use crate::shadows::camera::texels::{footprint, TexelRect};
use crate::shadows::ShadowView;

/// Whether redrawing `region` of a `size` map is cheaper than drawing it whole: when it is
/// at most half the map. A patch clears and fills at most half the texels and draws only
/// the casters over the region (their vertices are the full pass' at most); past half the
/// saving is under half the fill while the casters over the region are most of them, so
/// the one full pass (no scissor) is as cheap and simpler.
pub fn cheaper(region: TexelRect, size: MapSize) -> bool {
    region.texels() * 2 <= size.texels()
}

/// A patch of a map: the texels to clear and draw again (the scissor) and the casters that
/// can reach them (by item index).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Patch {
    pub region: TexelRect,
    pub casters: Vec<usize>,
}

/// The casters a depth pass draws: those a fitted box was fitted to (`fitted`; `None`:
/// every caster), and with `patch` only those of them that reach its region.
pub fn casters_within(fitted: Option<Vec<usize>>, patch: Option<&Patch>) -> Option<Vec<usize>> {
    match (fitted, patch) {
        (only, None) => only,
        (None, Some(p)) => Some(p.casters.clone()),
        (Some(f), Some(p)) => Some(f.into_iter().filter(|k| p.casters.contains(k)).collect()),
    }
}

/// A casting item as its map was drawn: where it was ([`crate::shadows::cache::hash_placement`]) and
/// the texels it could cover.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Placed {
    placement: u64,
    rect: TexelRect,
}

/// What a 2D map was drawn with, to tell what a later frame must draw again.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRecord {
    /// The light camera's matrices, bit for bit.
    camera: Vec<u64>,
    /// The light and its settings ([`crate::shadows::cache::hash_light`]).
    light: u64,
    size: MapSize,
    /// Per scene item: `None` for one that does not cast.
    items: Vec<Option<Placed>>,
}

impl MapRecord {
    /// A map of `size` as it would be drawn now through the fixed camera in `facts`
    /// (`None` for a map that follows the viewer: it is not patched), `boxes` and
    /// `placements` being the items' world boxes and placement hashes this frame
    /// ([`crate::shadows::camera::fitted::item_world_boxes`], [`crate::shadows::cache::placements`]).
    pub fn of(
        scene: &Scene,
        boxes: &[(DVec3, DVec3)],
        placements: &[u64],
        facts: &LightFacts,
        size: MapSize,
    ) -> Option<MapRecord> {
        let view = facts.camera.as_ref()?;
        let items = scene
            .items
            .iter()
            .zip(boxes)
            .zip(placements)
            .map(|((item, (lo, hi)), &placement)| {
                item.casts_shadows.then(|| Placed {
                    placement,
                    rect: footprint(view, size, *lo, *hi),
                })
            })
            .collect();
        Some(MapRecord {
            camera: camera_bits(view),
            light: facts.hash,
            size,
            items,
        })
    }

    /// What must be drawn to turn the map recorded by `self` into the one `now` records:
    /// `None` to draw it whole (the camera, light, settings, map or casters differ, or the
    /// patch is not [`cheaper`]). The region is the texels of every moved caster, where it
    /// was and where it is, grown by one texel on every side for safety and clipped to the
    /// map; the casters are those whose texels meet it.
    pub fn patch_to(&self, now: &MapRecord) -> Option<Patch> {
        let same_casters = self.items.len() == now.items.len()
            && self
                .items
                .iter()
                .zip(&now.items)
                .all(|(a, b)| a.is_some() == b.is_some());
        let same_view = self.camera == now.camera && self.light == now.light;
        if !same_view || self.size != now.size || !same_casters {
            return None;
        }
        let moved = self
            .items
            .iter()
            .zip(&now.items)
            .filter_map(|(a, b)| Some((a.as_ref()?, b.as_ref()?)))
            .filter(|(a, b)| a.placement != b.placement);
        let region = moved
            .fold(TexelRect::default(), |r, (a, b)| {
                r.union(a.rect).union(b.rect)
            })
            .grown(1, self.size);
        if !cheaper(region, self.size) {
            return None;
        }
        let casters = now
            .items
            .iter()
            .enumerate()
            .filter(|(_, p)| p.is_some_and(|p| p.rect.overlaps(region)))
            .map(|(k, _)| k)
            .collect();
        Some(Patch { region, casters })
    }
}

/// A light camera's matrices as bits: equal only if every float is the same.
fn camera_bits(view: &ShadowView) -> Vec<u64> {
    let singles = [view.view, view.projection]
        .into_iter()
        .flat_map(|m| m.to_cols_array())
        .map(|f| u64::from(f.to_bits()));
    view.view64
        .to_cols_array()
        .into_iter()
        .map(f64::to_bits)
        .chain(singles)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::PixelRect;
    use crate::settings::ShadowSettings;
    use glam::{DMat4, Mat4, Vec3};

    const MAP: MapSize = MapSize::square(1024);

    /// A light looking down -Z from the origin through `projection`.
    fn view(projection: Mat4, perspective: bool) -> ShadowView {
        ShadowView {
            view: Mat4::IDENTITY,
            view64: DMat4::IDENTITY,
            projection,
            perspective,
            linear_depth: false,
            near: 1.0,
            far: 20.0,
            texel_world: 20.0 / 1024.0,
            rays: crate::shadows::Rays::Parallel { to_light: Vec3::Z },
        }
    }

    fn ortho() -> ShadowView {
        view(
            Mat4::orthographic_rh_gl(-10.0, 10.0, -10.0, 10.0, -1.0, 20.0),
            false,
        )
    }

    fn rect(x0: u32, y0: u32, x1: u32, y1: u32) -> TexelRect {
        TexelRect { x0, y0, x1, y1 }
    }

    #[test]
    fn a_box_covers_the_whole_texels_its_light_space_rectangle_touches() {
        // 20 units over 1024 texels: x from 0 to 1 is texels 512 to 563.2, so 512..564;
        // y from -0.5 to 0.25 is 486.4 to 524.8, so 486..525.
        let lo = DVec3::new(0.0, -0.5, -5.0);
        let hi = DVec3::new(1.0, 0.25, -4.0);
        assert_eq!(footprint(&ortho(), MAP, lo, hi), rect(512, 486, 564, 525));
        // Clipped to the map at its edge, and empty off it.
        let edge = footprint(
            &ortho(),
            MAP,
            DVec3::new(9.5, 9.5, -5.0),
            DVec3::splat(12.0),
        );
        assert_eq!(edge, rect(998, 998, 1024, 1024));
        let off = footprint(
            &ortho(),
            MAP,
            DVec3::new(11.0, 0.0, -5.0),
            DVec3::splat(12.0),
        );
        assert!(off.is_empty() && off.texels() == 0, "{off:?}");
        // Behind a perspective light's eye: the whole map.
        let p = view(Mat4::perspective_rh_gl(1.5, 1.0, 1.0, 20.0), true);
        let behind = footprint(&p, MAP, DVec3::new(-1.0, -1.0, -2.0), DVec3::splat(1.0));
        assert_eq!(behind, TexelRect::whole(MAP));
    }

    #[test]
    fn rectangles_join_grow_within_the_map_and_meet() {
        let a = rect(10, 20, 30, 40);
        let b = rect(100, 0, 110, 5);
        assert_eq!(a.union(b), rect(10, 0, 110, 40));
        assert_eq!(TexelRect::default().union(a), a);
        assert_eq!(a.union(TexelRect::default()), a);
        assert_eq!(a.grown(1, MAP), rect(9, 19, 31, 41));
        assert_eq!(rect(0, 3, 1024, 1024).grown(1, MAP), rect(0, 2, 1024, 1024));
        assert!(TexelRect::default().grown(1, MAP).is_empty());
        assert!(a.overlaps(rect(29, 39, 31, 41)));
        // Half-open: touching edges share no texel.
        assert!(!a.overlaps(rect(30, 20, 40, 40)));
        assert!(!a.overlaps(TexelRect::default()));
        assert_eq!(
            a.pixels(),
            PixelRect {
                x: 10,
                y: 20,
                width: 20,
                height: 20
            }
        );
    }

    #[test]
    fn a_patch_is_cheaper_up_to_half_the_map() {
        assert!(cheaper(rect(0, 0, 1024, 512), MAP));
        assert!(!cheaper(rect(0, 0, 1024, 513), MAP));
        assert!(cheaper(TexelRect::default(), MAP));
    }

    #[test]
    fn a_moved_caster_dirties_where_it_was_and_is_and_what_reaches_there_is_drawn() {
        let mut scene = Scene::load("dummy").unwrap();
        let s = scene.shadow;
        let record = |sc: &Scene, s: &ShadowSettings| {
            let boxes = crate::shadows::camera::fitted::item_world_boxes(sc);
            let facts = LightFacts::of(sc, 0, s, false);
            let placements = crate::shadows::cache::placements(sc);
            MapRecord::of(sc, &boxes, &placements, &facts, s.map_size)
                .expect("a fixed camera is recorded")
        };
        let before = record(&scene, &s);
        assert_eq!(
            before.patch_to(&before),
            Some(Patch {
                region: TexelRect::default(),
                casters: vec![]
            })
        );
        scene.items[0].position.x += 2.0;
        let after = record(&scene, &s);
        let patch = before.patch_to(&after).unwrap();
        let (was, is) = (before.items[0].unwrap().rect, after.items[0].unwrap().rect);
        assert_ne!(was, is);
        assert_eq!(patch.region, was.union(is).grown(1, MAP));
        // The plane under the cube reaches the region too.
        assert_eq!(patch.casters, vec![0, 1]);
        // A cube over most of the map, a turned light, a new setting or one more caster:
        // drawn whole.
        let mut big = scene.clone();
        big.items[0].scale = Vec3::splat(8.0);
        assert_eq!(after.patch_to(&record(&big, &s)), None);
        let mut turned = scene.clone();
        turned.set_light_angle(50.0);
        assert_eq!(after.patch_to(&record(&turned, &s)), None);
        let biased = ShadowSettings { bias: 0.01, ..s };
        assert_eq!(after.patch_to(&record(&scene, &biased)), None);
        let mut more = scene.clone();
        more.items.push(scene.items[0].clone());
        assert_eq!(after.patch_to(&record(&more, &s)), None);
    }
}
