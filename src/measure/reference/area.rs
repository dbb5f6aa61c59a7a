//! The truth for soft shadows: a light with a size. Each receiver pixel casts N stratified
//! shadow rays to the light's disc (a directional light: over the cone of its angular
//! diameter; a spot or point light: over the disc its sphere shows the receiver) through the
//! same BVH as the hard reference; its visibility is the unblocked fraction.
//!
//! A receiver of a sized light is a point that sees some of the light above the plane of
//! the triangle it lies on (the face normal where the G-buffer has it): a sample below that
//! plane is blocked by the surface itself, whatever a ray from the lifted origin would miss.
//! So a point just past a curved caster's terminator still sees part of the light (a disk
//! segment), and a point whose whole light is below its plane is no receiver, as in the
//! hard reference. A light of size 0 keeps the hard reference's rules exactly.

use glam::{Vec2, Vec3};

use super::bvh::Bvh;
use super::visibility::RAY_EPSILON;
use super::visibility::{occluded_to, par_rows, receiver, GBuffer, LightKind, RefPixel};

/// A light's extent, as the area reference samples it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightExtent {
    /// Parallel rays within a cone about the light's direction: tan of its angular radius
    /// (a directional light of angular diameter `a`: tan(a / 2)).
    Cone { tan_half: f32 },
    /// A sphere of this radius about the light's position.
    Sphere { radius: f32 },
}

/// The soft-shadow truth of every pixel of `gbuf`: `rays` rays per receiver (at least 1)
/// to the light `light` of extent `extent`. Deterministic: the same inputs give the same
/// answer on any number of threads.
pub fn area_visibility(
    bvh: &Bvh,
    light: &LightKind,
    extent: LightExtent,
    gbuf: &GBuffer,
    rays: usize,
) -> Vec<RefPixel> {
    let rays = rays.max(1);
    let width = gbuf.width;
    par_rows(width, gbuf.height, RefPixel::EMPTY, |x, y| {
        let i = y * width + x;
        let r = match area_receiver(light, extent, gbuf, i) {
            Ok(r) => r,
            Err(not) => return not,
        };
        let (t, b) = r.to_light.any_orthonormal_pair();
        let shift = Vec2::new(unit(hash(i as u64 * 2)), unit(hash(i as u64 * 2 + 1)));
        let lit = (0..rays)
            .filter(|&k| {
                let d = concentric(stratified(k, rays, shift));
                let across = t * d.x + b * d.y;
                match (extent, light.position()) {
                    (LightExtent::Cone { tan_half }, _) => {
                        let dir = (r.to_light + across * tan_half).normalize();
                        dir.dot(r.plane) > 0.0 && !bvh.occluded(r.origin, dir, 0.0, f32::INFINITY)
                    }
                    (LightExtent::Sphere { radius }, Some(position)) => {
                        let target = position + across * radius;
                        (target - r.origin).dot(r.plane) > 0.0
                            && !occluded_to(bvh, r.origin, target)
                    }
                    (LightExtent::Sphere { .. }, None) => true,
                }
            })
            .count();
        RefPixel {
            covered: true,
            receiver: true,
            visibility: lit as f32 / rays as f32,
        }
    })
}

/// A receiver of a sized light: where its rays start, the direction to the light's centre,
/// and the plane (its normal) that blocks the samples below it.
struct AreaReceiver {
    origin: Vec3,
    to_light: Vec3,
    plane: Vec3,
}

