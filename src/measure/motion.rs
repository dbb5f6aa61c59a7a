//! Flicker: how much a receiver's shadow changes from one frame to the next where the
//! truth's does not (or the reverse), at the same world point.
//!
//! Each receiver of frame i is carried back through frame i-1's camera to the pixel that
//! saw the same world point there, so the camera's own motion is not counted. Two figures:
//!
//! - the **flicker energy** ([`energy`]): the root mean square over the matched points and
//!   frame pairs of the change of the continuous error, `Δe = (v_i - v*_i) - (v_i-1 -
//!   v*_i-1)`, `v` the filtered visibility, `v*` the truth (the area light's where the
//!   light has a size). A viewer sees crawl as the size of the jumps: a filter that spreads
//!   one flip over three steps of a third has a third of the energy, where any count of
//!   flips or sum of changes calls it the same;
//! - the **false flicker**: the share of receivers whose binary state (visibility under one
//!   half) changed without the truth's, or the reverse: (rendered changed) XOR (truth
//!   changed). It is blind to a symmetric filter, whose average crosses one half where the
//!   centre tap does, and is kept beside the energy as the count of flips.

use glam::{DMat4, DVec3, DVec4};
use serde::Serialize;

use super::compare::Reference;
use crate::reference::RefPixel;
use crate::scene::Camera;

/// One frame of a path as the metric needs it: where each pixel's surface is, what the
/// truth said there, and the camera that saw it.
#[derive(Debug, Clone)]
pub struct MotionFrame {
    pub width: usize,
    pub height: usize,
    /// World position per pixel (NaN off geometry).
    pub world: Vec<DVec3>,
    /// World to clip space of the frame's camera.
    pub view_proj: DMat4,
    /// Per pixel: `Some(shadowed)` from the hard truth where it is a receiver, else `None`.
    pub truth: Vec<Option<bool>>,
    /// Per pixel: the truth's visibility in [0, 1] where it is a receiver (the area light's
    /// where the light has a size, else the hard truth's 0 or 1), else `None`.
    pub truth_visibility: Vec<Option<f32>>,
}

/// Per frame: its error against the truth and, from the second frame on, its flicker.
#[derive(Debug, Clone, Copy, Serialize, PartialEq)]
pub struct FrameFlicker {
    pub frame: u32,
    /// Misclassified receivers of this frame against its truth.
    pub misclassified: f64,
    /// The mean |v - v*| of this frame against its continuous truth (the area light's
    /// where the light has a size): the still error the energy stands beside.
    pub mae: f64,
    /// Receivers matched to the previous frame (0 for frame 0).
    pub matched: usize,
    /// Share of the matched receivers whose error state changed (None for frame 0).
    pub false_flicker: Option<f64>,
    /// Share whose truth changed.
    pub truth_change: Option<f64>,
    /// Share whose rendered state changed.
    pub flicker: Option<f64>,
    /// The root mean square of the error's change over the matched receivers.
    pub energy: Option<f64>,
}

/// The path's figures: the means over the frame pairs, and each frame's.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct MotionScore {
    pub path: String,
    /// sqrt(mean over matched points and frame pairs of Δe²), in visibility units.
    pub energy: f64,
    /// sqrt(mean over points of max(0, Σ Δv² - Σ Δv*²) over the pairs): what the frame
    /// changed beyond the truth's own steps.
    pub excess_energy: f64,
    /// sqrt(mean of Δv*²): the truth's own change, what a correct renderer must change.
    pub truth_energy: f64,
    pub false_flicker: f64,
    pub truth_change: f64,
    pub frames: Vec<FrameFlicker>,
}

