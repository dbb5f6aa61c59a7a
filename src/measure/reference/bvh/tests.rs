//! The hierarchy against brute force: random scenes and rays, shared edges, parallel rays,
//! degenerate layouts.

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
