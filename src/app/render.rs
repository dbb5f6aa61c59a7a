//! `shadowmap render`: headless frames through EGL, written as PNGs.

use std::time::Instant;

use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::render_frames;
use shadowmap::image_data::save_grey_png;
use shadowmap::light_slots::ShadowKind;
use shadowmap::Result;

use super::cli::RenderArgs;

pub fn run(args: &RenderArgs) -> Result<()> {
    let start = Instant::now();
    let mut scene = args.scene.load()?;
    let settings = args.settings.apply(&scene)?;
    let (width, height) = args.scene.size(&scene);
    if let Some(path) = &args.depth_out {
        if ShadowKind::of(scene.light(), &settings) != ShadowKind::Map {
            return Err(shadowmap::Error::Invalid(format!(
                "--depth-out {}: the first light has no 2D depth map (it has a cube map, \
                 cascades or casts no shadow): use --show-depth-map to see its map",
                path.display()
            )));
        }
    }
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &settings)?;
    let outputs = Outputs {
        visibility: args.shadow_out.is_some(),
        gbuffer: false,
    };
    let frame = match args.hud {
        true => super::hud::render_frames_with_hud(
            &context,
            &mut scene,
            &settings,
            args.settings.step.as_deref(),
            (width, height),
            args.frames,
            outputs,
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
    frame.colour.save_png(&args.out)?;
    if let (Some(path), Some(image)) = (&args.shadow_out, frame.visibility_image()) {
        image.save_png(path)?;
    }
    if let Some(path) = &args.depth_out {
        if let Some((size, grey)) = frame.depth_grey() {
            save_grey_png(path, size, size, &grey)?;
        }
    }
    println!(
        "wrote {} ({}x{}, scene {}, {}, {}) in {:.0} ms",
        args.out.display(),
        width,
        height,
        scene.name,
        scene.light().describe(),
        settings.summary(),
        start.elapsed().as_secs_f64() * 1000.0
    );
    if let Some((median, p95)) = frame.frame_time_stats() {
        println!(
            "frame time over {} frames after the first: median {median:.2} ms, p95 {p95:.2} ms (wall, glFinish per frame)",
            frame.frame_ms.len() - 1
        );
    }
    Ok(())
}
