//! The light's camera fitted to what the scene needs (past the chapters: the book suggests
//! it and leaves it): an orthographic box around the receivers the camera can see and every
//! caster that can shadow them, snapped to whole texels so it does not shimmer as the
//! camera moves. (The light basis it builds on, finite at the poles, is
//! [`crate::transformation::light_basis`].)

use glam::{DMat3, DMat4, DVec3, Vec3};

use crate::scene::Scene;
use crate::settings::MapSize;
use crate::shadows::{Rays, ShadowView};
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
            linear_depth: false,
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
/// map of `map_size` (each side fitted on its own, so texels need not be square);
/// `snap` quantises its sides and snaps its position to whole texels.
pub fn fit_ortho(scene: &Scene, to_light: Vec3, map_size: MapSize, snap: bool) -> FittedBox {
    fit_ortho_casters(scene, to_light, map_size, snap).0
}

/// [`fit_ortho`], with the casters the box was fitted to (by item index): the only ones
/// that can shadow a receiver the camera sees. The others (a floor with nothing behind
/// it, a caster beside the view) need not be drawn into the map: where no caster is drawn
/// the map holds its clear depth and reads as lit, which is what they would give.
pub fn fit_ortho_casters(
    scene: &Scene,
    to_light: Vec3,
    map_size: MapSize,
    snap: bool,
) -> (FittedBox, Vec<usize>) {
    let fit = LightFit::new(scene, to_light);
    (
        fit.fit_box(&fit.casters, map_size, snap),
        fit.casters.clone(),
    )
}

/// What a directional light's fitted boxes are built on: the light's basis, each item's
/// box in light space, the part of the receivers the camera can see and the casters that
/// can shadow it. One box around all those casters is [`fit_ortho_casters`]; a box per
/// group of them is [`crate::shadows::groups`].
pub struct LightFit<'a> {
    scene: &'a Scene,
    basis: DMat3,
    light_boxes: Vec<(DVec3, DVec3)>,
    /// The receivers in view, in light space.
    visible: (DVec3, DVec3),
    /// The casters whose shadow the camera can see, by item index.
    pub casters: Vec<usize>,
}

impl<'a> LightFit<'a> {
    /// Item `item`'s rectangle across the light's view (x0, y0, x1, y1 in light space),
    /// cut to the receivers in view: the part of the map a box around it would spend.
    pub fn view_rect(&self, item: usize) -> [f64; 4] {
        let ((lo, hi), (vlo, vhi)) = (self.light_boxes[item], self.visible);
        let (x0, y0) = (lo.x.max(vlo.x), lo.y.max(vlo.y));
        [x0, y0, hi.x.min(vhi.x).max(x0), hi.y.min(vhi.y).max(y0)]
    }

