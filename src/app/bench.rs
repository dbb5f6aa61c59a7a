//! `shadowmap bench`: the speed-versus-accuracy sweep, with progress on standard error, a
//! CSV, a Markdown table and the Pareto plot.

use std::time::Instant;

use shadowmap::bench::{self, BenchConfig, BenchOptions, BenchRow};
use shadowmap::compare::Reference;
use shadowmap::engine::{gl_limits, Gl, HeadlessContext};
use shadowmap::output::{check_output_dir, write_into, Activity, Counter};
use shadowmap::scale;
use shadowmap::{Error, Result, Scene, ShadowSettings};

use super::cli::BenchArgs;

/// `--quick`'s frames a block and warm-up. Most of the quick bench's time is these frames
/// (58 configurations, two blocks each of warm-up + 2 x frames frames, shadowed and plain):
/// 40 frames took 85 s on a fresh 2-core machine, 20 hold it under a minute with a cold
/// shader cache. Each overhead's spread ([`bench::noise`]) says what the fewer frames cost
/// in precision, and an overhead within it is flagged and kept out of the presets. Two
/// warm-up frames: llvmpipe compiles a changed shader at its first draw.
const QUICK_FRAMES: u32 = 20;
const QUICK_WARMUP: u32 = 2;

pub fn run(args: &BenchArgs) -> Result<()> {
    if args.scale {
        return run_scale(args);
    }
    let start = Instant::now();
    let (scene, base) = load_still_scene(args)?;
    let [width, height] = scene.size;
    let dir = &args.out_dir;
    check_before_gl(args, &scene, &base)?;
    let path = args.motion.path(&scene)?;
    let activity = Activity::start("bench: opening a headless OpenGL context");
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &base)?;
    args.scene.check_size(context.gl(), &scene)?;
    let gl = context.gl();
    activity.done(&shadowmap::engine::check::renderer_name(gl));
    let max = gl_limits(gl).max_texture_size;
    let configs = bench::sweep(&base, args.quick, max, scene.light());
    let opts = BenchOptions {
        width,
        height,
        warmup: args
            .warmup
            .unwrap_or(if args.quick { QUICK_WARMUP } else { 10 }),
        frames: args
            .frames
            .unwrap_or(if args.quick { QUICK_FRAMES } else { 100 }),
        supersample: args.supersample,
        band: args.band,
        rays: args.rays,
    };
    eprintln!(
        "bench: {} configurations of the {} scene at {width}x{height}, {} frames each after {} \
         warm-up (max texture {max})",
        configs.len(),
        scene.name,
        opts.frames,
        opts.warmup,
    );
    let reference = trace_reference(gl, &scene, &base, &opts)?;
    let mut rows = time_configs(gl, &scene, &configs, &reference, &opts)?;
    if let Some(path) = &path {
        let frames = (path, args.motion_frames);
        super::motion::bench_flicker(gl, &scene, frames, &mut rows, (args.band, args.rays))?;
    }

    let mut markdown = markdown(&rows);
    let translucent = bench::volumetric::configs(&scene, &base);
    if !translucent.is_empty() {
        eprintln!("bench: each --volumetric choice on the scene's own settings");
        let rows = time_configs(gl, &scene, &translucent, &reference, &opts)?;
        markdown.push_str(
            "
translucent casters (--volumetric), on the scene's own settings:

",
        );
        markdown.push_str(&bench::volumetric::to_markdown(&rows));
    }
    let title = format!(
        "{}: shadow error against shadow overhead ({width}x{height})",
        scene.name
    );
    let files = [
        ("bench.csv", "the table", bench::to_csv(&rows).into_bytes()),
        ("bench.md", "the table", markdown.clone().into_bytes()),
        (
            "pareto.png",
            "the plot",
            super::plot::pareto_png(&title, &rows)?,
        ),
    ];
    write_into(dir, &files)?;
    println!("{markdown}");
    println!(
        "wrote {}/bench.csv, bench.md, pareto.png in {:.1} s",
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    if let Some(target) = args.target_error {
        let chosen = super::quality::cheapest_or_error(&rows, target)
            .map_err(|e| Error::Invalid(format!("{e}; the tables and plot above were written")))?;
        println!("{}", super::quality::describe_choice(chosen, target));
    }
    Ok(())
}

/// Everything that can be checked without the driver, before any GL work or file
/// (--target-error is checked as it is parsed).
fn check_before_gl(args: &BenchArgs, scene: &Scene, base: &ShadowSettings) -> Result<()> {
    args.settings.check_values(scene, base)?;
    super::quality::check_first_light(scene)?;
    if args.settings.quality.is_some() {
        return Err(Error::Invalid(
            "--quality: bench sweeps the map size, filter, bias, culling and depth format \
             itself, so a preset would be replaced; expected bench without it (the presets \
             are chosen from its measurements)"
                .into(),
        ));
    }
    check_output_dir("--out-dir", &args.out_dir)
}

