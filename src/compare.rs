//! Measuring a shadow map against the truth: render a frame with its G-buffer, trace the
//! exact hard-shadow visibility of every pixel on the CPU ([`crate::reference`]), and score
//! the shadow test's answer ([`crate::reference::metrics`]).

use std::time::Instant;

use crate::engine::{Gl, Outputs};
use crate::error::{Error, Result};
use crate::frame::{render_frames, Frame};
use crate::reference::{
    compute_metrics, reference_visibility, reference_visibility_supersampled, Bvh, GBuffer,
    LightKind, Metrics, RefPixel, Triangle,
};
use crate::scene::Scene;
use crate::settings::ShadowSettings;

/// How a comparison is made.
#[derive(Debug, Clone, Copy)]
pub struct CompareOptions {
    pub width: u32,
    pub height: u32,
    /// Sub-pixel rays per side for the supersampled reference (0 or 1 = none).
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    pub band: usize,
}

/// The exact visibility of a view of a scene; independent of the shadow settings, so one
/// reference scores many configurations.
pub struct Reference {
    pub width: u32,
    pub height: u32,
    pub gbuffer: GBuffer,
    pub hard: Vec<RefPixel>,
    pub supersampled: Option<Vec<RefPixel>>,
    /// CPU time to build the BVH and trace both references.
    pub trace_ms: f64,
    pub triangles: usize,
}

/// The light as the reference sees it: what the shadow map approximates (parallel rays for
/// an orthographic map, rays to the light's eye for a perspective one).
pub fn light_kind(scene: &Scene, settings: &ShadowSettings) -> LightKind {
    scene.light.shadow_view(settings).reference
}

/// A BVH over the scene's shadow casters, in world space.
pub fn caster_bvh(scene: &Scene) -> Bvh {
    let triangles = scene
        .world_triangles()
        .into_iter()
        .map(|[a, b, c]| Triangle { a, b, c })
        .collect();
    Bvh::build(triangles)
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
    let gbuffer = gbuffer_of(&frame)?;
    let n = opts.supersample;
    let hi = if n > 1 {
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
    let bvh = caster_bvh(scene);
    let light = light_kind(scene, settings);
    let hard = reference_visibility(&bvh, &light, &gbuffer);
    let supersampled = hi
        .as_ref()
        .map(|hi| reference_visibility_supersampled(&bvh, &light, hi, n as usize));
    Ok(Reference {
        width: opts.width,
        height: opts.height,
        gbuffer,
        hard,
        supersampled,
        trace_ms: start.elapsed().as_secs_f64() * 1000.0,
        triangles: bvh.triangle_count(),
    })
}

fn gbuffer_of(frame: &Frame) -> Result<GBuffer> {
    match (&frame.positions, &frame.normals) {
        (Some(p), Some(n)) => Ok(GBuffer {
            width: frame.width as usize,
            height: frame.height as usize,
            positions: p.clone(),
            normals: n.clone(),
        }),
        _ => Err(Error::Invalid("the frame has no G-buffer".into())),
    }
}

impl Reference {
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

/// A rendered frame, its reference and its scores.
pub struct Comparison {
    pub frame: Frame,
    pub reference: Reference,
    pub metrics: Metrics,
}

/// Renders `scene` with `settings`, traces the reference and scores the frame.
pub fn compare(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    opts: &CompareOptions,
) -> Result<Comparison> {
    let reference = compute_reference(gl, scene, settings, opts)?;
    let frame = render_visibility(gl, scene, settings, opts.width, opts.height)?;
    let visibility = frame.visibility.as_deref().unwrap_or_default();
    let metrics = reference.score(visibility, opts.band);
    Ok(Comparison {
        frame,
        reference,
        metrics,
    })
}

/// One frame with the visibility and G-buffer outputs.
pub fn render_visibility(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    width: u32,
    height: u32,
) -> Result<Frame> {
    let outputs = Outputs {
        visibility: true,
        gbuffer: true,
    };
    render_frames(gl, &mut scene.clone(), settings, width, height, 1, outputs)
}