    pub fn new(scene: &'a Scene, to_light: Vec3) -> LightFit<'a> {
        let basis = light_basis(to_light.as_dvec3());
        // Every item receives; casters can also shadow. Boxes in world space, then in light space.
        let item_corners = item_corners(scene);
        let boxes: Vec<(DVec3, DVec3)> = item_corners
            .iter()
            .map(|c| aabb(c.iter().copied()))
            .collect();
        let (reach, visible) = visible_receivers(scene, basis, &boxes);
        let light_boxes: Vec<(DVec3, DVec3)> = item_corners
            .iter()
            .map(|c| aabb(c.iter().map(|&p| basis.transpose() * p)))
            .collect();
        let frustum = frustum_corners(scene, reach);
        let test = CasterTest {
            scene,
            basis,
            to_light: to_light.as_dvec3().normalize(),
            // Each mesh's plane, found once per fit rather than once per pair of items.
            planes: scene.meshes.iter().map(|m| m.flat_plane()).collect(),
            item_corners,
            boxes,
            light_boxes,
            visible,
            frustum,
            frustum_edges: [
                frustum[1] - frustum[0],
                frustum[2] - frustum[0],
                frustum[4] - frustum[0],
                frustum[5] - frustum[1],
                frustum[6] - frustum[2],
                frustum[7] - frustum[3],
            ],
        };
        let casters = (0..scene.items.len())
            .filter(|&c| test.relevant(c))
            .collect();
        LightFit {
            scene,
            basis,
            light_boxes: test.light_boxes,
            visible,
            casters,
        }
    }

    /// The box around `casters` (item indices, from [`LightFit::casters`]) and the
    /// receivers in view they can shadow, for a map of `map_size` (each side fitted on its
    /// own, so texels need not be square); `snap` quantises its sides and snaps its
    /// position to whole texels. No casters: a minimal box, where everything reads lit.
    pub fn fit_box(&self, casters: &[usize], map_size: MapSize, snap: bool) -> FittedBox {
        let (scene, basis, light_boxes) = (self.scene, self.basis, &self.light_boxes);
        let to_light_space = |p: DVec3| basis.transpose() * p;
        let (texels_x, texels_y) = (f64::from(map_size.width), f64::from(map_size.height));
        let (mut llo, mut lhi) = self.visible;
        let mut z_top = lhi.z;
        if casters.is_empty() {
            // Nothing can cast here: a minimal box; everything reads as lit.
            let c = (llo + lhi) * 0.5;
            (llo, lhi) = (c - DVec3::splat(1e-3), c + DVec3::splat(1e-3));
        } else {
            let (clo, chi) = union(&casters.iter().map(|&c| light_boxes[c]).collect::<Vec<_>>());
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
                let inside =
                    lb.0.x >= llo.x && lb.1.x <= lhi.x && lb.0.y >= llo.y && lb.1.y <= lhi.y;
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
        // Each side fitted on its own: a box longer one way gets finer texels the other way.
        let texels = DVec3::new(texels_x, texels_y, 1.0);
        let mut size = (lhi - llo).max(DVec3::splat(1e-6));
        let mut centre = DVec3::new((llo.x + lhi.x) * 0.5, (llo.y + lhi.y) * 0.5, 0.0);
        // Two texels of room for filters that reach beside the looked-up texel.
        size.x *= 1.0 + 4.0 / texels_x;
        size.y *= 1.0 + 4.0 / texels_y;
        let (mut z_lo, mut z_hi) = (llo.z, z_top);
        if snap {
            // Each side to the next 1/8 of its power of two, so small camera moves keep it.
            let step = |side: f64| 2f64.powf(side.log2().floor()) / 8.0;
            let (step_x, step_y) = (step(size.x), step(size.y));
            size.x = (size.x / step_x).ceil() * step_x;
            size.y = (size.y / step_y).ceil() * step_y;
            let texel = size / texels;
            centre.x = (centre.x / texel.x).floor() * texel.x;
            centre.y = (centre.y / texel.y).floor() * texel.y;
            let zstep = step_x.max(step_y);
            z_lo = (z_lo / zstep).floor() * zstep;
            z_hi = (z_hi / zstep).ceil() * zstep;
        }
        // Depth room: a little beyond both ends so nothing sits exactly on a plane.
        let pad = (z_hi - z_lo).max(size.x).max(size.y) * 0.01;
        z_lo -= pad;
        z_hi += pad;
        // The eye sits on the box's top face, so view coordinates stay small wherever the scene is.
        let eye = basis * DVec3::new(centre.x, centre.y, z_hi);
        let (half_x, half_y) = (size.x * 0.5, size.y * 0.5);
        FittedBox {
            view: light_view(eye, basis),
            bounds: [-half_x, half_x, -half_y, half_y, 0.0, z_hi - z_lo],
            texel: (size.x / texels_x).max(size.y / texels_y),
        }
    }
}

/// The part of the receivers the camera can see, in light space: their box cut by the view
/// frustum's box (all of them where the two miss); and how far that frustum reaches.
fn visible_receivers(
    scene: &Scene,
    basis: DMat3,
    boxes: &[(DVec3, DVec3)],
) -> (f64, (DVec3, DVec3)) {
    let (rlo, rhi) = union(boxes);
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
    let visible = aabb(corners(vlo, vhi).map(|p| basis.transpose() * p).into_iter());
    (reach, visible)
}

/// What deciding which casters can shadow a visible receiver needs (see
/// [`CasterTest::relevant`]).
struct CasterTest<'s> {
    scene: &'s Scene,
    basis: DMat3,
    /// Towards the light, normalised.
    to_light: DVec3,
    planes: Vec<Option<(Vec3, Vec3)>>,
    item_corners: Vec<[DVec3; 8]>,
    /// Each item's box in world space.
    boxes: Vec<(DVec3, DVec3)>,
    light_boxes: Vec<(DVec3, DVec3)>,
    visible: (DVec3, DVec3),
    frustum: [DVec3; 8],
    frustum_edges: [DVec3; 6],
}

impl CasterTest<'_> {
    fn to_light_space(&self, p: DVec3) -> DVec3 {
        self.basis.transpose() * p
    }

