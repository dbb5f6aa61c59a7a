//! Caster groups: a directional light's box fitted per group of casters (past the chapters,
//! and past [`super::camera::fitted`]'s one box).
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

use super::camera::fitted::{FittedBox, LightFit};
use super::casters::casters;
use super::kind::{self, Family, IdleRules, KindFacts, LayerLayout, TechniqueFacts};
use super::layers::{self, Layout};
use super::{DepthPass, ShadowKind};
use crate::scene::{DirectionalLight, Scene};
use crate::settings::ShadowSettings;

/// Its sampler in the scene shader, per light.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["groupMap0", "groupMap1", "groupMap2", "groupMap3"];

/// Its part of the generated snippets (one light is layered): shaders/lib/shadow_groups.glsl
/// and its `calcShadowGroups` call.
/// Light `i`'s part of the scene program: the layered lookup of shadow_layers.glsl.
pub fn glsl(i: usize, _p: usize, test: &super::ShadowTest) -> Option<super::LightGlsl> {
    layers::glsl(&SNIPPET, i, test)
}

pub const SNIPPET: layers::Snippet = layers::Snippet {
    files: &["lib/shadow_groups.glsl"],
    function: "calcShadowGroups",
    takes_fragment: false,
    samplers: SAMPLERS,
};

/// The caster groups' row of the kind table.
pub const KIND: KindFacts = KindFacts {
    technique: Some(TechniqueFacts {
        create: |gl, s| Ok(Box::new(layers::Layered::<Groups>::new(gl, s)?)),
        glsl,
        samplers: &SAMPLERS,
        map_slot: false,
    }),
    words: |s| {
        let (size, depth) = (kind::sides(s.map_size), kind::depth_words(s.depth_format));
        format!(
            "Shadow: {} caster groups, a {size} map each, {depth}",
            s.caster_groups
        )
    },
    storage: layers::storage::<Groups>,
    // Each group's box is cut to the receivers in view.
    follows_camera: |_, _| true,
    // The cascades' layers (shadow_layers.glsl): the groups' count, no blend between them
    // and nothing to tint.
    layers: Some(|s| LayerLayout {
        count: s.caster_groups,
        blend_bits: 0f32.to_bits(),
        show: false,
    }),
    // A layered light's test reads per pixel.
    per_vertex: |_| false,
    family: |_| Family::Groups,
    idle: IdleRules {
        no_map: None,
        depth_lookup: |_| Some(kind::LAYERS_READ_NEAREST),
        light: layers::idle_for_light::<Groups>,
        scene: layers::idle_in_scene::<Groups>,
    },
};

/// `fit`'s casters in at most `count` groups (item indices, each group in item order, the
/// groups by their first item). A group's box spends its layer on its rectangle across
/// the light's view (cut to the receivers in view), so each of its casters gets texels of
/// that area: a grouping costs the sum over groups of area x casters. Starting from one
/// group per caster, the two groups whose joining adds least to that sum are joined until
/// `count` are left: casters side by side share a box, casters far apart keep their own,
/// and a caster that spans the view (a terrain) is not joined by the others for free.
pub fn group_casters(fit: &LightFit, count: usize) -> Vec<Vec<usize>> {
    let rects: Vec<(usize, [f64; 4])> =
        fit.casters.iter().map(|&c| (c, fit.view_rect(c))).collect();
    group_rects(&rects, count)
}

/// [`group_casters`] on (item, rectangle) pairs.
pub fn group_rects(rects: &[(usize, [f64; 4])], count: usize) -> Vec<Vec<usize>> {
    // Groups by slot (a joined group's slot empties), each with its casters, its
    // rectangle and its cheapest partner: (what joining it adds, the partner's slot).
    let mut groups: Vec<Option<(Vec<usize>, [f64; 4])>> =
        rects.iter().map(|&(c, r)| Some((vec![c], r))).collect();
    // What joining a and b adds (not a number, from coordinates too large to square,
    // counts as the most).
    let cost = |g: &[Option<(Vec<usize>, [f64; 4])>], a: usize, b: usize| match (&g[a], &g[b]) {
        (Some((ga, ra)), Some((gb, rb))) if a != b => {
            let (na, nb) = (ga.len() as f64, gb.len() as f64);
            let c = area(&join(ra, rb)) * (na + nb) - area(ra) * na - area(rb) * nb;
            if c.is_nan() {
                f64::INFINITY
            } else {
                c
            }
        }
        _ => f64::INFINITY,
    };
    // The cheapest other group; ties go to the lower slot, so the grouping does not depend
    // on rounding order. Only a lone group has none.
    let partner = |g: &[Option<(Vec<usize>, [f64; 4])>], a: usize| {
        (0..g.len())
            .filter(|&b| b != a && g[b].is_some())
            .map(|b| (cost(g, a, b), b))
            .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
            .unwrap_or((f64::INFINITY, usize::MAX))
    };
    let mut best: Vec<(f64, usize)> = (0..groups.len()).map(|a| partner(&groups, a)).collect();
    // Each join recomputes the joined group's partner and those of groups whose partner it
    // took; the others only compare their partner with the joined group: O(n^2) in all
    // for the usual case rather than O(n^3) (204 casters in view on `large`).
    for _ in count.max(1)..groups.len() {
        let Some((a, &(_, b))) = best
            .iter()
            .enumerate()
            .filter(|(a, _)| groups[*a].is_some())
            .min_by(|x, y| x.1 .0.total_cmp(&y.1 .0).then(x.0.cmp(&y.0)))
        else {
            break;
        };
        let Some((items, r)) = groups.get_mut(b).and_then(Option::take) else {
            break;
        };
        if let Some((ga, ra)) = groups[a].as_mut() {
            ga.extend(items);
            *ra = join(ra, &r);
        }
        best[a] = partner(&groups, a);
        for c in 0..groups.len() {
            if c == a || groups[c].is_none() {
                continue;
            }
            if best[c].1 == a || best[c].1 == b {
                best[c] = partner(&groups, c);
            } else {
                let with_a = cost(&groups, c, a);
                if with_a < best[c].0 || (with_a == best[c].0 && a < best[c].1) {
                    best[c] = (with_a, a);
                }
            }
        }
    }
    let mut out: Vec<Vec<usize>> = groups
        .into_iter()
        .flatten()
        .map(|(mut items, _)| {
            items.sort_unstable();
            items
        })
        .collect();
    out.sort();
    out
}

