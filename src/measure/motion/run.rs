//! A path scored frame by frame: each frame traced and drawn, and frame i-1's shadows drawn
//! again at frame i's pixels (its light, and its camera as the one the light's box or
//! cascades are fitted to), so both are compared at the same world points.

use super::{Drawn, FlickerMeter, MotionFrame, MotionScore};
use crate::compare::{compute_reference, render_visibility, CompareOptions, Reference};
use crate::engine::Gl;
use crate::error::Result;
use crate::frame::Frame;
use crate::scene::motion::MotionPath;
use crate::scene::Scene;
use crate::settings::ShadowSettings;

/// Scores `frames` frames of `path` from `scene` under `settings`; `each` sees every frame
/// with its reference (for pictures).
pub fn score_path(
    gl: &Gl,
    scene: &Scene,
    settings: &ShadowSettings,
    (path, frames): (&MotionPath, u32),
    opts: &CompareOptions,
    mut each: impl FnMut(&Frame, &Reference),
) -> Result<MotionScore> {
    let mut meter = FlickerMeter::default();
    for i in 0..frames {
        let mut s = scene.clone();
        path.pose(&mut s, i);
        let reference = compute_reference(gl, &s, settings, opts)?;
        let frame = render_visibility(gl, &s, settings, opts.width, opts.height, opts.light)?;
        each(&frame, &reference);
        let rendered = frame.visibility.clone().unwrap_or_default();
        let here = MotionFrame::of_reference(&reference, &s.camera);
        let before = match i {
            0 => None,
            _ => Some(previous_here(gl, scene, path, i, &here, settings, opts)?),
        };
        meter.push_after(before, here, rendered);
    }
    Ok(meter.finish(path.kind.name()))
}

/// Frame `i - 1`'s shadows at frame `i`'s pixels, with its truth (traced again only when
/// the light moved).
fn previous_here(
    gl: &Gl,
    scene: &Scene,
    path: &MotionPath,
    i: u32,
    here: &MotionFrame,
    settings: &ShadowSettings,
    opts: &CompareOptions,
) -> Result<Drawn> {
    let (mut now, mut before) = (scene.clone(), scene.clone());
    path.pose(&mut now, i);
    path.pose(&mut before, i - 1);
    before.fit_camera = Some(before.camera);
    before.camera = now.camera;
    let truth = match before.lights == now.lights {
        true => here.clone(),
        false => {
            let reference = compute_reference(gl, &before, settings, opts)?;
            MotionFrame::of_reference(&reference, &now.camera)
        }
    };
    let frame = render_visibility(gl, &before, settings, opts.width, opts.height, opts.light)?;
    Ok((truth, frame.visibility.unwrap_or_default()))
}