    /// Whether item `c` can shadow a receiver the camera sees. Along parallel rays only a
    /// caster with the same light-space x, y can shadow a point, and only one above it
    /// (towards the light). A flat caster (a floor) cannot shadow itself, nor anything on its
    /// side facing the light: it matters only if some visible receiver reaches behind its
    /// plane.
    fn relevant(&self, c: usize) -> bool {
        let (scene, light_boxes, visible) = (self.scene, &self.light_boxes, &self.visible);
        scene.items[c].casts_shadows
            && overlaps_xy(&light_boxes[c], visible)
            && self.sweep_in_view(c)
            && (self.planes[scene.items[c].mesh].is_none()
                || (0..scene.items.len()).any(|r| {
                    r != c
                        && overlaps_xy(&light_boxes[r], visible)
                        && overlaps_xy(&light_boxes[r], &light_boxes[c])
                        && light_boxes[r].0.z < light_boxes[c].1.z
                        && self.behind_plane(c, r)
                }))
    }

    /// Item `i`'s plane in world space, its normal towards the light, if its mesh is flat.
    fn world_plane(&self, i: usize) -> Option<(DVec3, DVec3)> {
        let item = &self.scene.items[i];
        let (point, normal) = self.planes[item.mesh]?;
        let m = item.model_matrix64();
        let p = m.transform_point3(point.as_dvec3());
        let n = m
            .inverse()
            .transpose()
            .transform_vector3(normal.as_dvec3())
            .normalize();
        Some((p, if n.dot(self.to_light) < 0.0 { -n } else { n }))
    }

    /// Whether some corner of item `r`'s box lies behind flat caster `c`'s plane (always,
    /// for a caster that is not flat).
    fn behind_plane(&self, c: usize, r: usize) -> bool {
        let Some((p, n)) = self.world_plane(c) else {
            return true;
        };
        let eps = 1e-6 * p.abs().max_element().max(1.0);
        corners(self.boxes[r].0, self.boxes[r].1)
            .iter()
            .any(|q| n.dot(*q - p) < -eps)
    }

    /// The lowest light-space z of item `r` over the x, y rectangle of `over`: a flat item's
    /// plane at the rectangle's corners (a floor far larger than the caster), else its box.
    fn lowest_under(&self, r: usize, over: &(DVec3, DVec3)) -> f64 {
        let within = self.light_boxes[r].0.z;
        let Some((p, n)) = self.world_plane(r) else {
            return within;
        };
        let (p, n) = (self.to_light_space(p), self.to_light_space(n));
        if n.z.abs() < 1e-6 {
            return within;
        }
        corners(over.0, over.1)
            .iter()
            .map(|q| p.z - (n.x * (q.x - p.x) + n.y * (q.y - p.y)) / n.z)
            .fold(f64::INFINITY, f64::min)
            .max(within)
    }

