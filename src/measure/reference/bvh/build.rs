//! Building the hierarchy: binned SAH splits, median splits past a depth, flat nodes in
//! the order traversal reads them.

use glam::Vec3;

use super::{Bvh, Node, Triangle, SAH_DEPTH_LIMIT};

/// Triangles per leaf. Small leaves keep shadow rays cheap.
const MAX_LEAF: usize = 4;

/// Number of SAH bins per axis; 16 is the usual quality/speed compromise.
const BINS: usize = 16;

/// Axis-aligned box used during the build.
#[derive(Clone, Copy)]
struct Aabb {
    lo: Vec3,
    hi: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        lo: Vec3::splat(f32::INFINITY),
        hi: Vec3::splat(f32::NEG_INFINITY),
    };

    fn grow(&mut self, other: &Aabb) {
        self.lo = self.lo.min(other.lo);
        self.hi = self.hi.max(other.hi);
    }

    fn grow_point(&mut self, p: Vec3) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }

    fn half_area(&self) -> f32 {
        let d = (self.hi - self.lo).max(Vec3::ZERO);
        d.x * d.y + d.y * d.z + d.z * d.x
    }
}

/// Bin of a centroid coordinate; shared by binning and partitioning so the
/// two can never disagree.
#[inline]
fn bin_of(c: f32, lo: f32, scale: f32) -> usize {
    // `as usize` saturates negatives and NaN to 0.
    (((c - lo) * scale) as usize).min(BINS - 1)
}

impl Bvh {
    /// Builds the hierarchy. Degenerate and non-finite triangles are dropped
    /// (see [`Triangle::is_degenerate`]); empty input gives an empty BVH.
    ///
    /// # Panics
    /// If more than `u32::MAX` triangles remain (memory would run out first).
    pub fn build(triangles: Vec<Triangle>) -> Bvh {
        let (kept, tris): (Vec<u32>, Vec<Triangle>) = (0u32..)
            .zip(triangles)
            .filter(|(_, t)| !t.is_degenerate())
            .unzip();
        let n = tris.len();
        if n == 0 {
            return Bvh {
                nodes: Vec::new(),
                tris: Vec::new(),
                ids: Vec::new(),
            };
        }
        assert!(u32::try_from(n).is_ok(), "too many triangles for the BVH");

        let boxes: Vec<Aabb> = tris
            .iter()
            .map(|t| Aabb {
                lo: t.a.min(t.b).min(t.c),
                hi: t.a.max(t.b).max(t.c),
            })
            .collect();
        let centroids: Vec<Vec3> = boxes.iter().map(|b| (b.lo + b.hi) * 0.5).collect();
        let mut order: Vec<u32> = (0..n as u32).collect();

        let mut nodes = Vec::with_capacity(2 * n.div_ceil(MAX_LEAF) + 1);
        nodes.push(Node::EMPTY);
        // (node index, first, end, depth)
        let mut work = vec![(0usize, 0usize, n, 0usize)];
        while let Some((ni, start, end, depth)) = work.pop() {
            let items = &mut order[start..end];
            let mut bounds = Aabb::EMPTY;
            let mut cbounds = Aabb::EMPTY;
            for &i in items.iter() {
                bounds.grow(&boxes[i as usize]);
                cbounds.grow_point(centroids[i as usize]);
            }
            // Pad by a few hundred ulps of the coordinates so rounding in the
            // slab test never culls a box whose triangle would be hit.
            let mag = bounds.lo.abs().max(bounds.hi.abs()).max_element();
            let pad = Vec3::splat(mag * 1e-6 + 1e-30);
            nodes[ni].lo = bounds.lo - pad;
            nodes[ni].hi = bounds.hi + pad;

            let count = end - start;
            if count <= MAX_LEAF {
                nodes[ni].start = start as u32;
                nodes[ni].count = count as u32;
                continue;
            }
            let split = if depth < SAH_DEPTH_LIMIT {
                sah_partition(items, &boxes, &centroids, &cbounds)
            } else {
                None
            };
            let mid =
                start + split.unwrap_or_else(|| median_partition(items, &centroids, &cbounds));

            let left = nodes.len();
            nodes.push(Node::EMPTY);
            nodes.push(Node::EMPTY);
            nodes[ni].start = left as u32;
            nodes[ni].count = 0;
            work.push((left + 1, mid, end, depth + 1));
            work.push((left, start, mid, depth + 1));
        }

        let tris = order.iter().map(|&i| tris[i as usize].prepared()).collect();
        let ids = order.iter().map(|&i| kept[i as usize]).collect();
        Bvh { nodes, tris, ids }
    }
}

/// Binned-SAH split of `items` in place; returns the size of the left part,
/// or None when no split separates the centroids.
fn sah_partition(
    items: &mut [u32],
    boxes: &[Aabb],
    centroids: &[Vec3],
    cbounds: &Aabb,
) -> Option<usize> {
    let extent = cbounds.hi - cbounds.lo;
    // (cost, axis, last bin of the left side, left count)
    let mut best: Option<(f32, usize, usize, usize)> = None;
    for axis in 0..3 {
        if extent[axis].is_nan() || extent[axis] <= 0.0 {
            continue;
        }
        let scale = BINS as f32 / extent[axis];
        let lo = cbounds.lo[axis];
        let mut bin_box = [Aabb::EMPTY; BINS];
        let mut bin_count = [0usize; BINS];
        for &i in items.iter() {
            let b = bin_of(centroids[i as usize][axis], lo, scale);
            bin_box[b].grow(&boxes[i as usize]);
            bin_count[b] += 1;
        }
        // Sweep from the right to get the cost of every right-hand side.
        let mut right_area = [0.0f32; BINS];
        let mut right_count = [0usize; BINS];
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0;
        for b in (1..BINS).rev() {
            acc.grow(&bin_box[b]);
            cnt += bin_count[b];
            right_area[b] = acc.half_area();
            right_count[b] = cnt;
        }
        let mut acc = Aabb::EMPTY;
        let mut cnt = 0;
        for b in 0..BINS - 1 {
            acc.grow(&bin_box[b]);
            cnt += bin_count[b];
            let rc = right_count[b + 1];
            if cnt == 0 || rc == 0 {
                continue;
            }
            let cost = acc.half_area() * cnt as f32 + right_area[b + 1] * rc as f32;
            if best.is_none_or(|(c, ..)| cost < c) {
                best = Some((cost, axis, b, cnt));
            }
        }
    }
    let (_, axis, last_left, left_count) = best?;
    let scale = BINS as f32 / extent[axis];
    let lo = cbounds.lo[axis];
    let mut i = 0;
    let mut j = items.len();
    while i < j {
        if bin_of(centroids[items[i] as usize][axis], lo, scale) <= last_left {
            i += 1;
        } else {
            j -= 1;
            items.swap(i, j);
        }
    }
    debug_assert_eq!(i, left_count);
    Some(i)
}

/// Splits `items` in half by centroid along the widest centroid axis. Always
/// succeeds, even when every centroid coincides.
fn median_partition(items: &mut [u32], centroids: &[Vec3], cbounds: &Aabb) -> usize {
    let extent = cbounds.hi - cbounds.lo;
    let axis = if extent.x >= extent.y && extent.x >= extent.z {
        0
    } else if extent.y >= extent.z {
        1
    } else {
        2
    };
    let mid = items.len() / 2;
    items.select_nth_unstable_by(mid, |&a, &b| {
        centroids[a as usize][axis].total_cmp(&centroids[b as usize][axis])
    });
    mid
}
