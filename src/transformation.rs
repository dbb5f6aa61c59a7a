//! `Transformation`: the matrices of the book's `Transformation` class, with `glam`, and the
//! one place their formulas are written. The renderer uses these formulas (in double
//! precision, see below); the tests check them against the book's.
//!
//! Conventions (as the book, i.e. OpenGL's): right-handed world, +Y up, cameras look down
//! their -Z axis, clip-space depth in [-1, 1], angles in degrees, column vectors
//! (`M * v`, so the rightmost matrix applies first).
//!
//! Model and view matrices are composed in double precision (`model64`, `view64`): far from
//! the origin, view x model cancels two large translations, and single precision would lose
//! the difference's digits (the extremes suite puts scenes 1e5 units out). The `f32`
//! versions are the same formulas rounded once at the end.

use glam::{DMat3, DMat4, DVec3, EulerRot, Mat4, Quat, Vec3};

/// The book's `Transformation`, without its cached members: every matrix is a pure function.
pub struct Transformation;

impl Transformation {
    /// Perspective projection (`getProjectionMatrix`): vertical field of view in degrees.
    pub fn projection(fov_deg: f32, width: f32, height: f32, near: f32, far: f32) -> Mat4 {
        Mat4::perspective_rh_gl(fov_deg.to_radians(), width / height.max(1.0), near, far)
    }

    /// A view matrix from a position and Euler angles in degrees (`getViewMatrix` and
    /// `updateLightViewMatrix`): rotateX(rx) * rotateY(ry) * translate(-position). The
    /// z angle is ignored, as in the book.
    pub fn view(position: Vec3, rotation_deg: Vec3) -> Mat4 {
        Self::view64(position, rotation_deg).as_mat4()
    }

    /// [`Transformation::view`] in double precision.
    pub fn view64(position: Vec3, rotation_deg: Vec3) -> DMat4 {
        let r = rotation_deg.as_dvec3();
        DMat4::from_rotation_x(r.x.to_radians())
            * DMat4::from_rotation_y(r.y.to_radians())
            * DMat4::from_translation(-position.as_dvec3())
    }

    /// The light's view matrix from its position and rotation angles; the same formula as
    /// the camera's ([`Transformation::view`]), named as the book names it.
    pub fn light_view(position: Vec3, rotation_deg: Vec3) -> Mat4 {
        Self::view(position, rotation_deg)
    }

    /// A light's view as a look-at from `eye` along `-to_light` with up +Y (past the book,
    /// whose angles work only in the YZ plane): glm's `lookAt(eye, eye - to_light, +Y)`,
    /// turned smoothly to another up near the poles ([`light_basis`]), finite everywhere.
    pub fn light_look_at(eye: DVec3, to_light: DVec3) -> DMat4 {
        light_view(eye, light_basis(to_light))
    }

    /// Orthographic projection (`updateOrthoProjectionMatrix`), as glOrtho.
    pub fn ortho(left: f32, right: f32, bottom: f32, top: f32, near: f32, far: f32) -> Mat4 {
        Mat4::orthographic_rh_gl(left, right, bottom, top, near, far)
    }

    /// The model matrix of an item (`buildModelViewMatrix` without the view):
    /// translate * rotateX(-rx) * rotateY(-ry) * rotateZ(-rz) * scale. The book negates the
    /// angles, so a positive angle turns the item clockwise seen from the axis' tip.
    pub fn model(position: Vec3, rotation_deg: Vec3, scale: Vec3) -> Mat4 {
        Self::model64(position, rotation_deg, scale).as_mat4()
    }

    /// [`Transformation::model`] in double precision.
    pub fn model64(position: Vec3, rotation_deg: Vec3, scale: Vec3) -> DMat4 {
        let r = rotation_deg.as_dvec3();
        DMat4::from_translation(position.as_dvec3())
            * DMat4::from_rotation_x(-r.x.to_radians())
            * DMat4::from_rotation_y(-r.y.to_radians())
            * DMat4::from_rotation_z(-r.z.to_radians())
            * DMat4::from_scale(scale.as_dvec3())
    }

