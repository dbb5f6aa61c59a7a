//! Our renderer on the built-in `learnopengl` scene (its own `[shadow]` settings) against
//! the baseline, LearnOpenGL's program 3.1.3 as `examples/learnopengl_3_1_3.rs` draws it
//! (the tutorial's shaders and draw calls, nothing else), in the same run:
//! both draw 800x600 frames in alternating blocks, each frame timed as wall time around
//! render + glFinish. Run with `cargo bench --bench learnopengl_baseline`;
//! `SHADOWMAP_BENCH_BLOCKS=N` changes the number of blocks per side (default 10). Two more
//! sides give the shadows' overhead: `plain` (no shadows) and `cached` (the map and every
//! pixel's tests kept while nothing moves, `shadow_cache`); ours draws its map every frame,
//! as the baseline does.
//!
//! Wall time on this machine drifts by more than the difference measured, so the frames
//! can also be counted in instructions, which do not drift: `SHADOWMAP_BENCH_ONLY=baseline`
//! (or `ours`, `cached`, `plain`) with `SHADOWMAP_BENCH_FRAMES=N` draws N frames of one side and nothing else;
//! run it under `valgrind --tool=callgrind` with `LP_NUM_THREADS=0` (llvmpipe rasterising
//! on the calling thread) for two values of N, and the difference over the difference in
//! N is the instructions per frame.

use std::time::Instant;

#[allow(dead_code)]
#[path = "../examples/learnopengl_3_1_3.rs"]
mod learnopengl;

use glam::Vec3;
use shadowmap::engine::{HeadlessContext, Outputs, RenderTarget};
use shadowmap::settings::ShadowSettings;
use shadowmap::{Renderer, Scene, Target};

const WARM_UP: usize = 20;
const BLOCK: usize = 50;
const WIDTH: u32 = 800;
const HEIGHT: u32 = 600;

fn time_block(frames: usize, mut frame: impl FnMut()) -> Vec<f64> {
    (0..frames)
        .map(|_| {
            let start = Instant::now();
            frame();
            start.elapsed().as_secs_f64() * 1000.0
        })
        .collect()
}

/// The value at quantile `q` (nearest rank) of `v`.
fn quantile(v: &[f64], q: f64) -> f64 {
    let mut v = v.to_vec();
    v.sort_by(f64::total_cmp);
    v[((v.len() - 1) as f64 * q).round() as usize]
}

