//! Culling against a light's view: whether a caster's world box can land in its map, so
//! depth passes and the cache skip the casters that would be clipped anyway.

use glam::{DMat4, DVec3};

use super::fitted::corners;
use crate::scene::Light;
use crate::shadows::ShadowView;

/// Whether a caster whose world box is `lo..hi` can land in the map of `light` seen through
/// `camera`: a point light's cube sees a ball of radius `far`; a 2D map its view volume.
pub fn may_land(light: &Light, camera: &ShadowView, lo: DVec3, hi: DVec3) -> bool {
    if let Light::Point(p) = light {
        let nearest = p.position.as_dvec3().clamp(lo, hi);
        return nearest.distance(p.position.as_dvec3()) <= f64::from(p.far);
    }
    !beyond_a_plane(camera.projection.as_dmat4() * camera.view64, lo, hi)
}

/// Whether the box `lo..hi` lies wholly beyond one of the clip planes of `clip` (all eight
/// corners beyond x < -w, x > w, y < -w, y > w, z < -w or z > w): a conservative cull, a box
/// it keeps may still miss the volume.
pub fn beyond_a_plane(clip: DMat4, lo: DVec3, hi: DVec3) -> bool {
    let corners = corners(lo, hi).map(|c| clip * c.extend(1.0));
    let beyond = |f: &dyn Fn(&glam::DVec4) -> bool| corners.iter().all(f);
    beyond(&|c| c.x < -c.w)
        || beyond(&|c| c.x > c.w)
        || beyond(&|c| c.y < -c.w)
        || beyond(&|c| c.y > c.w)
        || beyond(&|c| c.z < -c.w)
        || beyond(&|c| c.z > c.w)
}
