//! Bounding volume hierarchy over triangles. Shadow rays ask only "is anything
//! in the way?" (any-hit), so traversal stops at the first hit; the one other
//! query, [`Bvh::face_normal_near`], finds which triangle a camera ray meets
//! at a known distance (the face under a G-buffer pixel).

use glam::Vec3;

/// One triangle of the occluding scene, in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    pub a: Vec3,
    pub b: Vec3,
    pub c: Vec3,
}

/// Barycentric slack on every edge. Two triangles sharing an edge are then
/// both hit by a ray through that edge despite rounding, so shadow rays do
/// not leak through mesh seams.
const EDGE_TOL: f32 = 1e-6;

/// Triangles whose edges span a sine of angle below this are treated as
/// zero-area: they cannot block a ray, and their determinant is pure noise.
const DEGENERATE_SIN: f32 = 1e-6;

/// Triangles per leaf. Small leaves keep shadow rays cheap.
const MAX_LEAF: usize = 4;

/// Number of SAH bins per axis; 16 is the usual quality/speed compromise.
const BINS: usize = 16;

/// Beyond this depth the builder switches to median splits, which halve the
/// node every level. The tree depth is then at most 32 + 32 = 64, so a
/// fixed 64-entry traversal stack can never overflow.
const SAH_DEPTH_LIMIT: usize = 32;
const STACK_SIZE: usize = 64;

impl Triangle {
    /// Edges as used by the intersection test; computed the same way
    /// everywhere so the BVH and [`Triangle::intersects`] agree bit for bit.
    fn prepared(&self) -> [Vec3; 3] {
        [self.a, self.b - self.a, self.c - self.a]
    }

    /// True for triangles that can never block a ray: non-finite vertices,
    /// repeated vertices or (nearly) collinear vertices.
    pub fn is_degenerate(&self) -> bool {
        if !(self.a.is_finite() && self.b.is_finite() && self.c.is_finite()) {
            return true;
        }
        let [_, e1, e2] = self.prepared();
        let n2 = e1.cross(e2).length_squared();
        let bound = DEGENERATE_SIN * DEGENERATE_SIN * e1.length_squared() * e2.length_squared();
        // Written as a negation so that NaN counts as degenerate.
        !(n2 > bound && n2 > 0.0)
    }

    /// The same double-sided test the BVH uses, exposed for brute-force
    /// checks: true if the ray hits at some t in (t_min, t_max).
    pub fn intersects(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> bool {
        !self.is_degenerate() && hit(&self.prepared(), origin, dir, t_min, t_max)
    }
}

/// Double-sided Moller-Trumbore on a prepared triangle `[v0, e1, e2]`.
#[inline(always)]
fn hit(tri: &[Vec3; 3], origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> bool {
    hit_t(tri, origin, dir, t_min, t_max).is_some()
}

/// [`hit`], giving the distance of the hit.
#[inline(always)]
pub(super) fn hit_t(
    tri: &[Vec3; 3],
    origin: Vec3,
    dir: Vec3,
    t_min: f32,
    t_max: f32,
) -> Option<f32> {
    let [v0, e1, e2] = *tri;
    let p = dir.cross(e2);
    let det = e1.dot(p);
    // Parallel rays (and NaN input) give a zero or unusable determinant.
    if det.is_nan() || det.abs() < f32::MIN_POSITIVE {
        return None;
    }
    let inv_det = 1.0 / det;
    let s = origin - v0;
    let u = s.dot(p) * inv_det;
    if !((-EDGE_TOL..=1.0 + EDGE_TOL).contains(&u)) {
        return None;
    }
    let q = s.cross(e1);
    let v = dir.dot(q) * inv_det;
    if !(v >= -EDGE_TOL && u + v <= 1.0 + EDGE_TOL) {
        return None;
    }
    let t = e2.dot(q) * inv_det;
    (t > t_min && t < t_max).then_some(t)
}

/// Flat node. Leaves have `count > 0` and own `tris[start..start + count]`;
/// inner nodes have `count == 0` and children at `start` and `start + 1`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Node {
    lo: Vec3,
    hi: Vec3,
    pub(super) start: u32,
    pub(super) count: u32,
}

impl Node {
    const EMPTY: Node = Node {
        lo: Vec3::ZERO,
        hi: Vec3::ZERO,
        start: 0,
        count: 0,
    };
}

/// Any-hit BVH built with binned SAH. Nodes and triangles live in flat
/// vectors so traversal is a loop over indices, not pointer chasing.
#[derive(Debug, Clone)]
pub struct Bvh {
    pub(super) nodes: Vec<Node>,
    /// Triangles in leaf order, prepared as `[v0, e1, e2]`.
    pub(super) tris: Vec<[Vec3; 3]>,
    /// Each of `tris`' index in the triangles it was built from (for the crossings of
    /// [`super::transmittance`], which need to know whose surface a hit is).
    pub(super) ids: Vec<u32>,
}

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

