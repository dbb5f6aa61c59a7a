//! The speed-versus-accuracy benchmark: sweep shadow settings over one view of a scene,
//! time each configuration (GPU time per pass, wall time to glFinish) and score it against
//! the exact reference, then find the Pareto front and the cheapest configuration that is
//! accurate enough.

use std::time::Instant;

use serde::Serialize;

mod configs;
mod csv_rows;
pub mod noise;
mod report;
mod timed;
pub mod volumetric;
pub use configs::{configuration_counts, sweep, tutorial_configs, BenchConfig, BiasPreset, Family};
pub use csv_rows::{csv_text, to_csv, Fixed, Shown};
pub use report::{
    against_tutorials, against_tutorials_text, preset_choices, to_markdown, AgainstTutorial,
};
pub use timed::{bench_reference, run, Progress};

use super::reference::{Metrics, SoftMetrics, TransmittanceMetrics};
use super::timing::GpuPassTimes;
use crate::engine::RenderTarget;
use crate::error::Result;
use crate::renderer::{Renderer, Target};
use crate::scene::Scene;
use crate::settings::Fit;
use crate::shadows::{filter_cost, FilterCost};

/// How each configuration is measured.
#[derive(Debug, Clone, Copy)]
pub struct BenchOptions {
    pub width: u32,
    pub height: u32,
    pub warmup: u32,
    pub frames: u32,
    pub supersample: u32,
    pub band: usize,
    /// Rays per pixel of the area truth (a light with a size).
    pub rays: u32,
}

/// Median and 95th percentile.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Stat {
    pub median: f64,
    pub p95: f64,
}

impl Stat {
    pub fn of(values: &[f64]) -> Stat {
        let (median, p95) = super::frame::median_p95(values).unwrap_or((f64::NAN, f64::NAN));
        Stat { median, p95 }
    }
}

/// The measurements of one configuration.
#[derive(Debug, Clone, Serialize)]
pub struct BenchRow {
    pub config: BenchConfig,
    pub wall_ms: Stat,
    /// The shadows' cost: the median over the block of each frame minus a frame without
    /// shadows drawn just before it (the figure a technique can change; the scene pass'
    /// shading is in both).
    pub overhead_ms: f64,
    /// The overhead's spread ([`noise::overhead_spread`]): an overhead not above it is
    /// noise ([`BenchRow::overhead_is_noise`]).
    pub overhead_spread_ms: f64,
    /// The same by the GL timer queries: the median of each frame's two passes' GPU time
    /// minus the frame without shadows' (see the note in [`run`] on software drivers).
    pub overhead_gpu_ms: f64,
    /// Wall time of each pass, with glFinish between them. All timings come from the
    /// quieter of two blocks of frames (see [`run`]).
    pub depth_wall_ms: Stat,
    pub scene_wall_ms: Stat,
    /// GL timer queries per pass (see the note in [`run`] on software drivers).
    pub depth_gpu_ms: Stat,
    pub scene_gpu_ms: Stat,
    /// Shadow-volume pixels that passed the depth test per frame (median; 0 for maps): the
    /// fill the volumes cost.
    pub volume_pixels: u64,
    pub metrics: Metrics,
    /// Against the area truth for a light with a size; for a point light against the hard
    /// reference (its truth: `rays` 0).
    pub soft: SoftMetrics,
    /// Against the transmittance truth, for a scene with translucent casters.
    pub transmittance: Option<TransmittanceMetrics>,
    /// On the Pareto front of (wall median, error).
    pub pareto: bool,
    /// With `bench --motion`: the flicker energy over the path ([`crate::motion`]), the
    /// root mean square of the error's change a frame, in visibility units.
    pub flicker_energy: Option<f64>,
    /// With `bench --motion`: the false flicker over the path, the share of receivers a
    /// frame whose binary state flipped against the truth's.
    pub false_flicker: Option<f64>,
}

impl BenchRow {
    /// Whether the shadow overhead is within its spread of zero (or below it): a figure
    /// the table flags, the plot marks and the `--quality` rule leaves out.
    pub fn overhead_is_noise(&self) -> bool {
        noise::is_noise(self.overhead_ms, self.overhead_spread_ms)
    }

