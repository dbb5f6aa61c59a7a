//! Measuring a shadow map against the truth: render a frame with its G-buffer, trace the
//! exact hard-shadow visibility of every pixel on the CPU ([`crate::reference`]) (and, for a
//! light with a size, its soft visibility: [`crate::reference::area`]), and score the
//! shadow test's answer ([`crate::reference::metrics`]).

use std::time::Instant;

use glam::{DMat4, DVec3};

use super::frame::{render_frames, render_frames_of_light, Frame};
use super::reference::{
    area_visibility, compute_metrics, compute_soft_metrics, face_normals, reference_transmittance,
    reference_visibility, reference_visibility_supersampled, score_transmittance, Bvh, GBuffer,
    LightExtent, LightKind, Metrics, RefPixel, SoftMetrics, Translucent, TransmittanceMetrics,
    Triangle,
};
use crate::engine::{Gl, Outputs};
use crate::error::{Error, Result};
use crate::scene::{GameItem, Light, Scene, Shading};
use crate::settings::ShadowSettings;
use crate::shadows::plan::ShadowPlan;
use crate::shadows::Rays;

/// How a comparison is made.
#[derive(Debug, Clone, Copy)]
pub struct CompareOptions {
    pub width: u32,
    pub height: u32,
    /// Sub-pixel rays per side for the supersampled reference (0 or 1 = none).
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    pub band: usize,
    /// The light measured (its shadow test against its exact visibility); scenes with
    /// several lights are measured one light at a time.
    pub light: usize,
    /// Rays per pixel to a light with a size (the soft-shadow truth, [`AreaTruth`]).
    pub rays: u32,
}

/// The soft-shadow truth's rays per pixel unless told otherwise (`--rays`).
pub const AREA_RAYS: u32 = 64;

/// The truth for a light with a size: `rays` stratified rays per pixel to its disc.
pub struct AreaTruth {
    pub pixels: Vec<RefPixel>,
    pub rays: usize,
    pub extent: LightExtent,
}

/// The exact visibility of a view of a scene; independent of the shadow settings, so one
/// reference scores many configurations.
pub struct Reference {
    pub width: u32,
    pub height: u32,
    pub gbuffer: GBuffer,
    pub hard: Vec<RefPixel>,
    pub supersampled: Option<Vec<RefPixel>>,
    /// With a light of non-zero size, the soft truth ([`crate::reference::area`]); the
    /// figures above stay the hard ones of a point at its centre.
    pub area: Option<AreaTruth>,
    /// With translucent casters, the light each receiver gets: 0 behind an opaque caster,
    /// else the product of (1 - opacity) over the translucent crossings
    /// ([`crate::reference::transmittance`]).
    pub transmittance: Option<Vec<RefPixel>>,
    /// CPU time to build the BVH and trace the references.
    pub trace_ms: f64,
    pub triangles: usize,
    /// The G-buffer's positions and the traced triangles are relative to this point (the
    /// camera), so the reference keeps its precision far from the world's origin.
    pub origin: DVec3,
}

/// The light as the reference sees it, relative to `origin`: what the shadow map
/// approximates (parallel rays for an orthographic map, rays to the light's eye for a
/// perspective one).
pub fn light_kind(
    scene: &Scene,
    index: usize,
    settings: &ShadowSettings,
    origin: DVec3,
) -> LightKind {
    let cone = scene.lights.get(index).and_then(|l| match l.shading() {
        Shading::Position { cone, .. } => cone,
        Shading::Direction(_) => None,
    });
    let rays = crate::shadows::light_camera(scene, index, settings).rays;
    match (rays, cone) {
        (Rays::FromPoint { position }, None) => LightKind::Point {
            position: (position.as_dvec3() - origin).as_vec3(),
        },
        (Rays::FromPoint { position }, Some((cos, axis))) => LightKind::Spot {
            position: (position.as_dvec3() - origin).as_vec3(),
            axis,
            cos_full: cos + CONE_RIM,
        },
        (Rays::Parallel { to_light }, _) => LightKind::Directional { to_light },
    }
}