/// Whether G-buffer entry `i` sees part of the light `extent` above its triangle's plane
/// (see the module's doc); a light of size 0 is judged by the hard reference's rules.
fn area_receiver(
    light: &LightKind,
    extent: LightExtent,
    gbuf: &GBuffer,
    i: usize,
) -> Result<AreaReceiver, RefPixel> {
    let spread = match extent {
        LightExtent::Cone { tan_half } => tan_half,
        LightExtent::Sphere { radius } => radius,
    };
    if spread <= 0.0 || spread.is_nan() {
        let (origin, to_light) = receiver(light, gbuf, i)?;
        let n = gbuf.normals.get(i).map_or(to_light, |&n| Vec3::from(n));
        return Ok(AreaReceiver {
            origin,
            to_light,
            plane: n.normalize_or(to_light),
        });
    }
    let p = gbuf
        .positions
        .get(i)
        .map(|&p| Vec3::from(p))
        .filter(|p| p.is_finite())
        .ok_or(RefPixel::EMPTY)?;
    let not_receiver = RefPixel {
        covered: true,
        receiver: false,
        visibility: 0.0,
    };
    let smooth = gbuf.normals.get(i).map_or(Vec3::ZERO, |&n| Vec3::from(n));
    let face = gbuf
        .face_normals
        .get(i)
        .map_or(Vec3::ZERO, |&f| Vec3::from(f));
    let plane = if face != Vec3::ZERO { face } else { smooth }.normalize_or_zero();
    let (to_light, reach) = match (*light, light.position()) {
        (LightKind::Directional { to_light }, _) => (to_light.normalize_or_zero(), spread),
        (_, Some(position)) => {
            let d = position - p;
            (d.normalize_or_zero(), spread / d.length())
        }
        (_, None) => (Vec3::ZERO, 0.0),
    };
    // The highest point of the light's disc above the plane: its centre's height plus the
    // disc's radius times the plane normal's part across the light direction.
    let across = (plane - to_light * plane.dot(to_light)).length();
    let top = plane.dot(to_light) + reach * across;
    if plane == Vec3::ZERO || to_light == Vec3::ZERO || top.is_nan() || top <= 0.0 {
        return Err(not_receiver);
    }
    if let LightKind::Spot { axis, cos_full, .. } = *light {
        let c = (-to_light).dot(axis.normalize_or_zero());
        if c.is_nan() || c < cos_full {
            return Err(not_receiver);
        }
    }
    Ok(AreaReceiver {
        origin: p + plane * (RAY_EPSILON * p.abs().max_element().max(1.0)),
        to_light,
        plane,
    })
}

/// Point `k` of `n` in the unit square: the Hammersley set (k / n, the bit-reversed k),
/// each coordinate jittered within its own stratum, shifted by `shift` modulo 1 (a
/// per-pixel rotation, so neighbouring pixels' errors do not line up).
fn stratified(k: usize, n: usize, shift: Vec2) -> Vec2 {
    let u = (k as f32 + unit(hash(k as u64 ^ 0x9e37_79b9))) / n as f32;
    let v = (k as u32).reverse_bits() as f32 / 4_294_967_296.0;
    (Vec2::new(u, v) + shift).fract()
}

/// Shirley and Chiu's concentric map of the unit square onto the unit disc: strata stay
/// compact and areas are kept.
fn concentric(p: Vec2) -> Vec2 {
    let q = p * 2.0 - Vec2::ONE;
    if q == Vec2::ZERO {
        return Vec2::ZERO;
    }
    let quarter = std::f32::consts::FRAC_PI_4;
    let (r, phi) = if q.x.abs() > q.y.abs() {
        (q.x, quarter * (q.y / q.x))
    } else {
        (q.y, 2.0 * quarter - quarter * (q.x / q.y))
    };
    Vec2::new(phi.cos(), phi.sin()) * r
}