    /// The book's angles (for [`Transformation::model`]) of a rotation given as a quaternion:
    /// (rx, ry, rz) with rotateX(-rx) * rotateY(-ry) * rotateZ(-rz) equal to it.
    pub fn book_angles(q: Quat) -> Vec3 {
        let (a, b, c) = q.to_euler(EulerRot::XYZ);
        -Vec3::new(a, b, c).map(f32::to_degrees)
    }

    /// Model-view matrix: view * model.
    pub fn model_view(model: &Mat4, view: &Mat4) -> Mat4 {
        *view * *model
    }
}

/// Within this angle (degrees) of the up axis, either way, a look-at stops using `up` alone:
/// its up tilts smoothly towards [`fallback_up`] ...
pub const POLE_BLEND_OUTER_DEG: f64 = 5.0;
/// ... reaching its full tilt within this angle, so the pole itself is regular.
pub const POLE_BLEND_INNER_DEG: f64 = 1.0;
/// How far (degrees) the up tilts at most: more than [`POLE_BLEND_INNER_DEG`], so the tilted
/// up stays at least 4 degrees off the view direction around the pole, and small, so the
/// basis turns about as fast near its singular directions as anywhere near a pole.
pub const POLE_TILT_DEG: f64 = 5.0;

/// The way a look-at's up tilts near the poles: a fixed direction across `up` (in the
/// world's xz plane for +Y), off the axes, off the diagonals and off the DummyGame's YZ
/// plane. Every continuous choice of light basis has singular directions (the hairy-ball
/// theorem: around each pole a basis that is glm's lookAt on a ring turns once, so it has a
/// singular direction inside the ring). Tilting the up gives one per pole, about 2.8 degrees
/// from it on the side of this vector (above) or of its opposite (below), where no chapter's
/// light passes.
pub fn fallback_up(up: DVec3) -> DVec3 {
    let u = up.normalize();
    // Azimuth -56.25 degrees: midway between the 22.5-degree planes the tests cross in.
    let k = DVec3::new(0.555_570_233, 0.0, -0.831_469_612);
    let across = k - u * k.dot(u);
    if across.length_squared() > 0.01 {
        across.normalize()
    } else {
        let k = DVec3::new(0.8, 0.6, 0.0);
        (k - u * k.dot(u)).normalize()
    }
}

/// The tilt (degrees) of a look-at's up at `from_pole` degrees from the nearest pole: 0
/// beyond [`POLE_BLEND_OUTER_DEG`], [`POLE_TILT_DEG`] within [`POLE_BLEND_INNER_DEG`], a
/// smoothstep between (so the basis changes smoothly where the blend starts and ends).
fn pole_tilt(from_pole: f64) -> f64 {
    let s = ((POLE_BLEND_OUTER_DEG - from_pole) / (POLE_BLEND_OUTER_DEG - POLE_BLEND_INNER_DEG))
        .clamp(0.0, 1.0);
    POLE_TILT_DEG * s * s * (3.0 - 2.0 * s)
}

