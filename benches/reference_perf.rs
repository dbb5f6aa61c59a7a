//! Times the BVH build and one 1280x720 hard-shadow reference frame on a
//! ~100k-triangle scene: a bumpy terrain plus scattered boxes.
//! Run with `cargo bench --bench reference_perf`.

use std::time::Instant;

use glam::Vec3;
use shadowmap::geometry::MeshData;
use shadowmap::reference::{
    reference_visibility, reference_visibility_supersampled, Bvh, GBuffer, LightKind, Triangle,
};

const CELLS: usize = 200; // 200 x 200 cells, 80k terrain triangles
const SIZE: f32 = 100.0; // terrain spans [-50, 50]^2
const BOXES: usize = 2000; // 24k box triangles

fn height(x: f32, z: f32) -> f32 {
    1.5 * (0.13 * x).sin() * (0.11 * z).cos() + 0.4 * (0.7 * x + 0.3 * z).sin()
}

fn vertex(i: usize, j: usize) -> Vec3 {
    let x = -SIZE / 2.0 + SIZE * i as f32 / CELLS as f32;
    let z = -SIZE / 2.0 + SIZE * j as f32 / CELLS as f32;
    Vec3::new(x, height(x, z), z)
}

/// Point and face normal of the terrain surface above (x, z), on the same
/// triangles the BVH holds (each cell split along its i+j diagonal).
fn terrain_point(x: f32, z: f32) -> (Vec3, Vec3) {
    let fx = (x + SIZE / 2.0) / SIZE * CELLS as f32;
    let fz = (z + SIZE / 2.0) / SIZE * CELLS as f32;
    let (i, j) = ((fx as usize).min(CELLS - 1), (fz as usize).min(CELLS - 1));
    let (u, v) = (fx - i as f32, fz - j as f32);
    let (p00, p10, p01, p11) = (
        vertex(i, j),
        vertex(i + 1, j),
        vertex(i, j + 1),
        vertex(i + 1, j + 1),
    );
    let (a, b, c, w) = if u >= v {
        (p00, p10, p11, [1.0 - u, u - v, v])
    } else {
        (p00, p11, p01, [1.0 - v, u, v - u])
    };
    let p = a * w[0] + b * w[1] + c * w[2];
    let mut n = (b - a).cross(c - a).normalize();
    if n.y < 0.0 {
        n = -n;
    }
    (p, n)
}

struct Lcg(u64);
impl Lcg {
    fn unit(&mut self) -> f32 {
        self.0 = self.0.wrapping_mul(6364136223846793005).wrapping_add(1);
        (self.0 >> 40) as f32 / (1u64 << 24) as f32
    }
}

fn scene() -> Vec<Triangle> {
    let mut tris = Vec::with_capacity(2 * CELLS * CELLS + 12 * BOXES);
    for i in 0..CELLS {
        for j in 0..CELLS {
            let (p00, p10, p01, p11) = (
                vertex(i, j),
                vertex(i + 1, j),
                vertex(i, j + 1),
                vertex(i + 1, j + 1),
            );
            tris.push(Triangle {
                a: p00,
                b: p10,
                c: p11,
            });
            tris.push(Triangle {
                a: p00,
                b: p11,
                c: p01,
            });
        }
    }
    let mut rng = Lcg(12345);
    for _ in 0..BOXES {
        let x = (rng.unit() - 0.5) * SIZE * 0.95;
        let z = (rng.unit() - 0.5) * SIZE * 0.95;
        let h = Vec3::new(0.2 + rng.unit(), 0.2 + 1.5 * rng.unit(), 0.2 + rng.unit());
        let c = Vec3::new(x, height(x, z) + h.y, z);
        // The project's own unit cube, scaled and placed.
        tris.extend(MeshData::cube().triangles().map(|[a, b, cc]| Triangle {
            a: c + h * a,
            b: c + h * b,
            c: c + h * cc,
        }));
    }
    tris
}

/// Terrain G-buffer seen from above: a 96 x 54 window of the terrain.
fn gbuffer(w: usize, h: usize) -> GBuffer {
    let mut g = GBuffer::new_empty(w, h);
    for y in 0..h {
        for x in 0..w {
            let px = -48.0 + 96.0 * (x as f32 + 0.5) / w as f32;
            let pz = -27.0 + 54.0 * (y as f32 + 0.5) / h as f32;
            let (p, n) = terrain_point(px, pz);
            g.set(x, y, p, n);
        }
    }
    g
}

fn main() {
    let tris = scene();
    let t = Instant::now();
    let bvh = Bvh::build(tris.clone());
    let build = t.elapsed();
    println!(
        "triangles: {}  build: {:.1} ms",
        bvh.triangle_count(),
        build.as_secs_f64() * 1e3
    );

    let (w, h) = (1280, 720);
    let g = gbuffer(w, h);
    let lights = [
        (
            "directional",
            LightKind::Directional {
                to_light: Vec3::new(0.5, 0.6, 0.3),
            },
        ),
        (
            "directional low",
            LightKind::Directional {
                to_light: Vec3::new(1.0, 0.15, 0.2),
            },
        ),
        (
            "point",
            LightKind::Point {
                position: Vec3::new(5.0, 12.0, -3.0),
            },
        ),
    ];
    for (name, light) in lights {
        let t = Instant::now();
        let r = reference_visibility(&bvh, &light, &g);
        let dt = t.elapsed();
        let receivers = r.iter().filter(|p| p.receiver).count();
        let shadowed = r
            .iter()
            .filter(|p| p.receiver && p.visibility == 0.0)
            .count();
        println!(
            "{name:16} {w}x{h}: {:.0} ms  receivers {receivers}  shadowed {shadowed} ({:.1}%)",
            dt.as_secs_f64() * 1e3,
            100.0 * shadowed as f64 / receivers.max(1) as f64
        );
    }
    // Spot check against brute force so the timings are of a correct tracer.
    let mut rng = Lcg(99);
    let dir = Vec3::new(0.5, 0.6, 0.3).normalize();
    let mut mismatches = 0;
    for _ in 0..300 {
        let i = ((rng.unit() * (w * h) as f32) as usize).min(w * h - 1);
        let o = Vec3::from(g.positions[i]) + Vec3::from(g.normals[i]) * 1e-3;
        let brute = tris
            .iter()
            .any(|t| t.intersects(o, dir, 0.0, f32::INFINITY));
        mismatches += (brute != bvh.occluded(o, dir, 0.0, f32::INFINITY)) as usize;
    }
    println!("brute-force spot check: {mismatches} mismatches in 300 rays");

    let hi = gbuffer(2 * w, 2 * h);
    let t = Instant::now();
    let r = reference_visibility_supersampled(&bvh, &lights[0].1, &hi, 2);
    println!(
        "supersampled 2x2 {w}x{h}: {:.0} ms  fractional pixels {}",
        t.elapsed().as_secs_f64() * 1e3,
        r.iter()
            .filter(|p| p.visibility > 0.0 && p.visibility < 1.0)
            .count()
    );
}