    /// The overhead as the table shows it: "1.72", or "-1.33 (noise, ±0.40)".
    pub fn overhead_text(&self) -> String {
        match self.overhead_is_noise() {
            true => format!(
                "{:.2} (noise, ±{:.2})",
                self.overhead_ms, self.overhead_spread_ms
            ),
            false => format!("{:.2}", self.overhead_ms),
        }
    }

    /// The error the sweep optimises: the misclassified fraction of receiver pixels, or
    /// for a light with a size the visibility's MAE against its area truth (a soft shadow
    /// is right in between, where "misclassified" says nothing).
    pub fn error(&self) -> f64 {
        match self.soft.rays {
            0 => self.metrics.misclassified_rate,
            _ => self.soft.mae,
        }
    }

    /// [`BenchRow::error`] as messages say it: "0.014% misclassified", or for a light with
    /// a size "MAE 0.0050 against the area light".
    pub fn error_text(&self) -> String {
        match self.soft.rays {
            0 => format!("{:.3}% misclassified", self.error() * 100.0),
            _ => format!("MAE {:.4} against the area light", self.error()),
        }
    }

    /// How many times less error `self` has than `other`, as messages say it.
    fn fewer_errors_than(&self, other: &BenchRow) -> String {
        match (self.error() > 0.0, self.soft.rays) {
            (true, 0) => format!(
                "{:.1}x fewer misclassified receivers",
                other.error() / self.error()
            ),
            (true, _) => format!(
                "{:.1}x lower MAE against the area light",
                other.error() / self.error()
            ),
            (false, 0) => "no misclassified receiver at all".to_string(),
            (false, _) => "no error against the area light at all".to_string(),
        }
    }

    /// What [`BenchRow::error`] is, for axes and messages.
    pub fn error_name(&self) -> &'static str {
        match self.soft.rays {
            0 => "misclassified receiver pixels",
            _ => "MAE against the area light",
        }
    }

    /// What the configuration's filter costs: lookups per pixel, passes per frame (a
    /// cascade or a cube face drawn in its own pass counts as one) and blur reads.
    pub fn cost(&self) -> FilterCost {
        let s = &self.config.settings;
        let mut cost = filter_cost(s);
        match self.config.family {
            Family::OneMap | Family::Soft | Family::PointLayered => {}
            Family::Cascades => cost.passes *= s.cascades,
            // Every layer is drawn and read.
            Family::Groups => {
                cost.passes *= s.caster_groups;
                cost.taps *= s.caster_groups;
            }
            Family::PointSixPasses => cost.passes *= 6,
            // Per light a stencil pass of volumes and a lit pass; no map is read.
            Family::Volumes => {
                return FilterCost {
                    taps: 0,
                    passes: 2,
                    blur_taps: 0,
                    bytes_per_texel: 0,
                }
            }
        }
        if matches!(
            self.config.family,
            Family::PointLayered | Family::PointSixPasses
        ) {
            // A cube map: one lookup, or LearnOpenGL's 20 on a disk (shadow_cube.glsl).
            cost.taps = match s.filter.radius() {
                0 => 1,
                _ => 20,
            };
        }
        cost
    }

    /// The cost as the table shows it: "9 / 1 / 4.0", a blur's reads after the passes.
    pub fn cost_label(&self) -> String {
        let c = self.cost();
        let mib = self.map_bytes() as f64 / (1024.0 * 1024.0);
        match c.blur_taps {
            0 => format!("{} / {} / {mib:.1}", c.taps, c.passes),
            b => format!(
                "{} / {} (blur {b} reads a texel) / {mib:.1}",
                c.taps, c.passes
            ),
        }
    }

    /// Bytes of the light's maps (every cascade, every cube face).
    pub fn map_bytes(&self) -> u64 {
        let s = &self.config.settings;
        let layers = match self.config.family {
            Family::OneMap | Family::Soft => 1,
            Family::Cascades => u64::from(s.cascades),
            Family::Groups => u64::from(s.caster_groups),
            Family::PointLayered | Family::PointSixPasses => 6,
            Family::Volumes => 0,
        };
        s.map_size.texels() * layers * u64::from(filter_cost(s).bytes_per_texel)
    }

    /// A short name: "2048 hw2x2 slope cull-none 24", "... fitted" (the box fitted to the
    /// view), "4x1024 ... cascades", "... six-passes".
    pub fn label(&self) -> String {
        self.config.label_with(Some(self.volume_pixels))
    }
}

