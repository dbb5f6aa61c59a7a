//! `shadowmap compare`: one frame scored against the exact reference, with pictures.

use std::path::Path;

use shadowmap::compare::{compute_reference, render_visibility, CompareOptions, Reference};
use shadowmap::engine::Gl;
use shadowmap::frame::Frame;
use shadowmap::image_data::ImageData;
use shadowmap::output::{write_into, Activity};
use shadowmap::reference::{
    error_image, npy_bytes_f32_hw3, transmittance_error_image, Metrics, RefPixel,
    TransmittanceMetrics,
};
use shadowmap::settings::ShadowTechnique;
use shadowmap::{Error, Result, Scene, ShadowSettings};

use super::cli::{CompareArgs, Truth};
use super::compare_setup::CompareSetup;

pub fn run(args: &CompareArgs) -> Result<()> {
    check_motion_frames(args)?;
    if let Some(path) = super::motion::compare_path(args)? {
        return super::motion::run_compare(args, path);
    }
    let CompareSetup {
        scene,
        settings,
        context,
        plan,
        opts,
    } = CompareSetup::prepare(args)?;
    let (width, height, dir) = (opts.width, opts.height, &args.out_dir);
    // The steps of `shadowmap::compare::compare`, one at a time so each can be shown.
    let (reference, agreement) = trace_truth(context.gl(), args, &scene, &settings, &opts)?;
    let activity = Activity::start(format!(
        "compare: rendering light {}'s shadow test ({})",
        args.light,
        plan.in_use().summary()
    ));
    let frame = render_visibility(context.gl(), &scene, &settings, width, height, args.light)?;
    let vis = frame.visibility.as_deref().unwrap_or_default();
    let (metrics, opaque_vis) =
        binary_metrics(context.gl(), args, &scene, &settings, &reference, vis)?;
    let opaque_only = opaque_vis.is_some();
    let area = reference.score_area(vis);
    let transmittance = reference.score_transmittance(vis);
    activity.done("");

    // error.png shows what the binary line scores: with translucent casters, the opaque
    // casters' own shadow test.
    let binary_vis = opaque_vis.as_deref().unwrap_or(vis);
    let mut files = picture_files(&frame, binary_vis, &reference, width, height)?;
    if args.arrays {
        files.extend(gbuffer_files(&reference)?);
    }
    let json = serde_json::json!({
        "scene": scene.name,
        "size": [width, height],
        "light": args.light,
        "light_description": scene.lights.get(args.light).map(|l| l.describe()),
        "settings": settings,
        "supersample": args.supersample,
        "band": args.band,
        "reference_triangles": reference.triangles,
        "reference_ms": reference.trace_ms,
        "truth": match args.truth {
            Truth::Cpu => "cpu",
            Truth::Volumes => "volumes",
        },
        "volumes_vs_cpu": agreement,
        "metrics": metrics,
        // A light with a size: the soft truth's figures (null for a point light).
        "light_size": scene.lights.get(args.light).map(|l| l.size()),
        "area_light": area,
        // With translucent casters: against the transmittance truth (null without).
        "transmittance": transmittance,
    });
    files.push(("metrics.json", format!("{json:#}\n").into_bytes()));
    write_files(dir, &files)?;
    let line = summary(&scene.name, &plan.in_use().summary(), &metrics, args.band);
    match opaque_only {
        // The hard truth knows only the opaque casters: say so, and score their own test.
        true => println!(
            "{}",
            line.replacen(
                "]: misclassified",
                "]: opaque casters alone (their shadow test, volumetric off, against their \
                 truth): misclassified",
                1
            )
        ),
        false => println!("{line}"),
    }
    print_agreement(agreement.as_ref(), args.band);
    if let Some(a) = &area {
        println!("{}", area_summary(a));
    }
    if let Some(t) = &transmittance {
        println!("{}", transmittance_summary(t, settings.volumetric.name()));
    }
    let measured = &plan.lights[args.light.min(plan.lights.len().saturating_sub(1))];
    let filter = measured.settings.filter;
    if area.is_none() && (filter.soft() || filter.moments()) {
        println!("{}", hard_truth_note(filter.name()));
    }
    println!("{ERROR_COLOURS}");
    println!(
        "wrote {}: {}",
        dir.display(),
        files.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", ")
    );
    Ok(())
}

/// `--motion` scores how the error changes from each frame to the next: one frame has no
/// pair to score, so it is refused before the scene is loaded.
fn check_motion_frames(args: &CompareArgs) -> Result<()> {
    let frames = args.frames;
    if args.motion.motion.is_some() && frames < 2 {
        return Err(Error::Invalid(format!(
            "--frames {frames}: compare --motion scores the change between consecutive \
             frames, and {frames} frame has no pair; expected at least 2"
        )));
    }
    Ok(())
}