    /// Number of triangles stored (after dropping degenerate ones).
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// True if any triangle is hit at distance t in (t_min, t_max), with t
    /// measured in units of `dir` (which need not be normalised). Triangles
    /// are double-sided. `t_max` may be `f32::INFINITY`.
    pub fn occluded(&self, origin: Vec3, dir: Vec3, t_min: f32, t_max: f32) -> bool {
        // Also rejects NaN bounds.
        if self.nodes.is_empty() || t_min.is_nan() || t_max.is_nan() || t_max <= t_min {
            return false;
        }
        // Zero components become +-infinity; `slab_entry` copes with that.
        let inv = Vec3::ONE / dir;
        if slab_entry(&self.nodes[0], origin, inv, t_min, t_max).is_none() {
            return false;
        }
        let mut stack = [0u32; STACK_SIZE];
        let mut sp = 0usize;
        let mut ni = 0usize;
        loop {
            let node = &self.nodes[ni];
            if node.count > 0 {
                let first = node.start as usize;
                let leaf = &self.tris[first..first + node.count as usize];
                if leaf.iter().any(|t| hit(t, origin, dir, t_min, t_max)) {
                    return true;
                }
            } else {
                let l = node.start as usize;
                let r = l + 1;
                let el = slab_entry(&self.nodes[l], origin, inv, t_min, t_max);
                let er = slab_entry(&self.nodes[r], origin, inv, t_min, t_max);
                match (el, er) {
                    (Some(a), Some(b)) => {
                        // Nearer child first: a hit close to the origin is
                        // the likeliest and ends the search.
                        let (near, far) = if a <= b { (l, r) } else { (r, l) };
                        stack[sp] = far as u32;
                        sp += 1;
                        ni = near;
                        continue;
                    }
                    (Some(_), None) => {
                        ni = l;
                        continue;
                    }
                    (None, Some(_)) => {
                        ni = r;
                        continue;
                    }
                    (None, None) => {}
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            ni = stack[sp] as usize;
        }
    }
}

impl Bvh {
    /// The geometric normal (unit, in the triangle's winding) of the triangle the ray
    /// meets within (t_min, t_max) whose normal lines up best with `like`, if any. A
    /// G-buffer pixel's camera ray, cut to a thin window around the pixel's distance, finds
    /// the face the rasteriser drew there whatever lies in front of it; where another
    /// surface passes through the window too (two items that meet), the drawn face is the
    /// one whose normal its interpolated normal `like` follows.
    pub fn face_normal_near(
        &self,
        origin: Vec3,
        dir: Vec3,
        t_min: f32,
        t_max: f32,
        like: Vec3,
    ) -> Option<Vec3> {
        if self.nodes.is_empty() || t_min.is_nan() || t_max.is_nan() || t_max <= t_min {
            return None;
        }
        let inv = Vec3::ONE / dir;
        let mut best: Option<(f32, Vec3)> = None;
        // Both children are pushed, so the stack holds at most depth + 1 nodes.
        let mut stack = [0u32; STACK_SIZE + 2];
        let mut sp = 0usize;
        if slab_entry(&self.nodes[0], origin, inv, t_min, t_max).is_some() {
            stack[0] = 0;
            sp = 1;
        }
        while sp > 0 {
            sp -= 1;
            let node = &self.nodes[stack[sp] as usize];
            if node.count > 0 {
                let first = node.start as usize;
                for t in &self.tris[first..first + node.count as usize] {
                    if hit_t(t, origin, dir, t_min, t_max).is_some() {
                        let n = t[1].cross(t[2]).normalize_or_zero();
                        let agree = n.dot(like).abs();
                        if best.is_none_or(|(a, _)| agree > a) {
                            best = Some((agree, n));
                        }
                    }
                }
            } else {
                // Every child the window reaches: the best hit is wanted, not the first
                // one, and the window is thin, so few boxes qualify.
                for child in [node.start, node.start + 1] {
                    if slab_entry(&self.nodes[child as usize], origin, inv, t_min, t_max).is_some()
                    {
                        stack[sp] = child;
                        sp += 1;
                    }
                }
            }
        }
        best.map(|(_, n)| n)
    }
}

/// Entry distance of the ray into the node's box clipped to (t_min, t_max),
/// or None if it misses.
#[inline(always)]
pub(super) fn slab_entry(node: &Node, o: Vec3, inv: Vec3, t_min: f32, t_max: f32) -> Option<f32> {
    let mut near = t_min;
    let mut far = t_max;
    slab_axis(node.lo.x, node.hi.x, o.x, inv.x, &mut near, &mut far);
    slab_axis(node.lo.y, node.hi.y, o.y, inv.y, &mut near, &mut far);
    slab_axis(node.lo.z, node.hi.z, o.z, inv.z, &mut near, &mut far);
    (near <= far).then_some(near)
}

#[inline(always)]
fn slab_axis(lo: f32, hi: f32, o: f32, inv: f32, near: &mut f32, far: &mut f32) {
    let t1 = (lo - o) * inv;
    let t2 = (hi - o) * inv;
    // 0 * inf = NaN happens only when the ray is parallel to this slab and
    // starts exactly on one of its faces. Treat that face as inside, so the
    // box is kept: culling must never be stricter than the triangle test.
    let (n1, f1) = if t1.is_nan() {
        (f32::NEG_INFINITY, f32::INFINITY)
    } else {
        (t1, t1)
    };
    let (n2, f2) = if t2.is_nan() {
        (f32::NEG_INFINITY, f32::INFINITY)
    } else {
        (t2, t2)
    };
    *near = near.max(n1.min(n2));
    *far = far.min(f1.max(f2));
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Small deterministic generator so the tests need no extra crates.
    struct Rng(u64);
    impl Rng {
        fn next_u32(&mut self) -> u32 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 33) as u32
        }
        fn unit(&mut self) -> f32 {
            self.next_u32() as f32 / (1u64 << 31) as f32
        }
        fn range(&mut self, lo: f32, hi: f32) -> f32 {
            lo + (hi - lo) * self.unit()
        }
        fn vec(&mut self, lo: f32, hi: f32) -> Vec3 {
            Vec3::new(self.range(lo, hi), self.range(lo, hi), self.range(lo, hi))
        }
        /// Integer grid point, so rays and boxes share planes exactly.
        fn grid(&mut self, half: i32) -> Vec3 {
            let span = (2 * half + 1) as u32;
            let mut g = || (self.next_u32() % span) as i32 - half;
            Vec3::new(g() as f32, g() as f32, g() as f32)
        }
    }