/// The extent of light `index` as the soft reference samples it, under `settings`, or
/// `None` for a light of size 0 (a point: the hard reference is the truth). A directional
/// light traced with parallel rays is a cone of its angular diameter; traced from its
/// shadow position (a perspective map), a disc that subtends the same angle from the
/// origin; a spot or point light a sphere of its radius.
pub fn light_extent(scene: &Scene, index: usize, settings: &ShadowSettings) -> Option<LightExtent> {
    let light = scene.lights.get(index)?;
    let size = light.size();
    if size <= 0.0 {
        return None;
    }
    let tan_half = (size.to_radians() * 0.5).tan();
    let rays = crate::shadows::light_camera(scene, index, settings).rays;
    Some(match (light, rays) {
        (Light::Directional(_), Rays::Parallel { .. }) => LightExtent::Cone { tan_half },
        (Light::Directional(l), Rays::FromPoint { .. }) => LightExtent::Sphere {
            radius: l.shadow_pos_mult.abs() * tan_half,
        },
        (Light::Spot(_) | Light::Point(_), _) => LightExtent::Sphere { radius: size },
    })
}

/// The width, in cosine, of a spot's soft rim: the scene shader's
/// `smoothstep(lightConeCos, lightConeCos + CONE_RIM, c)` (shaders/lib/lighting.glsl).
/// Only inside the rim is the light full, so only there are receivers scored.
pub const CONE_RIM: f32 = 0.01;

/// A BVH over every drawn triangle (casters or not), relative to `origin`: what the
/// camera's rays meet, to find the face under each G-buffer pixel.
pub fn surface_bvh(scene: &Scene, origin: DVec3) -> Bvh {
    bvh_of(scene, origin, |_| true)
}

/// A BVH over the scene's shadow casters, in world space minus `origin` (computed in double
/// precision).
pub fn caster_bvh(scene: &Scene, origin: DVec3) -> Bvh {
    bvh_of(scene, origin, |i| i.casts_shadows)
}

fn bvh_of(scene: &Scene, origin: DVec3, keep: impl Fn(&GameItem) -> bool) -> Bvh {
    let mut triangles = Vec::new();
    for item in scene.items.iter().filter(|i| keep(i)) {
        triangles.extend(triangles_of(scene, item, origin));
    }
    Bvh::build(triangles)
}

/// An item's triangles in world space minus `origin` (composed in double precision).
fn triangles_of<'a>(
    scene: &'a Scene,
    item: &GameItem,
    origin: DVec3,
) -> impl Iterator<Item = Triangle> + 'a {
    let m = DMat4::from_translation(-origin) * item.model_matrix64();
    scene.meshes[item.mesh].triangles().map(move |t| {
        let [a, b, c] = t.map(|p| m.transform_point3(p.as_dvec3()).as_vec3());
        Triangle { a, b, c }
    })
}

/// The translucent casters, each its opacity and triangles, relative to `origin`.
pub fn translucent_casters(scene: &Scene, origin: DVec3) -> Translucent {
    let items = crate::shadows::volumetric::translucent_casters(scene);
    Translucent::new(items.map(|(_, i)| (i.opacity, triangles_of(scene, i, origin).collect())))
}

