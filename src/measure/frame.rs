//! Headless frames: render a scene into an offscreen target and read back what the caller
//! wants (colour, shadow-test visibility, world positions and normals, the depth map).

use std::rc::Rc;

use glam::DVec3;

use super::timing::GpuPassTimes;

use crate::engine::render_target::Outputs;
use crate::engine::{Gl, RenderTarget};
use crate::error::{Error, Result};
use crate::image_data::ImageData;
use crate::renderer::{DepthPasses, Renderer, Target};
use crate::scene::Scene;
use crate::settings::{MapSize, ShadowSettings};

/// What a headless render returns. Images are rows top to bottom.
pub struct Frame {
    pub width: u32,
    pub height: u32,
    pub colour: ImageData,
    /// Per pixel: the shadow test's visibility where geometry was drawn.
    pub visibility: Option<Vec<Option<f32>>>,
    /// World positions relative to `origin`, and world normals (NaN where no geometry).
    pub positions: Option<Vec<[f32; 3]>>,
    pub normals: Option<Vec<[f32; 3]>>,
    /// The first light's 2D shadow map: its size and depth values (rows top to bottom);
    /// `None` when that light has a cube map, cascades or no map.
    pub depth_map: Option<(MapSize, Vec<f32>)>,
    /// The light camera's near and far planes when that map is perspective (its depths
    /// are then not linear in distance); `None` for an orthographic map.
    pub depth_perspective: Option<(f32, f32)>,
    /// The greys of the depth view or inset the last frame drew, when it showed a 2D map.
    pub depth_view_range: Option<crate::renderer::DepthRange>,
    /// Whether that perspective map stores linear depth (`perspective_depth = "linear"`):
    /// shown as stored, not linearised.
    pub depth_linear: bool,
    /// Wall time of each frame in milliseconds, measured to glFinish.
    pub frame_ms: Vec<f64>,
    /// GPU time of each frame's depth passes (every map drawn, translucent ones too) and
    /// scene pass in milliseconds, from `GL_TIME_ELAPSED` queries ([`GpuPassTimes`]).
    pub gpu_ms: Vec<[f64; 2]>,
    /// The camera position the G-buffer positions are relative to.
    pub origin: DVec3,
    /// Depth passes drawn and skipped over the frames (the shadow cache).
    pub depth_passes: DepthPasses,
    /// Frames that wrote and read the cached shadow mask.
    pub mask_uses: crate::renderer::MaskUses,
    /// Translucent maps drawn and kept over the frames.
    pub volumetric_draws: crate::shadows::volumetric::cache::MapDraws,
    /// The translucent items' per-vertex light captured and kept over the frames.
    pub vertex_light: crate::renderer::VertexLightCounts,
    /// Casters drawn into maps against casters offered, over the frames.
    pub casters: crate::shadows::CasterCounts,
    /// Shadow-volume pixels that passed the depth test in the last frame (0 without
    /// volumes).
    pub volume_pixels: u64,
}

impl Frame {
    /// Absolute world positions (single precision; use `positions` + `origin` far from the
    /// world's origin).
    pub fn world_positions(&self) -> Option<Vec<[f32; 3]>> {
        let o = self.origin;
        self.positions.as_ref().map(|ps| {
            ps.iter()
                .map(|p| {
                    (DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) + o)
                        .as_vec3()
                        .to_array()
                })
                .collect()
        })
    }

    /// The visibility as an RGBA image: grey 255 lit, 0 shadowed, alpha 0 where no geometry.
    pub fn visibility_image(&self) -> Option<ImageData> {
        let vis = self.visibility.as_ref()?;
        Some(ImageData {
            width: self.width,
            height: self.height,
            rgba: visibility_rgba(vis, [0, 0, 0, 0]),
        })
    }

    /// Median and 95th percentile of the frame times after the first (warm-up) frame.
    pub fn frame_time_stats(&self) -> Option<(f64, f64)> {
        median_p95(self.frame_ms.get(1..).unwrap_or_default())
    }

    /// The GPU times after the first frame (timer queries): each pass' median and the
    /// frame's (the two passes together) median and 95th percentile.
    pub fn gpu_time_stats(&self) -> Option<GpuTimeStats> {
        let after = self.gpu_ms.get(1..).unwrap_or_default();
        let pass = |i: usize| median_p95(&after.iter().map(|t| t[i]).collect::<Vec<_>>());
        let (depth, _) = pass(0)?;
        let (scene, _) = pass(1)?;
        let frames: Vec<f64> = after.iter().map(|t| t[0] + t[1]).collect();
        let (frame, frame_p95) = median_p95(&frames)?;
        Some(GpuTimeStats {
            depth,
            scene,
            frame,
            frame_p95,
        })
    }

    /// The depth map as 8-bit grey (0 = the light's near plane, 255 = its far plane). A
    /// perspective map is linearised first, as the depth view does, or all but the surfaces
    /// next to the light would be white.
    pub fn depth_grey(&self) -> Option<(MapSize, Vec<u8>)> {
        let (size, depth) = self.depth_map.as_ref()?;
        let grey = depth
            .iter()
            .map(|&d| {
                let shown = match self.depth_perspective {
                    Some((near, far)) if !self.depth_linear => linear_depth(d, near, far),
                    _ => d,
                };
                (shown.clamp(0.0, 1.0) * 255.0).round() as u8
            })
            .collect();
        Some((*size, grey))
    }
}

