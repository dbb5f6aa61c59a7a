//! Cascaded shadow maps for a directional light (past the chapters: LearnOpenGL's "Shadow
//! Mapping" ends by pointing at them). The camera's view range is cut into slices, each
//! slice gets its own orthographic light box, and near slices get small boxes, so texels
//! stay about the size of a pixel from the camera's feet to the horizon.
//!
//! - Splits: the practical scheme (Zhang et al., "Parallel-split shadow maps"), a blend of
//!   the logarithmic split, which keeps texels per pixel constant, and the uniform one:
//!   `d_i = lambda * n (f/n)^(i/N) + (1 - lambda) (n + (f - n) i/N)`.
//! - Boxes: each slice's smallest bounding sphere. Its radius depends only on the slice's
//!   shape, not on where the camera looks, so the box keeps its size as the camera turns;
//!   its centre moves in whole texels (snapping), so shadow edges do not crawl.
//! - Reach: unless `shadow_distance` is set, the cascades cover the view depths the scene's
//!   receivers occupy, not the camera's whole far plane (the DummyGame's camera reaches
//!   1000 units over a scene 5 across: cascades that size lose the shadow).

use glam::{DVec3, Vec3};

use super::camera::fitted::{aabb, corners, FittedBox};
use super::casters::casters;
use super::kind::{self, Family, IdleRules, KindFacts, LayerLayout, TechniqueFacts};
use super::layers::{self, Layout};
use super::{DepthPass, ShadowKind};
use crate::engine::ShaderProgram;
use crate::scene::{Camera, DirectionalLight, Scene};
use crate::settings::ShadowSettings;
use crate::transformation::{light_basis, light_view};

/// `count + 1` view depths from `near` to `far`: the practical split scheme with `lambda`
/// from 0 (uniform) to 1 (logarithmic). Computed in double precision so a near plane of
/// 1e-3 and a far one of 1e5 still give finite, strictly increasing splits.
pub fn practical_splits(near: f64, far: f64, count: u32, lambda: f64) -> Vec<f64> {
    let n = near.max(f64::MIN_POSITIVE);
    let f = far.max(n);
    (0..=count)
        .map(|i| {
            let t = f64::from(i) / f64::from(count.max(1));
            let log = n * (f / n).powf(t);
            let uniform = n + (f - n) * t;
            let d = lambda * log + (1.0 - lambda) * uniform;
            // The ends exactly, whatever rounding did in between.
            match i {
                0 => n,
                _ if i == count => f,
                _ => d,
            }
        })
        .collect()
}

/// The smallest sphere around the slice of the camera's frustum between view depths `a`
/// and `b`: (distance of its centre along the view axis, radius). `k` is the slice's
/// half-diagonal per unit of depth, sqrt(tan^2(fov/2) (1 + aspect^2)).
pub fn slice_sphere(a: f64, b: f64, k: f64) -> (f64, f64) {
    // The centre on the axis equidistant from a near corner and a far corner, unless that
    // lies past the far plane (a wide slice), where the far cap alone decides.
    let z = ((a + b) * (1.0 + k * k) * 0.5).min(b);
    let near_corner = ((z - a).powi(2) + (a * k).powi(2)).sqrt();
    let far_corner = ((b - z).powi(2) + (b * k).powi(2)).sqrt();
    (z, near_corner.max(far_corner))
}

/// One cascade: its light box and the view depths it serves.
#[derive(Debug, Clone, Copy)]
pub struct Cascade {
    pub fitted: FittedBox,
    pub near: f64,
    pub far: f64,
}

/// How cascades are cut and fitted (the shadow settings' cascade fields).
#[derive(Debug, Clone, Copy)]
pub struct CascadeSpec {
    pub count: u32,
    pub lambda: f32,
    /// The fraction of each cascade's range that fades into the next: the next cascade's
    /// box starts that far before its split, so the fade reads inside it.
    pub blend: f32,
    /// Where shadows end (the camera's far plane when that is nearer).
    pub far: f32,
    pub map_size: u32,
    /// Move boxes in whole texels.
    pub snap: bool,
    /// The depth range (far - near) of the light's own ortho box: each cascade's depth
    /// range is at least this (see [`depth_reach`]).
    pub light_depth: f32,
}