/// The binary figures. With translucent casters the hard truth is the opaque casters'
/// alone, while the rendered light is also dimmed by the translucent ones (that is scored
/// against the transmittance truth): the binary line scores the opaque casters' own
/// shadow test, a frame with `volumetric` off, and gives that frame's visibility.
fn binary_metrics(
    gl: &Gl,
    args: &CompareArgs,
    scene: &Scene,
    settings: &ShadowSettings,
    reference: &Reference,
    vis: &[Option<f32>],
) -> Result<(Metrics, Option<Vec<Option<f32>>>)> {
    use shadowmap::settings::Volumetric;
    if reference.transmittance.is_none() || settings.volumetric == Volumetric::Off {
        return Ok((reference.score(vis, args.band), None));
    }
    let opaque = ShadowSettings {
        volumetric: Volumetric::Off,
        ..*settings
    };
    let (w, h) = (reference.width, reference.height);
    let frame = render_visibility(gl, scene, &opaque, w, h, args.light)?;
    let vis = frame.visibility.unwrap_or_default();
    Ok((reference.score(&vis, args.band), Some(vis)))
}

/// Traces the exact reference, and with `--truth volumes` swaps in the stencil shadow
/// volumes' answer as the truth, returning how far the two agree.
fn trace_truth(
    gl: &Gl,
    args: &CompareArgs,
    scene: &Scene,
    settings: &ShadowSettings,
    opts: &CompareOptions,
) -> Result<(Reference, Option<Metrics>)> {
    let n = args.supersample;
    let activity = Activity::start(format!(
        "compare: tracing the exact reference for the {} scene at {}x{}{}{}",
        scene.name,
        opts.width,
        opts.height,
        match n {
            1 => String::new(),
            _ => format!(" (and {n}x{n} supersampled)"),
        },
        match scene.lights.get(args.light).map_or(0.0, |l| l.size()) {
            0.0 => String::new(),
            _ => format!(" and the area light's, {} rays per pixel", args.rays),
        }
    ));
    // With --truth volumes the ray cast follows the volumes' light (they cast from the
    // light the scene is shaded with), so their agreement with it can be printed.
    let volumes = ShadowSettings {
        technique: ShadowTechnique::Volumes,
        ..*settings
    };
    let traced = match args.truth {
        Truth::Cpu => settings,
        Truth::Volumes => &volumes,
    };
    let reference = compute_reference(gl, scene, traced, opts)?;
    activity.done(&format!(
        "{} caster triangles, rays traced in {:.0} ms",
        reference.triangles, reference.trace_ms
    ));
    Ok(match args.truth {
        Truth::Cpu => (reference, None),
        Truth::Volumes => {
            let activity = Activity::start(format!(
                "compare: rendering light {}'s stencil shadow volumes as the truth",
                args.light
            ));
            let frame =
                render_visibility(gl, scene, &volumes, opts.width, opts.height, args.light)?;
            let vis = frame.visibility.as_deref().unwrap_or_default();
            let agreement = reference.score(vis, args.band);
            activity.done("");
            (reference.with_volumes_truth(vis), Some(agreement))
        }
    })
}

/// visibility.png, reference.png and error.png (of `binary_vis`, the visibility the binary
/// line scores), and for a light with a size reference-area.png and error-area.png.
fn picture_files(
    frame: &Frame,
    binary_vis: &[Option<f32>],
    reference: &Reference,
    width: u32,
    height: u32,
) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let vis = frame.visibility.as_deref().unwrap_or_default();
    let (w, h) = (width as usize, height as usize);
    let mut files: Vec<(&str, Vec<u8>)> = Vec::new();
    if let Some(image) = frame.visibility_image() {
        files.push(("visibility.png", image.encode_png()?));
    }
    files.push((
        "reference.png",
        reference_image(width, height, &reference.hard).encode_png()?,
    ));
    let grey: Vec<u8> = frame
        .colour
        .rgba
        .chunks_exact(4)
        .map(|p| ((u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10) as u8)
        .collect();
    let error = error_image(w, h, binary_vis, &reference.hard, &grey);
    let error = super::plot::with_error_legend(ImageData {
        width,
        height,
        rgba: error.concat(),
    })?;
    files.push(("error.png", error.encode_png()?));
    if let Some(truth) = &reference.transmittance {
        files.push((
            "reference-transmittance.png",
            reference_image(width, height, truth).encode_png()?,
        ));
        let error = transmittance_error_image(vis, truth, &grey);
        let error = super::plot::with_legend(
            ImageData {
                width,
                height,
                rgba: error.concat(),
            },
            &super::plot::TRANSMITTANCE_LEGEND,
        )?;
        files.push(("error-transmittance.png", error.encode_png()?));
    }
    if let Some(truth) = &reference.area {
        files.push((
            "reference-area.png",
            reference_image(width, height, &truth.pixels).encode_png()?,
        ));
        let error = error_image(width as usize, height as usize, vis, &truth.pixels, &grey);
        let error = super::plot::with_error_legend(ImageData {
            width,
            height,
            rgba: error.concat(),
        })?;
        files.push(("error-area.png", error.encode_png()?));
    }
    Ok(files)
}