impl MotionScore {
    /// From per-frame figures and the energies: the shares' means over the frames that
    /// have a previous one.
    pub fn of(path: &str, frames: Vec<FrameFlicker>, energies: Energies) -> MotionScore {
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
            energy: energies.energy,
            excess_energy: energies.excess,
            truth_energy: energies.truth,
            false_flicker: mean(|f| f.false_flicker),
            truth_change: mean(|f| f.truth_change),
            frames,
        }
    }

    /// The line `compare --motion` prints.
    pub fn line(&self) -> String {
        format!(
            "motion: {} frames, {}: flicker energy {:.4} (beyond the truth's own steps {:.4}; \
             the truth's own {:.4}); false flicker {:.3}% of receivers a frame (the truth's \
             own change {:.3}%)",
            self.frames.len(),
            self.path,
            self.energy,
            self.excess_energy,
            self.truth_energy,
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
    /// The frame of a traced reference seen by `camera`; its continuous truth is the area
    /// light's where the light has a size.
    pub fn of_reference(reference: &Reference, camera: &Camera) -> MotionFrame {
        let n = reference.hard.len();
        let continuous = reference
            .area
            .as_ref()
            .map_or(&reference.hard, |a| &a.pixels);
        MotionFrame {
            width: reference.width as usize,
            height: reference.height as usize,
            world: (0..n).map(|i| reference.world_position(i)).collect(),
            view_proj: view_projection(camera, reference.width, reference.height),
            truth: reference.hard.iter().map(truth_state).collect(),
            truth_visibility: continuous.iter().map(truth_visibility).collect(),
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

    /// The pixel of this frame that saw the same surface as pixel `i` of `next`.
    fn same_point(&self, next: &MotionFrame, i: usize) -> Option<usize> {
        let w = next.world[i];
        let j = self.pixel_of(w)?;
        // Another surface there (an occluder came between, or the point left the frame).
        (self.world[j].distance(w) <= self.footprint(j) + 1e-9).then_some(j)
    }
}

/// Shadowed (true) or lit at a receiver of the truth.
fn truth_state(p: &RefPixel) -> Option<bool> {
    p.receiver.then_some(p.visibility < 0.5)
}

/// The truth's visibility at a receiver.
fn truth_visibility(p: &RefPixel) -> Option<f32> {
    p.receiver.then_some(p.visibility)
}

/// Shadowed (true) or lit where the frame drew a receiver.
pub fn rendered_state(v: Option<f32>) -> Option<bool> {
    rendered_visibility(v).map(|v| v < 0.5)
}

/// The frame's visibility where it drew a receiver.
fn rendered_visibility(v: Option<f32>) -> Option<f32> {
    v.filter(|v| v.is_finite())
}

/// One frame pair's figures: the binary shares over the receivers matched with a hard
/// truth, and each matched point's changes for the energy.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PairScore {
    pub matched: usize,
    pub false_flicker: f64,
    pub truth_change: f64,
    pub flicker: f64,
    /// Per matched point with a continuous truth: (its pixel in the later frame, Δv, Δv*).
    pub changes: Vec<(usize, f64, f64)>,
}

impl PairScore {
    /// The root mean square of Δe = Δv - Δv* over this pair's points.
    pub fn energy(&self) -> f64 {
        match self.changes.len() {
            0 => 0.0,
            n => {
                let sum: f64 = self.changes.iter().map(|(_, v, t)| (v - t) * (v - t)).sum();
                (sum / n as f64).sqrt()
            }
        }
    }
}

/// Frame `next`'s flicker against `prev` (each given with the visibility it rendered):
/// each receiver of `next` whose world point `prev` saw (the same surface, within one
/// pixel's footprint there) is a matched receiver.
pub fn score_pair(
    prev: &MotionFrame,
    prev_rendered: &[Option<f32>],
    next: &MotionFrame,
    next_rendered: &[Option<f32>],
) -> PairScore {
    let (mut matched, mut false_flips, mut truth_flips, mut flips) = (0usize, 0usize, 0, 0);
    let mut changes = Vec::new();
    for (i, v1) in next_rendered.iter().enumerate().take(next.world.len()) {
        let Some(v1) = rendered_visibility(*v1) else {
            continue;
        };
        let Some(j) = prev.same_point(next, i) else {
            continue;
        };
        let Some(v0) = rendered_visibility(prev_rendered[j]) else {
            continue;
        };
        if let (Some(t0), Some(t1)) = (prev.truth_visibility[j], next.truth_visibility[i]) {
            let dv = f64::from(v1) - f64::from(v0);
            changes.push((i, dv, f64::from(t1) - f64::from(t0)));
        }
        let (Some(t0), Some(t1)) = (prev.truth[j], next.truth[i]) else {
            continue;
        };
        let (r0, r1) = (v0 < 0.5, v1 < 0.5);
        matched += 1;
        false_flips += usize::from((r0 != r1) != (t0 != t1));
        truth_flips += usize::from(t0 != t1);
        flips += usize::from(r0 != r1);
    }
    let share = |n: usize| match matched {
        0 => 0.0,
        m => n as f64 / m as f64,
    };
    PairScore {
        matched,
        false_flicker: share(false_flips),
        truth_change: share(truth_flips),
        flicker: share(flips),
        changes,
    }
}

/// Misclassified receivers of one frame (shadow state against the truth's).
pub fn misclassified(frame: &MotionFrame, rendered: &[Option<f32>]) -> f64 {
    let (mut n, mut wrong) = (0usize, 0usize);
    for (t, r) in frame.truth.iter().zip(rendered) {
        if let (Some(t), Some(r)) = (t, rendered_state(*r)) {
            n += 1;
            wrong += usize::from(*t != r);
        }
    }
    match n {
        0 => 0.0,
        n => wrong as f64 / n as f64,
    }
}

/// The mean |v - v*| of one frame over the receivers of its continuous truth.
pub fn mean_absolute_error(frame: &MotionFrame, rendered: &[Option<f32>]) -> f64 {
    let (mut n, mut sum) = (0usize, 0.0);
    for (t, r) in frame.truth_visibility.iter().zip(rendered) {
        if let (Some(t), Some(r)) = (t, rendered_visibility(*r)) {
            n += 1;
            sum += f64::from((r - t).abs());
        }
    }
    match n {
        0 => 0.0,
        n => sum / n as f64,
    }
}

/// A frame and the visibility drawn at its pixels.
pub type Drawn = (MotionFrame, Vec<Option<f32>>);

/// Scores a path frame by frame: keeps the previous frame only, so a long path needs the
/// memory of two (and one set of sums a pixel).
#[derive(Default)]
pub struct FlickerMeter {
    prev: Option<Drawn>,
    frames: Vec<FrameFlicker>,
    sums: energy::PointSums,
}

impl FlickerMeter {
    /// Adds the next frame (its truth and the visibility rendered) and returns its figures.
    pub fn push(&mut self, frame: MotionFrame, rendered: Vec<Option<f32>>) -> FrameFlicker {
        let prev = self.prev.take();
        self.push_after(prev, frame, rendered)
    }

    /// [`FlickerMeter::push`] against a given previous frame: the previous frame's shadows
    /// drawn at this frame's pixels (its light and fitting camera, this frame's view), so
    /// the points match pixel for pixel.
    pub fn push_after(
        &mut self,
        prev: Option<Drawn>,
        frame: MotionFrame,
        rendered: Vec<Option<f32>>,
    ) -> FrameFlicker {
        let index = self.frames.len() as u32;
        let mut f = FrameFlicker {
            frame: index,
            misclassified: misclassified(&frame, &rendered),
            mae: mean_absolute_error(&frame, &rendered),
            matched: 0,
            false_flicker: None,
            truth_change: None,
            flicker: None,
            energy: None,
        };
        if let Some((prev, prev_rendered)) = &prev {
            let pair = score_pair(prev, prev_rendered, &frame, &rendered);
            f.matched = pair.matched;
            f.false_flicker = Some(pair.false_flicker);
            f.truth_change = Some(pair.truth_change);
            f.flicker = Some(pair.flicker);
            f.energy = Some(pair.energy());
            self.sums.add(frame.world.len(), &pair.changes);
        }
        self.prev = Some((frame, rendered));
        self.frames.push(f);
        f
    }

    pub fn finish(self, path: &str) -> MotionScore {
        MotionScore::of(path, self.frames, self.sums.energies())
    }
}

mod energy;
mod run;
#[cfg(test)]
mod tests;

pub use energy::Energies;
pub use run::score_path;