impl CascadeSpec {
    /// The cascade fields of the shadow settings (`shadow_distance = 0`: as far as the
    /// scene reaches) for a light whose ortho box is `light_depth` deep.
    pub fn of(s: &ShadowSettings, light_depth: f32) -> CascadeSpec {
        CascadeSpec {
            count: s.cascades,
            lambda: s.cascade_lambda,
            blend: s.cascade_blend,
            far: if s.shadow_distance > 0.0 {
                s.shadow_distance
            } else {
                f32::INFINITY
            },
            map_size: s.map_size.max_side(),
            snap: s.snap,
            light_depth,
        }
    }
}

/// The view depths (near, far) the cascades cover for `camera`: the depths of the
/// receivers' boxes (every item receives) inside the view frustum's box, within the
/// camera's near plane and `far` (at most the camera's far plane). A box
/// is cut by the frustum's box first, so a floor reaching far to the sides does not push
/// the far end out; with nothing in view, a short range at the near plane (all lit).
pub fn scene_depth_range(
    camera: &Camera,
    aspect: f64,
    boxes: &[(DVec3, DVec3)],
    far: f64,
) -> (f64, f64) {
    let near = f64::from(camera.near).max(f64::MIN_POSITIVE);
    let far = far.min(f64::from(camera.far)).max(near);
    let view = camera.view_matrix64();
    let inverse_view = view.inverse();
    let tan = (f64::from(camera.fov).to_radians() * 0.5).tan();
    let frustum = aabb((0..8).map(|i| {
        let d = if i & 4 == 0 { near } else { far };
        let x = if i & 1 == 0 { -1.0 } else { 1.0 } * d * tan * aspect;
        let y = if i & 2 == 0 { -1.0 } else { 1.0 } * d * tan;
        inverse_view.transform_point3(DVec3::new(x, y, -d))
    }));
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (blo, bhi) in boxes {
        let (clo, chi) = (blo.max(frustum.0), bhi.min(frustum.1));
        if !clo.cmple(chi).all() {
            continue;
        }
        for p in corners(clo, chi) {
            let depth = -view.transform_point3(p).z;
            lo = lo.min(depth);
            hi = hi.max(depth);
        }
    }
    if hi < near || lo > far {
        return (near, near * 2.0);
    }
    // Both ends move in steps of 1/8 of their power of two (outwards, with a little room
    // past the farthest corner), so a camera that moves or turns a little keeps its
    // splits, and with them the boxes' sizes: snapped cascades then do not shimmer.
    let step = |d: f64| 2f64.powf(d.abs().max(f64::MIN_POSITIVE).log2().floor()) / 8.0;
    let lo = lo.clamp(near, far);
    let lo = ((lo / step(lo)).floor() * step(lo)).max(near);
    let hi = hi * (1.0 + 1e-3);
    let hi = ((hi / step(hi)).ceil() * step(hi)).min(far);
    (lo, hi.max(lo * (1.0 + 1e-3)).max(lo + 1e-6))
}

/// The cascades of a light shining from `to_light` for the scene's fitting camera (the
/// viewer, or `fit_camera`), one `map_size` layer each. `boxes` are the items' world boxes
/// ([`crate::shadows::camera::fitted::item_world_boxes`]; the depth pass culls with them too).
pub fn fit_cascades(
    scene: &Scene,
    boxes: &[(DVec3, DVec3)],
    to_light: Vec3,
    spec: &CascadeSpec,
) -> Vec<Cascade> {
    let CascadeSpec {
        count,
        lambda,
        blend,
        far,
        map_size,
        snap,
        light_depth,
    } = *spec;
    let camera = scene.fitting_camera();
    let aspect = f64::from(scene.size[0].max(1)) / f64::from(scene.size[1].max(1));
    // A shadow distance is taken as given; without one, the scene says how far.
    let (near, far) = match far.is_finite() {
        true => (f64::from(camera.near), f64::from(far.min(camera.far))),
        false => scene_depth_range(camera, aspect, boxes, f64::from(camera.far)),
    };
    let splits = practical_splits(near, far, count, f64::from(lambda));
    let basis = light_basis(to_light.as_dvec3());
    // The casters' boxes in light space (z points at the light).
    let casters: Vec<(DVec3, DVec3)> = scene
        .items
        .iter()
        .zip(boxes)
        .filter(|(i, _)| i.casts_shadows)
        .map(|(_, (lo, hi))| aabb(corners(*lo, *hi).map(|p| basis.transpose() * p).into_iter()))
        .collect();
    let light = LightSpace {
        basis,
        casters: &casters,
        depth: f64::from(light_depth),
    };
    splits
        .windows(2)
        .enumerate()
        .map(|(c, w)| {
            let (near, far) = (w[0], w[1]);
            // From where the previous cascade starts fading into this one.
            let from = match c {
                0 => near,
                _ => near - f64::from(blend) * (near - splits[c - 1]),
            };
            let fitted = fit_slice(camera, aspect, from, far, &light, map_size, snap);
            Cascade { fitted, near, far }
        })
        .collect()
}