/// Renders the view's G-buffer (and, with supersampling, one at N times the resolution) and
/// traces the exact visibility of every pixel.
pub fn compute_reference(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    opts: &CompareOptions,
) -> Result<Reference> {
    let gbuffer_only = Outputs {
        visibility: false,
        gbuffer: true,
    };
    // The G-buffer does not depend on the shadow settings; draw the scene, not the map.
    let settings = &ShadowSettings {
        show_depth_map: false,
        ..*settings
    };
    let frame = render_frames(
        gl,
        &mut scene.clone(),
        settings,
        opts.width,
        opts.height,
        1,
        gbuffer_only,
    )?;
    let mut gbuffer = gbuffer_of(&frame)?;
    let n = opts.supersample;
    let mut hi = if n > 1 {
        let frame = render_frames(
            gl,
            &mut scene.clone(),
            settings,
            opts.width * n,
            opts.height * n,
            1,
            gbuffer_only,
        )
        .map_err(|e| Error::Invalid(format!("supersampled G-buffer at {n}x{n}: {e}")))?;
        Some(gbuffer_of(&frame)?)
    } else {
        None
    };
    let start = Instant::now();
    let origin = frame.origin;
    let bvh = caster_bvh(scene, origin);
    // Receivers are judged by the face under each pixel too (see `GBuffer::face_normals`).
    let all_cast = scene.items.iter().all(|i| i.casts_shadows);
    let surfaces = (!all_cast).then(|| surface_bvh(scene, origin));
    let surfaces = surfaces.as_ref().unwrap_or(&bvh);
    let eye = (scene.camera.position.as_dvec3() - origin).as_vec3();
    gbuffer.face_normals = face_normals(surfaces, &gbuffer, eye);
    if let Some(hi) = hi.as_mut() {
        hi.face_normals = face_normals(surfaces, hi, eye);
    }
    check_light(scene, opts.light, "light", true)?;
    // The rays of the light's own map: its own table over the scene's settings.
    let own = ShadowPlan::decide(&scene.lights, settings).lights[opts.light].settings;
    let light = light_kind(scene, opts.light, &own, origin);
    let hard = reference_visibility(&bvh, &light, &gbuffer);
    let supersampled = hi
        .as_ref()
        .map(|hi| reference_visibility_supersampled(&bvh, &light, hi, n as usize));
    let translucent = translucent_casters(scene, origin);
    let transmittance = (!translucent.is_empty())
        .then(|| reference_transmittance(&hard, &translucent, &light, &gbuffer));
    let area = light_extent(scene, opts.light, &own).map(|extent| {
        let rays = opts.rays.max(1) as usize;
        AreaTruth {
            pixels: area_visibility(&bvh, &light, extent, &gbuffer, rays),
            rays,
            extent,
        }
    });
    Ok(Reference {
        width: opts.width,
        height: opts.height,
        gbuffer,
        hard,
        supersampled,
        area,
        transmittance,
        trace_ms: start.elapsed().as_secs_f64() * 1000.0,
        triangles: bvh.triangle_count(),
        origin,
    })
}

fn gbuffer_of(frame: &Frame) -> Result<GBuffer> {
    match (&frame.positions, &frame.normals) {
        (Some(p), Some(n)) => Ok(GBuffer {
            width: frame.width as usize,
            height: frame.height as usize,
            positions: p.clone(),
            normals: n.clone(),
            face_normals: Vec::new(),
        }),
        _ => Err(Error::Invalid("the frame has no G-buffer".into())),
    }
}

impl Reference {
    /// The absolute world position of pixel `i` (NaN where no geometry).
    pub fn world_position(&self, i: usize) -> DVec3 {
        let p = self.gbuffer.positions[i];
        DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) + self.origin
    }

    /// Scores a rendered visibility image against the soft truth, when the light has a
    /// size.
    pub fn score_area(&self, rendered: &[Option<f32>]) -> Option<SoftMetrics> {
        self.area.as_ref().map(|a| {
            compute_soft_metrics(
                self.width as usize,
                self.height as usize,
                rendered,
                &a.pixels,
                a.rays,
            )
        })
    }

    /// [`Reference::score_area`], or for a light of no size the same figures against the
    /// hard reference (its truth; `rays` 0).
    pub fn score_soft(&self, rendered: &[Option<f32>]) -> SoftMetrics {
        self.score_area(rendered).unwrap_or_else(|| {
            compute_soft_metrics(
                self.width as usize,
                self.height as usize,
                rendered,
                &self.hard,
                0,
            )
        })
    }

    /// Scores a rendered visibility image against the transmittance truth, when the scene
    /// has translucent casters.
    pub fn score_transmittance(&self, rendered: &[Option<f32>]) -> Option<TransmittanceMetrics> {
        (self.transmittance.as_ref()).map(|truth| score_transmittance(rendered, truth))
    }

    /// Scores a rendered visibility image against this reference.
    pub fn score(&self, rendered: &[Option<f32>], band: usize) -> Metrics {
        compute_metrics(
            self.width as usize,
            self.height as usize,
            rendered,
            &self.hard,
            self.supersampled.as_deref(),
            band,
        )
    }
}

