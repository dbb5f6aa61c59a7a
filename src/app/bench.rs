//! `shadowmap bench`: the speed-versus-accuracy sweep, with a progress bar, a CSV, a
//! Markdown table and the Pareto plot.

use std::time::Instant;

use indicatif::{ProgressBar, ProgressStyle};
use shadowmap::bench::{self, BenchOptions};
use shadowmap::engine::{gl_limits, HeadlessContext};
use shadowmap::{Error, Result};

use super::cli::BenchArgs;

pub fn run(args: &BenchArgs) -> Result<()> {
    let start = Instant::now();
    let mut scene = args.scene.load()?;
    // Time a still frame: the animation would change what is measured between frames.
    scene
        .items
        .iter_mut()
        .for_each(|i| i.spin = glam::Vec3::ZERO);
    let base = args.settings.apply(&scene)?;
    let (width, height) = args.scene.size(&scene);
    scene.size = [width, height];
    let dir = &args.out_dir;
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::file(dir, format!("cannot create the output folder: {e}")))?;
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &base)?;
    let gl = context.gl();
    let max = gl_limits(gl).max_texture_size;
    let configs = bench::sweep(&base, args.quick, max, scene.light());
    let opts = BenchOptions {
        width,
        height,
        warmup: args.warmup,
        frames: args.frames,
        supersample: args.supersample,
        band: args.band,
    };
    eprintln!(
        "bench: {} configurations of the {} scene at {width}x{height}, {} frames each after {} warm-up \
         ({}, max texture {max})",
        configs.len(),
        scene.name,
        opts.frames,
        opts.warmup,
        shadowmap::engine::check::renderer_name(gl),
    );
    let reference = bench::bench_reference(gl, &scene, &base, &opts)?;
    eprintln!(
        "reference: {} caster triangles traced in {:.0} ms ({}x{} supersampled)",
        reference.triangles, reference.trace_ms, opts.supersample, opts.supersample
    );
    let bar = ProgressBar::new(configs.len() as u64);
    eprintln!("timing runs in two passes over the sweep (the second in reverse); the bar counts the second");
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} [{elapsed} < {eta}] {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let rows = bench::run(gl, &scene, &configs, &reference, &opts, |row| {
        bar.set_message(format!(
            "{}: {:.2} ms, {:.3}% wrong",
            row.label(),
            row.wall_ms.median,
            row.error() * 100.0
        ));
        bar.inc(1);
    })?;
    bar.finish_and_clear();

    let write = |name: &str, text: String| {
        let path = dir.join(name);
        std::fs::write(&path, text).map_err(|e| Error::file(&path, format!("cannot write: {e}")))
    };
    write("bench.csv", bench::to_csv(&rows))?;
    write("bench.md", bench::to_markdown(&rows))?;
    super::plot::pareto_png(
        &dir.join("pareto.png"),
        &format!(
            "{}: shadow error against frame time ({width}x{height})",
            scene.name
        ),
        &rows,
    )?;
    println!("{}", bench::to_markdown(&rows));
    if let Some(target) = args.target_error {
        match bench::cheapest_under(&rows, target) {
            Some(r) => println!(
                "cheapest configuration with error <= {:.3}%: {} ({:.2} ms, {:.3}% misclassified)\n  \
                 as flags: --map-size {} --filter {} --bias-mode {} --bias {} --bias-min {} \
                 --normal-offset {} --polygon-offset {},{} --cull {} --depth-format {}",
                target * 100.0,
                r.label(),
                r.wall_ms.median,
                r.error() * 100.0,
                r.config.settings.map_size,
                r.config.settings.filter.name(),
                r.config.settings.bias_mode.name(),
                r.config.settings.bias,
                r.config.settings.bias_min,
                r.config.settings.normal_offset,
                r.config.settings.polygon_offset[0],
                r.config.settings.polygon_offset[1],
                r.config.settings.cull.name(),
                r.config.settings.depth_format.name(),
            ),
            None => {
                return Err(Error::Invalid(format!(
                    "no configuration reached an error of {:.3}% or less (best: {:.3}%)",
                    target * 100.0,
                    rows.iter().map(|r| r.error()).fold(f64::INFINITY, f64::min) * 100.0
                )))
            }
        }
    }
    println!(
        "wrote {}/bench.csv, bench.md, pareto.png in {:.1} s",
        dir.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
