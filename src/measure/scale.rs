//! `bench --scale`: how each pass' time grows with the work. One axis at a time moves away
//! from a base point — caster triangles, frame pixels, map texels, lights, cascades — over a
//! generated scene (spheres of rising detail scattered over a floor, written as a scene file
//! and loaded like any other), and a least-squares line on log-log axes gives each pass'
//! exponent: 1 is linear in the work, below 1 a fixed cost still dominates.

use std::time::Instant;

use serde::Serialize;

use super::bench::{csv_text, ms, time_passes, Fixed, Shown, Stat, Timings};
use super::timing::GpuPassTimes;
use crate::engine::{Gl, Outputs, RenderTarget};
use crate::error::Result;
use crate::renderer::{Renderer, Target};
use crate::scene::Scene;

/// What one sweep varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Axis {
    /// Caster triangles (64 spheres, each subdivided more finely).
    Triangles,
    /// Frame pixels (320 x 180 to 3840 x 2160).
    Pixels,
    /// Shadow-map texels (one side squared).
    MapTexels,
    /// Directional lights, each with its own map.
    Lights,
    /// Cascades of the one light.
    Cascades,
}

impl Axis {
    pub const ALL: [Axis; 5] = [
        Axis::Triangles,
        Axis::Pixels,
        Axis::MapTexels,
        Axis::Lights,
        Axis::Cascades,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Axis::Triangles => "triangles",
            Axis::Pixels => "pixels",
            Axis::MapTexels => "map-texels",
            Axis::Lights => "lights",
            Axis::Cascades => "cascades",
        }
    }

    /// The axis' label on the plot.
    pub fn description(self) -> &'static str {
        match self {
            Axis::Triangles => "caster triangles",
            Axis::Pixels => "frame pixels",
            Axis::MapTexels => "shadow-map texels",
            Axis::Lights => "lights (one map each)",
            Axis::Cascades => "cascades",
        }
    }
}

/// One point of the sweep: the scene and frame to time.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ScalePoint {
    pub axis: Axis,
    /// Caster triangles asked for (the scene has about this many: see [`ScaleRow`]).
    pub triangles: u32,
    pub width: u32,
    pub height: u32,
    pub map_size: u32,
    pub lights: u32,
    pub cascades: u32,
}

/// The spheres scattered over the floor.
const SPHERES: u32 = 64;

/// The lights' directions, the first the one that gets cascades.
const DIRECTIONS: [[f32; 3]; 4] = [
    [0.4, 1.0, 0.3],
    [-0.5, 1.0, 0.2],
    [0.2, 1.0, -0.5],
    [-0.3, 1.0, -0.4],
];

/// Each axis' values: triangles, frame sizes, map sides, light and cascade counts.
type Values = (
    &'static [u32],
    &'static [(u32, u32)],
    &'static [u32],
    &'static [u32],
);

/// The points to time: the base, then each axis on its own. `quick` is a small sweep (two
/// points an axis, small frames) for tests; the full one runs 1e3 to 1e6 triangles,
/// 320 x 180 to 3840 x 2160, maps of 256^2 up to the driver's largest (at most 8192^2),
/// 1 to 4 lights and 1 to 4 cascades.
pub fn plan(quick: bool, max_texture_size: u32) -> Vec<ScalePoint> {
    let base = match quick {
        true => ScalePoint {
            axis: Axis::Triangles,
            triangles: 1_000,
            width: 320,
            height: 180,
            map_size: 512,
            lights: 1,
            cascades: 1,
        },
        false => ScalePoint {
            axis: Axis::Triangles,
            triangles: 10_000,
            width: 640,
            height: 360,
            map_size: 1024,
            lights: 1,
            cascades: 1,
        },
    };
    let (triangles, sizes, maps, counts): Values = match quick {
        true => (
            &[1_000, 10_000],
            &[(320, 180), (640, 360)],
            &[256, 512],
            &[1, 2],
        ),
        false => (
            &[1_000, 3_000, 10_000, 30_000, 100_000, 300_000, 1_000_000],
            &[
                (320, 180),
                (640, 360),
                (1280, 720),
                (1920, 1080),
                (2560, 1440),
                (3840, 2160),
            ],
            &[256, 512, 1024, 2048, 4096, 8192],
            &[1, 2, 3, 4],
        ),
    };
    let mut out: Vec<ScalePoint> = triangles
        .iter()
        .map(|&triangles| ScalePoint { triangles, ..base })
        .collect();
    out.extend(sizes.iter().map(|&(width, height)| ScalePoint {
        axis: Axis::Pixels,
        width,
        height,
        ..base
    }));
    out.extend(
        maps.iter()
            .filter(|&&m| m <= max_texture_size)
            .map(|&map_size| ScalePoint {
                axis: Axis::MapTexels,
                map_size,
                ..base
            }),
    );
    out.extend(counts.iter().map(|&lights| ScalePoint {
        axis: Axis::Lights,
        lights,
        ..base
    }));
    out.extend(counts.iter().map(|&cascades| ScalePoint {
        axis: Axis::Cascades,
        cascades,
        ..base
    }));
    out
}

