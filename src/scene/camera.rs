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
}
