//! `shadowmap render`: headless frames through EGL, written as PNGs.

use std::path::Path;
use std::time::Instant;

use image::ColorType;

use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::render_frames;
use shadowmap::image_data::encode_png;
use shadowmap::output::{check_output_image, write_files};
use shadowmap::shadows::volumes::Adjacency;
use shadowmap::shadows::ShadowKind;
use shadowmap::{Error, Result};

use super::cli::RenderArgs;
use super::hud::{inset_rect, render_frames_with_overlays, Overlays};
use super::quality::choose_for_target;

pub fn run(args: &RenderArgs) -> Result<()> {
    let start = Instant::now();
    let mut scene = args.scene.load()?;
    let mut settings = args.settings.apply(&mut scene)?;
    let (width, height) = args.scene.size(&scene);
    // Everything that can be checked without the driver, before any GL work or file.
    let mut plan = args.settings.check_values(&scene, &settings)?;
    check_outputs(args)?;
    if let Some(target) = args.target_error {
        let chosen = choose_for_target(
            &scene,
            &settings,
            (width, height),
            target,
            &args.settings.patch,
        )?;
        chosen.apply_to(&mut settings);
        plan = args.settings.check_values(&scene, &settings)?;
    }
    if let Some(path) = &args.depth_out {
        if plan.lights[0].kind != ShadowKind::Map {
            return Err(Error::Invalid(format!(
                "--depth-out {}: the first light has no 2D depth map (it has a cube map, \
                 cascades, caster groups, a moment map, shadow volumes or casts no shadow): use \
                 --show-depth-map to see its map",
                path.display()
            )));
        }
    }
    if args.inset {
        // Legal but it would do nothing: say so once, naming the flag.
        if plan.lights.iter().all(|l| l.kind == ShadowKind::None) {
            eprintln!(
                "warning: --inset: no light of the {} scene casts a shadow, so there is no \
                 map to show; the image is drawn without it",
                scene.name
            );
        } else if inset_rect(width, height).is_none() {
            eprintln!(
                "warning: --inset: a {width}x{height} frame is too small for the inset (a \
                 quarter of the height on a side, 8 pixels from the edges); drawn without it"
            );
        }
    }
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &settings)?;
    args.scene.check_size(context.gl(), &scene)?;
    let outputs = Outputs {
        visibility: args.shadow_out.is_some(),
        gbuffer: false,
    };
    let overlays = Overlays {
        hud: args.hud,
        inset: args.inset,
    };
    let frame = match overlays.hud || overlays.inset {
        true => render_frames_with_overlays(
            &context,
            &mut scene,
            &settings,
            args.settings.step.as_deref(),
            (width, height),
            args.frames,
            outputs,
            overlays,
        )?,
        false => render_frames(
            context.gl(),
            &mut scene,
            &settings,
            width,
            height,
            args.frames,
            outputs,
        )?,
    };
    // Every image encoded first, then written as one: a failed write leaves none of them.
    let mut images = vec![(&args.out, frame.colour.encode_png()?)];
    if let (Some(path), Some(image)) = (&args.shadow_out, frame.visibility_image()) {
        images.push((path, image.encode_png()?));
    }
    if let (Some(path), Some((size, grey))) = (&args.depth_out, frame.depth_grey()) {
        images.push((
            path,
            encode_png(size.width, size.height, ColorType::L8, &grey)?,
        ));
    }
    let files: Vec<(&Path, &str, &[u8])> = images
        .iter()
        .map(|(path, bytes)| (path.as_path(), "the image", bytes.as_slice()))
        .collect();
    write_files(&files)?;
    println!(
        "wrote {} ({}x{}, scene {}, {}, {}) in {:.0} ms",
        args.out.display(),
        width,
        height,
        scene.name,
        scene.light().describe(),
        plan.in_use().summary(),
        start.elapsed().as_secs_f64() * 1000.0
    );
    if let Some(line) = args.settings.quality_summary()? {
        println!("{line}");
    }
    if let (Some(path), Some((size, _))) = (&args.depth_out, &frame.depth_map) {
        let shown = match frame.depth_perspective {
            Some((near, far)) => format!(
                "a perspective light's depth, linearised to eye distance as the depth view \
                 does: black at its near plane ({near}), white at its far plane ({far})"
            ),
            None => "an orthographic light's depth as stored: black at its near plane, white at \
                     its far plane"
                .to_string(),
        };
        println!(
            "wrote {} ({} shadow map: {shown})",
            path.display(),
            size.label()
        );
    }
    if plan.has(ShadowKind::Volume) {
        // The documented treatment of meshes that are not closed, said where it applies.
        for (id, mesh) in scene.meshes.iter().enumerate() {
            let casts = scene.items.iter().any(|i| i.mesh == id && i.casts_shadows);
            let a = Adjacency::of(mesh);
            if casts && !a.is_closed() {
                println!(
                    "shadow volumes: mesh '{}' is not closed ({} open, {} non-manifold \
                     edges): it casts from both sides of each triangle",
                    mesh.name, a.open_edges, a.non_manifold_edges
                );
            }
        }
    }
    if let Some((median, p95)) = frame.frame_time_stats() {
        println!(
            "frame time over {} frames after the first: median {median:.2} ms, p95 {p95:.2} ms (wall, glFinish per frame)",
            frame.frame_ms.len() - 1
        );
        let p = frame.depth_passes;
        println!(
            "shadow maps: {} depth passes drawn, {} patched ({} texels redrawn), {} reused (shadow_cache {}); casters drawn {} of {} offered",
            p.drawn,
            p.patched,
            p.patched_texels,
            p.skipped,
            if settings.shadow_cache { "on" } else { "off" },
            frame.casters.drawn,
            frame.casters.total
        );
        let m = frame.mask_uses;
        if m.written + m.read > 0 {
            println!(
                "shadow mask: written in {} frames, read in {} (each pixel's tests kept while \
                 nothing changes)",
                m.written, m.read
            );
        }
        if frame.volume_pixels > 0 {
            println!(
                "shadow volumes: {} volume pixels passed the depth test in the last frame \
                 ({:.2} per frame pixel)",
                frame.volume_pixels,
                frame.volume_pixels as f64 / f64::from(frame.width * frame.height)
            );
        }
    }
    Ok(())
}

/// The output files: known extensions, folders that exist and accept files, and three
/// different paths (a second write to the same file would replace the first).
fn check_outputs(args: &RenderArgs) -> Result<()> {
    let outputs = [
        ("--out", Some(&args.out)),
        ("--shadow-out", args.shadow_out.as_ref()),
        ("--depth-out", args.depth_out.as_ref()),
    ];
    let given: Vec<_> = outputs
        .iter()
        .filter_map(|(flag, path)| Some((*flag, (*path)?)))
        .collect();
    for (i, (flag, path)) in given.iter().enumerate() {
        check_output_image(flag, path)?;
        if let Some((other, _)) = given[..i].iter().find(|(_, p)| p == path) {
            return Err(Error::file(
                path,
                format!("{flag}: the same file as {other}; expected a different name"),
            ));
        }
    }
    Ok(())
}