/// positions.npy (absolute world positions) and normals.npy from the reference's G-buffer.
fn gbuffer_files(reference: &Reference) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let g = &reference.gbuffer;
    let world: Vec<[f32; 3]> = (0..g.positions.len())
        .map(|i| reference.world_position(i).as_vec3().to_array())
        .collect();
    let mut files = Vec::new();
    for (name, data) in [("positions.npy", &world), ("normals.npy", &g.normals)] {
        if data.len() != g.width * g.height {
            return Err(Error::Invalid(format!(
                "{name}: {} pixels for a {}x{} G-buffer",
                data.len(),
                g.width,
                g.height
            )));
        }
        files.push((name, npy_bytes_f32_hw3(g.width, g.height, data)));
    }
    Ok(files)
}

/// Writes the files into `dir`, each named in an error as an image or a file.
fn write_files(dir: &Path, files: &[(&str, Vec<u8>)]) -> Result<()> {
    let batch: Vec<(&str, &str, &[u8])> = files
        .iter()
        .map(|(name, bytes)| {
            let what = match name.ends_with(".png") {
                true => "the image",
                false => "the file",
            };
            (*name, what, bytes.as_slice())
        })
        .collect();
    write_into(dir, &batch)
}

/// With `--truth volumes`: how far the volumes agree with the CPU ray cast.
fn print_agreement(agreement: Option<&Metrics>, band: usize) {
    if let Some(a) = agreement {
        println!(
            "truth: stencil shadow volumes; against the CPU ray cast they agree on {} of {} \
             receivers ({} misclassified, {} outside a {}-px edge band)",
            a.receivers - a.misclassified,
            a.receivers,
            a.misclassified,
            a.misclassified_outside_band,
            band
        );
    }
}

/// What the error images' colours mean, printed with every comparison (without a file
/// name: each file is named once, on the line that says it was written).
pub const ERROR_COLOURS: &str = "the error images: red = false shadow (shadowed here, lit in the \
    reference), blue = false light (lit here, shadowed in the reference), grey = agrees";

/// The one-line summary printed by `compare`.
pub fn summary(scene: &str, settings: &str, m: &Metrics, band: usize) -> String {
    let pct = |x: f64| format!("{:.3}%", x * 100.0);
    format!(
        "{scene} [{settings}]: misclassified {} (false shadow {}, false light {}) of {} receivers; \
         outside a {band}-px edge band {}; MAE vs supersampled {}",
        pct(m.misclassified_rate),
        pct(m.false_shadow_rate),
        pct(m.false_light_rate),
        m.receivers,
        pct(m.misclassified_outside_band_rate),
        m.mae.map_or("n/a".to_string(), |v| format!("{v:.4}")),
    )
}

/// The line `compare` adds for a light with a size.
pub fn area_summary(a: &shadowmap::reference::SoftMetrics) -> String {
    format!(
        "against the area light ({} rays per pixel): MAE {:.4}, light bleeding {:.3}%, false \
         shadow {:.3}%, penumbra width error {:.2} px ({:.2} px against the truth's {:.2} px \
         over {} edges)",
        a.rays,
        a.mae,
        a.light_bleed_rate * 100.0,
        a.false_shadow_rate * 100.0,
        a.penumbra_width_error_px,
        a.penumbra_width_px,
        a.penumbra_width_truth_px,
        a.penumbra_edges
    )
}

/// The line `compare` adds for a scene with translucent casters.
pub fn transmittance_summary(t: &TransmittanceMetrics, volumetric: &str) -> String {
    format!(
        "transmittance: MAE {:.4} (within the translucent shadow {:.4} over {} receivers, \
         outside it {:.4}), max {:.4}, over {} receivers, volumetric = {volumetric}; \
         error-transmittance.png: red = too dark, blue = too bright",
        t.mae, t.mae_in_shadow, t.in_shadow, t.mae_outside, t.max_error, t.receivers
    )
}

/// The hard reference as the same kind of image as `--shadow-out`.
fn reference_image(width: u32, height: u32, hard: &[RefPixel]) -> ImageData {
    let rgba = hard
        .iter()
        .flat_map(|p| match p.covered {
            true => {
                let g = (p.visibility * 255.0).round() as u8;
                [g, g, g, 255]
            }
            false => [0, 0, 0, 0],
        })
        .collect();
    ImageData {
        width,
        height,
        rgba,
    }
}

/// Said when a soft filter is scored against a light of size 0: its truth is hard, so the
/// filter's penumbra counts as error.
fn hard_truth_note(filter: &str) -> String {
    format!(
        "note: --filter {filter} softens edges, but the measured light has size 0, so its \
         truth is the hard shadow and every penumbra pixel counts as error; give the light a \
         size (--light-size, or `size` in the scene) to score it against the area light"
    )
}
