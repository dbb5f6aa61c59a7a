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

    /// A light's view as a look-at from `eye` along `-to_light` (past the book, whose angles
    /// work only in the YZ plane): world to a light camera whose basis is
    /// [`light_basis`]`(to_light)`, finite for every direction.
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

/// The direction whose basis is not continuous (every continuous choice of basis on the
/// sphere has one): well below the horizon and off every axis, where no chapter's light
/// goes. The basis is finite there too.
const SINGULAR: DVec3 = DVec3::new(
    0.301_511_344_577_763_6,
    -0.904_534_033_733_291,
    0.301_511_344_577_763_6,
);

/// An orthonormal light basis: columns x, y and z = `to_light` (the light's view looks down
/// -z). Finite for every non-zero direction, and continuous everywhere but [`SINGULAR`], so
/// a sun passing overhead (the usual look-at's NaN, +-Y) turns its map smoothly.
pub fn light_basis(to_light: DVec3) -> DMat3 {
    let d = to_light.normalize();
    // The reference frame, for d = -SINGULAR: any orthonormal pair around it.
    let r = -SINGULAR;
    let x0 = r.any_orthonormal_vector();
    let y0 = r.cross(x0);
    // The shortest rotation from r to d; only d = -r = SINGULAR has no unique one.
    let q = glam::DQuat::from_rotation_arc(r, d);
    DMat3::from_cols(q * x0, q * y0, d)
}

/// World to light view for a light at `eye` with basis `basis` (a rigid transform).
pub fn light_view(eye: DVec3, basis: DMat3) -> DMat4 {
    DMat4::from_mat3(basis.transpose()) * DMat4::from_translation(-eye)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(d: DVec3) {
        let b = light_basis(d);
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

    #[test]
    fn basis_is_finite_and_orthonormal_everywhere() {
        // 10,000 directions spread over the sphere (a Fibonacci lattice) ...
        let n = 10_000;
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        for i in 0..n {
            let y = 1.0 - 2.0 * (i as f64 + 0.5) / n as f64;
            let r = (1.0 - y * y).sqrt();
            let a = golden * i as f64;
            check(DVec3::new(r * a.cos(), y, r * a.sin()));
        }
        // ... the poles, within 1e-7 of them, and the one singular direction itself.
        for d in [
            DVec3::Y,
            -DVec3::Y,
            DVec3::new(1e-7, 1.0, 0.0),
            DVec3::new(0.0, -1.0, 1e-7),
            SINGULAR,
            -SINGULAR,
        ] {
            check(d);
        }
    }

    #[test]
    fn basis_is_continuous_across_the_poles() {
        for pole in [DVec3::Y, -DVec3::Y] {
            for k in 0..64 {
                let a = k as f64 * std::f64::consts::TAU / 64.0;
                let off = DVec3::new(a.cos(), 0.0, a.sin()) * 1e-7;
                let (b0, b1) = (light_basis(pole), light_basis(pole + off));
                let diff = (b1 - b0)
                    .to_cols_array()
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(
                    diff < 1e-5,
                    "a step of 1e-7 from {pole} moves the basis by {diff}"
                );
            }
        }
    }
}