    fn brute(tris: &[Triangle], o: Vec3, d: Vec3, t0: f32, t1: f32) -> bool {
        tris.iter().any(|t| t.intersects(o, d, t0, t1))
    }

    fn random_scene(rng: &mut Rng, n: usize) -> Vec<Triangle> {
        let mut tris = Vec::with_capacity(n);
        for k in 0..n {
            let tri = match k % 10 {
                // Grid-aligned triangles, some axis-aligned, so box faces
                // coincide with ray origins.
                0..=2 => {
                    let a = rng.grid(8);
                    Triangle {
                        a,
                        b: a + rng.grid(2),
                        c: a + rng.grid(2),
                    }
                }
                // Zero-area triangles must never report a hit.
                3 => {
                    let a = rng.vec(-10.0, 10.0);
                    let b = rng.vec(-10.0, 10.0);
                    Triangle {
                        a,
                        b,
                        c: a + (b - a) * 0.25,
                    }
                }
                _ => {
                    let a = rng.vec(-10.0, 10.0);
                    Triangle {
                        a,
                        b: a + rng.vec(-1.5, 1.5),
                        c: a + rng.vec(-1.5, 1.5),
                    }
                }
            };
            tris.push(tri);
        }
        tris
    }

    #[test]
    fn matches_brute_force_on_random_rays() {
        let mut rng = Rng(7);
        let tris = random_scene(&mut rng, 2000);
        let bvh = Bvh::build(tris.clone());
        assert!(bvh.triangle_count() > 1500 && bvh.triangle_count() <= 2000);
        let (mut hits, mut misses) = (0, 0);
        for k in 0..5000 {
            let o = rng.vec(-12.0, 12.0);
            let d = if k % 2 == 0 {
                rng.vec(-1.0, 1.0).normalize_or_zero()
            } else {
                rng.vec(-1.0, 1.0) * 3.0
            };
            let (t0, t1) = match k % 3 {
                0 => (0.0, f32::INFINITY),
                1 => (0.0, rng.range(0.0, 20.0)),
                _ => (rng.range(0.0, 5.0), rng.range(5.0, 30.0)),
            };
            let expect = brute(&tris, o, d, t0, t1);
            assert_eq!(bvh.occluded(o, d, t0, t1), expect, "ray {k}: {o} {d}");
            if expect {
                hits += 1;
            } else {
                misses += 1;
            }
        }
        // Both outcomes must be well represented for the check to mean much.
        assert!(hits > 500 && misses > 500, "hits {hits} misses {misses}");
    }

