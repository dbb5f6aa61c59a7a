//! The demo without a display: the same scene rendered headless to a picture, and the one
//! line that says why and where.

use std::path::{Path, PathBuf};

use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::{render_frames, visibility_rgba};
use shadowmap::image_data::ImageData;
use shadowmap::output::check_output_image;
use shadowmap::{Error, Result, Scene, ShadowSettings};

use super::super::cli::DemoArgs;
use super::super::hud::{render_frames_with_overlays, Overlays};

/// Where the no-display fallback writes its picture.
const FALLBACK_IMAGE: &str = "shadowmap-demo.png";

/// The one line the no-display fallback prints: why, what was written, how to get a window.
pub fn fallback_message(
    reason: &str,
    scene: &str,
    frames: u32,
    path: &Path,
    replaced: bool,
) -> String {
    format!(
        "No display for a window ({reason}): rendered {frames} frame{} of the {scene} scene \
         headless to {}{} instead. {}",
        if frames == 1 { "" } else { "s" },
        path.display(),
        if replaced {
            " (replacing the file there)"
        } else {
            ""
        },
        shadowmap::engine::context::no_display_hint(),
    )
}

/// No display: render what the window would have shown headless, the same way with or
/// without `--exit-after-frames` (N frames, the scene animating between them, else one),
/// to `--screenshot` if given, else [`FALLBACK_IMAGE`]; the path is checked before any
/// rendering.
pub(super) fn headless_fallback(
    args: &DemoArgs,
    mut scene: Scene,
    settings: &ShadowSettings,
    reason: &str,
) -> Result<()> {
    let path = args
        .screenshot
        .clone()
        .unwrap_or_else(|| PathBuf::from(FALLBACK_IMAGE));
    check_output_image(
        match args.screenshot {
            Some(_) => "--screenshot",
            None => "the no-display fallback",
        },
        &path,
    )?;
    let frames = match args.exit_after_frames {
        None => 1,
        Some(n) => u32::try_from(n.max(1)).map_err(|_| {
            Error::Invalid(format!(
                "--exit-after-frames {n}: without a display the frames are rendered headless; \
                 expected at most {}",
                u32::MAX
            ))
        })?,
    };
    let (w, h) = args.scene.size(&scene);
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, settings)?;
    args.scene.check_size(context.gl(), &scene)?;
    let overlays = Overlays {
        hud: !args.no_hud,
        inset: args.inset,
    };
    let outputs = Outputs {
        // A depth-map view has no shadow test to show: the map is shown as it is.
        visibility: args.show_visibility && !settings.show_depth_map,
        gbuffer: false,
    };
    let frame = match overlays.hud || overlays.inset {
        true => render_frames_with_overlays(
            &context,
            &mut scene,
            settings,
            args.settings.step.as_deref(),
            (w, h),
            frames,
            outputs,
            overlays,
        )?,
        false => render_frames(context.gl(), &mut scene, settings, w, h, frames, outputs)?,
    };
    let replaced = std::fs::metadata(&path).is_ok_and(|m| m.is_file());
    // `--show-visibility`: the visibility view's picture, as the window shows it.
    match &frame.visibility {
        Some(v) => ImageData {
            width: frame.width,
            height: frame.height,
            rgba: visibility_rgba(v, super::frame::VISIBILITY_OFF),
        }
        .save_png(&path)?,
        None => frame.colour.save_png(&path)?,
    }
    let shown = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
    println!(
        "{}",
        fallback_message(reason, &scene.name, frames, &shown, replaced)
    );
    Ok(())
}
