//! The CSV files the bench writes (`bench.csv`; `scale.csv` and `scale-fit.csv` use the
//! same helpers): each line is a typed row written by the `csv` crate, and the row's field
//! names are the header.

use std::fmt::Display;

use serde::{Serialize, Serializer};

use super::BenchRow;
use crate::settings::{BeyondFar, BiasMode, Cull, DepthFormat, Filter, MapSize, Wrap};

/// A number shown with `P` decimals.
pub struct Fixed<const P: usize>(pub f64);

impl<const P: usize> Serialize for Fixed<P> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&format_args!("{:.*}", P, self.0))
    }
}

/// A value shown as `Display` shows it (a float's shortest form, `0.05` or `4`).
pub struct Shown<T>(pub T);

impl<T: Display> Serialize for Shown<T> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(&self.0)
    }
}

/// The rows as CSV text, a header line first (taken from the row's field names).
pub fn csv_text<R: Serialize>(rows: impl IntoIterator<Item = R>) -> String {
    let mut out = csv::Writer::from_writer(Vec::new());
    for row in rows {
        // Writing to memory fails only on a row the format cannot hold (none of ours).
        out.serialize(row).expect("a CSV row of plain values");
    }
    let bytes = out.into_inner().expect("writing to memory cannot fail");
    String::from_utf8(bytes).expect("CSV of UTF-8 text")
}

/// One line of `bench.csv`. The `area_*`, `light_bleed_rate` and `penumbra_*` columns are
/// against the area truth, or with `area_rays` 0 against the hard reference of a point
/// light; `taps`: shadow-map reads per fragment, [`Filter::lookups`].
#[derive(Serialize)]
struct BenchLine {
    tutorial: &'static str,
    family: String,
    cascades: u32,
    caster_groups: u32,
    point_pass: String,
    map_size: Shown<MapSize>,
    filter: Filter,
    bias_preset: &'static str,
    bias_mode: BiasMode,
    bias: Shown<f32>,
    bias_min: Shown<f32>,
    normal_offset: Shown<f32>,
    polygon_offset_factor: Shown<f32>,
    polygon_offset_units: Shown<f32>,
    cull: Cull,
    depth_format: DepthFormat,
    wrap: Wrap,
    beyond_far: BeyondFar,
    wall_ms_median: Fixed<4>,
    wall_ms_p95: Fixed<4>,
    overhead_ms: Fixed<4>,
    depth_wall_ms_median: Fixed<4>,
    scene_wall_ms_median: Fixed<4>,
    depth_gpu_ms_median: Fixed<4>,
    depth_gpu_ms_p95: Fixed<4>,
    scene_gpu_ms_median: Fixed<4>,
    scene_gpu_ms_p95: Fixed<4>,
    receivers: usize,
    misclassified_rate: Fixed<6>,
    false_shadow_rate: Fixed<6>,
    false_light_rate: Fixed<6>,
    misclassified_outside_band_rate: Fixed<6>,
    false_shadow_outside_band: usize,
    false_light_outside_band: usize,
    /// `nan` without a supersampled reference.
    mae: String,
    pareto: bool,
    volume_pixels: u64,
    area_rays: usize,
    area_mae: Fixed<6>,
    light_bleed_rate: Fixed<6>,
    area_false_shadow_rate: Fixed<6>,
    penumbra_width_px: Fixed<3>,
    penumbra_width_truth_px: Fixed<3>,
    penumbra_width_error_px: Fixed<3>,
    taps: u32,
    passes: u32,
    blur_taps: u32,
    map_bytes: u64,
    /// With `bench --motion` (else `-`): flicker energy, the root mean square of the
    /// error's change a frame (visibility units; [`crate::motion`]).
    flicker_energy: String,
    /// With `bench --motion` (else `-`): false flicker, a share of receivers a frame.
    false_flicker: String,
    /// The shadow overhead by the GL timer queries ([`BenchRow::overhead_gpu_ms`]).
    overhead_gpu_ms: Fixed<4>,
    /// The overhead's spread ([`BenchRow::overhead_spread_ms`]).
    overhead_spread_ms: Fixed<4>,
    /// Whether the overhead is within its spread of zero ([`BenchRow::overhead_is_noise`]).
    overhead_noise: bool,
}

/// A lowercased `Debug` name, as the first tables spelled families and point passes.
fn lower(v: impl std::fmt::Debug) -> String {
    format!("{v:?}").to_lowercase()
}

