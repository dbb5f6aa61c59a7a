//! Caster groups: a directional light's box fitted per group of casters (past the chapters,
//! and past [`super::fitted`]'s one box).
//!
//! One fitted box must hold every caster whose shadow the camera sees; two casters far
//! apart in the light's view make it large, and its texels coarse over both (LearnOpenGL's
//! scene: cube1 in the middle and cube3, whose shadow reaches the frame's corner). Here the
//! casters are grouped by where they lie across the light's view and each group gets its
//! own box ([`LightFit::fit_box`]) in a layer of a depth array ([`layers`]), so each group's
//! texels are as fine as if it were alone. The scene pass tests every layer and keeps the
//! darkest (`shaders/lib/shadow_groups.glsl`): a caster is drawn in its group's layer only,
//! and that layer's box covers every receiver in view it can shadow.

use glam::DVec3;

use super::casters::casters;
use super::fitted::{FittedBox, LightFit};
use super::layers::{self, Layout};
use super::{DepthPass, ShadowKind};
use crate::scene::{DirectionalLight, Scene};
use crate::settings::ShadowSettings;

/// Its sampler in the scene shader, per light.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["groupMap0", "groupMap1", "groupMap2", "groupMap3"];

/// Its part of the generated snippets (one light is layered): shaders/lib/shadow_groups.glsl
/// and its `addLightGroups` call.
pub const SNIPPET: layers::Snippet = layers::Snippet {
    file: "lib/shadow_groups.glsl",
    functions: &[
        "softTaps",
        "pcfArray",
        "layerLookup",
        "calcShadowGroups",
        "addLightGroups",
    ],
    add: "addLightGroups",
    samplers: SAMPLERS,
};

/// `fit`'s casters in at most `count` groups (item indices, each group in item order, the
/// groups by their first item). Starting from one group per caster, the two groups whose
/// rectangles across the light's view grow least when joined (the union's area less
/// theirs) are joined until `count` are left: casters side by side share a box, casters
/// far apart keep their own.
pub fn group_casters(fit: &LightFit, count: usize) -> Vec<Vec<usize>> {
    let rect = |i: usize| {
        let (lo, hi) = fit.light_box(i);
        [lo.x, lo.y, hi.x, hi.y]
    };
    let mut groups: Vec<(Vec<usize>, [f64; 4])> =
        fit.casters.iter().map(|&c| (vec![c], rect(c))).collect();
    let area = |r: &[f64; 4]| (r[2] - r[0]).max(0.0) * (r[3] - r[1]).max(0.0);
    let join = |a: &[f64; 4], b: &[f64; 4]| {
        [
            a[0].min(b[0]),
            a[1].min(b[1]),
            a[2].max(b[2]),
            a[3].max(b[3]),
        ]
    };
    while groups.len() > count.max(1) {
        let mut best = (f64::INFINITY, 0, 1);
        for a in 0..groups.len() {
            for b in a + 1..groups.len() {
                let (ra, rb) = (&groups[a].1, &groups[b].1);
                let growth = area(&join(ra, rb)) - area(ra) - area(rb);
                if growth < best.0 {
                    best = (growth, a, b);
                }
            }
        }
        let (_, a, b) = best;
        let (items, r) = groups.remove(b);
        groups[a].0.extend(items);
        groups[a].1 = join(&groups[a].1, &r);
    }
    let mut out: Vec<Vec<usize>> = groups
        .into_iter()
        .map(|(mut items, _)| {
            items.sort_unstable();
            items
        })
        .collect();
    out.sort();
    out
}

/// Caster groups as a [`Layout`]: a layer per group of casters, grouped and fitted each
/// depth pass (layers past the groups hold no caster and read lit).
#[derive(Default)]
pub struct Groups {
    groups: Vec<Vec<usize>>,
}

impl Layout for Groups {
    const KIND: ShadowKind = ShadowKind::Groups;
    const NAME: &'static str = "caster groups";

    fn count(s: &ShadowSettings) -> u32 {
        s.caster_groups
    }

    /// The casters whose shadow is in view, grouped; each group's box fitted to it.
    fn fit(&mut self, pass: &DepthPass, scene: &Scene, l: &DirectionalLight) -> Vec<FittedBox> {
        let s = pass.settings;
        let fit = LightFit::new(scene, l.direction);
        let count = s.caster_groups as usize;
        self.groups = group_casters(&fit, count);
        (0..count)
            .map(|k| {
                let group = self.groups.get(k).map_or(&[][..], Vec::as_slice);
                fit.fit_box(group, s.map_size, s.snap)
            })
            .collect()
    }

    /// A caster is drawn into its group's layer only.
    fn keeps(&self, layer: usize, item: usize, _: &(DVec3, DVec3)) -> bool {
        self.groups
            .get(layer)
            .is_some_and(|g| g.binary_search(&item).is_ok())
    }

    /// Each caster is offered once, to its group's layer.
    fn offered(&self, scene: &Scene) -> u64 {
        casters(scene)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Light;
    use glam::Vec3;

    fn learnopengl_fit(scene: &Scene) -> LightFit<'_> {
        let Light::Directional(l) = &scene.lights[0] else {
            panic!("learnopengl's light is directional");
        };
        LightFit::new(scene, l.direction)
    }

    fn names(scene: &Scene, groups: &[Vec<usize>]) -> Vec<Vec<String>> {
        groups
            .iter()
            .map(|g| g.iter().map(|&i| scene.items[i].name.clone()).collect())
            .collect()
    }

    #[test]
    fn far_apart_casters_get_their_own_groups_and_near_ones_share() {
        let mut scene = Scene::load("learnopengl").unwrap();
        // From the tutorial's camera: cube1 and cube3, far apart, one each.
        let fit = learnopengl_fit(&scene);
        assert_eq!(
            names(&scene, &group_casters(&fit, 2)),
            [["cube1"], ["cube3"]]
        );
        assert_eq!(
            names(&scene, &group_casters(&fit, 1)),
            [vec!["cube1", "cube3"]]
        );
        // From above all three cubes are in view: with two groups, the two nearest each
        // other across the light's view share one.
        scene.camera = crate::scene::Camera::look_at(Vec3::new(0.0, 12.0, 0.5), Vec3::ZERO)
            .expect("a direction");
        let fit = learnopengl_fit(&scene);
        let two = group_casters(&fit, 2);
        assert_eq!(two.len(), 2);
        assert_eq!(two.iter().map(Vec::len).sum::<usize>(), 3);
        assert_eq!(
            group_casters(&fit, 4).len(),
            3,
            "one group per caster at most"
        );
    }

    #[test]
    fn a_groups_box_is_smaller_than_the_box_around_every_caster() {
        let scene = Scene::load("learnopengl").unwrap();
        let fit = learnopengl_fit(&scene);
        let size = crate::settings::MapSize::square(1024);
        let all = fit.fit_box(&fit.casters, size, true);
        for group in group_casters(&fit, 2) {
            let own = fit.fit_box(&group, size, true);
            assert!(
                own.texel < all.texel * 0.75,
                "{group:?}: texel {} against {}",
                own.texel,
                all.texel
            );
        }
    }
}
