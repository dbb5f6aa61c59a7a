//! Exact hard-shadow visibility for the pixels of a G-buffer: one shadow ray
//! per pixel (or per sub-pixel) from the surface point to the light.

use std::sync::Mutex;

use glam::Vec3;

use super::bvh::Bvh;

/// The light whose shadows are being measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightKind {
    /// Light from infinitely far away; `to_light` points from the surface
    /// towards the light and need not be normalised.
    Directional { to_light: Vec3 },
    /// Light at a point in world space.
    Point { position: Vec3 },
    /// A spot: light at `position`, but only inside its cone. A surface receives its full
    /// light where the direction from the light makes a cosine of at least `cos_full` with
    /// `axis` (the shader's `lightConeCos` plus its soft rim); the rim and beyond are not
    /// receivers, since the light there is partial or none.
    Spot {
        position: Vec3,
        axis: Vec3,
        cos_full: f32,
    },
}

impl LightKind {
    /// The point the shadow rays go to, for lights at a point.
    pub fn position(&self) -> Option<Vec3> {
        match *self {
            LightKind::Directional { .. } => None,
            LightKind::Point { position } | LightKind::Spot { position, .. } => Some(position),
        }
    }
}

/// A G-buffer read back from the GPU: world positions and normals,
/// row-major, `width * height` entries, rows top to bottom. A pixel with a
/// non-finite position (the convention is NaN x) has no geometry; missing
/// entries count the same way.
#[derive(Debug, Clone, PartialEq)]
pub struct GBuffer {
    pub width: usize,
    pub height: usize,
    pub positions: Vec<[f32; 3]>,
    /// Interpolated (smooth) normals, as the shader lights with.
    pub normals: Vec<[f32; 3]>,
    /// The normal of the triangle under each pixel, turned to the side of `normals`
    /// (see [`face_normals`]); empty when unknown, and a zero entry is unknown too. On a
    /// smooth mesh the interpolated normal can face the light while the triangle does
    /// not; such a pixel is no receiver (its truth would hang on the ray's offset).
    pub face_normals: Vec<[f32; 3]>,
}

impl GBuffer {
    /// A G-buffer with no geometry anywhere, to be filled with [`GBuffer::set`].
    pub fn new_empty(width: usize, height: usize) -> GBuffer {
        let n = width.saturating_mul(height);
        GBuffer {
            width,
            height,
            positions: vec![[f32::NAN; 3]; n],
            normals: vec![[0.0; 3]; n],
            face_normals: Vec::new(),
        }
    }

    /// Stores one pixel; out-of-range coordinates are ignored.
    pub fn set(&mut self, x: usize, y: usize, position: Vec3, normal: Vec3) {
        if x < self.width && y < self.height {
            let i = y * self.width + x;
            if let (Some(p), Some(n)) = (self.positions.get_mut(i), self.normals.get_mut(i)) {
                *p = position.to_array();
                *n = normal.to_array();
            }
        }
    }
}

/// The triangle normal under every pixel of `gbuf`, found by the reference's own hit
/// test: the pixel's camera ray from `eye` (relative to the same origin as the positions)
/// is cast into `surfaces` (every drawn triangle), kept to a thin window around the
/// pixel's distance; the face met there (where two items meet, the one the interpolated
/// normal follows) gives the normal, turned to the side of the interpolated normal (the
/// side the shader lights). Pixels whose ray
/// finds no face (none expected; the window is 1e-3 of the distance) get a zero entry
/// and are judged by the interpolated normal alone.
pub fn face_normals(surfaces: &Bvh, gbuf: &GBuffer, eye: Vec3) -> Vec<[f32; 3]> {
    let width = gbuf.width;
    par_rows(width, gbuf.height, [0.0; 3], |x, y| {
        face_normal(surfaces, gbuf, eye, y * width + x)
    })
}

fn face_normal(surfaces: &Bvh, gbuf: &GBuffer, eye: Vec3, i: usize) -> [f32; 3] {
    let (Some(&p), Some(&n)) = (gbuf.positions.get(i), gbuf.normals.get(i)) else {
        return [0.0; 3];
    };
    let (p, n) = (Vec3::from(p), Vec3::from(n));
    let d = p - eye;
    let t = d.length();
    if !(t.is_finite() && t > 0.0) {
        return [0.0; 3];
    }
    let slack = t * 1e-3 + RAY_EPSILON * p.abs().max_element().max(1.0);
    let Some(face) = surfaces.face_normal_near(eye, d / t, t - slack, t + slack, n) else {
        return [0.0; 3];
    };
    let face = if face.dot(n) < 0.0 { -face } else { face };
    face.to_array()
}

