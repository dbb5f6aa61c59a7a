//! Timing and scoring each configuration: the shared reference, blocks of frames against
//! frames without shadows, the quieter block kept.

use std::time::Instant;

use super::super::compare::{compute_reference, CompareOptions, Reference};
use super::super::reference::{Metrics, SoftMetrics};
use super::super::timing::GpuPassTimes;
use super::noise::{overhead_spread, per_frame};
use super::{mark_pareto, ms, time_passes, BenchConfig, BenchOptions, BenchRow, Stat, Timings};
use crate::engine::{Gl, Outputs, RenderTarget};
use crate::error::Result;
use crate::renderer::{Renderer, Target};
use crate::scene::Scene;
use crate::settings::ShadowSettings;

/// The reference for the benchmark's view (traced once, shared by every configuration).
pub fn bench_reference(
    gl: &Gl,
    scene: &Scene,
    base: &ShadowSettings,
    opts: &BenchOptions,
) -> Result<Reference> {
    compute_reference(
        gl,
        scene,
        base,
        &CompareOptions {
            rays: opts.rays,
            width: opts.width,
            height: opts.height,
            supersample: opts.supersample,
            band: opts.band,
            light: 0,
        },
    )
}

/// Where [`run`] is, after each of its 2 x `configs.len()` blocks (so that a progress bar
/// can count, and estimate, both passes, and name the phase and the configuration).
pub enum Progress<'a> {
    /// A block of the first pass timed (its first frames compiled the shaders).
    Timed(&'a BenchConfig),
    /// A block of the second pass timed and the frame scored: the finished row.
    Scored(&'a BenchRow),
}

impl Progress<'_> {
    /// The progress line after a block, naming the phase and the configuration.
    pub fn line(&self) -> String {
        match self {
            Progress::Timed(config) => {
                format!("pass 1 of 2, compiling and timing: {}", config.label())
            }
            Progress::Scored(row) => format!(
                "pass 2 of 2, timing and scoring against the reference: {}: {:.2} ms, overhead \
                 {} ms, {} {:.3}% (taps / passes / map MiB: {})",
                row.label(),
                row.wall_ms.median,
                row.overhead_text(),
                row.error_name(),
                row.error() * 100.0,
                row.cost_label()
            ),
        }
    }
}

