//! `--motion`: a scripted path for `render`, `compare`, `bench` and `demo`, and `compare
//! --motion`'s run: every frame traced and scored, its flicker energy and false flicker
//! ([`shadowmap::motion`]) with an animation of the error and a plot of the flicker.

use shadowmap::compare::CompareOptions;
use shadowmap::motion::score_path;
use shadowmap::output::{write_into, Activity};
use shadowmap::reference::error_image;
use shadowmap::scene::motion::{MotionPath, PathKind};
use shadowmap::{Error, Result, Scene};

use super::cli::CompareArgs;
use super::compare_setup::CompareSetup;

/// What a path is, in words: "strafe, 0.05 world units a frame".
pub fn describe(path: &MotionPath) -> String {
    match path.kind {
        PathKind::Still | PathKind::Keyframes => path.kind.name().to_string(),
        k => format!("{}, {} {} a frame", k.name(), path.step, k.unit()),
    }
}

/// `compare --motion`: each frame of the path traced, rendered and scored.
pub fn run_compare(args: &CompareArgs, path: MotionPath) -> Result<()> {
    let setup = CompareSetup::prepare(args)?;
    let (scene, settings, opts) = (&setup.scene, &setup.settings, &setup.opts);
    let (width, height, dir) = (opts.width, opts.height, &args.out_dir);
    let gl = setup.context.gl();
    let mut pictures = Vec::new();
    let activity = Activity::start(format!(
        "compare: {} frames of {} ({}): tracing and rendering each",
        args.frames,
        describe(&path),
        setup.plan.in_use().summary()
    ));
    let score = score_path(
        gl,
        scene,
        settings,
        (&path, args.frames),
        opts,
        |frame, reference| {
            let vis = frame.visibility.as_deref().unwrap_or_default();
            let grey: Vec<u8> = (frame.colour.rgba.chunks_exact(4))
                .map(|p| ((u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10) as u8)
                .collect();
            let error = error_image(width as usize, height as usize, vis, &reference.hard, &grey);
            pictures.push(error.concat());
        },
    )?;
    activity.done("");
    let json = serde_json::json!({
        "scene": scene.name,
        "size": [width, height],
        "light": args.light,
        "settings": settings,
        "motion_step": path.step,
        "motion": score,
    });
    let files = [
        (
            "metrics.json",
            "the file",
            format!("{json:#}\n").into_bytes(),
        ),
        (
            "motion-error.png",
            "the image",
            apng(width, height, &pictures)?,
        ),
        (
            "motion-flicker.png",
            "the plot",
            super::motion_plot::flicker_png(&score)?,
        ),
    ];
    write_into(dir, &files)?;
    println!("{}", score.line());
    println!(
        "error per frame: {}",
        (score.frames.iter())
            .map(|f| format!("{:.3}%", f.misclassified * 100.0))
            .collect::<Vec<_>>()
            .join(" ")
    );
    if scene.lights.get(args.light).is_some_and(|l| l.size() > 0.0) {
        println!(
            "MAE against the area light per frame: {}",
            (score.frames.iter())
                .map(|f| format!("{:.4}", f.mae))
                .collect::<Vec<_>>()
                .join(" ")
        );
    }
    println!(
        "wrote {}: metrics.json, motion-error.png (the error over the path, animated: red = \
         false shadow, blue = false light, grey = agrees), motion-flicker.png (false flicker \
         and the truth's change per frame)",
        dir.display()
    );
    Ok(())
}

/// `bench --motion`: each configuration's flicker energy and false flicker over `frames`
/// of the path, into its row (each frame traced and drawn; no supersampling, which the
/// flicker does not use); the Pareto front is then marked again with the energy.
pub fn bench_flicker(
    gl: &shadowmap::engine::Gl,
    scene: &Scene,
    (path, frames): (&MotionPath, u32),
    rows: &mut [shadowmap::bench::BenchRow],
    (band, rays): (usize, u32),
) -> Result<()> {
    let opts = CompareOptions {
        width: scene.size[0],
        height: scene.size[1],
        supersample: 1,
        band,
        light: 0,
        rays,
    };
    eprintln!(
        "bench: flicker energy of {} configurations over {frames} frames of {}",
        rows.len(),
        describe(path)
    );
    let mut counter = shadowmap::output::Counter::new(rows.len() as u64);
    for row in rows.iter_mut() {
        let settings = row.config.settings;
        let score = score_path(gl, scene, &settings, (path, frames), &opts, |_, _| {})?;
        row.flicker_energy = Some(score.energy);
        row.false_flicker = Some(score.false_flicker);
        counter.step(&format!(
            "{}: flicker energy {:.4}, false flicker {:.3}%",
            row.label(),
            score.energy,
            score.false_flicker * 100.0
        ));
    }
    counter.finish();
    shadowmap::bench::mark_pareto(rows);
    Ok(())
}

/// The frames as an animated PNG, ten frames a second, looping.
pub fn apng(width: u32, height: u32, frames: &[Vec<u8>]) -> Result<Vec<u8>> {
    let err = |e: png::EncodingError| Error::Invalid(format!("cannot encode the animation: {e}"));
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, width, height);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        encoder
            .set_animated(frames.len().max(1) as u32, 0)
            .map_err(err)?;
        encoder.set_frame_delay(1, 10).map_err(err)?;
        let mut writer = encoder.write_header().map_err(err)?;
        for f in frames {
            writer.write_image_data(f).map_err(err)?;
        }
        writer.finish().map_err(err)?;
    }
    Ok(bytes)
}

/// Whether `compare` runs a path: any `--motion`, checked before any work.
pub fn compare_path(args: &CompareArgs) -> Result<Option<MotionPath>> {
    match args.motion.motion {
        None => Ok(None),
        Some(_) => {
            let (scene, _) = args.scene.load_with(&args.settings)?;
            args.motion.path(&scene)
        }
    }
}
