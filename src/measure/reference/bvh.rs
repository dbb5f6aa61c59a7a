//! Bounding volume hierarchy over triangles. Shadow rays ask only "is anything
//! in the way?" (any-hit), so traversal stops at the first hit; the one other
//! query, [`Bvh::face_normal_near`], finds which triangle a camera ray meets
//! at a known distance (the face under a G-buffer pixel).

use glam::Vec3;

mod build;
#[cfg(test)]
mod tests;

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

impl Bvh {
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