/// Offset of the shadow-ray origin along the normal, relative to the size of
/// the position: the origin is `p + n * RAY_EPSILON * max(1, |p|_inf)`.
///
/// Why this value: an f32 position carries about 1.2e-7 relative rounding,
/// and GPU interpolation across large triangles adds a few times more, so a
/// surface point may sit slightly below its own triangle. 1e-4 is roughly a
/// thousand ulps, far above that noise, so the reference shows no acne even
/// at grazing light. Scaling by the magnitude keeps that margin constant far
/// from the origin. The cost: occluders closer than this to the surface, along
/// the normal, are missed (0.1 mm in a metre-scale scene).
pub const RAY_EPSILON: f32 = 1e-4;

/// Result for one pixel. `visibility` is meaningful only for receivers; the
/// hard reference sets it to 0.0 elsewhere (surfaces facing away get no
/// direct light).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RefPixel {
    /// The pixel holds geometry.
    pub covered: bool,
    /// What the light lights: covered, with a usable normal, facing the light by both its
    /// interpolated normal and its triangle's (N.L > 0), and inside a spot's full cone.
    pub receiver: bool,
    /// 1.0 lit, 0.0 shadowed; fractional in the supersampled reference.
    pub visibility: f32,
}

impl RefPixel {
    pub(super) const EMPTY: RefPixel = RefPixel {
        covered: false,
        receiver: false,
        visibility: 0.0,
    };
}

/// Hard-shadow reference: one shadow ray per G-buffer pixel, rows spread
/// over all available cores. Output has `width * height` entries.
pub fn reference_visibility(bvh: &Bvh, light: &LightKind, gbuf: &GBuffer) -> Vec<RefPixel> {
    let width = gbuf.width;
    par_rows(width, gbuf.height, RefPixel::EMPTY, |x, y| {
        sample(bvh, light, gbuf, y * width + x)
    })
}

/// Supersampled reference. `hi` is rendered at `n` times the output width
/// and height; the output is `(hi.width / n) x (hi.height / n)`.
///
/// Each output pixel's visibility is the mean over its receiver sub-pixels
/// (0.0 if there are none). `covered` and `receiver` take a strict majority
/// of the n*n sub-pixels, so a tie (possible for even n) counts as false:
/// that keeps silhouette pixels, whose value mixes two surfaces, out of the
/// comparison. `n == 0` gives an empty result.
pub fn reference_visibility_supersampled(
    bvh: &Bvh,
    light: &LightKind,
    hi: &GBuffer,
    n: usize,
) -> Vec<RefPixel> {
    if n == 0 {
        return Vec::new();
    }
    let (width, height) = (hi.width / n, hi.height / n);
    let half = n * n / 2;
    par_rows(width, height, RefPixel::EMPTY, |x, y| {
        let (mut covered, mut receivers, mut lit) = (0usize, 0usize, 0.0f32);
        for sy in 0..n {
            let row = (y * n + sy) * hi.width;
            for sx in 0..n {
                let s = sample(bvh, light, hi, row + x * n + sx);
                covered += s.covered as usize;
                if s.receiver {
                    receivers += 1;
                    lit += s.visibility;
                }
            }
        }
        RefPixel {
            covered: covered > half,
            receiver: receivers > half,
            visibility: if receivers > 0 {
                lit / receivers as f32
            } else {
                0.0
            },
        }
    })
}

/// Traces the shadow ray of G-buffer entry `i`.
fn sample(bvh: &Bvh, light: &LightKind, gbuf: &GBuffer, i: usize) -> RefPixel {
    let (origin, to_light) = match receiver(light, gbuf, i) {
        Ok(r) => r,
        Err(not) => return not,
    };
    let blocked = match (*light, light.position()) {
        (LightKind::Directional { .. }, _) => bvh.occluded(origin, to_light, 0.0, f32::INFINITY),
        (_, None) => false,
        (_, Some(position)) => occluded_to(bvh, origin, position),
    };
    RefPixel {
        covered: true,
        receiver: true,
        visibility: if blocked { 0.0 } else { 1.0 },
    }
}