impl BenchConfig {
    /// [`BenchRow::label`] before the configuration is measured (the volumes' fill unknown).
    pub fn label(&self) -> String {
        self.label_with(None)
    }

    fn label_with(&self, volume_pixels: Option<u64>) -> String {
        let s = &self.settings;
        let (size, suffix) = match self.family {
            Family::OneMap => (s.map_size.to_string(), ""),
            Family::Cascades => (format!("{}x{}", s.cascades, s.map_size), " cascades"),
            Family::Groups => (
                format!("{}x{}", s.caster_groups, s.map_size),
                " caster groups",
            ),
            Family::PointLayered => (s.map_size.to_string(), " cube layered"),
            Family::PointSixPasses => (s.map_size.to_string(), " cube six-passes"),
            Family::Volumes => {
                return match volume_pixels {
                    Some(px) => format!("stencil shadow volumes ({px} volume px/frame)"),
                    None => "stencil shadow volumes".to_string(),
                }
            }
            Family::Soft => (s.map_size.to_string(), ""),
        };
        let fitted = match s.fit {
            Fit::Scene if !matches!(self.family, Family::Cascades | Family::Groups) => " fitted",
            Fit::Scene | Fit::Manual => "",
        };
        format!(
            "{size} {} {} cull-{} {}{fitted}{suffix}",
            s.filter.name(),
            self.bias_preset.name(),
            s.cull.name(),
            s.depth_format.name()
        )
    }
}

/// Times `frames` frames of `renderer`, each pass on its own, into `t`.
pub(super) fn time_passes(
    renderer: &mut Renderer,
    scene: &Scene,
    target: &RenderTarget,
    timer: &GpuPassTimes,
    frames: u32,
    t: &mut Timings,
) -> Result<()> {
    for _ in 0..frames {
        // glFinish after each pass splits the wall time per pass. A software driver like
        // llvmpipe rasterises the depth pass only when its result is needed, so its GPU
        // timer queries charge that work to the scene pass; the split wall times do not.
        let start = Instant::now();
        renderer.render_shadows(scene)?;
        renderer.finish();
        let mid = Instant::now();
        renderer.render_scene(scene, Target::Offscreen(target))?;
        renderer.finish();
        let end = Instant::now();
        t.wall.push(ms(end - start));
        t.depth_wall.push(ms(mid - start));
        t.scene_wall.push(ms(end - mid));
        t.volume_pixels.push(renderer.volume_pixels() as f64);
        let [d, s] = timer.read_ms();
        t.depth_gpu.push(d);
        t.scene_gpu.push(s);
    }
    Ok(())
}

/// Frame and pass times of one block of frames, in milliseconds.
#[derive(Default)]
pub(super) struct Timings {
    pub wall: Vec<f64>,
    /// Frames without shadows, one before each frame of the block.
    pub plain: Vec<f64>,
    /// Their GPU time, both passes together.
    pub plain_gpu: Vec<f64>,
    pub depth_wall: Vec<f64>,
    pub scene_wall: Vec<f64>,
    pub depth_gpu: Vec<f64>,
    pub scene_gpu: Vec<f64>,
    /// Shadow volumes' pixels per frame (0 for maps).
    pub volume_pixels: Vec<f64>,
}