/// A 64-bit mix (SplitMix64's finaliser).
fn hash(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The top 24 bits of `h` as a number in [0, 1).
fn unit(h: u64) -> f32 {
    (h >> 40) as f32 / 16_777_216.0
}

#[cfg(test)]
mod tests {
    use super::super::bvh::Triangle;
    use super::*;
    use glam::Vec3;

    #[test]
    fn samples_cover_the_disc_evenly() {
        let n = 64;
        let pts: Vec<Vec2> = (0..n)
            .map(|k| concentric(stratified(k, n, Vec2::new(0.3, 0.7))))
            .collect();
        assert!(pts.iter().all(|p| p.length() <= 1.0 + 1e-5));
        // A uniform disc: mean near the centre, mean squared radius near 1/2; every
        // quadrant gets a quarter.
        let mean = pts.iter().copied().sum::<Vec2>() / n as f32;
        let r2 = pts.iter().map(|p| p.length_squared()).sum::<f32>() / n as f32;
        assert!(mean.length() < 0.08, "{mean}");
        assert!((r2 - 0.5).abs() < 0.05, "{r2}");
        for (sx, sy) in [(1.0, 1.0), (-1.0, 1.0), (1.0, -1.0), (-1.0, -1.0)] {
            let q = pts
                .iter()
                .filter(|p| p.x * sx > 0.0 && p.y * sy > 0.0)
                .count();
            assert!((12..=20).contains(&q), "quadrant ({sx}, {sy}): {q}");
        }
    }

    /// A 2 x 2 square blocker at height h over the plane y = 0, lit from straight above by
    /// a cone of angular radius atan(tan_half): along x its penumbra is 2 h tan_half wide.
    #[test]
    fn a_cone_light_makes_a_penumbra_as_wide_as_similar_triangles_say() {
        let h = 2.0;
        let tan_half = 0.1;
        let blocker = vec![
            Triangle {
                a: Vec3::new(-1.0, h, -1.0),
                b: Vec3::new(1.0, h, -1.0),
                c: Vec3::new(1.0, h, 1.0),
            },
            Triangle {
                a: Vec3::new(-1.0, h, -1.0),
                b: Vec3::new(1.0, h, 1.0),
                c: Vec3::new(-1.0, h, 1.0),
            },
        ];
        let bvh = Bvh::build(blocker);
        // Pixels along x from 0.5 to 1.5 at z = 0, one every 0.01.
        let mut g = GBuffer::new_empty(101, 1);
        for k in 0..101 {
            g.set(k, 0, Vec3::new(0.5 + k as f32 * 0.01, 0.0, 0.0), Vec3::Y);
        }
        let light = LightKind::Directional { to_light: Vec3::Y };
        let v = area_visibility(&bvh, &light, LightExtent::Cone { tan_half }, &g, 256);
        let at = |x: f32| v[((x - 0.5) / 0.01).round() as usize].visibility;
        // Fully shadowed inside x < 1 - h tan_half, fully lit beyond 1 + h tan_half, half at
        // the edge, and rising in between.
        assert_eq!(at(0.75), 0.0);
        assert_eq!(at(1.25), 1.0);
        assert!((at(1.0) - 0.5).abs() < 0.05, "{}", at(1.0));
        assert!(at(0.9) < at(1.0) && at(1.0) < at(1.1));
        // A point light of no size: the hard answer.
        let hard = area_visibility(&bvh, &light, LightExtent::Cone { tan_half: 0.0 }, &g, 16);
        assert!(hard
            .iter()
            .enumerate()
            .all(|(k, p)| p.visibility == if k < 50 { 0.0 } else { 1.0 } || k == 50));
    }

    /// The lit fraction of a disc whose centre is `d` radii above a straight edge (a disc
    /// segment): 1/2 at 0, 0 at -1, 1 at 1.
    fn segment(d: f32) -> f32 {
        let d = d.clamp(-1.0, 1.0);
        1.0 - (d.acos() - d * (1.0 - d * d).sqrt()) / std::f32::consts::PI
    }

    /// A unit sphere (256 x 128 facets) under a sun of 10 degrees: near its own terminator
    /// a point sees the part of the sun above its tangent plane. Binned by the sun centre's
    /// elevation in sun radii (d = tan e / tan 5 deg, exact for the sampled cone), every
    /// bin's mean is the disc segment's within 0.02, on both sides of the terminator.
    #[test]
    fn a_sphere_sees_the_disc_segment_of_the_sun_at_its_own_terminator() {
        let mesh = crate::geometry::MeshData::sphere(256, 128);
        let triangles: Vec<[Vec3; 3]> = mesh.triangles().collect();
        let bvh = Bvh::build(
            triangles
                .iter()
                .map(|&[a, b, c]| Triangle { a, b, c })
                .collect(),
        );
        let tan_half = 5f32.to_radians().tan();
        let to_light = Vec3::new(1.0, 0.3, 0.2).normalize();
        let near: Vec<(Vec3, Vec3, f32)> = triangles
            .iter()
            .filter_map(|&[a, b, c]| {
                let centre = (a + b + c) / 3.0;
                let n = centre.normalize();
                let e = n.dot(to_light).asin();
                let d = e.tan() / tan_half;
                let face = (b - a).cross(c - a).normalize();
                (d.abs() < 1.0).then_some((centre, face, d))
            })
            .collect();
        let mut g = GBuffer::new_empty(near.len(), 1);
        g.face_normals = vec![[0.0; 3]; near.len()];
        for (k, &(p, face, _)) in near.iter().enumerate() {
            g.set(k, 0, p, p.normalize());
            g.face_normals[k] = face.to_array();
        }
        let light = LightKind::Directional { to_light };
        let v = area_visibility(&bvh, &light, LightExtent::Cone { tan_half }, &g, 256);
        for bin in 0..8 {
            let lo = -1.0 + bin as f32 * 0.25;
            let in_bin: Vec<usize> = (0..near.len())
                .filter(|&k| near[k].2 >= lo && near[k].2 < lo + 0.25)
                .collect();
            assert!(in_bin.len() > 100, "bin {lo}: {} points", in_bin.len());
            let mean = |f: &dyn Fn(usize) -> f32| {
                in_bin.iter().map(|&k| f(k)).sum::<f32>() / in_bin.len() as f32
            };
            let truth = mean(&|k| v[k].visibility);
            let exact = mean(&|k| segment(near[k].2));
            assert!(
                (truth - exact).abs() <= 0.02,
                "elevation [{lo}, {}) radii: {truth:.3} against the segment's {exact:.3}",
                lo + 0.25
            );
        }
        // Every point that sees a tenth of the sun's radius above its plane receives it
        // (a facet's plane differs a little from the sphere's tangent plane).
        assert!((0..near.len()).all(|k| near[k].2 < -0.9 || v[k].receiver));
    }

    /// The straight edge of a plate at height 2 under a cone light of tan 0.1: across the
    /// edge the truth is the disc segment, so its 10-90% width is the analytic one within
    /// 3% at 256 rays, and within 2% of each other at 64 and 1024 rays.
    #[test]
    fn a_plates_penumbra_is_as_wide_as_the_disc_segment_says() {
        let (h, tan_half) = (2.0, 0.1);
        let plate = [
            [-1.0, -1.0, 1.0, -1.0, 1.0, 1.0],
            [-1.0, -1.0, 1.0, 1.0, -1.0, 1.0],
        ]
        .iter()
        .map(|t| Triangle {
            a: Vec3::new(t[0], h, t[1] * 5.0),
            b: Vec3::new(t[2], h, t[3] * 5.0),
            c: Vec3::new(t[4], h, t[5] * 5.0),
        })
        .collect();
        let bvh = Bvh::build(plate);
        let w = h * tan_half;
        let n = 2001;
        let x_at = |k: usize| 1.0 - 1.2 * w + 2.4 * w * k as f32 / (n - 1) as f32;
        let mut g = GBuffer::new_empty(n, 1);
        for k in 0..n {
            g.set(k, 0, Vec3::new(x_at(k), 0.0, 0.0), Vec3::Y);
        }
        let light = LightKind::Directional { to_light: Vec3::Y };
        let width = |rays: usize| {
            let v = area_visibility(&bvh, &light, LightExtent::Cone { tan_half }, &g, rays);
            let smooth: Vec<f32> = (0..n)
                .map(|k| {
                    let (a, b) = (k.saturating_sub(10), (k + 11).min(n));
                    v[a..b].iter().map(|p| p.visibility).sum::<f32>() / (b - a) as f32
                })
                .collect();
            let cross = |level: f32| x_at(smooth.iter().position(|&s| s >= level).unwrap());
            cross(0.9) - cross(0.1)
        };
        // segment(d) = 0.9 at d = 0.6870 (and 0.1 at -0.6870): the width is 2 * 0.687 w.
        let d90 = (0..100_000)
            .map(|k| k as f32 / 100_000.0)
            .find(|&d| segment(d) >= 0.9)
            .unwrap();
        let exact = 2.0 * d90 * w;
        let (w64, w256, w1024) = (width(64), width(256), width(1024));
        assert!((w256 / exact - 1.0).abs() < 0.03, "{w256} vs {exact}");
        assert!((w64 / w1024 - 1.0).abs() < 0.02, "{w64} vs {w1024}");
        for got in [w64, w1024] {
            assert!((got / exact - 1.0).abs() < 0.03, "{got} vs {exact}");
        }
    }
}