impl ScalePoint {
    /// The sphere detail `[segments, rings]` closest to the triangles asked for: a sphere
    /// of `s` segments and `s / 2 + 1` rings has about `s^2` triangles.
    pub fn sphere_detail(&self) -> [u32; 2] {
        let each = (self.triangles as f64 / SPHERES as f64).max(1.0);
        let segments = (each.sqrt().round() as u32).clamp(4, 512);
        [segments, (segments / 2 + 1).clamp(2, 256)]
    }

    /// The generated scene as a scene file: a 60 x 60 floor, 64 spheres scattered over it
    /// (a fixed seed), the lights from above at different azimuths, each with a box that
    /// holds the whole floor, and a camera that sees all of it.
    pub fn scene_toml(&self) -> String {
        let [segments, rings] = self.sphere_detail();
        let mut text = format!(
            "name = \"scale\"\nsize = [{w}, {h}]\nclear_colour = [0.55, 0.7, 0.9]\n\
             ambient = [0.3, 0.3, 0.3]\nspecular_power = 16.0\n\n\
             [camera]\nposition = [0.0, 38.0, 48.0]\nrotation = [40.0, 0.0, 0.0]\nfov = 60.0\n\
             near = 0.5\nfar = 200.0\n\n\
             [shadow]\nmap_size = {m}\nfilter = \"pcf3x3\"\nbias_mode = \"slope\"\nbias = 0.005\n\
             bias_min = 0.0005\nnormal_offset = 1.0\ncull = \"none\"\nlight_view = \"look-at\"\n\
             cascades = {c}\nshadow_cache = false\n\n\
             [[item]]\nname = \"floor\"\nmesh = \"plane\"\nposition = [0.0, 0.0, 0.0]\nscale = 30.0\n\
             colour = [0.7, 0.7, 0.65, 1.0]\nreflectance = 0.1\n\n\
             [[item]]\nname = \"ball\"\nmesh = \"sphere\"\ndetail = [{segments}, {rings}]\n\
             position = [0.0, 1.0, 0.0]\nscale = 1.0\ncolour = [0.8, 0.3, 0.2, 1.0]\n\
             reflectance = 0.5\nscatter = {{ count = {SPHERES}, seed = 16, area = [-26.0, 26.0, \
             -26.0, 26.0], scale_min = [0.6, 0.6, 0.6], scale_max = [1.4, 1.4, 1.4] }}\n",
            w = self.width,
            h = self.height,
            m = self.map_size,
            c = self.cascades,
        );
        for d in DIRECTIONS.iter().take(self.lights as usize) {
            text.push_str(&format!(
                "\n[[lights]]\ncolour = [1.0, 1.0, 1.0]\nintensity = {:.3}\n\
                 direction = [{}, {}, {}]\nshadow_pos_mult = 40.0\n\
                 ortho = {{ left = -45.0, right = 45.0, bottom = -45.0, top = 45.0, near = 1.0, \
                 far = 90.0 }}\n",
                1.0 / self.lights as f32,
                d[0],
                d[1],
                d[2]
            ));
        }
        text
    }

    pub fn scene(&self) -> Result<Scene> {
        crate::scene::file::parse(
            &self.scene_toml(),
            std::path::Path::new("<generated scale scene>"),
            None,
        )
    }