pub(super) fn ms(d: std::time::Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

/// Marks the rows no other row beats on both shadow overhead and error: the quantity the
/// comparison with the tutorials and the presets rank by, so that their picks are on the
/// front the table shows (the frame time carries the scene pass' shading and more of the
/// machine's load). With `bench --motion` the flicker energy is a third term: a row that
/// crawls less is on the front even if another is cheaper and as accurate when still.
pub fn mark_pareto(rows: &mut [BenchRow]) {
    let points: Vec<[f64; 3]> = rows
        .iter()
        .map(|r| [r.overhead_ms, r.error(), r.flicker_energy.unwrap_or(0.0)])
        .collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let p = points[i];
        row.pareto = !points
            .iter()
            .any(|q| q.iter().zip(&p).all(|(a, b)| a <= b) && q.iter().zip(&p).any(|(a, b)| a < b));
    }
}

/// The fastest configuration whose error is at most `target`.
pub fn cheapest_under(rows: &[BenchRow], target: f64) -> Option<&BenchRow> {
    rows.iter()
        .filter(|r| r.error() <= target)
        .min_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::settings::ShadowSettings;

    /// A row with the given frame time, overhead and error.
    fn row(tutorial: Option<&'static str>, wall: f64, overhead: f64, error: f64) -> BenchRow {
        let mut metrics = super::super::reference::compute_metrics(0, 0, &[], &[], None, 0);
        metrics.misclassified_rate = error;
        let stat = Stat {
            median: wall,
            p95: wall,
        };
        BenchRow {
            config: BenchConfig {
                settings: ShadowSettings::default(),
                bias_preset: BiasPreset::Book,
                tutorial,
                family: Family::OneMap,
            },
            wall_ms: stat,
            overhead_ms: overhead,
            overhead_spread_ms: 0.0,
            overhead_gpu_ms: overhead,
            depth_wall_ms: stat,
            scene_wall_ms: stat,
            depth_gpu_ms: stat,
            scene_gpu_ms: stat,
            metrics,
            pareto: false,
            volume_pixels: 0,
            soft: super::super::reference::compute_soft_metrics(0, 0, &[], &[], 0),
            transmittance: None,
            flicker_energy: None,
            false_flicker: None,
        }
    }

    #[test]
    fn tutorials_are_compared_at_equal_error_and_equal_overhead() {
        let rows = vec![
            row(Some("learnopengl"), 7.0, 2.0, 0.010),
            row(None, 5.5, 0.5, 0.020),  // cheaper but worse
            row(None, 6.0, 0.8, 0.009),  // cheapest at equal error
            row(None, 6.9, 1.9, 0.0005), // most accurate at equal overhead
            row(None, 9.0, 4.0, 0.0),    // more accurate, too expensive
        ];
        let a = &against_tutorials(&rows)[0];
        assert_eq!(a.at_equal_error.unwrap().overhead_ms, 0.8);
        assert_eq!(a.at_equal_overhead.unwrap().error(), 0.0005);
        let text = against_tutorials_text(&rows);
        assert!(text.contains("0.40 of the tutorial's overhead"), "{text}");
        assert!(
            text.contains("20.0x fewer misclassified receivers"),
            "{text}"
        );

        let [low, medium, high] = preset_choices(&rows);
        assert_eq!(low.1.unwrap().overhead_ms, 0.5);
        assert_eq!(medium.1.unwrap().overhead_ms, 0.8);
        assert_eq!(high.1.unwrap().overhead_ms, 1.9);
    }

    #[test]
    fn an_overhead_within_its_noise_is_flagged_and_no_preset_rests_on_it() {
        let mut noisy = row(None, 5.0, -1.33, 0.005);
        noisy.overhead_spread_ms = 0.4;
        let mut rows = vec![
            row(Some("learnopengl"), 7.0, 2.0, 0.010),
            noisy,
            row(None, 5.5, 0.5, 0.020),
            row(None, 6.0, 0.8, 0.009),
        ];
        mark_pareto(&mut rows);
        assert!(rows[1].overhead_is_noise() && !rows[2].overhead_is_noise());
        let table = to_markdown(&rows);
        assert!(table.contains("| -1.33 (noise, ±0.40) |"), "{table}");
        assert!(table.contains(report::NOISE_NOTE), "{table}");
        // The least overhead is the noise row's; low takes the least overhead above noise,
        // and medium does not take the noise row for its -1.33 ms within a 1 ms budget.
        let [low, medium, high] = preset_choices(&rows);
        assert_eq!(low.1.unwrap().overhead_ms, 0.5);
        assert_eq!(medium.1.unwrap().overhead_ms, 0.8);
        assert_eq!(high.1.unwrap().overhead_ms, 0.8);
        // A tutorial overhead lost in noise gives no budget.
        rows[0].overhead_spread_ms = 3.0;
        let [low, medium, high] = preset_choices(&rows);
        assert!(low.1.is_some() && medium.1.is_none() && high.1.is_none());
        // Without noise the table carries no flag and no note.
        let clean = to_markdown(&rows[2..]);
        assert!(!clean.contains("noise"), "{clean}");
    }

    #[test]
    fn the_tutorials_picks_are_on_the_front_the_table_shows() {
        // Frame time and overhead rank these differently (the scene pass varies).
        let mut rows = vec![
            row(Some("book"), 28.0, 7.5, 0.026),
            row(None, 7.5, 1.3, 0.005), // fastest frame, not the least overhead
            row(None, 7.7, 1.2, 0.012), // least overhead at equal error
            row(None, 11.2, 4.9, 0.0),  // least error at equal overhead
            row(None, 8.0, 5.0, 0.0003), // beaten on overhead and error
        ];
        mark_pareto(&mut rows);
        let a = &against_tutorials(&rows)[0];
        let (error, overhead) = (a.at_equal_error.unwrap(), a.at_equal_overhead.unwrap());
        assert_eq!(error.overhead_ms, 1.2);
        assert_eq!(overhead.overhead_ms, 4.9);
        assert!(error.pareto && overhead.pareto);
        assert!(!rows[4].pareto);
        let table = to_markdown(&rows);
        let lines: Vec<&str> = table.lines().filter(|l| l.contains("(Pareto)")).collect();
        assert_eq!(lines.len(), 3, "{table}");
        // Ranked by overhead, as the text is.
        let overheads: Vec<&str> = lines
            .iter()
            .map(|l| l.split(" | ").nth(2).unwrap())
            .collect();
        assert_eq!(overheads, ["1.20", "1.30", "4.90"], "{table}");
    }

    #[test]
    fn with_motion_a_row_that_crawls_less_stays_on_the_front() {
        let mut rows = vec![
            row(None, 7.0, 1.0, 0.010),
            row(None, 8.0, 2.0, 0.010), // dearer, as accurate when still
        ];
        mark_pareto(&mut rows);
        assert!(rows[0].pareto && !rows[1].pareto);
        rows[0].flicker_energy = Some(0.04);
        rows[1].flicker_energy = Some(0.03); // but steadier
        mark_pareto(&mut rows);
        assert!(rows[0].pareto && rows[1].pareto);
        rows[1].flicker_energy = Some(0.04);
        mark_pareto(&mut rows);
        assert!(!rows[1].pareto, "beaten on every term");
        let table = to_markdown(&rows);
        assert!(
            table.contains("flicker energy | false flicker a frame"),
            "{table}"
        );
        assert!(table.contains(" 0.0400 | n/a |"), "{table}");
    }

    #[test]
    fn a_sized_lights_comparison_speaks_of_its_area_mae_not_of_misclassified_pixels() {
        let soft = |tutorial, wall, overhead, mae| {
            let mut r = row(tutorial, wall, overhead, 0.5);
            r.soft.rays = 64;
            r.soft.mae = mae;
            r
        };
        let rows = vec![
            soft(Some("learnopengl"), 7.0, 2.0, 0.010),
            soft(None, 6.0, 0.8, 0.009),
            soft(None, 6.9, 1.9, 0.0025),
        ];
        assert_eq!(rows[1].error_text(), "MAE 0.0090 against the area light");
        let text = against_tutorials_text(&rows);
        assert!(
            text.contains("(MAE 0.0090 against the area light)"),
            "{text}"
        );
        assert!(
            text.contains("4.0x lower MAE against the area light"),
            "{text}"
        );
        assert!(!text.contains("misclassif"), "{text}");
        assert_eq!(
            row(None, 1.0, 1.0, 0.00014).error_text(),
            "0.014% misclassified"
        );
    }
}