/// The light's side of a fit: its basis, the casters' light-space boxes and its own box's
/// depth range.
struct LightSpace<'a> {
    basis: glam::DMat3,
    casters: &'a [(DVec3, DVec3)],
    depth: f64,
}

/// How far a cascade's box reaches towards the light from its centre `c` (light space, the
/// box `radius` across each way), so that its depth range is `reach + radius`.
///
/// A depth-unit bias (`bias`, the slope bias, polygon offset units) is a fraction of the
/// depth range, so it means `bias * range` world units. The one map's range is the light's
/// own ortho box (`far - near`: 21 units in the DummyGame, so the book's 0.05 is 1.05 units);
/// a cascade's range depends on its slice and on the casters. Each cascade therefore
/// reaches to the highest caster over its footprint (only those can shadow it along
/// parallel rays), and when that is shallower than the light's box it is deepened to the
/// box's depth, so the bias means the same world distance in every cascade as with one
/// map. A cascade whose casters need more depth keeps what it needs (its bias grows, as the
/// one map's would in a deeper box). Deepening rather than a bias per cascade keeps the
/// shader's bias a literal, shared with the other maps.
fn depth_reach(c: DVec3, radius: f64, light: &LightSpace) -> f64 {
    let top = light
        .casters
        .iter()
        .filter(|(lo, hi)| {
            lo.x <= c.x + radius
                && hi.x >= c.x - radius
                && lo.y <= c.y + radius
                && hi.y >= c.y - radius
        })
        .map(|(_, hi)| hi.z)
        .fold(f64::NEG_INFINITY, f64::max);
    (top - c.z).max(radius).max(light.depth - radius)
}

fn fit_slice(
    camera: &Camera,
    aspect: f64,
    near: f64,
    far: f64,
    light: &LightSpace,
    map_size: u32,
    snap: bool,
) -> FittedBox {
    let basis = light.basis;
    let tan = (f64::from(camera.fov).to_radians() * 0.5).tan();
    let k = tan * (1.0 + aspect * aspect).sqrt();
    let (z, radius) = slice_sphere(near, far, k);
    let inverse_view = camera.view_matrix64().inverse();
    let centre = inverse_view.transform_point3(DVec3::new(0.0, 0.0, -z));
    let texel = 2.0 * radius / f64::from(map_size);
    // The centre in light space, its x and y rounded to whole texels.
    let mut c = basis.transpose() * centre;
    if snap {
        c.x = (c.x / texel).round() * texel;
        c.y = (c.y / texel).round() * texel;
    }
    // The box reaches from the sphere's back to the highest caster over it, so everything
    // that can shadow the slice is drawn into the cascade.
    let reach = depth_reach(c, radius, light);
    let eye = basis * c;
    FittedBox {
        view: light_view(eye, basis),
        bounds: [-radius, radius, -radius, radius, -reach, radius],
        texel,
    }
}

impl Cascade {
    /// Whether an item with world box `(lo, hi)` can land in this cascade's map: seen from
    /// the light, its box overlaps the cascade's across and reaches in front of its far
    /// plane. The depth pass draws only those (the near cascades hold few casters).
    pub fn may_hold(&self, lo: DVec3, hi: DVec3) -> bool {
        let view = self.fitted.view;
        let (l, h) = aabb(
            corners(lo, hi)
                .into_iter()
                .map(|c| view.transform_point3(c)),
        );
        let [left, right, bottom, top, _near, far] = self.fitted.bounds;
        // View space looks down -z: depth is -z.
        l.x <= right && h.x >= left && l.y <= top && h.y >= bottom && -h.z <= far
    }
}

/// Its sampler in the scene shader, per light.
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["cascadeMap0", "cascadeMap1", "cascadeMap2", "cascadeMap3"];