/// Whether the segment from `origin` to the point `to` is blocked, stopping just short of
/// the point so that geometry the light sits on does not count as an occluder.
pub(super) fn occluded_to(bvh: &Bvh, origin: Vec3, to: Vec3) -> bool {
    let d = to - origin;
    let dist = d.length();
    let t_max = dist - RAY_EPSILON * to.abs().max_element().max(1.0);
    t_max > 0.0 && bvh.occluded(origin, d / dist, 0.0, t_max)
}

/// Whether G-buffer entry `i` receives the light: the ray origin (offset along the normal)
/// and the unit direction towards the light's centre if so, else the pixel as it stands.
pub(super) fn receiver(
    light: &LightKind,
    gbuf: &GBuffer,
    i: usize,
) -> Result<(Vec3, Vec3), RefPixel> {
    let Some(&p) = gbuf.positions.get(i) else {
        return Err(RefPixel::EMPTY);
    };
    let p = Vec3::from(p);
    if !p.is_finite() {
        return Err(RefPixel::EMPTY);
    }
    let not_receiver = RefPixel {
        covered: true,
        receiver: false,
        visibility: 0.0,
    };
    let n = gbuf
        .normals
        .get(i)
        .map(|&n| Vec3::from(n).normalize_or_zero())
        .unwrap_or(Vec3::ZERO);
    let to_light = match (*light, light.position()) {
        (LightKind::Directional { to_light }, _) => to_light.normalize_or_zero(),
        (_, Some(position)) => (position - p).normalize_or_zero(),
        (_, None) => Vec3::ZERO,
    };
    // A zero normal or light direction gives 0 here and is not a receiver.
    let cos = n.dot(to_light);
    if cos.is_nan() || cos <= 0.0 {
        return Err(not_receiver);
    }
    // The triangle itself must face the light too, where it is known.
    let face = gbuf
        .face_normals
        .get(i)
        .map_or(Vec3::ZERO, |&f| Vec3::from(f));
    // (Written so that NaN counts as facing away.)
    let face_cos = face.dot(to_light);
    if face != Vec3::ZERO && (face_cos.is_nan() || face_cos <= 0.0) {
        return Err(not_receiver);
    }
    if let LightKind::Spot { axis, cos_full, .. } = *light {
        let c = (-to_light).dot(axis.normalize_or_zero());
        if c.is_nan() || c < cos_full {
            return Err(not_receiver);
        }
    }
    let origin = p + n * (RAY_EPSILON * p.abs().max_element().max(1.0));
    Ok((origin, to_light))
}