/// The singular directions of [`look_at_basis`] for `up`: the two where the tilted up lines
/// up with the view direction (the basis spins about its axis around them; it is finite
/// there too).
pub fn look_at_singular_directions(up: DVec3) -> [DVec3; 2] {
    let u = up.normalize();
    let f = fallback_up(u);
    // Bisect for the angle from the pole equal to the tilt there.
    let (mut lo, mut hi) = (POLE_BLEND_INNER_DEG, POLE_BLEND_OUTER_DEG);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if pole_tilt(mid) > mid {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let a = (0.5 * (lo + hi)).to_radians();
    [u * a.cos() + f * a.sin(), -u * a.cos() - f * a.sin()]
}

/// A look-at light basis: columns x, y and z = `to_light` (the light's view looks down -z),
/// exactly glm's `lookAt(eye, eye - to_light, up)` wherever the direction is more than
/// [`POLE_BLEND_OUTER_DEG`] from `up` or its opposite. Nearer the poles the up tilts smoothly
/// towards [`fallback_up`], so a light passing overhead turns its map about its axis with no jump
/// and no NaN. Finite and orthonormal for every non-zero direction; continuous everywhere
/// but [`look_at_singular_directions`].
pub fn look_at_basis(to_light: DVec3, up: DVec3) -> DMat3 {
    let d = to_light.normalize();
    let u = up.try_normalize().unwrap_or(DVec3::Y);
    let from_pole = d.cross(u).length().atan2(d.dot(u).abs()).to_degrees();
    let tilt = pole_tilt(from_pole).to_radians();
    let up = if tilt > 0.0 {
        u * tilt.cos() + fallback_up(u) * tilt.sin()
    } else {
        u
    };
    // glm: s = normalize(cross(forward, up)) with forward = -d; the camera's y is d x s.
    let x = up.cross(d);
    let x = x - d * x.dot(d);
    let x = x
        .try_normalize()
        .unwrap_or_else(|| d.any_orthonormal_vector());
    DMat3::from_cols(x, d.cross(x), d)
}

/// [`look_at_basis`] with up +Y: the light basis of a directional light, its cascades and its
/// fitted box (LearnOpenGL's `glm::lookAt(lightPos, origin, (0, 1, 0))`).
pub fn light_basis(to_light: DVec3) -> DMat3 {
    look_at_basis(to_light, DVec3::Y)
}

/// World to light view for a light at `eye` with basis `basis` (a rigid transform).
pub fn light_view(eye: DVec3, basis: DMat3) -> DMat4 {
    DMat4::from_mat3(basis.transpose()) * DMat4::from_translation(-eye)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(d: DVec3, up: DVec3) {
        let b = look_at_basis(d, up);
        assert!(
            b.to_cols_array().iter().all(|v| v.is_finite()),
            "{d}: not finite"
        );
        let e = b.transpose() * b - DMat3::IDENTITY;
        let worst = e.to_cols_array().iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(worst < 1e-5, "{d}: not orthonormal ({worst:e})");
        assert!(
            (b.z_axis - d.normalize()).length() < 1e-9,
            "{d}: z is not the direction"
        );
        assert!(
            (b.x_axis.cross(b.y_axis) - b.z_axis).length() < 1e-9,
            "{d}: left-handed"
        );
    }

    fn fibonacci(n: usize) -> impl Iterator<Item = DVec3> {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        (0..n).map(move |i| {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let a = golden * i as f64;
            DVec3::new(r * a.cos(), y, r * a.sin())
        })
    }

    fn largest(m: DMat3) -> f64 {
        m.to_cols_array().iter().fold(0.0f64, |a, v| a.max(v.abs()))
    }

    #[test]
    fn basis_is_finite_and_orthonormal_everywhere() {
        for up in [DVec3::Y, DVec3::Z, DVec3::new(0.8, 0.6, 0.0)] {
            // 10,000 directions spread over the sphere ...
            for d in fibonacci(10_000) {
                check(d, up);
            }
            // ... the poles, within 1e-7 of them, and the singular directions themselves.
            let [s0, s1] = look_at_singular_directions(up);
            for d in [
                up,
                -up,
                up + up.any_orthonormal_vector() * 1e-7,
                -up + up.any_orthonormal_vector() * 1e-7,
                s0,
                s1,
            ] {
                check(d, up);
            }
        }
    }

    #[test]
    fn basis_is_glm_look_at_away_from_the_poles() {
        // glm::lookAt's rows are s, u, -f: the transpose of our basis.
        for d in fibonacci(2_000) {
            let from_pole = d.y.abs().acos().to_degrees();
            if from_pole < POLE_BLEND_OUTER_DEG {
                continue;
            }
            let ours = DMat4::from_mat3(light_basis(d).transpose());
            let glm = DMat4::look_at_rh(DVec3::ZERO, -d, DVec3::Y);
            let diff = (ours - glm)
                .to_cols_array()
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()));
            assert!(diff < 1e-12, "{d}: {diff:e} from lookAt");
        }
    }

    /// The largest change of the basis in one step of `step` radians along a great circle
    /// through `pole`, from 10 degrees before it to 10 degrees after, in `azimuths` planes.
    fn worst_step_across(pole: DVec3, step: f64, azimuths: usize) -> (f64, DVec3) {
        let mut worst = (0.0, pole);
        let span = 10f64.to_radians();
        let steps = (2.0 * span / step).round() as usize;
        for k in 0..azimuths {
            let a = k as f64 * std::f64::consts::TAU / azimuths as f64;
            let across = DVec3::new(a.cos(), 0.0, a.sin());
            let at = |i: usize| {
                let t = -span + i as f64 * step;
                pole * t.cos() + across * t.sin()
            };
            let mut prev = light_basis(at(0));
            for i in 1..=steps {
                let d = at(i);
                let b = light_basis(d);
                let diff = largest(b - prev);
                if diff > worst.0 {
                    worst = (diff, d);
                }
                prev = b;
            }
        }
        worst
    }

    #[test]
    fn basis_is_continuous_across_the_poles() {
        // Steps of 1e-4 rad through each pole in 16 planes (among them the DummyGame's YZ
        // plane and the XY plane): the basis turns half a turn about its axis within the
        // blend, fastest where a plane passes nearest a singular direction (0.55 degrees
        // off it), yet a step moves it by at most 0.05 (measured 0.027; a jump would be of
        // order 1), and ten times smaller steps move it about ten times less: no jump.
        for pole in [DVec3::Y, -DVec3::Y] {
            let (coarse, at) = worst_step_across(pole, 1e-4, 16);
            assert!(
                coarse < 5e-2,
                "across {pole}: a 1e-4 rad step at {at} moves the basis by {coarse:e}"
            );
            let (fine, at) = worst_step_across(pole, 1e-5, 16);
            eprintln!(
                "across {pole}: worst change per 1e-4 rad step {coarse:.2e}, per 1e-5 {fine:.2e}"
            );
            assert!(
                fine < coarse / 5.0,
                "across {pole}: a 1e-5 rad step at {at} moves the basis by {fine:e}"
            );
        }
        // And steps of 1e-7 from the pole itself, every way.
        for pole in [DVec3::Y, -DVec3::Y] {
            for k in 0..64 {
                let a = k as f64 * std::f64::consts::TAU / 64.0;
                let off = DVec3::new(a.cos(), 0.0, a.sin()) * 1e-7;
                let diff = largest(light_basis(pole + off) - light_basis(pole));
                assert!(
                    diff < 1e-5,
                    "a step of 1e-7 from {pole} moves the basis by {diff}"
                );
            }
        }
    }

    #[test]
    fn basis_is_continuous_away_from_its_two_singular_directions() {
        // Neighbours on a fine lattice: a step of about 1e-3 rad moves the basis by about as
        // much, except within a degree of the two singular directions.
        let singular = look_at_singular_directions(DVec3::Y);
        let mut checked = 0;
        for d in fibonacci(20_000) {
            if singular
                .iter()
                .any(|s| s.angle_between(d) < 1f64.to_radians())
            {
                continue;
            }
            let e = d.any_orthonormal_vector() * 1e-3;
            let diff = largest(light_basis(d + e) - light_basis(d));
            assert!(diff < 0.2, "{d}: a step of 1e-3 moves the basis by {diff}");
            checked += 1;
        }
        assert!(checked > 19_900);
        // The singular directions are where the text says: about 2.8 degrees from each pole.
        for (s, pole) in singular.iter().zip([DVec3::Y, -DVec3::Y]) {
            let a = s.angle_between(pole).to_degrees();
            assert!((2.6..3.0).contains(&a), "{s}: {a} degrees from {pole}");
        }
    }
}