/// The scene held still at its frame size, with the settings the flags give.
pub(super) fn load_still_scene(args: &BenchArgs) -> Result<(Scene, ShadowSettings)> {
    let (mut scene, base) = args.scene.load_with(&args.settings)?;
    // Time a still frame: the animation would change what is measured between frames.
    scene
        .items
        .iter_mut()
        .for_each(|i| i.spin = glam::Vec3::ZERO);
    let (width, height) = args.scene.size(&scene);
    scene.size = [width, height];
    Ok((scene, base))
}

/// The exact reference every configuration is scored against, with a spinner.
fn trace_reference(
    gl: &Gl,
    scene: &Scene,
    base: &ShadowSettings,
    opts: &BenchOptions,
) -> Result<Reference> {
    let n = opts.supersample;
    let activity = Activity::start(format!(
        "bench: tracing the exact reference at {}x{}{}",
        opts.width,
        opts.height,
        match n {
            1 => String::new(),
            _ => format!(" (and {n}x{n} supersampled)"),
        }
    ));
    let reference = bench::bench_reference(gl, scene, base, opts)?;
    activity.done(&format!(
        "{} caster triangles, rays traced in {:.0} ms",
        reference.triangles, reference.trace_ms
    ));
    Ok(reference)
}

/// The sweep timed and scored, with one progress bar (and its estimate) over both passes.
fn time_configs(
    gl: &Gl,
    scene: &Scene,
    configs: &[BenchConfig],
    reference: &Reference,
    opts: &BenchOptions,
) -> Result<Vec<BenchRow>> {
    // Each configuration is timed twice: once in the first pass over the sweep, and again
    // in reverse order, when it is also scored.
    let mut counter = Counter::new(2 * configs.len() as u64);
    let rows = bench::run(gl, scene, configs, reference, opts, |p| {
        counter.step(&p.line());
    })?;
    counter.finish();
    Ok(rows)
}

/// bench.md: the table, the comparison with the tutorials' settings and the presets the
/// --quality rule picks from this sweep.
fn markdown(rows: &[BenchRow]) -> String {
    let mut markdown = bench::to_markdown(rows);
    markdown.push('\n');
    markdown.push_str(&bench::against_tutorials_text(rows));
    markdown
        .push_str("\nthe --quality rule (docs/results.md, \"Quality presets\") on this sweep:\n");
    for (level, row) in bench::preset_choices(rows) {
        markdown.push_str(&match row {
            Some(r) => format!(
                "  {level}: {} (overhead {:.2} ± {:.2} ms, {})\n",
                r.label(),
                r.overhead_ms,
                r.overhead_spread_ms,
                r.error_text()
            ),
            None => format!(
                "  {level}: no configuration meets the rule (an overhead within noise \
                 counts for none)\n"
            ),
        });
    }
    markdown
}

/// `bench --scale`: each pass' time against the work, with the fitted exponents.
fn run_scale(args: &BenchArgs) -> Result<()> {
    let start = Instant::now();
    let dir = &args.out_dir;
    check_output_dir("--out-dir", dir)?;
    let activity = Activity::start("bench --scale: opening a headless OpenGL context");
    let context = HeadlessContext::new()?;
    let gl = context.gl();
    activity.done(&shadowmap::engine::check::renderer_name(gl));
    let max = gl_limits(gl).max_texture_size;
    let points = scale::plan(args.quick, max);
    let opts = scale::ScaleOptions::new(args.quick);
    eprintln!(
        "bench --scale: {} points, each timed twice (forward, then in reverse) with frames \
         for about {:.1} s ({} to {})",
        points.len(),
        opts.budget_ms / 1000.0,
        opts.min_frames,
        opts.max_frames
    );
    let mut counter = Counter::new(2 * points.len() as u64);
    let rows = scale::run(gl, &points, &opts, |row| {
        counter.step(&format!(
            "{} = {}: depth {:.2} ms, scene {:.2} ms ({} frames)",
            row.point.axis.name(),
            row.work,
            row.depth_wall_ms.median,
            row.scene_wall_ms.median,
            row.frames
        ))
    })?;
    counter.finish();
    let fits = scale::fits(&rows);
    let markdown = scale::fits_to_markdown(&fits);
    let files = [
        ("scale.csv", "the table", scale::to_csv(&rows).into_bytes()),
        (
            "scale-fit.csv",
            "the exponents",
            scale::fits_to_csv(&fits).into_bytes(),
        ),
        (
            "scale.png",
            "the plot",
            super::plot::scale_png(&rows, &fits)?,
        ),
    ];
    write_into(dir, &files)?;
    println!("{markdown}");
    println!(
        "wrote {}/scale.csv, scale-fit.csv, scale.png in {:.1} s",
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