    #[test]
    fn face_normal_near_takes_the_face_the_normal_follows() {
        // A floor at y = 1 and a steep wall crossing it, met by an upward ray at the same
        // height; a ceiling at y = 3 facing down.
        let quad =
            |a: Vec3, b: Vec3, c: Vec3, d: Vec3| [Triangle { a, b, c }, Triangle { a, b: c, c: d }];
        let v = Vec3::new;
        let mut tris = quad(
            v(-1., 1., 1.),
            v(1., 1., 1.),
            v(1., 1., -1.),
            v(-1., 1., -1.),
        )
        .to_vec();
        tris.extend(quad(
            v(-1., 0., -1.),
            v(-1., 2., 1.),
            v(1., 2., 1.),
            v(1., 0., -1.),
        ));
        tris.extend(quad(
            v(-1., 3., -1.),
            v(1., 3., -1.),
            v(1., 3., 1.),
            v(-1., 3., 1.),
        ));
        // Many distant triangles so the tree has inner nodes.
        let mut rng = Rng(3);
        tris.extend(random_scene(&mut rng, 300).into_iter().map(|t| Triangle {
            a: t.a + Vec3::X * 40.0,
            b: t.b + Vec3::X * 40.0,
            c: t.c + Vec3::X * 40.0,
        }));
        let bvh = Bvh::build(tris);
        let o = Vec3::new(0.2, 0.0, 0.0);
        let near = |t0: f32, t1: f32, like: Vec3| bvh.face_normal_near(o, Vec3::Y, t0, t1, like);
        let wall = v(0.0, 1.0, -1.0).normalize();
        let is = |n: Option<Vec3>, want: Vec3| n.is_some_and(|n| n.abs_diff_eq(want, 1e-6));
        assert!(is(near(0.99, 1.01, Vec3::Y), Vec3::Y));
        assert!(is(near(0.99, 1.01, wall), wall));
        assert!(is(near(2.9, 3.1, Vec3::Y), -Vec3::Y));
        // A window that holds no face, and a ray that meets nothing.
        assert_eq!(near(1.5, 2.5, Vec3::Y), None);
        assert_eq!(bvh.face_normal_near(o, -Vec3::Y, 0.0, 9.0, Vec3::Y), None);
    }