/// GPU milliseconds over a run's frames after the first ([`Frame::gpu_time_stats`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuTimeStats {
    /// The depth passes' median.
    pub depth: f64,
    /// The scene pass' median.
    pub scene: f64,
    /// The median and 95th percentile of each frame's two passes together.
    pub frame: f64,
    pub frame_p95: f64,
}

/// A perspective depth in [0, 1] back to eye distance, then scaled to [0, 1] over
/// [near, far] (shaders/depth_view.frag's `linearDepth`).
pub fn linear_depth(depth: f32, near: f32, far: f32) -> f32 {
    let z = depth * 2.0 - 1.0;
    let eye = (2.0 * near * far) / (far + near - z * (far - near));
    (eye - near) / (far - near)
}

/// Visibility as greys, RGBA8: 255 lit .. 0 shadowed, `off` where no geometry was drawn
/// (`--shadow-out`: transparent; the demo's visibility view: a blue no grey can be).
pub fn visibility_rgba(visibility: &[Option<f32>], off: [u8; 4]) -> Vec<u8> {
    let mut rgba = Vec::with_capacity(visibility.len() * 4);
    for v in visibility {
        match v {
            Some(v) => {
                let g = (v * 255.0).round() as u8;
                rgba.extend_from_slice(&[g, g, g, 255]);
            }
            None => rgba.extend_from_slice(&off),
        }
    }
    rgba
}

/// Renders `frames` frames (updating the scene before each one after the first) at
/// `width` x `height` and reads the last one back.
pub fn render_frames(
    gl: &Gl,
    scene: &mut Scene,
    settings: &ShadowSettings,
    width: u32,
    height: u32,
    frames: u32,
    outputs: Outputs,
) -> Result<Frame> {
    render_frames_of_light(gl, scene, settings, width, height, frames, outputs, 0)
}

/// [`render_frames`] with the visibility output carrying light `light`'s shadow test.
#[allow(clippy::too_many_arguments)]
pub fn render_frames_of_light(
    gl: &Gl,
    scene: &mut Scene,
    settings: &ShadowSettings,
    width: u32,
    height: u32,
    frames: u32,
    outputs: Outputs,
    light: usize,
) -> Result<Frame> {
    let mut nothing = |_: &mut Renderer, _: &RenderTarget, _: &Scene, _: Option<f64>| Ok(());
    let size = (width, height);
    render_frames_with(
        gl,
        scene,
        settings,
        size,
        frames,
        outputs,
        light,
        &mut nothing,
    )
}

/// Drawn over each frame after the scene, before it is timed to its end: gets the frame's
/// renderer (its maps, for the inset), the target (to bind), the scene and the previous
/// frame's time (the HUD and inset of `render --hud --inset`).
pub type AfterScene<'a> =
    &'a mut dyn FnMut(&mut Renderer, &RenderTarget, &Scene, Option<f64>) -> Result<()>;