fn main() -> shadowmap::Result<()> {
    let blocks: usize = match std::env::var("SHADOWMAP_BENCH_BLOCKS") {
        Ok(s) => s
            .parse()
            .ok()
            .filter(|&n| n > 0)
            .unwrap_or_else(|| panic!("SHADOWMAP_BENCH_BLOCKS={s}: expected a count >= 1")),
        Err(_) => 10,
    };
    let ctx = HeadlessContext::new()?;
    let gl = ctx.gl();
    let mut scene = Scene::load("learnopengl")?;
    for item in &mut scene.items {
        item.spin = Vec3::ZERO;
    }
    // Ours draws its map every frame, as the baseline does; `cached` reuses it (nothing
    // moves) and `plain` draws no shadows: the shadows' overhead is a frame minus `plain`.
    let settings = ShadowSettings {
        shadow_cache: false,
        ..scene.shadow
    };
    let baseline = learnopengl::ShadowMapping::new(gl)?;
    let target = RenderTarget::new(gl, WIDTH, HEIGHT, Outputs::default())?;
    let side = |s: ShadowSettings| Renderer::new(gl, &scene, &s);
    let mut renderer = side(settings)?;
    let mut cached = side(ShadowSettings {
        shadow_cache: true,
        ..settings
    })?;
    let mut plain = side(ShadowSettings {
        shadows: false,
        ..settings
    })?;
    // The first error of any side; checked after timing.
    let error = std::cell::RefCell::new(None);
    let frame_of = |r: &mut Renderer| {
        if let Err(e) = r.render(&scene, Target::Offscreen(&target)) {
            error.borrow_mut().get_or_insert(e);
        }
        r.finish();
    };
    let mut ours_frame = || frame_of(&mut renderer);
    let mut cached_frame = || frame_of(&mut cached);
    let mut plain_frame = || frame_of(&mut plain);
    let mut base_frame = || {
        baseline.render_frame();
        baseline.finish();
    };
    if let Ok(side) = std::env::var("SHADOWMAP_BENCH_ONLY") {
        let frames: usize = std::env::var("SHADOWMAP_BENCH_FRAMES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(10);
        match side.as_str() {
            "baseline" => time_block(frames, &mut base_frame),
            "ours" => time_block(frames, &mut ours_frame),
            "cached" => time_block(frames, &mut cached_frame),
            "plain" => time_block(frames, &mut plain_frame),
            other => {
                panic!("SHADOWMAP_BENCH_ONLY={other}: expected baseline, ours, cached or plain")
            }
        };
        if let Some(e) = error.borrow_mut().take() {
            return Err(e);
        }
        println!("drew {frames} frames of {side}");
        return Ok(());
    }
    time_block(WARM_UP, &mut base_frame);
    time_block(WARM_UP, &mut ours_frame);
    time_block(WARM_UP, &mut cached_frame);
    time_block(WARM_UP, &mut plain_frame);
    let (mut base_all, mut ours_all, mut pair_ratios) = (Vec::new(), Vec::new(), Vec::new());
    let (mut cached_all, mut plain_all, mut overhead_ratios) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..blocks {
        let base = time_block(BLOCK, &mut base_frame);
        let ours = time_block(BLOCK, &mut ours_frame);
        let plain = time_block(BLOCK, &mut plain_frame);
        let cached = time_block(BLOCK, &mut cached_frame);
        pair_ratios.push(quantile(&ours, 0.5) / quantile(&base, 0.5));
        let p = quantile(&plain, 0.5);
        overhead_ratios.push((quantile(&cached, 0.5) - p) / (quantile(&ours, 0.5) - p));
        base_all.extend(base);
        ours_all.extend(ours);
        plain_all.extend(plain);
        cached_all.extend(cached);
    }
    if let Some(e) = error.borrow_mut().take() {
        return Err(e);
    }

    let base_image = baseline.read_colour();
    let ours_image = target.read_colour();
    let diff = base_image
        .iter()
        .zip(&ours_image)
        .map(|(a, b)| a.abs_diff(*b) as f64)
        .sum::<f64>()
        / base_image.len() as f64;

    println!(
        "learnopengl scene, {WIDTH}x{HEIGHT}, {blocks} blocks of {BLOCK} frames per side \
         (wall time to glFinish), on {}",
        ctx.device_name()
    );
    for (name, t) in [
        ("baseline", &base_all),
        ("ours", &ours_all),
        ("cached", &cached_all),
        ("plain", &plain_all),
    ] {
        println!(
            "  {name:9} median {:7.3} ms   p95 {:7.3} ms",
            quantile(t, 0.5),
            quantile(t, 0.95)
        );
    }
    println!(
        "  ours / baseline: {:.3} (medians); per block pair min {:.3} median {:.3} max {:.3}",
        quantile(&ours_all, 0.5) / quantile(&base_all, 0.5),
        quantile(&pair_ratios, 0.0),
        quantile(&pair_ratios, 0.5),
        quantile(&pair_ratios, 1.0)
    );
    let plain_median = quantile(&plain_all, 0.5);
    println!(
        "  shadow overhead (frame minus plain): ours {:.3} ms, cached {:.3} ms; cached / ours \
         per block: min {:.3} median {:.3} max {:.3}",
        quantile(&ours_all, 0.5) - plain_median,
        quantile(&cached_all, 0.5) - plain_median,
        quantile(&overhead_ratios, 0.0),
        quantile(&overhead_ratios, 0.5),
        quantile(&overhead_ratios, 1.0)
    );
    println!("  image difference: {diff:.3} mean absolute per channel (0..255)");
    Ok(())
}
