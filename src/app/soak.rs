//! `shadowmap soak`: many frames while the light angle, the map size and the chapter step
//! change, reporting resident memory at the start and the end, and the first error.

use std::time::Instant;

use shadowmap::engine::{HeadlessContext, Outputs, RenderTarget};
use shadowmap::output::Counter;
use shadowmap::{steps, Renderer, Result, Scene, ShadowSettings, Target};

use super::cli::{SettingsArgs, SoakArgs};

/// Resident memory of this process in KiB (Linux `/proc/self/statm`), if readable.
pub fn resident_kib() -> Option<u64> {
    let statm = std::fs::read_to_string("/proc/self/statm").ok()?;
    let pages: u64 = statm.split_whitespace().nth(1)?.parse().ok()?;
    Some(pages * 4)
}

/// Frames in one full cycle of steps and map sizes.
const WARM_FRAMES: u64 = 600;

/// The scene as `render --step` shows `step` (the scene's own settings for `None`), with
/// the flags, at the frame size.
pub(super) fn at_step(
    args: &SoakArgs,
    loaded: &Scene,
    step: Option<&str>,
) -> Result<(Scene, ShadowSettings)> {
    let mut scene = loaded.clone();
    let settings = SettingsArgs {
        step: step.map(str::to_string),
        ..args.settings.clone()
    };
    let s = settings.resolve(&args.scene, &mut scene)?;
    let (width, height) = args.scene.size(&scene);
    scene.size = [width, height];
    Ok((scene, s))
}

pub fn run(args: &SoakArgs) -> Result<()> {
    let loaded = args.scene.load()?;
    let (mut scene, base) = at_step(args, &loaded, args.settings.step.as_deref())?;
    let (width, height) = args.scene.size(&scene);
    let context = HeadlessContext::new()?;
    let gl = context.gl();
    args.settings.check(gl, &scene, &base)?;
    args.scene.check_size(gl, &scene)?;
    let target = RenderTarget::new(gl, width, height, Outputs::default())?;
    let mut renderer = Renderer::new(gl, &scene, &base)?;
    let sizes = [256, 512, 1024, 2048];
    let start = Instant::now();
    let (mut rss_start, mut rss_peak) = (None, 0);
    // A bar on a terminal; in a log or a pipe a line per 100 frames, so that a long run
    // says how far it is.
    let mut progress = Counter::new(args.frames.div_ceil(100));
    // Taken once: past the overhead a light's own horizontal part points the other way.
    let azimuth = scene.light_azimuth();
    let baseline = baseline_frame(args.frames);
    for frame in 0..args.frames {
        if frame == baseline {
            renderer.finish();
            rss_start = resident_kib();
        }
        if frame % 50 == 0 {
            // Every 50 frames: the next step and the next map size.
            // `--step` holds one step; each step is drawn in its own view.
            let k = (frame / 50) as usize;
            let list = steps::of(&loaded);
            let step = args
                .settings
                .step
                .as_deref()
                .unwrap_or(list[k % list.len()].name);
            let (staged, mut s) = at_step(args, &loaded, Some(step))?;
            (scene.camera, scene.lights, scene.items) =
                (staged.camera, staged.lights, staged.items);
            s.map_size = sizes[k % sizes.len()].into();
            renderer.set_settings(&s)?;
        }
        let angle = 10.0 + (frame as f32 * 0.7) % 160.0;
        if let Some(azimuth) = azimuth {
            scene.set_light_angle_about(azimuth, angle);
        }
        scene.update();
        renderer
            .render(&scene, Target::Offscreen(&target))
            .map_err(|e| shadowmap::Error::Invalid(format!("frame {frame}: {e}")))?;
        if frame % 100 == 0 {
            renderer.finish();
            let rss = resident_kib().unwrap_or(0);
            rss_peak = rss_peak.max(rss);
        }
        if frame % 100 == 99 || frame + 1 == args.frames {
            let rss = resident_kib().unwrap_or(0) / 1024;
            let done = frame + 1;
            progress.step(&format!(
                "{done} of {} frames, {rss} MiB resident",
                args.frames
            ));
        }
    }
    renderer.finish();
    progress.finish();
    let rss_end = resident_kib().unwrap_or(0);
    let first = rss_start.unwrap_or(rss_end);
    println!(
        "soak: {} of the {} scene in {:.1} s, no error; resident memory {} MiB {}, {} MiB at \
         the end (peak {} MiB, growth {:+} KiB)",
        count(args.frames),
        scene.name,
        start.elapsed().as_secs_f64(),
        first / 1024,
        baseline_words(baseline),
        rss_end / 1024,
        rss_peak.max(rss_end) / 1024,
        rss_end as i64 - first as i64
    );
    Ok(())
}

/// The frame before which memory is first taken: the end of the first full cycle (12
/// steps x 4 map sizes, 50 frames each), which fills the driver's and the allocator's
/// caches; in a shorter run frame 100, and in one of 100 frames or fewer the start.
fn baseline_frame(frames: u64) -> u64 {
    match frames {
        f if f > WARM_FRAMES => WARM_FRAMES,
        f if f > 100 => 100,
        _ => 0,
    }
}

/// When the first memory figure was taken, in words.
fn baseline_words(baseline: u64) -> String {
    match baseline {
        0 => "before the first frame".into(),
        WARM_FRAMES => format!("after {WARM_FRAMES} frames (the first full cycle)"),
        n => format!("after {n} frames"),
    }
}

/// "1 frame", "300 frames".
fn count(frames: u64) -> String {
    match frames {
        1 => "1 frame".into(),
        n => format!("{n} frames"),
    }
}