    /// A caster shadows only points along its rays, below it: inside the hull of its box and
    /// that box slid down the rays to the deepest receiver under it. If the view frustum
    /// misses that hull, neither the caster nor its shadow is in view and the map need not
    /// cover it.
    fn sweep_in_view(&self, c: usize) -> bool {
        let (light_boxes, to_light) = (&self.light_boxes, self.to_light);
        let lo = light_boxes[c].0;
        let deepest = (0..self.scene.items.len())
            .filter(|&r| overlaps_xy(&light_boxes[r], &light_boxes[c]))
            .map(|r| self.lowest_under(r, &light_boxes[c]))
            .fold(lo.z, f64::min);
        // The caster's box corners and the same corners slid down its rays to that depth:
        // their hull holds everything the caster can shadow.
        let sweep: Vec<DVec3> = self.item_corners[c]
            .iter()
            .flat_map(|&p| {
                let drop = self.to_light_space(p).z - deepest;
                [p, p - to_light * drop]
            })
            .collect();
        let axes = self.item_corners[c];
        let slid = |e: DVec3| e - to_light * self.to_light_space(e).z;
        let sweep_edges = [
            axes[1] - axes[0],
            axes[2] - axes[0],
            axes[4] - axes[0],
            to_light,
            // The box's edges slid onto the plane: the same edges less their drop.
            slid(axes[1] - axes[0]),
            slid(axes[2] - axes[0]),
            slid(axes[4] - axes[0]),
        ];
        hulls_overlap(&sweep, &sweep_edges, &self.frustum, &self.frustum_edges)
    }
}

/// Whether two light-space boxes overlap across the light's view (in x and y): along
/// parallel rays only such boxes can shadow one another.
fn overlaps_xy(a: &(DVec3, DVec3), b: &(DVec3, DVec3)) -> bool {
    a.0.x <= b.1.x && a.1.x >= b.0.x && a.0.y <= b.1.y && a.1.y >= b.0.y
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
    item_corners(scene)
        .into_iter()
        .map(|c| aabb(c.into_iter()))
        .collect()
}