impl BenchLine {
    fn of(r: &BenchRow) -> BenchLine {
        let s = &r.config.settings;
        let (m, a, cost) = (&r.metrics, &r.soft, r.cost());
        BenchLine {
            tutorial: r.config.tutorial.unwrap_or("-"),
            family: lower(r.config.family),
            cascades: s.cascades,
            caster_groups: s.caster_groups,
            point_pass: lower(s.point_pass),
            map_size: Shown(s.map_size),
            filter: s.filter,
            bias_preset: r.config.bias_preset.name(),
            bias_mode: s.bias_mode,
            bias: Shown(s.bias),
            bias_min: Shown(s.bias_min),
            normal_offset: Shown(s.normal_offset),
            polygon_offset_factor: Shown(s.polygon_offset[0]),
            polygon_offset_units: Shown(s.polygon_offset[1]),
            cull: s.cull,
            depth_format: s.depth_format,
            wrap: s.wrap,
            beyond_far: s.beyond_far,
            wall_ms_median: Fixed(r.wall_ms.median),
            wall_ms_p95: Fixed(r.wall_ms.p95),
            overhead_ms: Fixed(r.overhead_ms),
            depth_wall_ms_median: Fixed(r.depth_wall_ms.median),
            scene_wall_ms_median: Fixed(r.scene_wall_ms.median),
            depth_gpu_ms_median: Fixed(r.depth_gpu_ms.median),
            depth_gpu_ms_p95: Fixed(r.depth_gpu_ms.p95),
            scene_gpu_ms_median: Fixed(r.scene_gpu_ms.median),
            scene_gpu_ms_p95: Fixed(r.scene_gpu_ms.p95),
            receivers: m.receivers,
            misclassified_rate: Fixed(m.misclassified_rate),
            false_shadow_rate: Fixed(m.false_shadow_rate),
            false_light_rate: Fixed(m.false_light_rate),
            misclassified_outside_band_rate: Fixed(m.misclassified_outside_band_rate),
            false_shadow_outside_band: m.false_shadow_outside_band,
            false_light_outside_band: m.false_light_outside_band,
            mae: m.mae.map_or("nan".to_string(), |v| format!("{v:.6}")),
            pareto: r.pareto,
            volume_pixels: r.volume_pixels,
            area_rays: a.rays,
            area_mae: Fixed(a.mae),
            light_bleed_rate: Fixed(a.light_bleed_rate),
            area_false_shadow_rate: Fixed(a.false_shadow_rate),
            penumbra_width_px: Fixed(a.penumbra_width_px),
            penumbra_width_truth_px: Fixed(a.penumbra_width_truth_px),
            penumbra_width_error_px: Fixed(a.penumbra_width_error_px),
            taps: cost.taps,
            passes: cost.passes,
            blur_taps: cost.blur_taps,
            map_bytes: r.map_bytes(),
            flicker_energy: r.flicker_energy.map_or("-".into(), |f| format!("{f:.6}")),
            false_flicker: r.false_flicker.map_or("-".into(), |f| format!("{f:.6}")),
            overhead_gpu_ms: Fixed(r.overhead_gpu_ms),
            overhead_spread_ms: Fixed(r.overhead_spread_ms),
            overhead_noise: r.overhead_is_noise(),
        }
    }
}

/// `bench.csv`: one line per configuration.
pub fn to_csv(rows: &[BenchRow]) -> String {
    csv_text(rows.iter().map(BenchLine::of))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_written_under_a_header_of_their_field_names() {
        #[derive(Serialize)]
        struct Line {
            name: &'static str,
            ms: Fixed<4>,
            bias: Shown<f32>,
            filter: Filter,
            pareto: bool,
        }
        let line = |name, ms, bias| Line {
            name,
            ms: Fixed(ms),
            bias: Shown(bias),
            filter: Filter::Hardware2x2,
            pareto: true,
        };
        let text = csv_text([line("a b", 1.0, 0.05), line("c", 0.123456, 0.0)]);
        assert_eq!(
            text,
            "name,ms,bias,filter,pareto\na b,1.0000,0.05,hw2x2,true\nc,0.1235,0,hw2x2,true\n"
        );
        // A field holding the separator is quoted, so the columns stay put.
        assert!(csv_text([line("x,y", 0.0, 1.0)]).contains("\"x,y\",0.0000,1,"));
    }
}
