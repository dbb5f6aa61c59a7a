//! Which depth passes a frame draws (past the chapters, which draw every map every frame).
//! With `shadow_cache` on, a map whose [`cache::content_key`] is the one it was drawn with
//! is kept, one whose fixed camera saw only casters move is patched ([`super::patch`]), and
//! any other is drawn whole. The renderer asks per light ([`DepthSchedule::step`]) and says
//! what it drew ([`DepthSchedule::drawn`]); the keys and records stay here, as Filament keeps
//! its `ShadowMapManager` apart from each `ShadowMap`.

use glam::DVec3;

use super::patch::{MapRecord, Patch};
use crate::scene::Scene;
use crate::settings::ShadowSettings;
use crate::shadows::camera::fitted;
use crate::shadows::{cache, Technique};

/// How many lights' depth passes were drawn whole, how many were skipped because the map
/// still held what the light sees, and how many drew only the part moved casters changed
/// (`shadow_cache`; [`super::patch`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DepthPasses {
    pub drawn: u64,
    pub skipped: u64,
    pub patched: u64,
    /// The texels the patches cleared and drew again, summed.
    pub patched_texels: u64,
}

impl DepthPasses {
    /// Counts a pass drawn whole, or `patch`.
    fn count(&mut self, patch: Option<&Patch>) {
        match patch {
            Some(p) => {
                self.patched += 1;
                self.patched_texels += p.region.texels();
            }
            None => self.drawn += 1,
        }
    }
}

/// A light's depth pass this frame: the whole map, or with `patch` that part alone; and what
/// the map holds once it is drawn.
pub struct Step {
    pub patch: Option<Patch>,
    key: Option<u64>,
    record: Option<MapRecord>,
}

/// What each light's map holds, and the items' boxes and placements of this frame.
#[derive(Default)]
pub struct DepthSchedule {
    /// What each light's map holds ([`cache::content_key`]); `None`: draw it again.
    keys: Vec<Option<u64>>,
    /// What each patchable map was drawn with, to patch it when only casters move.
    records: Vec<Option<MapRecord>>,
    /// Depth passes drawn, skipped and patched so far.
    passes: DepthPasses,
    /// Every item's world box this frame ([`fitted::item_world_boxes`]).
    boxes: Vec<(DVec3, DVec3)>,
    /// Every item's placement this frame ([`cache::placements`]).
    placements: Vec<u64>,
}

impl DepthSchedule {
    /// One entry per scene light.
    pub fn resize(&mut self, lights: usize) {
        self.keys.resize(lights, None);
        self.records.resize(lights, None);
    }

    /// Light `index`'s storage is new: its map holds nothing yet.
    pub fn forget(&mut self, index: usize) {
        self.keys[index] = None;
        self.records[index] = None;
    }

    /// Starts a frame: the items' world boxes when a light has a map (`techniques`: one
    /// per light), and with `cache` their placements, once for every light's key and record.
    pub fn begin(&mut self, scene: &Scene, techniques: &[Option<Box<dyn Technique>>], cache: bool) {
        self.boxes = match techniques.iter().any(Option::is_some) {
            true => fitted::item_world_boxes(scene),
            false => Vec::new(),
        };
        self.placements = match cache && !self.boxes.is_empty() {
            true => cache::placements(scene),
            false => Vec::new(),
        };
    }

    /// Every item's world box this frame, in the scene's item order.
    pub fn boxes(&self) -> &[(DVec3, DVec3)] {
        &self.boxes
    }

    /// What light `index`'s `technique` draws this frame under its `settings`: `None` when
    /// the map still holds what the light sees (`has_view`: it was drawn), else the whole
    /// map or a patch of it. The map's old key is forgotten first, so a pass that fails
    /// leaves it to be drawn again.
    pub fn step(
        &mut self,
        scene: &Scene,
        index: usize,
        technique: &dyn Technique,
        settings: &ShadowSettings,
        has_view: bool,
    ) -> Option<Step> {
        let light = &scene.lights[index];
        let follows = cache::follows_camera(light, technique.kind(), settings);
        let facts = settings
            .shadow_cache
            .then(|| cache::LightFacts::of(scene, index, settings, follows));
        let (boxes, placements) = (&self.boxes, &self.placements);
        let key = facts
            .as_ref()
            .map(|f| cache::content_key(scene, boxes, placements, index, f));
        if key.is_some() && key == self.keys[index] && has_view {
            self.passes.skipped += 1;
            return None;
        }
        // A kept map of a fixed camera can be patched where only casters moved.
        let record = facts
            .filter(|_| technique.patches())
            .and_then(|f| MapRecord::of(scene, boxes, placements, &f, settings.map_size));
        let kept = self.keys[index].is_some() && has_view;
        let patch = match (&self.records[index], &record) {
            (Some(old), Some(now)) if kept => old.patch_to(now),
            _ => None,
        };
        self.forget(index);
        Some(Step { patch, key, record })
    }