fn area(r: &[f64; 4]) -> f64 {
    (r[2] - r[0]).max(0.0) * (r[3] - r[1]).max(0.0)
}

fn join(a: &[f64; 4], b: &[f64; 4]) -> [f64; 4] {
    [
        a[0].min(b[0]),
        a[1].min(b[1]),
        a[2].max(b[2]),
        a[3].max(b[3]),
    ]
}

/// Caster groups as a [`Layout`]: a layer per group of casters, grouped and fitted each
/// depth pass (layers past the groups hold no caster and read lit).
#[derive(Default)]
pub struct Groups {
    groups: Vec<Vec<usize>>,
}

impl Layout for Groups {
    const KIND: ShadowKind = ShadowKind::Groups;
    const SETTING: &'static str = "caster_groups";
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
    fn the_grouping_joins_the_cheapest_pair_each_time() {
        // Against the plain search over every pair at every join, on scattered
        // rectangles of mixed sizes (one spanning most of the others).
        fn plain(rects: &[(usize, [f64; 4])], count: usize) -> Vec<Vec<usize>> {
            let mut g: Vec<(Vec<usize>, [f64; 4])> =
                rects.iter().map(|&(c, r)| (vec![c], r)).collect();
            while g.len() > count.max(1) {
                let mut best = (f64::INFINITY, 0, 1);
                for a in 0..g.len() {
                    for b in a + 1..g.len() {
                        let (na, nb) = (g[a].0.len() as f64, g[b].0.len() as f64);
                        let c = area(&join(&g[a].1, &g[b].1)) * (na + nb)
                            - area(&g[a].1) * na
                            - area(&g[b].1) * nb;
                        if c < best.0 {
                            best = (c, a, b);
                        }
                    }
                }
                let (items, r) = g.remove(best.2);
                g[best.1].0.extend(items);
                g[best.1].1 = join(&g[best.1].1, &r);
            }
            let mut out: Vec<Vec<usize>> = g
                .into_iter()
                .map(|(mut i, _)| {
                    i.sort_unstable();
                    i
                })
                .collect();
            out.sort();
            out
        }
        for seed in 1..=30u64 {
            let mut state = seed;
            let mut next = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (state >> 33) as f64 / f64::from(1u32 << 31)
            };
            // Clusters of small rectangles, some large ones, one spanning most of them.
            let mut rects: Vec<(usize, [f64; 4])> = (0..30)
                .map(|i| {
                    let (cx, cy) = ((i % 3) as f64 * 40.0, (i % 2) as f64 * 50.0);
                    let size = if next() < 0.2 { 30.0 } else { 4.0 };
                    let (x, y) = (cx + next() * 20.0, cy + next() * 20.0);
                    (i, [x, y, x + next() * size, y + next() * size])
                })
                .collect();
            rects.push((30, [0.0, 0.0, 90.0, 90.0]));
            for count in [1, 2, 3, 4, 7, 31, 40] {
                assert_eq!(
                    group_rects(&rects, count),
                    plain(&rects, count),
                    "seed {seed}, {count} groups"
                );
            }
        }
        assert!(group_rects(&[], 2).is_empty());
        // Coordinates whose areas overflow still give `count` groups.
        let huge: Vec<(usize, [f64; 4])> = (0..5)
            .map(|i| (i, [-1e300, f64::from(i as u32), 1e300, 1e300]))
            .collect();
        assert_eq!(group_rects(&huge, 2).len(), 2);
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
