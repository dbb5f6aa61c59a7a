//! `Camera`: the book's first-person camera (position plus pitch and yaw in degrees).

use glam::{DMat4, Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::transformation::Transformation;

/// The viewer. `rotation.x` pitches (positive looks down), `rotation.y` yaws (positive turns
/// right); the view matrix is rotateX * rotateY * translate(-position), as in the book.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Camera {
    pub position: Vec3,
    /// Degrees: x = pitch, y = yaw, z unused (the book ignores it).
    pub rotation: Vec3,
    /// Vertical field of view in degrees.
    pub fov: f32,
    pub near: f32,
    pub far: f32,
}

impl Default for Camera {
    /// The book's camera: FOV 60, near 0.01, far 1000, at z = 2.
    fn default() -> Self {
        Camera {
            position: Vec3::new(0.0, 0.0, 2.0),
            rotation: Vec3::ZERO,
            fov: 60.0,
            near: 0.01,
            far: 1000.0,
        }
    }
}

impl Camera {
    /// Hashes every field bit for bit (a cache's key: no formatting per frame).
    pub fn hash_bits(&self, h: &mut impl std::hash::Hasher) {
        use std::hash::Hash;
        let Camera {
            position,
            rotation,
            fov,
            near,
            far,
        } = self;
        let (p, r) = (position.to_array(), rotation.to_array());
        [p, r, [*fov, *near, *far]]
            .map(|v| v.map(f32::to_bits))
            .hash(h);
    }

    /// Moves relative to the yaw, as the book's `movePosition`: z forward/back, x sideways,
    /// y straight up.
    pub fn move_position(&mut self, offset: Vec3) {
        let yaw = self.rotation.y.to_radians();
        if offset.z != 0.0 {
            self.position.x += -yaw.sin() * offset.z;
            self.position.z += yaw.cos() * offset.z;
        }
        if offset.x != 0.0 {
            let side = yaw - std::f32::consts::FRAC_PI_2;
            self.position.x += -side.sin() * offset.x;
            self.position.z += side.cos() * offset.x;
        }
        self.position.y += offset.y;
    }

    /// Adds pitch / yaw in degrees (the book's `moveRotation`).
    pub fn move_rotation(&mut self, delta: Vec3) {
        self.rotation += delta;
    }

    pub fn view_matrix(&self) -> Mat4 {
        Transformation::view(self.position, self.rotation)
    }

    /// The view matrix in double precision, so that view x model keeps its digits when the
    /// scene sits far from the origin.
    pub fn view_matrix64(&self) -> DMat4 {
        Transformation::view64(self.position, self.rotation)
    }

    pub fn projection_matrix(&self, width: u32, height: u32) -> Mat4 {
        Transformation::projection(self.fov, width as f32, height as f32, self.near, self.far)
    }

    /// A camera at `position` looking at `target`, as the book's angles: the pitch and
    /// yaw whose view direction points at the target, roll 0 (so the camera stays the
    /// book's and its keys turn it from there). Straight up or down, the yaw is 0. `None`
    /// when the target is the position or either is not finite: no direction.
    pub fn look_at(position: Vec3, target: Vec3) -> Option<Camera> {
        let d = (target.as_dvec3() - position.as_dvec3()).normalize_or_zero();
        if d == glam::DVec3::ZERO || !d.is_finite() {
            return None;
        }
        // The book's view looks along (cos p sin y, -sin p, -cos p cos y).
        let pitch = (-d.y).clamp(-1.0, 1.0).asin();
        let yaw = if d.x == 0.0 && d.z == 0.0 {
            0.0
        } else {
            d.x.atan2(-d.z)
        };
        Some(Camera {
            position,
            rotation: Vec3::new(pitch.to_degrees() as f32, yaw.to_degrees() as f32, 0.0),
            ..Camera::default()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn look_at_puts_the_target_in_the_frame_centre() {
        let cases = [
            (Vec3::new(0.0, 4.0, 9.0), Vec3::ZERO),
            (Vec3::new(3.0, -2.0, 1.0), Vec3::new(-5.0, 4.0, 7.0)),
            (
                Vec3::new(1e4, 10.0, -1e4),
                Vec3::new(1e4 + 3.0, 0.0, -1e4 - 1.0),
            ),
            (Vec3::new(1.0, 5.0, 1.0), Vec3::new(1.0, -5.0, 1.0)), // straight down
            (Vec3::ZERO, Vec3::new(0.0, 0.0, 1.0)),                // behind the default view
        ];
        for (eye, target) in cases {
            let cam = Camera::look_at(eye, target).unwrap();
            let view = cam.view_matrix64().transform_point3(target.as_dvec3());
            // In front of the camera (view space looks down -Z) and on its axis.
            assert!(view.z < 0.0, "{eye} -> {target}: behind ({view})");
            let off_axis = view.truncate().length() / -view.z;
            assert!(off_axis < 1e-5, "{eye} -> {target}: {off_axis}");
            let ndc = cam.projection_matrix(640, 360).as_dmat4() * glam::DVec4::from((view, 1.0));
            assert!((ndc.x / ndc.w).abs() < 1e-5 && (ndc.y / ndc.w).abs() < 1e-5);
            assert_eq!(cam.rotation.z, 0.0);
        }
        assert_eq!(Camera::look_at(Vec3::ONE, Vec3::ONE), None);
        assert_eq!(Camera::look_at(Vec3::ONE, Vec3::splat(f32::NAN)), None);
    }
}
