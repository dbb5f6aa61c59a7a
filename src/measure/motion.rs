//! False flicker: how often a receiver's shadow state changes from one frame to the next
//! while the truth's does not (or the reverse), at the same world point.
//!
//! Each receiver of frame i is carried back through frame i-1's camera to the pixel that
//! saw the same world point there, so the camera's own motion is not counted. A receiver
//! is shadowed where the visibility is under one half. Its error state is
//! `rendered != truth`; a false flip is a change of that state between the two frames:
//! (rendered changed) XOR (truth changed). The truth's own change is reported beside it.

use glam::{DMat4, DVec3, DVec4};
use serde::Serialize;

use super::compare::Reference;
use crate::reference::RefPixel;
use crate::scene::Camera;

/// One frame of a path as the metric needs it: where each pixel's surface is, what the
/// frame and the truth said there, and the camera that saw it.
#[derive(Debug, Clone)]
pub struct MotionFrame {
    pub width: usize,
    pub height: usize,
    /// World position per pixel (NaN off geometry).
    pub world: Vec<DVec3>,
    /// World to clip space of the frame's camera.
    pub view_proj: DMat4,
    /// Per pixel: `Some(shadowed)` from the truth where it is a receiver, else `None`.
    pub truth: Vec<Option<bool>>,
}

/// Per frame: its error against the truth and, from the second frame on, its flicker.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct FrameFlicker {
    pub frame: u32,
    /// Misclassified receivers of this frame against its truth.
    pub misclassified: f64,
    /// Receivers matched to the previous frame (0 for frame 0).
    pub matched: usize,
    /// Share of the matched receivers whose error state changed (None for frame 0).
    pub false_flicker: Option<f64>,
    /// Share whose truth changed.
    pub truth_change: Option<f64>,
    /// Share whose rendered state changed.
    pub flicker: Option<f64>,
}

/// The path's figures: the means over the frame pairs, and each frame's.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MotionScore {
    pub path: String,
    pub false_flicker: f64,
    pub truth_change: f64,
    pub frames: Vec<FrameFlicker>,
}

impl MotionScore {
    /// From per-frame figures: the means over the frames that have a previous one.
    pub fn of(path: &str, frames: Vec<FrameFlicker>) -> MotionScore {
        let pairs: Vec<_> = frames
            .iter()
            .filter(|f| f.false_flicker.is_some())
            .collect();
        let mean = |g: fn(&FrameFlicker) -> Option<f64>| match pairs.len() {
            0 => 0.0,
            n => pairs.iter().filter_map(|f| g(f)).sum::<f64>() / n as f64,
        };
        MotionScore {
            path: path.to_string(),
            false_flicker: mean(|f| f.false_flicker),
            truth_change: mean(|f| f.truth_change),
            frames,
        }
    }

    /// The line `compare --motion` prints.
    pub fn line(&self) -> String {
        format!(
            "motion: {} frames, {}: false flicker {:.3}% of receivers a frame (the truth's own \
             change {:.3}%)",
            self.frames.len(),
            self.path,
            self.false_flicker * 100.0,
            self.truth_change * 100.0
        )
    }
}

/// World to clip space for `camera` drawing a `width` x `height` frame (double precision,
/// as the positions far from the origin need).
pub fn view_projection(camera: &Camera, width: u32, height: u32) -> DMat4 {
    camera.projection_matrix(width, height).as_dmat4() * camera.view_matrix64()
}

impl MotionFrame {
    /// The frame of a traced reference seen by `camera`.
    pub fn of_reference(reference: &Reference, camera: &Camera) -> MotionFrame {
        let n = reference.hard.len();
        MotionFrame {
            width: reference.width as usize,
            height: reference.height as usize,
            world: (0..n).map(|i| reference.world_position(i)).collect(),
            view_proj: view_projection(camera, reference.width, reference.height),
            truth: reference.hard.iter().map(truth_state).collect(),
        }
    }

    /// The pixel of this frame that sees `world`, if it is in the frame.
    fn pixel_of(&self, world: DVec3) -> Option<usize> {
        let c = self.view_proj * DVec4::new(world.x, world.y, world.z, 1.0);
        if c.w <= 0.0 {
            return None;
        }
        let x = (c.x / c.w * 0.5 + 0.5) * self.width as f64;
        let y = (0.5 - c.y / c.w * 0.5) * self.height as f64;
        let inside =
            (0.0..self.width as f64).contains(&x) && (0.0..self.height as f64).contains(&y);
        inside.then(|| y as usize * self.width + x as usize)
    }