    /// How much work the axis counts at this point.
    pub fn work(&self, triangles: u64) -> f64 {
        match self.axis {
            Axis::Triangles => triangles as f64,
            Axis::Pixels => self.width as f64 * self.height as f64,
            Axis::MapTexels => self.map_size as f64 * self.map_size as f64,
            Axis::Lights => self.lights as f64,
            Axis::Cascades => self.cascades as f64,
        }
    }
}

/// How long each point is timed: frames enough for `budget_ms` of frames, within
/// `min_frames..=max_frames` (a 1e6-triangle frame on a software driver takes a good part
/// of a second, a small one a few milliseconds).
#[derive(Debug, Clone, Copy)]
pub struct ScaleOptions {
    pub budget_ms: f64,
    pub min_frames: u32,
    pub max_frames: u32,
}

impl ScaleOptions {
    pub fn new(quick: bool) -> ScaleOptions {
        match quick {
            true => ScaleOptions {
                budget_ms: 100.0,
                min_frames: 2,
                max_frames: 5,
            },
            false => ScaleOptions {
                budget_ms: 3000.0,
                min_frames: 3,
                max_frames: 100,
            },
        }
    }
}

/// The measurements of one point.
#[derive(Debug, Clone, Serialize)]
pub struct ScaleRow {
    pub point: ScalePoint,
    /// Caster triangles in the scene (every item casts).
    pub triangles: u64,
    pub work: f64,
    pub frames: u32,
    /// Bytes of shadow maps.
    pub map_bytes: u64,
    pub frame_wall_ms: Stat,
    pub depth_wall_ms: Stat,
    pub scene_wall_ms: Stat,
    pub depth_gpu_ms: Stat,
    pub scene_gpu_ms: Stat,
}

/// Times every point twice, the second time in reverse order, and keeps each point's
/// quieter block (the lower median frame): a burst of load from elsewhere on the machine
/// then spoils at most one of them, as in the bench. `progress` is told after each block.
pub fn run(
    gl: &Gl,
    points: &[ScalePoint],
    opts: &ScaleOptions,
    mut progress: impl FnMut(&ScaleRow),
) -> Result<Vec<ScaleRow>> {
    let mut rows: Vec<Option<ScaleRow>> = vec![None; points.len()];
    let order = (0..points.len()).chain((0..points.len()).rev());
    for i in order {
        let row = time_point(gl, &points[i], opts)?;
        progress(&row);
        let keep = match rows[i].take() {
            Some(old) if old.frame_wall_ms.median <= row.frame_wall_ms.median => old,
            _ => row,
        };
        rows[i] = Some(keep);
    }
    Ok(rows.into_iter().flatten().collect())
}

/// One block of frames of one point, on a renderer of its own.
fn time_point(gl: &Gl, point: &ScalePoint, opts: &ScaleOptions) -> Result<ScaleRow> {
    let scene = point.scene()?;
    let triangles: u64 = scene
        .items
        .iter()
        .filter(|i| i.casts_shadows)
        .map(|i| scene.meshes[i.mesh].indices.len() as u64 / 3)
        .sum();
    let mut renderer = Renderer::new(gl, &scene, &scene.shadow)?;
    let timer = std::rc::Rc::new(GpuPassTimes::new(gl)?);
    renderer.set_hooks(timer.clone());
    let target = RenderTarget::new(gl, point.width, point.height, Outputs::default())?;
    // One untimed frame (programs, uploads), then one timed to choose the frame count.
    renderer.render(&scene, Target::Offscreen(&target))?;
    renderer.finish();
    let start = Instant::now();
    renderer.render(&scene, Target::Offscreen(&target))?;
    renderer.finish();
    let one = ms(start.elapsed()).max(0.01);
    let frames = ((opts.budget_ms / one).ceil() as u32).clamp(opts.min_frames, opts.max_frames);
    let mut t = Timings::default();
    time_passes(&mut renderer, &scene, &target, &timer, frames, &mut t)?;
    Ok(ScaleRow {
        point: *point,
        triangles,
        work: point.work(triangles),
        frames,
        map_bytes: renderer.shadow_memory().1,
        frame_wall_ms: Stat::of(&t.wall),
        depth_wall_ms: Stat::of(&t.depth_wall),
        scene_wall_ms: Stat::of(&t.scene_wall),
        depth_gpu_ms: Stat::of(&t.depth_gpu),
        scene_gpu_ms: Stat::of(&t.scene_gpu),
    })
}