/// Evaluates `f(x, y)` for every pixel, handing rows to
/// `available_parallelism()` scoped threads on demand, so expensive rows
/// (deep shadow regions) do not leave other cores idle.
pub(super) fn par_rows<T, F>(width: usize, height: usize, empty: T, f: F) -> Vec<T>
where
    T: Copy + Send,
    F: Fn(usize, usize) -> T + Sync,
{
    let mut out = vec![empty; width.saturating_mul(height)];
    if out.is_empty() {
        return out;
    }
    let threads = std::thread::available_parallelism()
        .map(|n| n.get())
        .unwrap_or(1)
        .min(height);
    {
        let rows = Mutex::new(out.chunks_mut(width).enumerate());
        std::thread::scope(|s| {
            for _ in 0..threads {
                s.spawn(|| loop {
                    // A poisoned lock means another worker panicked; the
                    // scope re-raises that panic, so just keep going here.
                    let next = rows.lock().unwrap_or_else(|e| e.into_inner()).next();
                    let Some((y, row)) = next else { break };
                    for (x, px) in row.iter_mut().enumerate() {
                        *px = f(x, y);
                    }
                });
            }
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::bvh::Triangle;
    use super::*;

    fn quad(p: [Vec3; 4]) -> [Triangle; 2] {
        [
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

    /// 12 triangles of the axis-aligned box centre `c`, half-size `h`.
    fn cube(c: Vec3, h: f32) -> Vec<Triangle> {
        let v = |x: f32, y: f32, z: f32| c + Vec3::new(x, y, z) * h;
        let faces = [
            [
                v(-1., -1., -1.),
                v(1., -1., -1.),
                v(1., -1., 1.),
                v(-1., -1., 1.),
            ],
            [
                v(-1., 1., -1.),
                v(-1., 1., 1.),
                v(1., 1., 1.),
                v(1., 1., -1.),
            ],
            [
                v(-1., -1., -1.),
                v(-1., 1., -1.),
                v(1., 1., -1.),
                v(1., -1., -1.),
            ],
            [
                v(-1., -1., 1.),
                v(1., -1., 1.),
                v(1., 1., 1.),
                v(-1., 1., 1.),
            ],
            [
                v(-1., -1., -1.),
                v(-1., -1., 1.),
                v(-1., 1., 1.),
                v(-1., 1., -1.),
            ],
            [
                v(1., -1., -1.),
                v(1., 1., -1.),
                v(1., 1., 1.),
                v(1., -1., 1.),
            ],
        ];
        faces.iter().flat_map(|f| quad(*f)).collect()
    }

    /// Plane y = `y` over [x0, x1] x [z0, z1], split into `cells`^2 squares
    /// so that shadow rays start next to many coplanar neighbours.
    fn plane(y: f32, x0: f32, x1: f32, z0: f32, z1: f32, cells: usize) -> Vec<Triangle> {
        let mut out = Vec::new();
        let at = |i: usize, j: usize| {
            Vec3::new(
                x0 + (x1 - x0) * i as f32 / cells as f32,
                y,
                z0 + (z1 - z0) * j as f32 / cells as f32,
            )
        };
        for i in 0..cells {
            for j in 0..cells {
                out.extend(quad([
                    at(i, j),
                    at(i, j + 1),
                    at(i + 1, j + 1),
                    at(i + 1, j),
                ]));
            }
        }
        out
    }

    /// G-buffer of points on y = `y` (normal +Y): pixel (i, j) sits at
    /// x = x0 + (i + 0.5) * step, z = z0 + (j + 0.5) * step.
    fn plane_gbuf(y: f32, x0: f32, z0: f32, step: f32, w: usize, h: usize) -> GBuffer {
        let mut g = GBuffer::new_empty(w, h);
        for j in 0..h {
            for i in 0..w {
                let p = Vec3::new(
                    x0 + (i as f32 + 0.5) * step,
                    y,
                    z0 + (j as f32 + 0.5) * step,
                );
                g.set(i, j, p, Vec3::Y);
            }
        }
        g
    }

    fn point_of(g: &GBuffer, i: usize) -> Vec3 {
        Vec3::from(g.positions[i])
    }

    fn cube_on_plane() -> Bvh {
        let mut tris = cube(Vec3::ZERO, 0.5);
        tris.extend(plane(-1.0, -50.0, 50.0, -50.0, 50.0, 1));
        Bvh::build(tris)
    }

    const DOWN_LIGHT: LightKind = LightKind::Directional { to_light: Vec3::Y };

    #[test]
    fn directional_shadow_is_the_cube_footprint() {
        let bvh = cube_on_plane();
        // Points at +-0.05, +-0.15, ... +-1.95: never on the |x| = 0.5 edge,
        // and some on the diagonal x == z where face triangles meet.
        let g = plane_gbuf(-1.0, -2.0, -2.0, 0.1, 40, 40);
        let r = reference_visibility(&bvh, &DOWN_LIGHT, &g);
        assert_eq!(r.len(), 1600);
        let mut shadowed = 0;
        for (i, px) in r.iter().enumerate() {
            let p = point_of(&g, i);
            assert!(px.covered && px.receiver);
            let inside = p.x.abs() < 0.5 && p.z.abs() < 0.5;
            assert_eq!(px.visibility, if inside { 0.0 } else { 1.0 }, "at {p}");
            shadowed += inside as usize;
        }
        assert_eq!(shadowed, 100);
    }

    #[test]
    fn cube_top_face_is_fully_lit() {
        let bvh = cube_on_plane();
        let g = plane_gbuf(0.5, -0.5, -0.5, 0.05, 20, 20);
        let r = reference_visibility(&bvh, &DOWN_LIGHT, &g);
        assert!(r.iter().all(|p| p.receiver && p.visibility == 1.0));
    }

    #[test]
    fn light_from_below_makes_no_receivers() {
        let bvh = cube_on_plane();
        let g = plane_gbuf(-1.0, -2.0, -2.0, 0.1, 40, 40);
        let light = LightKind::Directional { to_light: -Vec3::Y };
        let r = reference_visibility(&bvh, &light, &g);
        assert!(r
            .iter()
            .all(|p| p.covered && !p.receiver && p.visibility == 0.0));
    }

    #[test]
    fn no_acne_on_open_planes() {
        let one_degree = 1.0f32.to_radians();
        let grazing = LightKind::Directional {
            to_light: Vec3::new(one_degree.cos(), one_degree.sin(), 0.0),
        };
        let tilted = LightKind::Directional {
            to_light: Vec3::new(-0.3, 1.0, 0.2),
        };
        // Near the origin and far from it, tessellated so every ray starts
        // beside coplanar neighbours.
        for (cx, y) in [(0.0f32, -1.0f32), (1e4, -1.0), (1e4, 250.0)] {
            let bvh = Bvh::build(plane(y, cx - 20.0, cx + 20.0, -20.0, 20.0, 16));
            // Pitch 0.37 does not line up with the 2.5 tessellation.
            let g = plane_gbuf(y, cx - 18.0, -18.0, 0.37, 97, 97);
            for light in [DOWN_LIGHT, grazing, tilted] {
                let r = reference_visibility(&bvh, &light, &g);
                let dark = r.iter().filter(|p| p.visibility != 1.0).count();
                assert_eq!(dark, 0, "acne at x={cx} y={y} light {light:?}");
                assert!(r.iter().all(|p| p.receiver));
            }
        }
    }

    /// Tessellated plane through `centre` with unit normal `n` (half-size
    /// 20), and a 64x64 G-buffer of points on it interpolated in f32 from the
    /// triangle corners, as a rasteriser would, then pushed `ulps` f32 ulps
    /// of |p|_inf below the surface to mimic read-back error.
    fn tilted_plane(centre: Vec3, n: Vec3, ulps: f32) -> (Vec<Triangle>, GBuffer) {
        let (t1, t2) = n.any_orthonormal_pair();
        let cells = 16;
        let corner = |i: usize, j: usize| {
            let u = -20.0 + 40.0 * i as f32 / cells as f32;
            let v = -20.0 + 40.0 * j as f32 / cells as f32;
            centre + t1 * u + t2 * v
        };
        let mut tris = Vec::new();
        for i in 0..cells {
            for j in 0..cells {
                tris.extend(quad([
                    corner(i, j),
                    corner(i, j + 1),
                    corner(i + 1, j + 1),
                    corner(i + 1, j),
                ]));
            }
        }
        let mut g = GBuffer::new_empty(64, 64);
        let mut seed = 1u32;
        let mut unit = || {
            seed = seed.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (seed >> 8) as f32 / (1u32 << 24) as f32
        };
        for y in 0..64 {
            for x in 0..64 {
                // Skip the outermost cells so every point has neighbours.
                let cell = (1 + x % (cells - 2)) * cells + 1 + y % (cells - 2);
                let t = tris[2 * cell + (x + y) % 2];
                let (r1, r2) = (unit(), unit());
                let (w1, w2) = if r1 + r2 > 1.0 {
                    (1.0 - r1, 1.0 - r2)
                } else {
                    (r1, r2)
                };
                let p = t.a * (1.0 - w1 - w2) + t.b * w1 + t.c * w2;
                let p = p - n * (ulps * f32::EPSILON * p.abs().max_element());
                g.set(x, y, p, n);
            }
        }
        (tris, g)
    }

    #[test]
    fn no_acne_on_tilted_planes_with_readback_error() {
        let n = Vec3::new(0.3, 1.0, 0.2).normalize();
        let (t1, _) = n.any_orthonormal_pair();
        let deg = |d: f32| d.to_radians();
        let lights = [
            LightKind::Directional { to_light: n },
            LightKind::Directional {
                to_light: t1 * deg(60.0).cos() + n * deg(60.0).sin(),
            },
            LightKind::Directional {
                to_light: t1 * deg(1.0).cos() + n * deg(1.0).sin(),
            },
        ];
        for centre in [
            Vec3::ZERO,
            Vec3::new(1e4, 0.0, 0.0),
            Vec3::new(1e4, 250.0, -3e3),
        ] {
            let (tris, g) = tilted_plane(centre, n, 8.0);
            let bvh = Bvh::build(tris);
            let mut lights = lights.to_vec();
            lights.push(LightKind::Point {
                position: centre + n * 30.0 + t1 * 10.0,
            });
            for light in lights {
                let r = reference_visibility(&bvh, &light, &g);
                let dark = r.iter().filter(|p| p.visibility != 1.0).count();
                assert_eq!(dark, 0, "acne at {centre} light {light:?}");
                assert!(r.iter().all(|p| p.receiver));
            }
        }
    }

    #[test]
    fn far_from_origin_still_finds_occluders() {
        // Guards the acne test against a reference that never shadows.
        let mut tris = plane(-1.0, 1e4 - 20.0, 1e4 + 20.0, -20.0, 20.0, 16);
        tris.extend(cube(Vec3::new(1e4, 2.0, 0.0), 0.5));
        let bvh = Bvh::build(tris);
        let g = plane_gbuf(-1.0, 1e4 - 2.0, -2.0, 0.1, 40, 40);
        let r = reference_visibility(&bvh, &DOWN_LIGHT, &g);
        for (i, px) in r.iter().enumerate() {
            let p = point_of(&g, i);
            // Coordinates near 1e4 are rounded to ~1e-3; stay clear of edges.
            let dx = (p.x - 1e4).abs();
            if (dx - 0.5).abs() < 0.01 {
                continue;
            }
            let inside = dx < 0.5 && p.z.abs() < 0.5;
            assert_eq!(px.visibility, if inside { 0.0 } else { 1.0 }, "at {p}");
        }
    }

    #[test]
    fn point_light_projects_the_cube() {
        let bvh = cube_on_plane();
        let light = LightKind::Point {
            position: Vec3::new(0.0, 3.0, 0.0),
        };
        // Top face edges project to half-size 0.5 * (3 + 1) / (3 - 0.5).
        let half = 0.5 * (3.0 + 1.0) / (3.0 - 0.5);
        assert!((half - 0.8f32).abs() < 1e-6);
        // Points at +-0.025, +-0.075, ...: the nearest to 0.8 are 0.775, 0.825.
        let g = plane_gbuf(-1.0, -1.5, -1.5, 0.05, 60, 60);
        let r = reference_visibility(&bvh, &light, &g);
        let (mut inside_n, mut outside_n) = (0, 0);
        for (i, px) in r.iter().enumerate() {
            let p = point_of(&g, i);
            let m = p.x.abs().max(p.z.abs());
            assert!(px.receiver);
            if m < half - 0.02 {
                assert_eq!(px.visibility, 0.0, "should be shadowed at {p}");
                inside_n += 1;
            } else if m > half + 0.02 {
                assert_eq!(px.visibility, 1.0, "should be lit at {p}");
                outside_n += 1;
            }
        }
        assert_eq!(inside_n, 32 * 32);
        assert_eq!(inside_n + outside_n, 3600);
    }

    #[test]
    fn a_spot_lights_only_its_cone_and_faces_must_face_it() {
        let bvh = cube_on_plane();
        // Straight down from y = 3 with a 30-degree half angle: the full cone on the plane
        // (4 below) has radius 4 tan 30 = 2.31, a little less inside the rim.
        let cos_full = 30f32.to_radians().cos();
        let light = LightKind::Spot {
            position: Vec3::new(0.0, 3.0, 0.0),
            axis: -Vec3::Y,
            cos_full,
        };
        let mut g = plane_gbuf(-1.0, -4.0, -4.0, 0.1, 80, 80);
        let r = reference_visibility(&bvh, &light, &g);
        for (i, px) in r.iter().enumerate() {
            let p = point_of(&g, i);
            let c = (p - Vec3::new(0.0, 3.0, 0.0)).normalize().dot(-Vec3::Y);
            assert_eq!(px.receiver, c >= cos_full, "at {p}");
        }
        assert!(r.iter().filter(|p| p.receiver).count() > 1000);
        // A triangle facing away takes the pixel out, whatever its interpolated normal.
        g.face_normals = vec![[0.0, -1.0, 0.0]; g.positions.len()];
        g.face_normals[0] = [0.0; 3];
        let r = reference_visibility(&bvh, &DOWN_LIGHT, &g);
        assert!(
            r[0].receiver,
            "an unknown face leaves the interpolated normal to decide"
        );
        assert!(r[1..].iter().all(|p| p.covered && !p.receiver));
    }

    #[test]
    fn point_light_ignores_geometry_beyond_it() {
        // Light between the plane and the cube: the cube is behind it.
        let bvh = cube_on_plane();
        let light = LightKind::Point {
            position: Vec3::new(0.0, -0.7, 0.0),
        };
        let g = plane_gbuf(-1.0, -2.0, -2.0, 0.1, 40, 40);
        let r = reference_visibility(&bvh, &light, &g);
        assert!(r.iter().all(|p| p.receiver && p.visibility == 1.0));
    }

    #[test]
    fn uncovered_and_bad_pixels() {
        let bvh = cube_on_plane();
        let mut g = GBuffer::new_empty(3, 2);
        g.set(0, 0, Vec3::new(2.0, -1.0, 0.0), Vec3::Y);
        g.set(1, 0, Vec3::new(2.0, -1.0, 0.0), Vec3::ZERO);
        g.set(2, 0, Vec3::new(f32::NAN, -1.0, 0.0), Vec3::Y);
        // Short buffers: the last pixels are simply missing.
        g.positions.truncate(4);
        let r = reference_visibility(&bvh, &DOWN_LIGHT, &g);
        assert_eq!(r.len(), 6);
        assert_eq!(
            (r[0].covered, r[0].receiver, r[0].visibility),
            (true, true, 1.0)
        );
        assert_eq!((r[1].covered, r[1].receiver), (true, false));
        assert!(r[2..].iter().all(|p| !p.covered && !p.receiver));
        assert!(reference_visibility(&bvh, &DOWN_LIGHT, &GBuffer::new_empty(0, 5)).is_empty());
    }

    #[test]
    fn supersampled_edges_are_fractional() {
        let bvh = cube_on_plane();
        let n = 4;
        // Output pixels of pitch 0.1 starting at -1.05, so output column 15
        // covers x in [0.45, 0.55] and straddles the shadow edge at 0.5.
        let hi = plane_gbuf(-1.0, -1.05, -1.05, 0.1 / n as f32, 21 * n, 21 * n);
        let r = reference_visibility_supersampled(&bvh, &DOWN_LIGHT, &hi, n);
        assert_eq!(r.len(), 21 * 21);
        let at = |x: usize, z: usize| r[z * 21 + x];
        // Column 15, row 10 (z in [-0.05, 0.05]): half the sub-pixels lit.
        assert_eq!(at(15, 10).visibility, 0.5);
        // Corner pixel: only x < 0.5 and z < 0.5 together are shadowed.
        assert_eq!(at(15, 15).visibility, 0.75);
        assert_eq!(at(10, 10).visibility, 0.0);
        assert_eq!(at(2, 10).visibility, 1.0);
        assert!(r.iter().all(|p| p.covered && p.receiver));
        // Matches the hard reference wherever it is not on an edge.
        let hard = reference_visibility(
            &bvh,
            &DOWN_LIGHT,
            &plane_gbuf(-1.0, -1.05, -1.05, 0.1, 21, 21),
        );
        let fractional = r.iter().filter(|p| p.visibility % 1.0 != 0.0).count();
        assert_eq!(fractional, 4 * 11 - 4);
        for (s, h) in r.iter().zip(&hard) {
            if s.visibility % 1.0 == 0.0 {
                assert_eq!(s.visibility, h.visibility);
            }
        }
        assert!(reference_visibility_supersampled(&bvh, &DOWN_LIGHT, &hi, 0).is_empty());
    }

    #[test]
    fn supersampled_majority_rules_for_coverage() {
        let bvh = cube_on_plane();
        // 2x2 sub-pixels: 3 covered (one facing away) vs 2 covered.
        let mut hi = GBuffer::new_empty(4, 2);
        let p = Vec3::new(3.0, -1.0, 0.0);
        hi.set(0, 0, p, Vec3::Y);
        hi.set(1, 0, p, Vec3::Y);
        hi.set(0, 1, p, -Vec3::Y);
        hi.set(2, 0, p, Vec3::Y);
        hi.set(3, 1, p, Vec3::Y);
        let r = reference_visibility_supersampled(&bvh, &DOWN_LIGHT, &hi, 2);
        assert_eq!(r.len(), 2);
        assert_eq!(
            (r[0].covered, r[0].receiver, r[0].visibility),
            (true, false, 1.0)
        );
        assert_eq!((r[1].covered, r[1].receiver), (false, false));
    }
}
