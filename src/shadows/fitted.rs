//! The light's camera fitted to what the scene needs (past the chapters: the book suggests
//! it and leaves it): an orthographic box around the receivers the camera can see and every
//! caster that can shadow them, snapped to whole texels so it does not shimmer as the
//! camera moves. (The light basis it builds on, finite at the poles, is
//! [`crate::transformation::light_basis`].)

use glam::{DMat4, DVec3, Vec3};

use super::{Rays, ShadowView};
use crate::scene::Scene;
use crate::settings::MapSize;
use crate::transformation::{light_basis, light_view};

/// A fitted orthographic light camera.
#[derive(Debug, Clone, Copy)]
pub struct FittedBox {
    pub view: DMat4,
    /// left, right, bottom, top, near, far in the light's view space.
    pub bounds: [f64; 6],
    /// One texel in world units.
    pub texel: f64,
}

impl FittedBox {
    /// The fitted box as the depth pass' camera for a light shining from `to_light`.
    pub fn shadow_view(&self, to_light: Vec3) -> ShadowView {
        let [left, right, bottom, top, near, far] = self.bounds;
        let projection = DMat4::orthographic_rh_gl(left, right, bottom, top, near, far).as_mat4();
        ShadowView {
            view: self.view.as_mat4(),
            view64: self.view,
            projection,
            perspective: false,
            near: near as f32,
            far: far as f32,
            texel_world: self.texel as f32,
            rays: Rays::Parallel {
                to_light: to_light.normalize(),
            },
        }
    }
}