/// Its part of the generated snippets (one light has cascades): shaders/lib/shadow_cascades.glsl
/// and its `calcShadowCascades` call.
/// Light `i`'s part of the scene program: the layered lookup of shadow_layers.glsl.
pub fn glsl(i: usize, _p: usize, test: &super::ShadowTest) -> Option<super::LightGlsl> {
    layers::glsl(&SNIPPET, i, test)
}

pub const SNIPPET: layers::Snippet = layers::Snippet {
    files: &["lib/shadow_cascades.glsl"],
    function: "calcShadowCascades",
    takes_fragment: true,
    samplers: SAMPLERS,
};

/// The cascades' row of the kind table.
pub const KIND: KindFacts = KindFacts {
    technique: Some(TechniqueFacts {
        create: |gl, s| Ok(Box::new(layers::Layered::<Cascades>::new(gl, s)?)),
        glsl,
        samplers: &SAMPLERS,
        map_slot: false,
    }),
    words: |s| {
        let (size, depth) = (kind::sides(s.map_size), kind::depth_words(s.depth_format));
        format!("Shadow: {} cascades of {size}, {depth}", s.cascades)
    },
    storage: layers::storage::<Cascades>,
    // Fitted to the view's slices each frame.
    follows_camera: |_, _| true,
    layers: Some(|s| LayerLayout {
        count: s.cascades,
        blend_bits: s.cascade_blend.to_bits(),
        show: s.show_cascades,
    }),
    // A layered light's test reads per pixel.
    per_vertex: |_| false,
    family: |_| Family::Cascades,
    idle: IdleRules {
        no_map: None,
        depth_lookup: |_| Some(kind::LAYERS_READ_NEAREST),
        light: layers::idle_for_light::<Cascades>,
        scene: layers::idle_in_scene::<Cascades>,
    },
};

/// Cascades as a [`Layout`]: a layer per slice of the view, fitted each depth pass.
#[derive(Default)]
pub struct Cascades {
    cascades: Vec<Cascade>,
}

impl Layout for Cascades {
    const KIND: ShadowKind = ShadowKind::Cascades;
    const SETTING: &'static str = "cascades";
    const NAME: &'static str = "cascades";

    fn count(s: &ShadowSettings) -> u32 {
        s.cascades
    }

    /// The slices' boxes; the box reaches the casters over it.
    fn fit(&mut self, pass: &DepthPass, scene: &Scene, l: &DirectionalLight) -> Vec<FittedBox> {
        let spec = CascadeSpec::of(pass.settings, l.ortho.far - l.ortho.near);
        self.cascades = fit_cascades(scene, pass.boxes, l.direction, &spec);
        self.cascades.iter().map(|c| c.fitted).collect()
    }

    /// The casters that can land in the cascade.
    fn keeps(&self, layer: usize, _: usize, (lo, hi): &(DVec3, DVec3)) -> bool {
        self.cascades[layer].may_hold(*lo, *hi)
    }

    /// Counted per cascade: a caster in two cascades is two of those offered.
    fn offered(&self, scene: &Scene) -> u64 {
        casters(scene) * self.cascades.len() as u64
    }

    /// The split depths (`cascadeSplit`).
    fn set_uniforms(&self, p: &ShaderProgram) {
        let mut splits: Vec<f32> = self.cascades.iter().map(|c| c.near as f32).collect();
        splits.extend(self.cascades.last().map(|c| c.far as f32));
        p.set_f32_array("cascadeSplit", &splits);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sphere_holds_every_corner_of_its_slice() {
        for (a, b, k) in [
            (0.1, 1.0, 0.7),
            (1.0, 1.5, 0.7),
            (0.001, 1e4, 2.0),
            (5.0, 6.0, 0.1),
        ] {
            let (z, r) = slice_sphere(a, b, k);
            for (d, h) in [(a, a * k), (b, b * k)] {
                let dist = ((d - z).powi(2) + h * h).sqrt();
                assert!(
                    dist <= r * (1.0 + 1e-12),
                    "corner at {d} outside ({dist} > {r})"
                );
            }
        }
    }

    #[test]
    fn splits_interpolate_between_uniform_and_log() {
        let u = practical_splits(1.0, 100.0, 4, 0.0);
        let l = practical_splits(1.0, 100.0, 4, 1.0);
        assert!((u[2] - 50.5).abs() < 1e-9, "{u:?}");
        assert!((l[2] - 10.0).abs() < 1e-9, "{l:?}");
    }
}
