//! `DirectionalLight` and `OrthoCoords` ("Shadows": the light's ortho box and
//! `shadowPosMult`), and the light's view and projection matrices.

use glam::{Mat4, Vec3};
use serde::{Deserialize, Serialize};

use crate::settings::LightView;
use crate::transformation::Transformation;

/// The box the orthographic light projection keeps, in light-view units (the book's
/// `OrthoCoords`). `near` and `far` are distances along the light's view direction from the
/// light's position, so a negative near reaches behind it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OrthoCoords {
    pub left: f32,
    pub right: f32,
    pub bottom: f32,
    pub top: f32,
    pub near: f32,
    pub far: f32,
}

impl Default for OrthoCoords {
    /// The DummyGame's box: +-10 across, near -1, far 20.
    fn default() -> Self {
        OrthoCoords {
            left: -10.0,
            right: 10.0,
            bottom: -10.0,
            top: 10.0,
            near: -1.0,
            far: 20.0,
        }
    }
}

/// A light infinitely far away. `direction` points from the scene TOWARDS the light (the
/// book's convention), so (0, 1, 0) is the sun straight overhead.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DirectionalLight {
    pub colour: Vec3,
    pub direction: Vec3,
    pub intensity: f32,
    pub ortho: OrthoCoords,
    /// Where the shadow "camera" sits: `direction * shadow_pos_mult`.
    pub shadow_pos_mult: f32,
}

impl DirectionalLight {
    /// The DummyGame's direction for a light angle in degrees: (0, sin a, cos a), so 90 is
    /// overhead, 0 and 180 are at the horizon along +Z and -Z.
    pub fn direction_from_angle(angle_deg: f32) -> Vec3 {
        let a = angle_deg.to_radians();
        Vec3::new(0.0, a.sin(), a.cos()).normalize()
    }

    /// The inverse of [`Self::direction_from_angle`] for directions in the YZ plane.
    pub fn angle_deg(&self) -> f32 {
        self.direction.y.atan2(self.direction.z).to_degrees()
    }

    /// The shadow camera's position.
    pub fn position(&self) -> Vec3 {
        self.direction * self.shadow_pos_mult
    }

    /// The light's view matrix, built the book's way or with a look-at.
    pub fn view_matrix(&self, mode: LightView) -> Mat4 {
        let d = self.direction.normalize();
        match mode {
            LightView::BookAngles => {
                // The book: rotation x = acos(dir.z), y = asin(dir.x). This maps the direction
                // onto +Z only while dir.x == 0 (as in the DummyGame, whose light turns in the
                // YZ plane). With an x component the two rotations no longer compose to the
                // right orientation and the shadow map looks at the scene askew: use LookAt.
                let rotation = Vec3::new(
                    d.z.clamp(-1.0, 1.0).acos().to_degrees(),
                    d.x.clamp(-1.0, 1.0).asin().to_degrees(),
                    0.0,
                );
                Transformation::light_view(self.position(), rotation)
            }
            LightView::LookAt => {
                // Keep "up" away from the direction so the basis never degenerates.
                let up = if d.y.abs() < 0.99 { Vec3::Y } else { Vec3::Z };
                Mat4::look_at_rh(self.position(), self.position() - d, up)
            }
        }
    }

    /// The orthographic projection of the ortho box.
    pub fn projection_matrix(&self) -> Mat4 {
        let o = &self.ortho;
        Transformation::ortho(o.left, o.right, o.bottom, o.top, o.near, o.far)
    }
}
