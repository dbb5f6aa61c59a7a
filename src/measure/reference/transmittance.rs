//! The truth for translucent casters: a shadow ray collects every surface it crosses on its
//! way to the light, 0 at an opaque one (the hard reference's answer), and (1 - opacity) at
//! each crossing of a translucent item's surface; the light left is the product.

use glam::Vec3;

use super::bvh::{hit_t, slab_entry, Bvh, Triangle};
use super::visibility::{par_rows, receiver, LightKind, RefPixel, RAY_EPSILON};

/// Every crossing of a translucent surface, with whose it is.
pub struct Translucent {
    bvh: Bvh,
    /// The item of each triangle, in the order they were given.
    item_of: Vec<u32>,
    /// Each item's opacity.
    opacity: Vec<f32>,
}

/// One crossing of a translucent surface along a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    /// Distance along the ray, in units of its direction.
    pub t: f32,
    /// The item crossed (its index among those given to [`Translucent::new`]).
    pub item: u32,
    pub opacity: f32,
}

/// Hits of one item closer than this (relative to the distance) are one crossing: a ray
/// through an edge meets both triangles that share it.
const SAME_CROSSING: f32 = 1e-5;

impl Translucent {
    /// The translucent items, each its opacity and its triangles (world space, relative
    /// to the reference's origin).
    pub fn new(items: impl IntoIterator<Item = (f32, Vec<Triangle>)>) -> Translucent {
        let (mut triangles, mut item_of, mut opacity) = (Vec::new(), Vec::new(), Vec::new());
        for (k, (a, tris)) in items.into_iter().enumerate() {
            item_of.extend(std::iter::repeat_n(k as u32, tris.len()));
            triangles.extend(tris);
            opacity.push(a);
        }
        Translucent {
            bvh: Bvh::build(triangles),
            item_of,
            opacity,
        }
    }

    pub fn is_empty(&self) -> bool {
        self.bvh.triangle_count() == 0
    }

