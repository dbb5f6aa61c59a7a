//! Light cameras shared by the techniques: a perspective light "camera" (the slides', the
//! blog's, a spot's) and a point light's.

pub mod culling;
pub mod fitted;
pub mod texels;

use glam::{Mat4, Vec3};

use super::{Rays, ShadowView};
use crate::scene::PointLight;
use crate::settings::{MapSize, ShadowSettings};
use crate::transformation::{light_view, look_at_basis};

/// The camera reported for a point light: its +Z face (the reference casts rays to the
/// point; a texel is about 2 far / size at the far plane).
pub fn point_camera(p: &PointLight, settings: &ShadowSettings) -> ShadowView {
    let frustum = Perspective {
        fov: 90.0,
        aspect: 1.0,
        near: p.near,
        far: p.far,
    };
    let mut v = perspective_view(
        p.position,
        p.position + Vec3::Z,
        Some(-Vec3::Y),
        frustum,
        settings.map_size,
    );
    v.texel_world = 2.0 * p.far / settings.map_size.min_side() as f32;
    v
}

/// A perspective light camera's frustum: vertical field of view (degrees), width over
/// height, near and far.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Perspective {
    pub fov: f32,
    pub aspect: f32,
    pub near: f32,
    pub far: f32,
}

/// A perspective light camera (the slides' and the blog's light "camera", a spot's), drawn
/// into a map of `map_size`.
pub fn perspective_view(
    eye: Vec3,
    target: Vec3,
    up: Option<Vec3>,
    frustum: Perspective,
    map_size: MapSize,
) -> ShadowView {
    let Perspective {
        fov,
        aspect,
        near,
        far,
    } = frustum;
    let distance = (target - eye).length().max(near);
    let view = look_at(eye, target, up);
    let half_height = distance * (fov.to_radians() * 0.5).tan();
    // The larger of a texel's two sides, at the target's distance.
    let texel = (2.0 * half_height / map_size.height as f32)
        .max(2.0 * half_height * aspect / map_size.width as f32);
    ShadowView {
        view,
        view64: view.as_dmat4(),
        projection: Mat4::perspective_rh_gl(fov.to_radians(), aspect, near, far),
        perspective: true,
        linear_depth: false,
        near,
        far,
        texel_world: texel,
        rays: Rays::FromPoint { position: eye },
    }
}

/// A right-handed look-at with `up` (+Y when there is none): glm's `lookAt`, except within
/// a few degrees of the poles (the view direction near `up` or its opposite, where glm's
/// gives NaN), where the up turns smoothly to another
/// ([`crate::transformation::look_at_basis`]); finite everywhere.
pub fn look_at(eye: Vec3, target: Vec3, up: Option<Vec3>) -> Mat4 {
    let to_light = (eye - target).as_dvec3();
    let to_light = to_light.try_normalize().unwrap_or(glam::DVec3::Z);
    let up = up.unwrap_or(Vec3::Y).as_dvec3();
    light_view(eye.as_dvec3(), look_at_basis(to_light, up)).as_mat4()
}
