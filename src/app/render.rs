//! `shadowmap render`: headless frames through EGL, written as PNGs.

use std::path::Path;
use std::time::Instant;

use image::ColorType;

use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::{render_frames, Frame};
use shadowmap::image_data::encode_png;
use shadowmap::output::{check_output_image, write_files};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::shadows::volumes::Adjacency;
use shadowmap::shadows::ShadowKind;
use shadowmap::{Error, Result, Scene, ShadowSettings};

use super::cli::RenderArgs;
use super::hud::{inset_rect, render_frames_with_overlays, Overlays};
use super::quality::choose_for_target;

pub fn run(args: &RenderArgs) -> Result<()> {
    let start = Instant::now();
    // A step is shown as `steps` shows it, unless a flag picks the view or the light's size.
    let (mut scene, mut settings) = args.scene.load_with(&args.settings)?;
    args.motion.start(&mut scene)?;
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
    check_depth_out(args, &plan)?;
    if args.inset {
        warn_about_inset(&scene, &plan, width, height);
    }
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &settings)?;
    args.scene.check_size(context.gl(), &scene)?;
    let frame = render_frame(&context, args, &mut scene, &settings, (width, height))?;
    write_images(args, &frame)?;
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
    if let Some(path) = &scene.motion {
        let moved = super::motion::describe(path);
        println!("motion: {moved}; the image is frame {}", path.frame);
    }
    if let Some(path) = &args.shadow_out {
        println!(
            "wrote {} (what the shadow test said per pixel: white lit, black shadowed)",
            path.display()
        );
    }
    if let (Some(path), Some((size, _))) = (&args.depth_out, &frame.depth_map) {
        let linear = frame.depth_linear;
        print_depth_out(path, &size.label(), frame.depth_perspective, linear);
    }
    if let Some(range) = frame.depth_view_range {
        let shown = match settings.show_depth_map {
            true => "the depth view",
            false => "the inset",
        };
        println!("{shown}: {}", range.words());
    }
    if plan.has(ShadowKind::Volume) {
        print_open_meshes(&scene);
    }
    if !shadowmap::engine::instances::instancing() {
        println!(
            "instancing off (SHADOWMAP_INSTANCING=off): every item drawn with a call of its \
             own, through its uniforms"
        );
    }
    let gl_renderer = shadowmap::engine::check::renderer_name(context.gl());
    print_frame_stats(&frame, &settings, &gl_renderer);
    Ok(())
}

/// `--depth-out` needs a 2D depth map on the first light.
fn check_depth_out(args: &RenderArgs, plan: &ShadowPlan) -> Result<()> {
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
    Ok(())
}

/// `--inset` is legal but would do nothing without a map or room: say so once, naming the
/// flag.
fn warn_about_inset(scene: &Scene, plan: &ShadowPlan, width: u32, height: u32) {
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

/// The frames, with the HUD and the inset drawn over them when asked for.
fn render_frame(
    context: &HeadlessContext,
    args: &RenderArgs,
    scene: &mut Scene,
    settings: &ShadowSettings,
    (width, height): (u32, u32),
) -> Result<Frame> {
    let outputs = Outputs {
        visibility: args.shadow_out.is_some(),
        gbuffer: false,
    };
    let overlays = Overlays {
        hud: args.hud,
        inset: args.inset,
    };
    match overlays.hud || overlays.inset {
        true => render_frames_with_overlays(
            context,
            scene,
            settings,
            args.settings.step.as_deref(),
            (width, height),
            args.frames,
            outputs,
            overlays,
        ),
        false => render_frames(
            context.gl(),
            scene,
            settings,
            width,
            height,
            args.frames,
            outputs,
        ),
    }
}

/// Every image encoded first, then written as one: a failed write leaves none of them.
fn write_images(args: &RenderArgs, frame: &Frame) -> Result<()> {
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
    write_files(&files)
}

/// What the `--depth-out` image's greys mean.
fn print_depth_out(path: &Path, size: &str, perspective: Option<(f32, f32)>, linear: bool) {
    let shown = match perspective {
        Some((near, far)) if linear => format!(
            "a perspective light's depth as stored, linear in distance along its axis: black \
             at its near plane ({near}), white at its far plane ({far})"
        ),
        Some((near, far)) => format!(
            "a perspective light's depth, linearised to eye distance as the depth view \
             does: black at its near plane ({near}), white at its far plane ({far})"
        ),
        None => "an orthographic light's depth as stored: black at its near plane, white at \
                 its far plane"
            .to_string(),
    };
    println!("wrote {} ({size} shadow map: {shown})", path.display());
}

/// The documented treatment of meshes that are not closed, said where it applies.
fn print_open_meshes(scene: &Scene) {
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

/// Frame times (wall and GPU) and what the shadow passes did, for a run of more than one
/// frame; `gl_renderer` names the driver the GPU times are from.
fn print_frame_stats(frame: &Frame, settings: &ShadowSettings, gl_renderer: &str) {
    let Some((median, p95)) = frame.frame_time_stats() else {
        return;
    };
    // The slowest frame after the first: a hitch (lazy work in frame 2) shows here, where
    // a p95 over few frames hides or includes it by rounding.
    let (at, slowest) = (frame.frame_ms.iter().enumerate().skip(1))
        .fold((0, 0.0), |a, (i, &ms)| if ms > a.1 { (i, ms) } else { a });
    println!(
        "frame time over {} frames after the first: median {median:.2} ms, p95 {p95:.2} ms, \
         slowest {slowest:.2} ms (frame {}, {:.2} x the median) (wall, glFinish per frame)",
        frame.frame_ms.len() - 1,
        at + 1,
        slowest / median
    );
    if let Some(g) = frame.gpu_time_stats() {
        println!(
            "GPU time over {} frames after the first: median {:.3} ms a frame (depth passes \
             {:.3} ms, scene pass {:.3} ms), p95 {:.3} ms (timer queries; {gl_renderer})",
            frame.gpu_ms.len() - 1,
            g.frame,
            g.depth,
            g.scene,
            g.frame_p95
        );
    }
    let p = frame.depth_passes;
    println!(
        "shadow-map passes over {} frames: {} drawn whole, {} patched where casters moved ({} \
         texels redrawn), {} kept unchanged (shadow cache {}); {} of {} casters drawn",
        frame.frame_ms.len(),
        p.drawn,
        p.patched,
        p.patched_texels,
        p.skipped,
        if settings.shadow_cache { "on" } else { "off" },
        frame.casters.drawn,
        frame.casters.total
    );
    let v = frame.volumetric_draws;
    if v.drawn + v.kept > 0 {
        println!(
            "translucent maps over {} frames: {} drawn, {} kept unchanged",
            frame.frame_ms.len(),
            v.drawn,
            v.kept
        );
    }
    let l = frame.vertex_light;
    if l.captured + l.kept > 0 {
        println!(
            "vertex light over {} frames: {} captured, {} kept",
            frame.frame_ms.len(),
            l.captured,
            l.kept
        );
    }
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