    #[test]
    fn axis_parallel_rays_match_brute_force() {
        let mut rng = Rng(99);
        let tris = random_scene(&mut rng, 2000);
        let bvh = Bvh::build(tris.clone());
        let axes = [Vec3::X, Vec3::Y, Vec3::Z, -Vec3::X, -Vec3::Y, -Vec3::Z];
        let (mut hits, mut total) = (0, 0);
        for k in 0..3000 {
            // Half the origins sit exactly on grid planes shared with boxes.
            let o = if k % 2 == 0 {
                rng.grid(10)
            } else {
                rng.vec(-12.0, 12.0)
            };
            let d = axes[k % 6];
            let expect = brute(&tris, o, d, 0.0, f32::INFINITY);
            assert_eq!(bvh.occluded(o, d, 0.0, f32::INFINITY), expect, "{o} {d}");
            hits += expect as usize;
            total += 1;
        }
        assert!(hits > 300 && hits < total - 300, "hits {hits}/{total}");
    }

    #[test]
    fn single_triangle_hits_and_misses() {
        let t = Triangle {
            a: Vec3::new(-1.0, 0.0, -1.0),
            b: Vec3::new(1.0, 0.0, -1.0),
            c: Vec3::new(0.0, 0.0, 1.0),
        };
        let bvh = Bvh::build(vec![t]);
        // Straight down and straight up (double-sided).
        assert!(bvh.occluded(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y, 0.0, 2.0));
        assert!(bvh.occluded(Vec3::new(0.0, -1.0, 0.0), Vec3::Y, 0.0, f32::INFINITY));
        // Interval is open and respected.
        assert!(!bvh.occluded(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y, 0.0, 1.0));
        assert!(!bvh.occluded(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y, 1.0, 5.0));
        assert!(!bvh.occluded(Vec3::new(0.0, 1.0, 0.0), Vec3::Y, 0.0, f32::INFINITY));
        // Outside the triangle.
        assert!(!bvh.occluded(Vec3::new(0.9, 1.0, 0.9), -Vec3::Y, 0.0, 2.0));
        // Parallel to the plane, inside it: no hit, no NaN trouble.
        assert!(!bvh.occluded(Vec3::new(-5.0, 0.0, 0.0), Vec3::X, 0.0, 10.0));
        // Zero direction and NaN input never hit.
        assert!(!bvh.occluded(Vec3::new(0.0, 1.0, 0.0), Vec3::ZERO, 0.0, 2.0));
        assert!(!bvh.occluded(Vec3::splat(f32::NAN), -Vec3::Y, 0.0, 2.0));
        assert!(!bvh.occluded(Vec3::new(0.0, 1.0, 0.0), -Vec3::Y, 0.0, f32::NAN));
    }

    #[test]
    fn empty_and_degenerate_never_occlude() {
        let empty = Bvh::build(Vec::new());
        assert_eq!(empty.triangle_count(), 0);
        let a = Vec3::new(0.0, 0.0, 0.0);
        let b = Vec3::new(1.0, 1.0, 1.0);
        let degenerate = vec![
            Triangle { a, b: a, c: a },
            Triangle { a, b, c: b },
            Triangle { a, b, c: b * 3.0 },
            Triangle {
                a: Vec3::splat(f32::NAN),
                b,
                c: Vec3::X,
            },
        ];
        let bvh = Bvh::build(degenerate);
        assert_eq!(bvh.triangle_count(), 0);
        let mut rng = Rng(3);
        for _ in 0..500 {
            let o = rng.vec(-2.0, 2.0);
            let d = rng.vec(-1.0, 1.0);
            assert!(!empty.occluded(o, d, 0.0, f32::INFINITY));
            assert!(!bvh.occluded(o, d, 0.0, f32::INFINITY));
        }
    }