/// The corners of each item's mesh box placed in the world (turned with the item, so
/// tighter than the axis-aligned box around them), in the scene's item order.
fn item_corners(scene: &Scene) -> Vec<[DVec3; 8]> {
    let mesh_bounds: Vec<(Vec3, Vec3)> = scene.meshes.iter().map(|m| m.bounds()).collect();
    scene
        .items
        .iter()
        .map(|i| {
            let (lo, hi) = mesh_bounds[i.mesh];
            let m = i.model_matrix64();
            corners(lo.as_dvec3(), hi.as_dvec3()).map(|c| m.transform_point3(c))
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

/// Whether the convex hulls of the points `a` and `b` meet, given every direction of
/// their edges (`a_edges`, `b_edges`): the separating axis test, on the edges' cross
/// products (the faces' normals among them).
fn hulls_overlap(a: &[DVec3], a_edges: &[DVec3], b: &[DVec3], b_edges: &[DVec3]) -> bool {
    let span = |points: &[DVec3], axis: DVec3| {
        points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                let d = p.dot(axis);
                (lo.min(d), hi.max(d))
            })
    };
    let edges: Vec<DVec3> = a_edges.iter().chain(b_edges).copied().collect();
    let scale = a
        .iter()
        .chain(b)
        .map(|p| p.abs().max_element())
        .fold(1.0, f64::max);
    for (i, e) in edges.iter().enumerate() {
        for f in &edges[i + 1..] {
            let axis = e.cross(*f);
            if axis.length_squared() < 1e-18 * e.length_squared() * f.length_squared() {
                continue;
            }
            let ((alo, ahi), (blo, bhi)) = (span(a, axis), span(b, axis));
            // A little slack so a hull touching the frustum still counts as in view.
            let slack = 1e-9 * scale * axis.length();
            if ahi < blo - slack || bhi < alo - slack {
                return false;
            }
        }
    }
    true
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Camera, Light};

    fn fit(scene: &Scene) -> (FittedBox, Vec<usize>) {
        let Light::Directional(l) = &scene.lights[0] else {
            panic!("learnopengl's light is directional");
        };
        fit_ortho_casters(scene, l.direction, MapSize::square(1024), true)
    }

    #[test]
    fn the_box_covers_only_casters_whose_shadow_the_camera_can_see() {
        let mut scene = Scene::load("learnopengl").unwrap();
        let names = |casters: &[usize]| -> Vec<String> {
            casters
                .iter()
                .map(|&c| scene.items[c].name.clone())
                .collect()
        };
        // From the tutorial's camera: the floor has nothing behind it, and cube2 (beside
        // the view, its shadow beside it too) is out of sight; cube3's hull reaches the
        // corner of the view.
        let (tutorial_box, casters) = fit(&scene);
        assert_eq!(names(&casters), ["cube1", "cube3"]);
        // From above, every cube and its shadow is in view: the box grows to hold cube2.
        scene.camera = Camera::look_at(Vec3::new(0.0, 12.0, 0.5), Vec3::ZERO).expect("a direction");
        let (above_box, casters) = fit(&scene);
        assert_eq!(names(&casters), ["cube1", "cube2", "cube3"]);
        let area = |b: &FittedBox| (b.bounds[1] - b.bounds[0]) * (b.bounds[3] - b.bounds[2]);
        assert!(area(&above_box) > area(&tutorial_box) * 1.2);
        // Looking away from every cube: nothing to cover.
        scene.camera = Camera::look_at(Vec3::new(0.0, 0.0, 3.0), Vec3::new(0.0, 0.0, 10.0))
            .expect("a direction");
        assert!(fit(&scene).1.is_empty());
    }

    #[test]
    fn each_side_of_the_box_is_fitted_on_its_own() {
        // The tutorial's two covered cubes lie side by side in the light's view: the box is
        // wider than it is tall, each side snapped to its own step.
        let scene = Scene::load("learnopengl").unwrap();
        let [l, r, b, t, ..] = fit(&scene).0.bounds;
        let (w, h) = (r - l, t - b);
        assert!(w > h * 1.3 || h > w * 1.3, "{w} x {h}");
        let snapped = |side: f64| {
            let step = 2f64.powf(side.log2().floor()) / 8.0;
            (side / step - (side / step).round()).abs() < 1e-9
        };
        assert!(snapped(w) && snapped(h), "{w} x {h}");
    }

    #[test]
    fn separating_axes_tell_touching_hulls_from_apart_ones() {
        let cube = |o: DVec3| corners(o, o + DVec3::ONE).to_vec();
        let axes = [DVec3::X, DVec3::Y, DVec3::Z];
        assert!(hulls_overlap(
            &cube(DVec3::ZERO),
            &axes,
            &cube(DVec3::splat(0.5)),
            &axes
        ));
        assert!(!hulls_overlap(
            &cube(DVec3::ZERO),
            &axes,
            &cube(DVec3::new(1.5, 0.0, 0.0)),
            &axes
        ));
        // Apart only along a diagonal: no face normal separates them, an edge cross does.
        // A tetrahedron beside the cube's edge at x = y = 1: their shadows on x, y and z
        // overlap; the plane x + y = 2 (a cross of their edges) parts them.
        let tetra = vec![
            DVec3::new(1.2, 0.9, 0.0),
            DVec3::new(0.9, 1.2, 0.0),
            DVec3::new(1.2, 1.2, 0.0),
            DVec3::new(1.2, 1.2, 1.0),
        ];
        let tetra_edges = [
            DVec3::new(-1.0, 1.0, 0.0),
            DVec3::X,
            DVec3::Y,
            DVec3::new(0.0, 0.3, 1.0),
            DVec3::new(0.3, 0.0, 1.0),
            DVec3::Z,
        ];
        assert!(!hulls_overlap(
            &cube(DVec3::ZERO),
            &axes,
            &tetra,
            &tetra_edges
        ));
    }
}