/// Fits the light's box to `scene` for a light shining from `to_light`, with a
/// map of `map_size` (a square box: with a non-square map its texels are not square);
/// `snap` quantises its size and snaps its position to whole texels.
pub fn fit_ortho(scene: &Scene, to_light: Vec3, map_size: MapSize, snap: bool) -> FittedBox {
    let (texels_x, texels_y) = (f64::from(map_size.width), f64::from(map_size.height));
    let basis = light_basis(to_light.as_dvec3());
    let to_light_space = |p: DVec3| basis.transpose() * p;

    // Every item receives; casters can also shadow. Boxes in world space, then in light space.
    let boxes = item_world_boxes(scene);
    let (rlo, rhi) = union(&boxes);

    // The part of the receivers the camera can see: their box cut by the view frustum's box.
    // The camera the fit follows: the viewer, or `fit_camera` (to watch the fit from elsewhere).
    let cam = scene.fitting_camera();
    let eye = cam.position.as_dvec3();
    let reach = corners(rlo, rhi)
        .iter()
        .map(|c| (*c - eye).length())
        .fold(0.0, f64::max)
        .min(cam.far as f64);
    let (flo, fhi) = aabb(frustum_corners(scene, reach).into_iter());
    let (vlo, vhi) = (rlo.max(flo), rhi.min(fhi));
    let (vlo, vhi) = if vlo.cmple(vhi).all() {
        (vlo, vhi)
    } else {
        (rlo, rhi)
    };
    let (vl_lo, vl_hi) = aabb(corners(vlo, vhi).map(to_light_space).into_iter());
    let light_boxes: Vec<(DVec3, DVec3)> = boxes
        .iter()
        .map(|(lo, hi)| aabb(corners(*lo, *hi).map(to_light_space).into_iter()))
        .collect();
    let overlaps_xy = |a: &(DVec3, DVec3), b: &(DVec3, DVec3)| {
        a.0.x <= b.1.x && a.1.x >= b.0.x && a.0.y <= b.1.y && a.1.y >= b.0.y
    };
    let visible = (vl_lo, vl_hi);
    // Along parallel rays only a caster with the same light-space x, y can shadow a point,
    // and only one above it (towards the light). A flat caster (a floor) cannot shadow
    // itself, nor anything on its side facing the light: it matters only if some visible
    // receiver reaches behind its plane.
    let to_light = to_light.as_dvec3().normalize();
    // Each mesh's plane, found once per fit rather than once per pair of items.
    let planes: Vec<Option<(Vec3, Vec3)>> = scene.meshes.iter().map(|m| m.flat_plane()).collect();
    let behind_plane = |c: usize, r: usize| -> bool {
        let item = &scene.items[c];
        let Some((point, normal)) = planes[item.mesh] else {
            return true;
        };
        let m = item.model_matrix64();
        let p = m.transform_point3(point.as_dvec3());
        let mut n = m
            .inverse()
            .transpose()
            .transform_vector3(normal.as_dvec3())
            .normalize();
        if n.dot(to_light) < 0.0 {
            n = -n;
        }
        let eps = 1e-6 * p.abs().max_element().max(1.0);
        corners(boxes[r].0, boxes[r].1)
            .iter()
            .any(|q| n.dot(*q - p) < -eps)
    };
    let relevant: Vec<usize> = (0..scene.items.len())
        .filter(|&c| scene.items[c].casts_shadows && overlaps_xy(&light_boxes[c], &visible))
        .filter(|&c| {
            planes[scene.items[c].mesh].is_none()
                || (0..scene.items.len()).any(|r| {
                    r != c
                        && overlaps_xy(&light_boxes[r], &visible)
                        && overlaps_xy(&light_boxes[r], &light_boxes[c])
                        && light_boxes[r].0.z < light_boxes[c].1.z
                        && behind_plane(c, r)
                })
        })
        .collect();
    let (mut llo, mut lhi) = visible;
    let mut z_top = lhi.z;
    if relevant.is_empty() {
        // Nothing can cast here: a minimal box; everything reads as lit.
        let c = (llo + lhi) * 0.5;
        (llo, lhi) = (c - DVec3::splat(1e-3), c + DVec3::splat(1e-3));
    } else {
        let (clo, chi) = union(&relevant.iter().map(|&c| light_boxes[c]).collect::<Vec<_>>());
        llo = DVec3::new(llo.x.max(clo.x), llo.y.max(clo.y), llo.z);
        lhi = DVec3::new(lhi.x.min(chi.x), lhi.y.min(chi.y), lhi.z);
        z_top = chi.z;
        // The deepest receiver point inside the box's x, y: whole items when they fit in
        // it, their triangles clipped to it when they reach past it (a floor).
        let mut z_deep = f64::INFINITY;
        for (i, lb) in light_boxes.iter().enumerate() {
            if !overlaps_xy(lb, &(llo, lhi)) {
                continue;
            }
            let inside = lb.0.x >= llo.x && lb.1.x <= lhi.x && lb.0.y >= llo.y && lb.1.y <= lhi.y;
            if inside {
                z_deep = z_deep.min(lb.0.z);
                continue;
            }
            let item = &scene.items[i];
            let m = item.model_matrix64();
            for t in scene.meshes[item.mesh].triangles() {
                let t = t.map(|p| to_light_space(m.transform_point3(p.as_dvec3())));
                if let Some(z) = clipped_min_z(&t, llo, lhi) {
                    z_deep = z_deep.min(z);
                }
            }
        }
        if z_deep.is_finite() {
            llo.z = z_deep;
        }
    }
    let mut size = (lhi.x - llo.x).max(lhi.y - llo.y).max(1e-6);
    let mut centre = DVec3::new((llo.x + lhi.x) * 0.5, (llo.y + lhi.y) * 0.5, 0.0);
    // Two texels of room for filters that reach beside the looked-up texel.
    size *= 1.0 + 4.0 / texels_x.min(texels_y);
    let (mut z_lo, mut z_hi) = (llo.z, z_top);
    if snap {
        // Size to the next 1/8 of its power of two, so small camera moves keep it.
        let step = 2f64.powf(size.log2().floor()) / 8.0;
        size = (size / step).ceil() * step;
        let (texel_x, texel_y) = (size / texels_x, size / texels_y);
        centre.x = (centre.x / texel_x).floor() * texel_x;
        centre.y = (centre.y / texel_y).floor() * texel_y;
        let zstep = step;
        z_lo = (z_lo / zstep).floor() * zstep;
        z_hi = (z_hi / zstep).ceil() * zstep;
    }
    // Depth room: a little beyond both ends so nothing sits exactly on a plane.
    let pad = (z_hi - z_lo).max(size) * 0.01;
    z_lo -= pad;
    z_hi += pad;
    // The eye sits on the box's top face, so view coordinates stay small wherever the scene is.
    let eye = basis * DVec3::new(centre.x, centre.y, z_hi);
    let half = size * 0.5;
    FittedBox {
        view: light_view(eye, basis),
        bounds: [-half, half, -half, half, 0.0, z_hi - z_lo],
        texel: size / texels_x.min(texels_y),
    }
}