/// [`render_frames_of_light`] with `after_scene` drawn over every frame.
#[allow(clippy::too_many_arguments)]
pub fn render_frames_with(
    gl: &Gl,
    scene: &mut Scene,
    settings: &ShadowSettings,
    (width, height): (u32, u32),
    frames: u32,
    outputs: Outputs,
    light: usize,
    after_scene: AfterScene,
) -> Result<Frame> {
    check_frame_size(gl, width, height)?;
    // The frame's shape is the scene's from now on (a fitted light box follows it).
    scene.size = [width, height];
    let mut renderer = Renderer::new(gl, scene, settings)?;
    renderer.set_visibility_light(light);
    // Each pass' GPU time beside the wall time (read once the frame is finished, so the
    // queries wait for nothing more than glFinish did).
    let timer = Rc::new(GpuPassTimes::new(gl)?);
    renderer.set_hooks(timer.clone());
    let target = RenderTarget::new(gl, width, height, outputs)?;
    renderer.prepare_frame(scene, Target::Offscreen(&target))?;
    let mut frame_ms = Vec::with_capacity(frames as usize);
    let mut gpu_ms = Vec::with_capacity(frames as usize);
    for i in 0..frames.max(1) {
        if i > 0 {
            scene.update();
        }
        let start = std::time::Instant::now();
        renderer.render(scene, Target::Offscreen(&target))?;
        after_scene(&mut renderer, &target, scene, frame_ms.last().copied())?;
        renderer.finish();
        frame_ms.push(start.elapsed().as_secs_f64() * 1000.0);
        gpu_ms.push(timer.read_ms());
    }
    let colour = ImageData {
        width,
        height,
        rgba: target.read_colour(),
    };
    let visibility = outputs
        .visibility
        .then(|| target.read_visibility())
        .transpose()?;
    let (positions, normals) = match outputs.gbuffer {
        true => {
            let (p, n) = target.read_gbuffer()?;
            (Some(p), Some(n))
        }
        false => (None, None),
    };
    let depth_map = read_depth_map(&renderer);
    let view = renderer
        .shadow_view()
        .filter(|v| v.perspective && depth_map.is_some());
    let depth_perspective = view.map(|v| (v.near, v.far));
    let depth_linear = view.is_some_and(|v| v.linear_depth);
    crate::engine::check_gl(gl, "reading the frame back")?;
    Ok(Frame {
        width,
        height,
        colour,
        visibility,
        positions,
        normals,
        depth_map,
        depth_perspective,
        depth_view_range: renderer.depth_view_range(),
        depth_linear,
        frame_ms,
        gpu_ms,
        origin: scene.camera.position.as_dvec3(),
        depth_passes: renderer.depth_passes(),
        mask_uses: renderer.mask_uses(),
        volumetric_draws: renderer.volumetric_maps().draws(),
        vertex_light: renderer.vertex_light_counts(),
        casters: renderer.caster_counts(),
        volume_pixels: renderer.volume_pixels(),
    })
}

/// Refuses a frame the driver cannot draw: each side from 1 to its largest renderbuffer
/// and viewport.
fn check_frame_size(gl: &Gl, width: u32, height: u32) -> Result<()> {
    let limits = crate::engine::gl_limits(gl);
    let max = limits
        .max_renderbuffer_size
        .min(limits.max_viewport[0])
        .min(limits.max_viewport[1]);
    if width == 0 || height == 0 || width > max || height > max {
        return Err(Error::Invalid(format!(
            "frame size {width}x{height}: expected each side from 1 to {max} (the driver's maximum)"
        )));
    }
    Ok(())
}

/// The first light's depth map, read back with its rows top-down (GL's run bottom-up), so
/// the image shows the map with +v up.
fn read_depth_map(renderer: &Renderer) -> Option<(MapSize, Vec<f32>)> {
    renderer.shadow_map().map(|map| {
        let size = map.size();
        let mut depth = map.read_depth();
        let (row, rows) = (size.width as usize, size.height as usize);
        for y in 0..rows / 2 {
            let (a, b) = depth.split_at_mut((rows - 1 - y) * row);
            a[y * row..(y + 1) * row].swap_with_slice(&mut b[..row]);
        }
        (size, depth)
    })
}

/// Median and 95th percentile (nearest rank) of `times`; `None` when there are none.
pub fn median_p95(times: &[f64]) -> Option<(f64, f64)> {
    let mut t = times.to_vec();
    if t.is_empty() {
        return None;
    }
    t.sort_by(f64::total_cmp);
    let at = |q: f64| t[((t.len() - 1) as f64 * q).round() as usize];
    Some((at(0.5), at(0.95)))
}

#[cfg(test)]
mod tests {
    use super::linear_depth;

    #[test]
    fn linear_depth_maps_the_planes_to_the_ends() {
        let (near, far) = (1.0, 25.0);
        assert!(linear_depth(0.0, near, far).abs() < 1e-6);
        assert!((linear_depth(1.0, near, far) - 1.0).abs() < 1e-6);
        // Halfway in eye distance (13) is far past halfway in stored depth.
        let z = (far + near - 2.0 * near * far / 13.0) / (far - near);
        let stored = (z + 1.0) * 0.5;
        assert!(stored > 0.9, "{stored}");
        assert!((linear_depth(stored, near, far) - 0.5).abs() < 1e-4);
    }
}
