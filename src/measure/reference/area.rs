//! The truth for soft shadows: a light with a size. Each receiver pixel casts N stratified
//! shadow rays to the light's disc (a directional light: over the cone of its angular
//! diameter; a spot or point light: over the disc its sphere shows the receiver) through the
//! same BVH as the hard reference; its visibility is the unblocked fraction. Pixels are
//! receivers exactly as in the hard reference (judged towards the light's centre).

use glam::Vec2;

use super::bvh::Bvh;
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
        let (origin, to_light) = match receiver(light, gbuf, i) {
            Ok(r) => r,
            Err(not) => return not,
        };
        let (t, b) = to_light.any_orthonormal_pair();
        let shift = Vec2::new(unit(hash(i as u64 * 2)), unit(hash(i as u64 * 2 + 1)));
        let lit = (0..rays)
            .filter(|&k| {
                let d = concentric(stratified(k, rays, shift));
                let across = t * d.x + b * d.y;
                match (extent, light.position()) {
                    (LightExtent::Cone { tan_half }, _) => {
                        let dir = (to_light + across * tan_half).normalize();
                        !bvh.occluded(origin, dir, 0.0, f32::INFINITY)
                    }
                    (LightExtent::Sphere { radius }, Some(position)) => {
                        !occluded_to(bvh, origin, position + across * radius)
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
}