    /// How far pixel `i`'s surface reaches: along each axis the nearer neighbour's
    /// distance (so an edge between two surfaces does not widen it), summed.
    fn footprint(&self, i: usize) -> f64 {
        let p = self.world[i];
        let (x, y) = (i % self.width, i / self.width);
        let d = |j: Option<usize>| j.map_or(f64::INFINITY, |j| self.world[j].distance(p));
        let nearer = |a: f64, b: f64| match a.min(b) {
            m if m.is_finite() => m,
            _ => 0.0,
        };
        let left = (x > 0).then(|| i - 1);
        let right = (x + 1 < self.width).then(|| i + 1);
        let up = (y > 0).then(|| i - self.width);
        let down = (y + 1 < self.height).then(|| i + self.width);
        nearer(d(left), d(right)) + nearer(d(up), d(down))
    }
}

/// Shadowed (true) or lit at a receiver of the truth.
fn truth_state(p: &RefPixel) -> Option<bool> {
    p.receiver.then_some(p.visibility < 0.5)
}

/// Shadowed (true) or lit where the frame drew a receiver.
pub fn rendered_state(v: Option<f32>) -> Option<bool> {
    v.filter(|v| v.is_finite()).map(|v| v < 0.5)
}

/// Frame `next`'s flicker against `prev`: each receiver of `next` whose world point `prev`
/// saw (the same surface, within one pixel's footprint there) is a matched receiver.
pub fn score_pair(
    prev: &MotionFrame,
    prev_rendered: &[Option<bool>],
    next: &MotionFrame,
    next_rendered: &[Option<bool>],
) -> (usize, f64, f64, f64) {
    let (mut matched, mut false_flips, mut truth_flips, mut flips) = (0usize, 0usize, 0, 0);
    for (i, w) in next.world.iter().enumerate() {
        let (Some(t1), Some(r1)) = (next.truth[i], next_rendered[i]) else {
            continue;
        };
        let Some(j) = prev.pixel_of(*w) else {
            continue;
        };
        let (Some(t0), Some(r0)) = (prev.truth[j], prev_rendered[j]) else {
            continue;
        };
        // Another surface there (an occluder came between, or the point left the frame).
        if prev.world[j].distance(*w) > prev.footprint(j) + 1e-9 {
            continue;
        }
        matched += 1;
        false_flips += usize::from((r0 != r1) != (t0 != t1));
        truth_flips += usize::from(t0 != t1);
        flips += usize::from(r0 != r1);
    }
    let share = |n: usize| match matched {
        0 => 0.0,
        m => n as f64 / m as f64,
    };
    (
        matched,
        share(false_flips),
        share(truth_flips),
        share(flips),
    )
}

/// Misclassified receivers of one frame (shadow state against the truth's).
pub fn misclassified(frame: &MotionFrame, rendered: &[Option<bool>]) -> f64 {
    let (mut n, mut wrong) = (0usize, 0usize);
    for (t, r) in frame.truth.iter().zip(rendered) {
        if let (Some(t), Some(r)) = (t, r) {
            n += 1;
            wrong += usize::from(t != r);
        }
    }
    match n {
        0 => 0.0,
        n => wrong as f64 / n as f64,
    }
}

/// Scores a path frame by frame: keeps the previous frame only, so a long path needs the
/// memory of two.
#[derive(Default)]
pub struct FlickerMeter {
    prev: Option<(MotionFrame, Vec<Option<bool>>)>,
    frames: Vec<FrameFlicker>,
}

impl FlickerMeter {
    /// Adds the next frame (its truth and what was rendered) and returns its figures.
    pub fn push(&mut self, frame: MotionFrame, rendered: Vec<Option<bool>>) -> FrameFlicker {
        let prev = self.prev.take();
        self.push_after(prev, frame, rendered)
    }

    /// [`FlickerMeter::push`] against a given previous frame: the previous frame's shadows
    /// drawn at this frame's pixels (its light and fitting camera, this frame's view), so
    /// the points match pixel for pixel.
    pub fn push_after(
        &mut self,
        prev: Option<(MotionFrame, Vec<Option<bool>>)>,
        frame: MotionFrame,
        rendered: Vec<Option<bool>>,
    ) -> FrameFlicker {
        let index = self.frames.len() as u32;
        let mut f = FrameFlicker {
            frame: index,
            misclassified: misclassified(&frame, &rendered),
            matched: 0,
            false_flicker: None,
            truth_change: None,
            flicker: None,
        };
        if let Some((prev, prev_rendered)) = &prev {
            let (matched, false_flicker, truth, flicker) =
                score_pair(prev, prev_rendered, &frame, &rendered);
            f.matched = matched;
            f.false_flicker = Some(false_flicker);
            f.truth_change = Some(truth);
            f.flicker = Some(flicker);
        }
        self.prev = Some((frame, rendered));
        self.frames.push(f);
        f
    }

    pub fn finish(self, path: &str) -> MotionScore {
        MotionScore::of(path, self.frames)
    }
}

mod run;
#[cfg(test)]
mod tests;

pub use run::score_path;