    /// Light `index`'s map was drawn as `step` says: it holds the step's key now.
    pub fn drawn(&mut self, index: usize, step: Step) {
        self.passes.count(step.patch.as_ref());
        self.keys[index] = step.key;
        self.records[index] = step.record;
    }

    /// What each light's map holds ([`cache::content_key`]), `None` where it is drawn again.
    pub fn keys(&self) -> &[Option<u64>] {
        &self.keys
    }

    /// Depth passes drawn, skipped and patched so far.
    pub fn passes(&self) -> DepthPasses {
        self.passes
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::engine::{Sampling, Texture};
    use crate::error::Result;
    use crate::scene::Light;
    use crate::shadows::{DepthPass, DepthViewKind, ShadowKind, ShadowView, SlotTransform};

    /// The chapter's kind of map without its storage: the schedule only asks its kind and
    /// whether it patches.
    struct Map;

    impl Technique for Map {
        fn kind(&self) -> ShadowKind {
            ShadowKind::Map
        }
        fn fits(&self, _: &ShadowSettings) -> bool {
            true
        }
        fn render_depth(&mut self, _: &mut DepthPass, _: &Scene, _: usize) -> Result<ShadowView> {
            unreachable!("the schedule draws nothing")
        }
        fn patches(&self) -> bool {
            true
        }
        fn texture(&self) -> &Texture {
            unreachable!("the schedule samples nothing")
        }
        fn sampling(&self, _: &ShadowSettings) -> Sampling {
            Sampling::PLAIN
        }
        fn slot_transform(
            &self,
            _: &Light,
            _: &ShadowView,
            _: &ShadowSettings,
        ) -> Option<SlotTransform> {
            None
        }
        fn bytes(&self) -> u64 {
            0
        }
        fn depth_view(&self) -> DepthViewKind {
            DepthViewKind::Flat
        }
    }

    /// The step for light 0 of `scene` this frame, and whether it patches.
    fn step(s: &mut DepthSchedule, scene: &Scene, has_view: bool) -> Option<Step> {
        let settings = crate::scene::refusals::own_settings(&scene.lights[0], &scene.shadow);
        let techniques: [Option<Box<dyn Technique>>; 1] = [Some(Box::new(Map))];
        s.begin(scene, &techniques, settings.shadow_cache);
        s.step(scene, 0, &Map, &settings, has_view)
    }

    #[test]
    fn a_map_is_kept_while_its_light_sees_the_same_and_patched_when_a_caster_moves() {
        let mut scene = Scene::load("dummy").unwrap();
        scene.shadow.shadow_cache = true;
        let mut s = DepthSchedule::default();
        s.resize(scene.lights.len());
        let first = step(&mut s, &scene, false).expect("a new map is drawn");
        assert!(first.patch.is_none());
        s.drawn(0, first);
        assert!(
            step(&mut s, &scene, true).is_none(),
            "an unchanged map is kept"
        );
        // A map never drawn into (no view yet) is drawn whole even with the key it had.
        assert!(step(&mut s, &scene, false).is_some_and(|st| st.patch.is_none()));
        let again = step(&mut s, &scene, false).unwrap();
        s.drawn(0, again);
        scene.items[0].position.x += 0.5;
        let moved = step(&mut s, &scene, true).expect("a moved caster redraws");
        let region = moved
            .patch
            .as_ref()
            .expect("a fixed camera is patched")
            .region;
        assert!(region.texels() > 0);
        s.drawn(0, moved);
        // A pass that fails (no `drawn`) leaves the map to be drawn whole.
        scene.items[0].position.x += 0.5;
        assert!(step(&mut s, &scene, true).is_some());
        assert!(step(&mut s, &scene, true).is_some_and(|st| st.patch.is_none()));
        // New storage holds nothing.
        let whole = step(&mut s, &scene, true).unwrap();
        s.drawn(0, whole);
        s.forget(0);
        assert!(step(&mut s, &scene, true).is_some_and(|st| st.patch.is_none()));
        let counted = DepthPasses {
            drawn: 3,
            skipped: 1,
            patched: 1,
            patched_texels: region.texels(),
        };
        assert_eq!(s.passes(), counted);
    }

    #[test]
    fn without_the_cache_every_map_is_drawn_whole() {
        let mut scene = Scene::load("dummy").unwrap();
        scene.shadow.shadow_cache = false;
        let mut s = DepthSchedule::default();
        s.resize(1);
        for _ in 0..3 {
            let st = step(&mut s, &scene, true).expect("drawn every frame");
            assert!(st.patch.is_none() && st.key.is_none());
            s.drawn(0, st);
        }
        assert_eq!(s.passes().drawn, 3);
        assert_eq!(s.keys(), &[None]);
    }
}