    #[test]
    fn shared_edge_does_not_leak() {
        // Unit square of two triangles sharing the diagonal x == z.
        let p = |x: f32, z: f32| Vec3::new(x, 0.0, z);
        let tris = vec![
            Triangle {
                a: p(0.0, 0.0),
                b: p(1.0, 0.0),
                c: p(1.0, 1.0),
            },
            Triangle {
                a: p(0.0, 0.0),
                b: p(1.0, 1.0),
                c: p(0.0, 1.0),
            },
        ];
        let bvh = Bvh::build(tris);
        for k in 1..100 {
            let s = k as f32 / 100.0;
            let o = Vec3::new(s, 1.0, s);
            assert!(bvh.occluded(o, -Vec3::Y, 0.0, 2.0), "leak at {s}");
            let dir = Vec3::new(0.1, -1.0, 0.1);
            // Slanted ray through the diagonal point (s, 0, s) at t = 1.
            let on_edge = Vec3::new(s, 0.0, s);
            assert!(bvh.occluded(on_edge - dir, dir, 0.0, 2.0), "leak at {s}");
        }
    }

    #[test]
    fn random_shared_edges_do_not_leak() {
        // Rays aimed at points on the edge shared by two random triangles:
        // rounding puts the point a few ulps to either side, and without the
        // edge tolerance some rays slip between the two.
        let mut rng = Rng(2024);
        let mut leaks = 0;
        for _ in 0..2000 {
            let (a, c) = (rng.vec(-1.0, 1.0), rng.vec(-1.0, 1.0));
            let (b, d) = (rng.vec(-1.0, 1.0), rng.vec(-1.0, 1.0));
            let t1 = Triangle { a, b, c };
            let t2 = Triangle { a, b: c, c: d };
            if t1.is_degenerate() || t2.is_degenerate() {
                continue;
            }
            let bvh = Bvh::build(vec![t1, t2]);
            let target = a + (c - a) * rng.range(0.05, 0.95);
            // Keep well away from grazing so only edge rounding matters.
            let n = (b - a).cross(c - a).normalize();
            let dir = (n + rng.vec(-0.3, 0.3)).normalize();
            let origin = target - dir * 2.0;
            leaks += !bvh.occluded(origin, dir, 0.0, 4.0) as usize;
        }
        assert_eq!(leaks, 0);
    }

    #[test]
    fn slab_keeps_boxes_touched_by_parallel_rays() {
        // Ray parallel to x, starting exactly on the box's x = 0 face: the
        // slab product is 0 * inf = NaN and must not cull the box.
        let node = Node {
            lo: Vec3::ZERO,
            hi: Vec3::ONE,
            start: 0,
            count: 1,
        };
        let inv = Vec3::ONE / Vec3::Y;
        let on_face = Vec3::new(0.0, -1.0, 0.5);
        assert_eq!(
            slab_entry(&node, on_face, inv, 0.0, f32::INFINITY),
            Some(1.0)
        );
        let on_far_face = Vec3::new(1.0, -1.0, 1.0);
        assert_eq!(slab_entry(&node, on_far_face, inv, 0.0, 5.0), Some(1.0));
        // Just outside the face: culled.
        let outside = Vec3::new(-1e-3, -1.0, 0.5);
        assert_eq!(slab_entry(&node, outside, inv, 0.0, f32::INFINITY), None);
        // Negative zero direction components behave the same.
        let inv_neg = Vec3::ONE / Vec3::new(-0.0, 1.0, -0.0);
        assert_eq!(slab_entry(&node, on_face, inv_neg, 0.0, 5.0), Some(1.0));
        assert_eq!(slab_entry(&node, outside, inv_neg, 0.0, 5.0), None);
        // Box behind the ray or beyond t_max: culled.
        assert_eq!(slab_entry(&node, on_face, inv, 3.0, 5.0), None);
        assert_eq!(slab_entry(&node, on_face, inv, 0.0, 0.5), None);
    }

    #[test]
    fn deep_degenerate_layout_builds_and_traverses() {
        // Many triangles with identical centroids force median splits.
        let t = Triangle {
            a: Vec3::new(-1.0, 0.0, -1.0),
            b: Vec3::new(1.0, 0.0, -1.0),
            c: Vec3::new(0.0, 0.0, 2.0),
        };
        let bvh = Bvh::build(vec![t; 1000]);
        assert_eq!(bvh.triangle_count(), 1000);
        assert!(bvh.occluded(Vec3::Y, -Vec3::Y, 0.0, 2.0));
        assert!(!bvh.occluded(Vec3::new(5.0, 1.0, 0.0), -Vec3::Y, 0.0, 2.0));
    }
}
