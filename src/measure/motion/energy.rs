//! The energies of a path, summed point by point over its frame pairs.
//!
//! A point is a pixel of the later frame of each pair. On a path whose camera holds still
//! (a light sweep, or keyframes of the light alone) each pixel is one world point all
//! along; where the camera moves, the truth holds still (the shadows are fixed in the
//! world) and the excess is the frame's own change, pixel by pixel.

use serde::Serialize;

/// Per pixel over the pairs so far: Σ Δe², Σ Δv², Σ Δv*² and how many pairs matched it.
#[derive(Debug, Clone, Default)]
pub struct PointSums {
    points: Vec<Sums>,
}

#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    error: f64,
    rendered: f64,
    truth: f64,
    pairs: u32,
}

/// A path's three energies, in visibility units (0: nothing changed; 1: every point
/// jumped from lit to shadowed every frame).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct Energies {
    /// sqrt(Σ Δe² / Σ pairs): the error's change, pooled over points and pairs.
    pub energy: f64,
    /// sqrt(Σ_p max(0, Σ Δv² - Σ Δv*²) / Σ pairs): not charging the truth's own steps.
    pub excess: f64,
    /// sqrt(Σ Δv*² / Σ pairs): the truth's own steps.
    pub truth: f64,
}

impl PointSums {
    /// Adds one pair's changes, (pixel, Δv, Δv*) each, in a frame of `pixels` pixels.
    pub fn add(&mut self, pixels: usize, changes: &[(usize, f64, f64)]) {
        if self.points.len() < pixels {
            self.points.resize(pixels, Sums::default());
        }
        for &(i, dv, dt) in changes {
            let p = &mut self.points[i];
            p.error += (dv - dt) * (dv - dt);
            p.rendered += dv * dv;
            p.truth += dt * dt;
            p.pairs += 1;
        }
    }

    /// The energies over every point and pair added (0 where none matched).
    pub fn energies(&self) -> Energies {
        let pairs: f64 = self.points.iter().map(|p| f64::from(p.pairs)).sum();
        if pairs == 0.0 {
            return Energies::default();
        }
        let rms = |f: fn(&Sums) -> f64| (self.points.iter().map(f).sum::<f64>() / pairs).sqrt();
        Energies {
            energy: rms(|p| p.error),
            excess: rms(|p| (p.rendered - p.truth).max(0.0)),
            truth: rms(|p| p.truth),
        }
    }
}