/// The lowest z of a light-space triangle clipped to the x, y box [lo, hi], if any of it
/// lies inside (Sutherland-Hodgman against the four sides).
fn clipped_min_z(t: &[DVec3; 3], lo: DVec3, hi: DVec3) -> Option<f64> {
    let mut poly: Vec<DVec3> = t.to_vec();
    let sides: [(usize, f64, f64); 4] = [
        (0, lo.x, 1.0),
        (0, hi.x, -1.0),
        (1, lo.y, 1.0),
        (1, hi.y, -1.0),
    ];
    for (axis, bound, sign) in sides {
        let inside = |p: &DVec3| (p[axis] - bound) * sign >= 0.0;
        let mut out = Vec::with_capacity(poly.len() + 2);
        for k in 0..poly.len() {
            let (a, b) = (poly[k], poly[(k + 1) % poly.len()]);
            if inside(&a) {
                out.push(a);
            }
            if inside(&a) != inside(&b) {
                let s = (bound - a[axis]) / (b[axis] - a[axis]);
                out.push(a + (b - a) * s);
            }
        }
        poly = out;
        if poly.is_empty() {
            return None;
        }
    }
    poly.iter().map(|p| p.z).reduce(f64::min)
}

/// Each item's axis-aligned box in world space, in the scene's item order.
pub fn item_world_boxes(scene: &Scene) -> Vec<(DVec3, DVec3)> {
    let mesh_bounds: Vec<(Vec3, Vec3)> = scene.meshes.iter().map(|m| m.bounds()).collect();
    scene
        .items
        .iter()
        .map(|i| {
            let (lo, hi) = mesh_bounds[i.mesh];
            let m = i.model_matrix64();
            aabb(
                corners(lo.as_dvec3(), hi.as_dvec3())
                    .map(|c| m.transform_point3(c))
                    .into_iter(),
            )
        })
        .collect()
}

pub(crate) fn corners(lo: DVec3, hi: DVec3) -> [DVec3; 8] {
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        )
    })
}

pub(crate) fn aabb(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

fn union(boxes: &[(DVec3, DVec3)]) -> (DVec3, DVec3) {
    if boxes.is_empty() {
        return (DVec3::splat(-1.0), DVec3::splat(1.0));
    }
    aabb(boxes.iter().flat_map(|(a, b)| [*a, *b]))
}

/// The camera frustum's corners, its far plane pulled in to `reach`.
fn frustum_corners(scene: &Scene, reach: f64) -> [DVec3; 8] {
    let cam = scene.fitting_camera();
    let [w, h] = scene.size;
    let aspect = w as f64 / h.max(1) as f64;
    let t = (cam.fov as f64).to_radians() * 0.5;
    let inv_view = cam.view_matrix64().inverse();
    let near = cam.near as f64;
    let far = reach.max(near * 2.0);
    std::array::from_fn(|i| {
        let d = if i & 4 == 0 { near } else { far };
        let x = if i & 1 == 0 { -1.0 } else { 1.0 } * d * t.tan() * aspect;
        let y = if i & 2 == 0 { -1.0 } else { 1.0 } * d * t.tan();
        inv_view.transform_point3(DVec3::new(x, y, -d))
    })
}