    /// The crossings at t in (t_min, t_max), nearest first.
    pub fn crossings(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> Vec<Crossing> {
        let mut hits = Vec::new();
        let b = &self.bvh;
        // Written so that NaN bounds give no crossings.
        if b.nodes.is_empty() || t_max.partial_cmp(&t_min) != Some(std::cmp::Ordering::Greater) {
            return hits;
        }
        let inv = Vec3::ONE / dir;
        let mut stack = vec![0usize];
        while let Some(ni) = stack.pop() {
            let node = &b.nodes[ni];
            if slab_entry(node, origin, inv, t_min, t_max).is_none() {
                continue;
            }
            let start = node.start as usize;
            if node.count == 0 {
                stack.extend([start, start + 1]);
                continue;
            }
            for k in start..start + node.count as usize {
                if let Some(t) = hit_t(&b.tris[k], origin, dir, t_min, t_max) {
                    let item = self.item_of[b.ids[k] as usize];
                    let opacity = self.opacity[item as usize];
                    hits.push(Crossing { t, item, opacity });
                }
            }
        }
        hits.sort_by(|a, b| a.t.total_cmp(&b.t).then(a.item.cmp(&b.item)));
        let mut out: Vec<Crossing> = Vec::with_capacity(hits.len());
        for h in hits {
            let same = out
                .iter()
                .rev()
                .take_while(|c| h.t - c.t <= SAME_CROSSING * h.t.abs().max(1.0));
            if !same.clone().any(|c| c.item == h.item) {
                out.push(h);
            }
        }
        out
    }

    /// The light left after the crossings at t in (t_min, t_max).
    pub fn transmittance(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> f32 {
        left_after(&self.crossings(origin, dir, t_min, t_max))
    }
}

/// The product of (1 - opacity) over `crossings`.
pub fn left_after(crossings: &[Crossing]) -> f32 {
    crossings.iter().map(|c| 1.0 - c.opacity).product()
}

/// The transmittance truth per G-buffer pixel: `hard` (the opaque casters' hard reference)
/// where it is 0, else the light the translucent crossings leave. Receivers are `hard`'s.
pub fn reference_transmittance(
    hard: &[RefPixel],
    translucent: &Translucent,
    light: &LightKind,
    gbuf: &super::GBuffer,
) -> Vec<RefPixel> {
    let width = gbuf.width;
    par_rows(width, gbuf.height, RefPixel::EMPTY, |x, y| {
        let i = y * width + x;
        let opaque = hard.get(i).copied().unwrap_or(RefPixel::EMPTY);
        if !opaque.receiver || opaque.visibility <= 0.0 {
            return opaque;
        }
        let Ok((origin, dir)) = receiver(light, gbuf, i) else {
            return opaque;
        };
        let t_max = match light.position() {
            None => f32::INFINITY,
            Some(p) => (p - origin).length() - RAY_EPSILON * p.abs().max_element().max(1.0),
        };
        RefPixel {
            visibility: translucent.transmittance(origin, dir, 0.0, t_max),
            ..opaque
        }
    })
}

/// How far a rendered light (the visibility output: the shadow test times the light its
/// translucent casters leave) is from the transmittance truth, over its receivers.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct TransmittanceMetrics {
    pub receivers: usize,
    pub mae: f64,
    pub max_error: f64,
    /// Receivers the opaque casters leave lit but a translucent one dims (truth below 1).
    pub in_shadow: usize,
    /// The mean error there ("within the translucent shadow"); 0 where there are none.
    pub mae_in_shadow: f64,
    /// The mean error over the other receivers.
    pub mae_outside: f64,
}

/// Scores `rendered` (`None` or NaN: no value) against `truth` ([`reference_transmittance`]).
/// A receiver without a rendered value counts as fully wrong.
pub fn score_transmittance(rendered: &[Option<f32>], truth: &[RefPixel]) -> TransmittanceMetrics {
    let (mut all, mut inside, mut outside) = ((0.0, 0), (0.0, 0), (0.0, 0));
    let mut max_error = 0.0f64;
    for (i, r) in truth.iter().enumerate().filter(|(_, r)| r.receiver) {
        let v = rendered.get(i).copied().flatten().filter(|v| v.is_finite());
        let e = v.map_or(1.0, |v| f64::from((v.clamp(0.0, 1.0) - r.visibility).abs()));
        let part = match r.visibility > 0.0 && r.visibility < 1.0 {
            true => &mut inside,
            false => &mut outside,
        };
        *part = (part.0 + e, part.1 + 1);
        all = (all.0 + e, all.1 + 1);
        max_error = max_error.max(e);
    }
    let mean = |(sum, n): (f64, usize)| if n == 0 { 0.0 } else { sum / n as f64 };
    TransmittanceMetrics {
        receivers: all.1,
        mae: mean(all),
        max_error,
        in_shadow: inside.1,
        mae_in_shadow: mean(inside),
        mae_outside: mean(outside),
    }
}

/// RGBA picture of the errors against the transmittance truth: `base_grey` where they
/// agree, towards red where the rendered light is too dark, towards blue where too bright
/// (full colour at an error of 0.5 or more).
pub fn transmittance_error_image(
    rendered: &[Option<f32>],
    truth: &[RefPixel],
    base_grey: &[u8],
) -> Vec<[u8; 4]> {
    (0..truth.len())
        .map(|i| {
            let g = f32::from(base_grey.get(i).copied().unwrap_or(0));
            let v = rendered.get(i).copied().flatten().filter(|v| v.is_finite());
            let e = match (truth[i].receiver, v) {
                (true, Some(v)) => v.clamp(0.0, 1.0) - truth[i].visibility,
                _ => 0.0,
            };
            let w = (e.abs() * 2.0).min(1.0);
            let towards = if e < 0.0 {
                [255.0, 0.0, 0.0]
            } else {
                [0.0, 0.0, 255.0]
            };
            let c = towards.map(|t| (g + (t - g) * w).round() as u8);
            [c[0], c[1], c[2], 255]
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A square sheet at height `y`, x and z in [-1, 1].
    fn sheet(y: f32) -> Vec<Triangle> {
        let p =
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)].map(|(x, z)| Vec3::new(x, y, z));
        vec![
            Triangle {
                a: p[0],
                b: p[1],
                c: p[2],
            },
            Triangle {
                a: p[0],
                b: p[2],
                c: p[3],
            },
        ]
    }

    const UP: Vec3 = Vec3::Y;

    #[test]
    fn one_sheet_leaves_one_minus_its_opacity_behind_it_and_all_beside_it() {
        let t = Translucent::new([(0.3, sheet(1.0))]);
        let behind = t.transmittance(Vec3::new(0.2, 0.0, 0.4), UP, 0.0, f32::INFINITY);
        assert!((behind - 0.7).abs() < 1e-6, "{behind}");
        let beside = t.transmittance(Vec3::new(1.5, 0.0, 0.0), UP, 0.0, f32::INFINITY);
        assert_eq!(beside, 1.0);
        let above = t.transmittance(Vec3::new(0.0, 2.0, 0.0), UP, 0.0, f32::INFINITY);
        assert_eq!(above, 1.0);
    }

    #[test]
    fn stacked_sheets_multiply_and_come_nearest_first() {
        let t = Translucent::new([(0.5, sheet(2.0)), (0.25, sheet(1.0))]);
        let c = t.crossings(Vec3::new(0.1, 0.0, -0.3), UP, 0.0, f32::INFINITY);
        assert_eq!(c.iter().map(|c| c.item).collect::<Vec<_>>(), [1, 0]);
        assert!((left_after(&c) - 0.75 * 0.5).abs() < 1e-6);
        // Between the sheets only the upper one is crossed.
        let between = t.transmittance(Vec3::new(0.1, 1.5, -0.3), UP, 0.0, f32::INFINITY);
        assert!((between - 0.5).abs() < 1e-6);
    }

    #[test]
    fn a_ray_through_a_shared_edge_crosses_once() {
        // The sheet's diagonal runs from (-1, -1) to (1, 1): both triangles meet there.
        let t = Translucent::new([(0.4, sheet(1.0))]);
        let c = t.crossings(Vec3::new(0.25, 0.0, 0.25), UP, 0.0, f32::INFINITY);
        assert_eq!(c.len(), 1, "{c:?}");
    }

    fn px(visibility: f32) -> RefPixel {
        RefPixel {
            covered: true,
            receiver: true,
            visibility,
        }
    }

    #[test]
    fn scores_split_within_and_outside_the_translucent_shadow() {
        let truth = [px(0.5), px(0.5), px(1.0), px(0.0), RefPixel::EMPTY];
        let rendered = [Some(0.5), Some(1.0), Some(0.75), None, Some(0.0)];
        let m = score_transmittance(&rendered, &truth);
        assert_eq!((m.receivers, m.in_shadow), (4, 2));
        assert!(
            (m.mae - (0.0 + 0.5 + 0.25 + 1.0) / 4.0).abs() < 1e-9,
            "{m:?}"
        );
        assert!((m.mae_in_shadow - 0.25).abs() < 1e-9);
        assert!((m.mae_outside - 0.625).abs() < 1e-9);
        assert_eq!(m.max_error, 1.0);
        let image = transmittance_error_image(&rendered, &truth, &[100; 5]);
        assert_eq!(image[0], [100, 100, 100, 255]);
        assert_eq!(image[1], [0, 0, 255, 255]);
    }

    #[test]
    fn t_max_stops_short_of_a_sheet_past_the_light() {
        let t = Translucent::new([(0.9, sheet(3.0))]);
        assert_eq!(t.transmittance(Vec3::ZERO, UP, 0.0, 2.0), 1.0);
        assert!((t.transmittance(Vec3::ZERO, UP, 0.0, 4.0) - 0.1).abs() < 1e-6);
    }
}