/// Which time a fit is of.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Pass {
    Depth,
    Scene,
    Frame,
}

impl Pass {
    pub const ALL: [Pass; 3] = [Pass::Depth, Pass::Scene, Pass::Frame];

    pub fn name(self) -> &'static str {
        match self {
            Pass::Depth => "depth pass",
            Pass::Scene => "scene pass",
            Pass::Frame => "frame",
        }
    }

    /// The pass' median wall time in a row.
    pub fn of(self, row: &ScaleRow) -> f64 {
        match self {
            Pass::Depth => row.depth_wall_ms.median,
            Pass::Scene => row.scene_wall_ms.median,
            Pass::Frame => row.frame_wall_ms.median,
        }
    }
}

/// A fitted power law `ms = coefficient * work^exponent` for one pass along one axis.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PowerFit {
    pub axis: Axis,
    pub pass: Pass,
    pub exponent: f64,
    pub coefficient: f64,
    /// How much of the log-time variance the line explains.
    pub r2: f64,
    pub points: usize,
    /// Fitted over the upper half of the axis only (where fixed costs no longer hide the
    /// growth), not over all of it.
    pub upper: bool,
}

/// Least squares on `(ln x, ln y)`; `None` with fewer than two distinct positive `x`.
pub fn fit_power(points: &[(f64, f64)]) -> Option<(f64, f64, f64)> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let syy: f64 = logs.iter().map(|p| (p.1 - my).powi(2)).sum();
    if logs.len() < 2 || sxx <= 0.0 {
        return None;
    }
    let slope = sxy / sxx;
    let r2 = match syy > 0.0 {
        true => (sxy * sxy) / (sxx * syy),
        false => 1.0,
    };
    Some((slope, (my - slope * mx).exp(), r2))
}

/// Every axis' fit for every pass over all its points, and for axes of six points or
/// more also over its upper half (axes with fewer than two points are left out).
pub fn fits(rows: &[ScaleRow]) -> Vec<PowerFit> {
    let mut out = Vec::new();
    for axis in Axis::ALL {
        let on: Vec<&ScaleRow> = rows.iter().filter(|r| r.point.axis == axis).collect();
        for upper in [false, true] {
            let from = match (upper, on.len()) {
                (false, _) => 0,
                (true, n) if n >= 6 => n / 2,
                (true, _) => continue,
            };
            for pass in Pass::ALL {
                let points: Vec<(f64, f64)> =
                    on[from..].iter().map(|r| (r.work, pass.of(r))).collect();
                if let Some((exponent, coefficient, r2)) = fit_power(&points) {
                    out.push(PowerFit {
                        axis,
                        pass,
                        exponent,
                        coefficient,
                        r2,
                        points: points.len(),
                        upper,
                    });
                }
            }
        }
    }
    out
}

/// One line of `scale.csv`.
#[derive(Serialize)]
struct ScaleLine {
    axis: Axis,
    work: Shown<f64>,
    triangles: u64,
    width: u32,
    height: u32,
    pixels: u64,
    map_size: u32,
    lights: u32,
    cascades: u32,
    frames: u32,
    map_bytes: u64,
    frame_wall_ms_median: Fixed<4>,
    frame_wall_ms_p95: Fixed<4>,
    depth_wall_ms_median: Fixed<4>,
    depth_wall_ms_p95: Fixed<4>,
    scene_wall_ms_median: Fixed<4>,
    scene_wall_ms_p95: Fixed<4>,
    depth_gpu_ms_median: Fixed<4>,
    scene_gpu_ms_median: Fixed<4>,
}