/// Times and scores every configuration; `progress` is told after each block.
pub fn run(
    gl: &Gl,
    scene: &Scene,
    configs: &[BenchConfig],
    reference: &Reference,
    opts: &BenchOptions,
    mut progress: impl FnMut(Progress<'_>),
) -> Result<Vec<BenchRow>> {
    let Some(first) = configs.first() else {
        return Ok(Vec::new());
    };
    let mut renderer = Renderer::new(gl, scene, &uncached(&first.settings))?;
    // The same frame without shadows, for each configuration's overhead.
    let mut plain = Renderer::new(
        gl,
        scene,
        &ShadowSettings {
            shadows: false,
            ..uncached(&first.settings)
        },
    )?;
    let timer = std::rc::Rc::new(GpuPassTimes::new(gl)?);
    renderer.set_hooks(timer.clone());
    plain.set_hooks(timer.clone());
    let target = RenderTarget::new(gl, opts.width, opts.height, Outputs::default())?;
    let scored = RenderTarget::new(
        gl,
        opts.width,
        opts.height,
        Outputs {
            visibility: true,
            gbuffer: false,
        },
    )?;
    // A second of untimed frames first: the driver and the CPU settle before anything counts.
    let settle = Instant::now();
    while settle.elapsed().as_secs_f64() < 1.0 {
        renderer.render(scene, Target::Offscreen(&target))?;
        renderer.finish();
    }
    // Two passes over the sweep, the second in reverse order, `frames` frames each: a burst
    // of load from elsewhere on the machine then spoils at most one block per
    // configuration, and each configuration keeps its quieter block (the lower median).
    let mut best: Vec<Option<Timings>> = (0..configs.len()).map(|_| None).collect();
    let mut rows: Vec<Option<BenchRow>> = (0..configs.len()).map(|_| None).collect();
    let order: Vec<usize> = (0..configs.len()).chain((0..configs.len()).rev()).collect();
    for &i in &order {
        let config = &configs[i];
        renderer.set_settings(&uncached(&config.settings))?;
        let t = time_block(&mut renderer, &mut plain, scene, &target, &timer, opts)?;
        let Some(first) = best[i].take() else {
            best[i] = Some(t);
            progress(Progress::Timed(config));
            continue;
        };
        let (quieter, other) = match Stat::of(&first.wall).median <= Stat::of(&t.wall).median {
            true => (first, t),
            false => (t, first),
        };
        // Second pass: score the frame and finish the row.
        renderer.render(scene, Target::Offscreen(&scored))?;
        let visibility = scored.read_visibility()?;
        let metrics = reference.score(&visibility, opts.band);
        let mut row = timed_row(config, &quieter, metrics, reference.score_soft(&visibility));
        row.overhead_spread_ms = overhead_spread(
            &per_frame(&quieter.wall, &quieter.plain),
            &per_frame(&other.wall, &other.plain),
        );
        row.transmittance = reference.score_transmittance(&visibility);
        progress(Progress::Scored(&row));
        rows[i] = Some(row);
    }
    let mut rows: Vec<BenchRow> = rows.into_iter().flatten().collect();
    mark_pareto(&mut rows);
    Ok(rows)
}

/// The bench measures the cost of drawing each map, so no map is reused from the cache.
fn uncached(s: &ShadowSettings) -> ShadowSettings {
    ShadowSettings {
        shadow_cache: false,
        ..*s
    }
}

/// One block of timed frames of `renderer` (after its warm-up frames), each paired with a
/// frame of `plain` drawn just before it: load from elsewhere on the machine that lasts
/// longer than a frame falls on both and cancels in their difference.
fn time_block(
    renderer: &mut Renderer,
    plain: &mut Renderer,
    scene: &Scene,
    target: &RenderTarget,
    timer: &GpuPassTimes,
    opts: &BenchOptions,
) -> Result<Timings> {
    for _ in 0..opts.warmup {
        renderer.render(scene, Target::Offscreen(target))?;
    }
    renderer.finish();
    let mut t = Timings::default();
    for _ in 0..opts.frames.max(1) {
        let start = Instant::now();
        plain.render(scene, Target::Offscreen(target))?;
        plain.finish();
        t.plain.push(ms(start.elapsed()));
        t.plain_gpu.push(timer.read_ms().iter().sum());
        time_passes(renderer, scene, target, timer, 1, &mut t)?;
    }
    Ok(t)
}

/// A configuration's row from its quieter block of timings and its scores.
fn timed_row(
    config: &BenchConfig,
    quieter: &Timings,
    metrics: Metrics,
    soft: SoftMetrics,
) -> BenchRow {
    BenchRow {
        config: config.clone(),
        wall_ms: Stat::of(&quieter.wall),
        overhead_ms: Stat::of(&per_frame(&quieter.wall, &quieter.plain)).median,
        // Set from both blocks by the caller.
        overhead_spread_ms: f64::NAN,
        overhead_gpu_ms: Stat::of(
            &(quieter.depth_gpu.iter().zip(&quieter.scene_gpu))
                .zip(&quieter.plain_gpu)
                .map(|((d, s), p)| d + s - p)
                .collect::<Vec<_>>(),
        )
        .median,
        depth_wall_ms: Stat::of(&quieter.depth_wall),
        scene_wall_ms: Stat::of(&quieter.scene_wall),
        depth_gpu_ms: Stat::of(&quieter.depth_gpu),
        scene_gpu_ms: Stat::of(&quieter.scene_gpu),
        volume_pixels: Stat::of(&quieter.volume_pixels).median.max(0.0) as u64,
        metrics,
        soft,
        transmittance: None,
        pareto: false,
        flicker_energy: None,
        false_flicker: None,
    }
}
