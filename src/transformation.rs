//! `Transformation`: the matrices of the book's `Transformation` class, with `glam`.
//!
//! Conventions (as the book, i.e. OpenGL's): right-handed world, +Y up, cameras look down
//! their -Z axis, clip-space depth in [-1, 1], angles in degrees, column vectors
//! (`M * v`, so the rightmost matrix applies first).

use glam::{EulerRot, Mat4, Quat, Vec3};

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
        Mat4::from_rotation_x(rotation_deg.x.to_radians())
            * Mat4::from_rotation_y(rotation_deg.y.to_radians())
            * Mat4::from_translation(-position)
    }

    /// The light's view matrix from its position and rotation angles; the same formula as
    /// the camera's ([`Transformation::view`]), named as the book names it.
    pub fn light_view(position: Vec3, rotation_deg: Vec3) -> Mat4 {
        Self::view(position, rotation_deg)
    }

    /// Orthographic projection (`updateOrthoProjectionMatrix`), as glOrtho.
    pub fn ortho(left: f32, right: f32, bottom: f32, top: f32, near: f32, far: f32) -> Mat4 {
        Mat4::orthographic_rh_gl(left, right, bottom, top, near, far)
    }

    /// The model matrix of an item (`buildModelViewMatrix` without the view):
    /// translate * rotateX(-rx) * rotateY(-ry) * rotateZ(-rz) * scale. The book negates the
    /// angles, so a positive angle turns the item clockwise seen from the axis' tip.
    pub fn model(position: Vec3, rotation_deg: Vec3, scale: Vec3) -> Mat4 {
        Mat4::from_translation(position)
            * Mat4::from_rotation_x(-rotation_deg.x.to_radians())
            * Mat4::from_rotation_y(-rotation_deg.y.to_radians())
            * Mat4::from_rotation_z(-rotation_deg.z.to_radians())
            * Mat4::from_scale(scale)
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