/// `scale.csv`: one line per point.
pub fn to_csv(rows: &[ScaleRow]) -> String {
    csv_text(rows.iter().map(|r| {
        let p = &r.point;
        ScaleLine {
            axis: p.axis,
            work: Shown(r.work),
            triangles: r.triangles,
            width: p.width,
            height: p.height,
            pixels: u64::from(p.width) * u64::from(p.height),
            map_size: p.map_size,
            lights: p.lights,
            cascades: p.cascades,
            frames: r.frames,
            map_bytes: r.map_bytes,
            frame_wall_ms_median: Fixed(r.frame_wall_ms.median),
            frame_wall_ms_p95: Fixed(r.frame_wall_ms.p95),
            depth_wall_ms_median: Fixed(r.depth_wall_ms.median),
            depth_wall_ms_p95: Fixed(r.depth_wall_ms.p95),
            scene_wall_ms_median: Fixed(r.scene_wall_ms.median),
            scene_wall_ms_p95: Fixed(r.scene_wall_ms.p95),
            depth_gpu_ms_median: Fixed(r.depth_gpu_ms.median),
            scene_gpu_ms_median: Fixed(r.scene_gpu_ms.median),
        }
    }))
}

/// One line of `scale-fit.csv`.
#[derive(Serialize)]
struct FitLine {
    axis: Axis,
    pass: &'static str,
    /// `all` the points, or the `upper-half`.
    range: &'static str,
    exponent: Fixed<4>,
    coefficient_ms: Shown<String>,
    r2: Fixed<4>,
    points: usize,
}

/// `scale-fit.csv`: one line per fit.
pub fn fits_to_csv(fits: &[PowerFit]) -> String {
    csv_text(fits.iter().map(|f| FitLine {
        axis: f.axis,
        pass: f.pass.name(),
        range: if f.upper { "upper-half" } else { "all" },
        exponent: Fixed(f.exponent),
        coefficient_ms: Shown(format!("{:.6e}", f.coefficient)),
        r2: Fixed(f.r2),
        points: f.points,
    }))
}

/// A Markdown table of the exponents: one row per axis, one column per pass; each cell
/// the fit over all points, then over the upper half where there is one.
pub fn fits_to_markdown(fits: &[PowerFit]) -> String {
    let mut out = String::from(
        "| work | depth pass exponent | scene pass exponent | frame exponent |\n|---|---|---|---|\n",
    );
    for axis in Axis::ALL {
        // "all points / upper half" where both were fitted.
        let cell = |pass: Pass| {
            let of = |upper: bool| {
                fits.iter()
                    .find(|f| f.axis == axis && f.pass == pass && f.upper == upper)
            };
            match (of(false), of(true)) {
                (Some(a), Some(u)) => format!("{:.2} / {:.2}", a.exponent, u.exponent),
                (Some(a), None) => format!("{:.2}", a.exponent),
                _ => "-".to_string(),
            }
        };
        if fits.iter().any(|f| f.axis == axis) {
            out.push_str(&format!(
                "| {} | {} | {} | {} |\n",
                axis.description(),
                cell(Pass::Depth),
                cell(Pass::Scene),
                cell(Pass::Frame)
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_power_law_is_fitted_exactly() {
        let points: Vec<(f64, f64)> = [1.0, 10.0, 100.0, 1000.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(0.75)))
            .collect();
        let (e, c, r2) = fit_power(&points).unwrap();
        assert!((e - 0.75).abs() < 1e-9, "{e}");
        assert!((c - 3.0).abs() < 1e-9, "{c}");
        assert!((r2 - 1.0).abs() < 1e-9, "{r2}");
        assert!(fit_power(&[(2.0, 1.0), (2.0, 3.0)]).is_none());
        assert!(fit_power(&[(2.0, 1.0)]).is_none());
    }

    #[test]
    fn the_generated_scenes_have_the_work_asked_for() {
        for point in plan(false, 16384) {
            let scene = point.scene().unwrap();
            let triangles: u64 = scene
                .items
                .iter()
                .map(|i| scene.meshes[i.mesh].indices.len() as u64 / 3)
                .sum();
            let asked = point.triangles as f64;
            assert!(
                (triangles as f64 / asked - 1.0).abs() < 0.3,
                "{triangles} triangles for {asked}"
            );
            assert_eq!(scene.lights.len() as u32, point.lights);
            assert_eq!(scene.shadow.cascades, point.cascades);
            assert_eq!(scene.size, [point.width, point.height]);
        }
    }
}