impl Reference {
    /// This reference with the stencil shadow volumes' answer as its truth (`compare
    /// --truth volumes`): a receiver here that the volumes' frame covers keeps being one,
    /// with the volumes' visibility; the supersampled reference and the area truth (the
    /// volumes are hard shadows) are dropped.
    pub fn with_volumes_truth(&self, volumes: &[Option<f32>]) -> Reference {
        let hard = self
            .hard
            .iter()
            .enumerate()
            .map(|(i, r)| match volumes.get(i).copied().flatten() {
                Some(v) if v.is_finite() => RefPixel {
                    covered: true,
                    receiver: r.receiver,
                    visibility: if v >= 0.5 { 1.0 } else { 0.0 },
                },
                _ => RefPixel {
                    receiver: false,
                    ..*r
                },
            })
            .collect();
        Reference {
            width: self.width,
            height: self.height,
            gbuffer: self.gbuffer.clone(),
            hard,
            supersampled: None,
            area: None,
            transmittance: None,
            trace_ms: self.trace_ms,
            triangles: self.triangles,
            origin: self.origin,
        }
    }
}

/// A rendered frame, its reference and its scores.
pub struct Comparison {
    pub frame: Frame,
    pub reference: Reference,
    pub metrics: Metrics,
    /// Against the soft truth, for a light with a size.
    pub area: Option<SoftMetrics>,
    /// Against the transmittance truth, for a scene with translucent casters.
    pub transmittance: Option<TransmittanceMetrics>,
}

/// Renders `scene` with `settings`, traces the reference and scores the frame.
pub fn compare(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    opts: &CompareOptions,
) -> Result<Comparison> {
    let reference = compute_reference(gl, scene, settings, opts)?;
    let frame = render_visibility(gl, scene, settings, opts.width, opts.height, opts.light)?;
    let visibility = frame.visibility.as_deref().unwrap_or_default();
    let metrics = reference.score(visibility, opts.band);
    let area = reference.score_area(visibility);
    let transmittance = reference.score_transmittance(visibility);
    Ok(Comparison {
        frame,
        reference,
        metrics,
        area,
        transmittance,
    })
}

/// One frame with the visibility (of light `light`'s shadow test) and G-buffer outputs.
pub fn render_visibility(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    width: u32,
    height: u32,
    light: usize,
) -> Result<Frame> {
    check_light(scene, light, "light", true)?;
    let outputs = Outputs {
        visibility: true,
        gbuffer: true,
    };
    render_frames_of_light(
        gl,
        &mut scene.clone(),
        settings,
        width,
        height,
        1,
        outputs,
        light,
    )
}

/// The measured light must exist and, when `casting`, cast shadows: a light that does not
/// cast has nothing to measure, and one past the end is a user's typo. `name` is how the
/// caller's user names the number (`--light` on the command line).
pub fn check_light(scene: &Scene, light: usize, name: &str, casting: bool) -> Result<()> {
    match scene.lights.get(light) {
        None => Err(Error::Invalid(format!(
            "{name} {light}: the scene {} has {} light(s), numbered from 0",
            scene.source.display(),
            scene.lights.len()
        ))),
        Some(l) if casting && !l.casts_shadows() => Err(Error::Invalid(format!(
            "{name} {light}: that light of {} does not cast shadows (casts_shadows = false); \
             expected a light that casts",
            scene.source.display()
        ))),
        Some(_) => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::CONE_RIM;

    #[test]
    fn the_cone_rim_is_the_shaders() {
        let shader = include_str!("../../shaders/lib/lighting.glsl");
        let rim = format!("smoothstep(lightConeCos[i], lightConeCos[i] + {CONE_RIM}, c)");
        assert!(shader.contains(&rim), "lighting.glsl no longer has {rim}");
    }
}
