//! The speed-versus-accuracy benchmark: sweep shadow settings over one view of a scene,
//! time each configuration (GPU time per pass, wall time to glFinish) and score it against
//! the exact reference, then find the Pareto front and the cheapest configuration that is
//! accurate enough.

use std::time::Instant;

use glam::Vec3;
use serde::Serialize;

mod csv_rows;
pub mod volumetric;
pub use csv_rows::{csv_text, to_csv, Fixed, Shown};

use super::compare::{compute_reference, CompareOptions, Reference};
use super::reference::{Metrics, SoftMetrics, TransmittanceMetrics};
use super::timing::GpuPassTimes;
use crate::engine::{Gl, Outputs, RenderTarget};
use crate::error::Result;
use crate::renderer::{Renderer, Target};
use crate::scene::refusals::Refusal;
use crate::scene::Scene;
use crate::scene::{DirectionalLight, Light, OrthoCoords, PointLight, SpotLight};
use crate::settings::{
    BiasMode, Cull, DepthFormat, Filter, Fit, MapSize, PointPass, ShadowPatch, ShadowSettings,
    ShadowTechnique,
};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::{filter_cost, FilterCost, ShadowKind};

/// The bias configurations the sweep tries, by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum BiasPreset {
    /// The plain comparison.
    None,
    /// The book's constant 0.05.
    Book,
    /// LearnOpenGL's constant 0.005.
    LearnOpenGL,
    /// LearnOpenGL's slope-scaled max(0.05 (1 - n.l), 0.005).
    Slope,
    /// One shadow-map texel along the normal, no depth bias.
    NormalOffset,
    /// glPolygonOffset(1.1, 4) in the depth pass, no shader bias.
    PolygonOffset,
}

impl BiasPreset {
    pub const ALL: [BiasPreset; 6] = [
        BiasPreset::None,
        BiasPreset::Book,
        BiasPreset::LearnOpenGL,
        BiasPreset::Slope,
        BiasPreset::NormalOffset,
        BiasPreset::PolygonOffset,
    ];

    pub fn name(self) -> &'static str {
        match self {
            BiasPreset::None => "none",
            BiasPreset::Book => "book-0.05",
            BiasPreset::LearnOpenGL => "learnopengl-0.005",
            BiasPreset::Slope => "slope",
            BiasPreset::NormalOffset => "normal-offset",
            BiasPreset::PolygonOffset => "polygon-offset",
        }
    }

    /// Sets every bias knob of `s` to this preset.
    pub fn apply(self, s: &mut ShadowSettings) {
        s.normal_offset = 0.0;
        s.polygon_offset = [0.0, 0.0];
        s.bias_min = 0.005;
        match self {
            BiasPreset::None => s.bias_mode = BiasMode::None,
            BiasPreset::Book => {
                s.bias_mode = BiasMode::Constant;
                s.bias = 0.05;
            }
            BiasPreset::LearnOpenGL => {
                s.bias_mode = BiasMode::Constant;
                s.bias = 0.005;
            }
            BiasPreset::Slope => {
                s.bias_mode = BiasMode::Slope;
                s.bias = 0.05;
            }
            BiasPreset::NormalOffset => {
                s.bias_mode = BiasMode::None;
                s.normal_offset = 1.0;
            }
            BiasPreset::PolygonOffset => {
                s.bias_mode = BiasMode::None;
                s.polygon_offset = [1.1, 4.0];
            }
        }
    }
}

/// What kind of shadow a configuration draws, for the plot's series and the tables.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Family {
    /// One 2D map (the chapters).
    OneMap,
    /// A directional light's cascades.
    Cascades,
    /// A directional light's box per group of casters (`caster_groups`).
    Groups,
    /// A point light's cube map drawn in one layered pass.
    PointLayered,
    /// A point light's cube map drawn face by face.
    PointSixPasses,
    /// Stencil shadow volumes (no map).
    Volumes,
    /// One 2D map read through a soft filter (the playground's, PCSS).
    Soft,
}

impl Family {
    /// Every family, in the order plots list them.
    pub const ALL: [Family; 7] = [
        Family::OneMap,
        Family::Cascades,
        Family::Groups,
        Family::PointLayered,
        Family::PointSixPasses,
        Family::Volumes,
        Family::Soft,
    ];

    pub fn of(light: &Light, s: &ShadowSettings) -> Family {
        let plan = ShadowPlan::decide(std::slice::from_ref(light), s);
        let own = &plan.lights[0];
        match (own.kind, s.point_pass) {
            (ShadowKind::Cascades, _) => Family::Cascades,
            (ShadowKind::Groups, _) => Family::Groups,
            (ShadowKind::Cube, PointPass::Layered) => Family::PointLayered,
            (ShadowKind::Cube, PointPass::SixPasses) => Family::PointSixPasses,
            (ShadowKind::Volume, _) => Family::Volumes,
            (ShadowKind::Map, _) if own.settings.filter.soft() => Family::Soft,
            (ShadowKind::Moments, _) if Filter::SOFT_MOMENTS.contains(&own.settings.filter) => {
                Family::Soft
            }
            _ => Family::OneMap,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Family::OneMap => "one map",
            Family::Cascades => "cascades",
            Family::Groups => "caster groups",
            Family::PointLayered => "point light, layered",
            Family::PointSixPasses => "point light, six passes",
            Family::Volumes => "shadow volumes",
            Family::Soft => "one map, soft filter",
        }
    }
}

/// One configuration of the sweep.
#[derive(Debug, Clone, Serialize)]
pub struct BenchConfig {
    pub settings: ShadowSettings,
    pub bias_preset: BiasPreset,
    /// Set for the tutorials' own configurations ("book", "learnopengl").
    pub tutorial: Option<&'static str>,
    pub family: Family,
}

/// The tutorials' own final configurations, on top of the scene's settings. Both keep the
/// light's box as the scene gives it (neither fits it to the view), so a sweep run with
/// `--fit scene` still measures the tutorials as they are.
pub fn tutorial_configs(base: &ShadowSettings) -> Vec<BenchConfig> {
    let mut book = *base;
    book.fit = Fit::Manual;
    book.map_size = MapSize::square(1024);
    book.filter = Filter::Pcf3x3;
    book.cull = Cull::None;
    book.depth_format = DepthFormat::D24;
    BiasPreset::Book.apply(&mut book);
    // LearnOpenGL 3.1.3: slope bias, 3x3 PCF, a border of depth 1, z > 1 lit.
    let mut learn = book;
    BiasPreset::Slope.apply(&mut learn);
    learn.wrap = crate::settings::Wrap::ClampToBorder;
    learn.beyond_far = crate::settings::BeyondFar::Lit;
    vec![
        BenchConfig {
            settings: book,
            bias_preset: BiasPreset::Book,
            tutorial: Some("book"),
            family: Family::OneMap,
        },
        BenchConfig {
            settings: learn,
            bias_preset: BiasPreset::Slope,
            tutorial: Some("learnopengl"),
            family: Family::OneMap,
        },
    ]
}

/// The configurations to try for the scene's first light. The full sweep is the grid map
/// size x filter x bias (no culling, 24-bit), then culling and depth format varied around
/// 1024^2 with 3x3 PCF, and the driver's largest map; for a directional light, cascades
/// (2 to 4 layers) over sizes, filters and biases; for a point light, the cube faces drawn
/// in six passes as well as in one; and stencil shadow volumes. `quick` keeps a
/// representative subset (with the volumes).
pub fn sweep(
    base: &ShadowSettings,
    quick: bool,
    max_texture_size: u32,
    light: &Light,
) -> Vec<BenchConfig> {
    let base = &ShadowSettings {
        cascades: 1,
        caster_groups: 1,
        ..*base
    };
    let mut out = sweep_grid(base, quick, max_texture_size);
    out.extend(soft_grid(base, quick, light));
    // The tutorials' configurations go in the middle of the sweep (below): the first and
    // last places (timed at the start and at the very end) are the likeliest to catch the
    // machine changing state.
    let tutorials = tutorial_configs(base);
    out.retain(|c| !tutorials.iter().any(|t| t.settings == c.settings));
    out.extend(tutorials);
    let variants = |c: &BenchConfig| -> Vec<ShadowSettings> {
        let s = c.settings;
        match (Family::of(light, &s), quick) {
            (Family::OneMap, _)
                if Family::of(light, &ShadowSettings { cascades: 2, ..s }) == Family::Cascades =>
            {
                // The layered kinds (a directional light's), at the filters and biases the
                // fitted one-map rows do best with.
                let layered = matches!(s.filter, Filter::Single | Filter::Hardware2x2)
                    && matches!(c.bias_preset, BiasPreset::Slope | BiasPreset::NormalOffset)
                    && s.cull == Cull::None
                    && s.depth_format == DepthFormat::D24;
                let side = s.map_size.max_side();
                let mut out = Vec::new();
                // Cascades: the same total memory as some one-map sizes (4 x 1024^2 = 2048^2).
                if layered
                    && (512..=2048).contains(&side)
                    && (!quick || s.map_size == MapSize::square(1024))
                {
                    let counts: &[u32] = if quick { &[2, 4] } else { &[2, 3, 4] };
                    out.extend(counts.iter().map(|&n| ShadowSettings { cascades: n, ..s }));
                }
                // Caster groups: a box per group of casters, each layer the one map's size.
                if layered && (256..=1024).contains(&side) && (!quick || side >= 512) {
                    let counts: &[u32] = if quick { &[2] } else { &[2, 4] };
                    out.extend(counts.iter().map(|&n| ShadowSettings {
                        caster_groups: n,
                        ..s
                    }));
                }
                out
            }
            (Family::PointLayered, _)
                if s.cull == Cull::None && s.depth_format == DepthFormat::D24 =>
            {
                vec![ShadowSettings {
                    point_pass: PointPass::SixPasses,
                    ..s
                }]
            }
            _ => Vec::new(),
        }
    };
    let extra: Vec<BenchConfig> = out
        .iter()
        .flat_map(|c| {
            variants(c).into_iter().map(|settings| BenchConfig {
                settings,
                family: Family::of(light, &settings),
                tutorial: None,
                ..c.clone()
            })
        })
        .collect();
    out.extend(extra);
    // The slides' exact technique, once: it has no map, filter or bias to sweep.
    out.push(BenchConfig {
        settings: ShadowSettings {
            technique: ShadowTechnique::Volumes,
            ..tutorial_configs(base)[0].settings
        },
        bias_preset: BiasPreset::None,
        tutorial: None,
        family: Family::Volumes,
    });
    for c in &mut out {
        c.family = Family::of(light, &c.settings);
    }
    // Combinations the light refuses (a moment filter on a point light's cube map). The
    // measured light is the scene's first, so it gets the layers it asks for.
    out.retain(|c| refused(light, &c.settings).is_none());
    // The tutorials back in the middle of the whole sweep.
    let (tutorials, mut rest): (Vec<_>, Vec<_>) =
        out.into_iter().partition(|c| c.tutorial.is_some());
    let mid = rest.len() / 2;
    rest.splice(mid..mid, tutorials);
    rest
}

/// Why the measured light (alone, so first) cannot be drawn under `settings`, if it cannot.
fn refused(light: &Light, settings: &ShadowSettings) -> Option<Refusal> {
    ShadowPlan::resolve_named(std::slice::from_ref(light), settings, |_| {
        "the light".into()
    })
    .err()
}

/// The soft filters' configurations, for a light with a size (a point light has none: its
/// cube map takes no soft filter): 1024^2 (and 2048^2 in the full sweep), each soft filter
/// (and the soft moment filters, vssm and msm-soft),
/// LearnOpenGL's constant and slope biases.
fn soft_grid(base: &ShadowSettings, quick: bool, light: &Light) -> Vec<BenchConfig> {
    if light.size() <= 0.0 {
        return Vec::new();
    }
    let sizes: &[u32] = if quick { &[1024] } else { &[1024, 2048] };
    let mut out = Vec::new();
    for &side in sizes {
        for filter in Filter::SOFT.into_iter().chain(Filter::SOFT_MOMENTS) {
            for bias in [BiasPreset::LearnOpenGL, BiasPreset::Slope] {
                let mut s = *base;
                s.map_size = MapSize::square(side);
                s.filter = filter;
                s.cull = Cull::None;
                s.depth_format = DepthFormat::D24;
                bias.apply(&mut s);
                if refused(light, &s).is_none() {
                    out.push(BenchConfig {
                        settings: s,
                        bias_preset: bias,
                        tutorial: None,
                        family: Family::Soft,
                    });
                }
            }
        }
    }
    out
}

/// How many configurations [`sweep`] tries for each kind of light, with the default
/// settings: (the kind, quick, full). `bench --help` states these; `max_texture_size`
/// decides whether the driver's largest map joins the full sweep.
pub fn configuration_counts(max_texture_size: u32) -> [(&'static str, usize, usize); 3] {
    let base = ShadowSettings::default();
    let count = |light: &Light, quick| sweep(&base, quick, max_texture_size, light).len();
    let directional = Light::Directional(DirectionalLight {
        colour: Vec3::ONE,
        direction: Vec3::Y,
        intensity: 1.0,
        ortho: OrthoCoords::default(),
        shadow_pos_mult: 5.0,
        shading_position: None,
        casts_shadows: true,
        shadow: ShadowPatch::default(),
        size: 0.0,
    });
    let spot = Light::Spot(SpotLight {
        colour: Vec3::ONE,
        intensity: 1.0,
        position: Vec3::Y * 10.0,
        target: Vec3::ZERO,
        up: None,
        fov: 45.0,
        aspect: 1.0,
        cone: true,
        near: 1.0,
        far: 20.0,
        casts_shadows: true,
        shadow: ShadowPatch::default(),
        size: 0.0,
    });
    let point = Light::Point(PointLight {
        colour: Vec3::ONE,
        intensity: 1.0,
        position: Vec3::ZERO,
        near: 1.0,
        far: 25.0,
        oscillate: Vec3::ZERO,
        centre: Vec3::ZERO,
        casts_shadows: true,
        shadow: ShadowPatch::default(),
        size: 0.0,
    });
    [
        (
            "directional",
            count(&directional, true),
            count(&directional, false),
        ),
        ("spot", count(&spot, true), count(&spot, false)),
        ("point", count(&point, true), count(&point, false)),
    ]
}

fn sweep_grid(base: &ShadowSettings, quick: bool, max_texture_size: u32) -> Vec<BenchConfig> {
    let mut out: Vec<BenchConfig> = Vec::new();
    let mut push = |settings: ShadowSettings, bias_preset: BiasPreset| {
        let dup = out.iter().any(|c| c.settings == settings);
        if !dup {
            out.push(BenchConfig {
                settings,
                bias_preset,
                tutorial: None,
                family: Family::OneMap,
            });
        }
    };
    // The moment filters' maps hold 2 x 16 + 4 bytes a texel: tried at 1024^2 only.
    let (moment_filters, depth_filters) = (Filter::MOMENTS, Filter::ALL);
    let grid = |sizes: &[u32], filters: &[Filter], biases: &[BiasPreset]| {
        let mut v = Vec::new();
        for &map_size in sizes {
            for &filter in filters {
                for &bias in biases {
                    let mut s = *base;
                    s.map_size = MapSize::square(map_size);
                    s.filter = filter;
                    s.cull = Cull::None;
                    s.depth_format = DepthFormat::D24;
                    bias.apply(&mut s);
                    v.push((s, bias));
                }
            }
        }
        v
    };
    if quick {
        // From 256^2: a box fitted to few casters may need no more texels than that.
        for (s, b) in grid(
            &[256, 512, 1024, 2048],
            &[Filter::Single, Filter::Pcf3x3, Filter::Hardware2x2],
            &[
                BiasPreset::Book,
                BiasPreset::Slope,
                BiasPreset::NormalOffset,
            ],
        ) {
            push(s, b);
        }
        for (s, b) in grid(&[1024], &moment_filters, &[BiasPreset::Book]) {
            push(s, b);
        }
        return out;
    }
    let sizes: Vec<u32> = [256, 512, 1024, 2048, 4096, 8192]
        .into_iter()
        .filter(|&s| s <= max_texture_size)
        .collect();
    for (s, b) in grid(&sizes, &depth_filters, &BiasPreset::ALL) {
        push(s, b);
    }
    for (s, b) in grid(
        &[1024],
        &moment_filters,
        &[BiasPreset::Book, BiasPreset::Slope],
    ) {
        push(s, b);
    }
    for cull in [Cull::Back, Cull::Front] {
        for format in DepthFormat::ALL {
            for bias in BiasPreset::ALL {
                let mut s = *base;
                s.map_size = MapSize::square(1024);
                s.filter = Filter::Pcf3x3;
                s.cull = cull;
                s.depth_format = format;
                bias.apply(&mut s);
                push(s, bias);
            }
        }
    }
    for format in [DepthFormat::D16, DepthFormat::D32F] {
        for bias in BiasPreset::ALL {
            let mut s = *base;
            s.map_size = MapSize::square(1024);
            s.filter = Filter::Pcf3x3;
            s.cull = Cull::None;
            s.depth_format = format;
            bias.apply(&mut s);
            push(s, bias);
        }
    }
    if max_texture_size > 8192 {
        let mut s = tutorial_configs(base)[0].settings;
        s.map_size = MapSize::square(max_texture_size);
        push(s, BiasPreset::Book);
    }
    out
}

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
}

impl BenchRow {
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
        let s = &self.config.settings;
        let (size, suffix) = match self.config.family {
            Family::OneMap => (s.map_size.to_string(), ""),
            Family::Cascades => (format!("{}x{}", s.cascades, s.map_size), " cascades"),
            Family::Groups => (
                format!("{}x{}", s.caster_groups, s.map_size),
                " caster groups",
            ),
            Family::PointLayered => (s.map_size.to_string(), " cube layered"),
            Family::PointSixPasses => (s.map_size.to_string(), " cube six-passes"),
            Family::Volumes => {
                return format!(
                    "stencil shadow volumes ({} volume px/frame)",
                    self.volume_pixels
                )
            }
            Family::Soft => (s.map_size.to_string(), ""),
        };
        let fitted = match s.fit {
            Fit::Scene if !matches!(self.config.family, Family::Cascades | Family::Groups) => {
                " fitted"
            }
            _ => "",
        };
        format!(
            "{size} {} {} cull-{} {}{fitted}{suffix}",
            s.filter.name(),
            self.config.bias_preset.name(),
            s.cull.name(),
            s.depth_format.name()
        )
    }
}

/// The reference for the benchmark's view (traced once, shared by every configuration).
pub fn bench_reference(
    gl: &Gl,
    scene: &Scene,
    base: &ShadowSettings,
    opts: &BenchOptions,
) -> Result<Reference> {
    compute_reference(
        gl,
        scene,
        base,
        &CompareOptions {
            rays: opts.rays,
            width: opts.width,
            height: opts.height,
            supersample: opts.supersample,
            band: opts.band,
            light: 0,
        },
    )
}

/// Times and scores every configuration; `progress` is told after each one.
pub fn run(
    gl: &Gl,
    scene: &Scene,
    configs: &[BenchConfig],
    reference: &Reference,
    opts: &BenchOptions,
    mut progress: impl FnMut(&BenchRow),
) -> Result<Vec<BenchRow>> {
    let Some(first) = configs.first() else {
        return Ok(Vec::new());
    };
    let mut renderer = Renderer::new(gl, scene, &uncached(&first.settings))?;
    // The same frame without shadows, for each configuration's overhead.
    let mut plain = Renderer::new(
        gl,
        scene,
        &ShadowSettings {
            shadows: false,
            ..uncached(&first.settings)
        },
    )?;
    let timer = std::rc::Rc::new(GpuPassTimes::new(gl)?);
    renderer.set_hooks(timer.clone());
    let target = RenderTarget::new(gl, opts.width, opts.height, Outputs::default())?;
    let scored = RenderTarget::new(
        gl,
        opts.width,
        opts.height,
        Outputs {
            visibility: true,
            gbuffer: false,
        },
    )?;
    // A second of untimed frames first: the driver and the CPU settle before anything counts.
    let settle = Instant::now();
    while settle.elapsed().as_secs_f64() < 1.0 {
        renderer.render(scene, Target::Offscreen(&target))?;
        renderer.finish();
    }
    // Two passes over the sweep, the second in reverse order, `frames` frames each: a burst
    // of load from elsewhere on the machine then spoils at most one block per
    // configuration, and each configuration keeps its quieter block (the lower median).
    let mut best: Vec<Option<Timings>> = (0..configs.len()).map(|_| None).collect();
    let mut rows: Vec<Option<BenchRow>> = (0..configs.len()).map(|_| None).collect();
    let order: Vec<usize> = (0..configs.len()).chain((0..configs.len()).rev()).collect();
    for (step, &i) in order.iter().enumerate() {
        let config = &configs[i];
        renderer.set_settings(&uncached(&config.settings))?;
        let t = time_block(&mut renderer, &mut plain, scene, &target, &timer, opts)?;
        let quieter = match best[i].take() {
            Some(old) if Stat::of(&old.wall).median <= Stat::of(&t.wall).median => old,
            _ => t,
        };
        if step < configs.len() {
            best[i] = Some(quieter);
            continue;
        }
        // Second pass: score the frame and finish the row.
        renderer.render(scene, Target::Offscreen(&scored))?;
        let visibility = scored.read_visibility()?;
        let metrics = reference.score(&visibility, opts.band);
        let mut row = timed_row(config, &quieter, metrics, reference.score_soft(&visibility));
        row.transmittance = reference.score_transmittance(&visibility);
        progress(&row);
        rows[i] = Some(row);
    }
    let mut rows: Vec<BenchRow> = rows.into_iter().flatten().collect();
    mark_pareto(&mut rows);
    Ok(rows)
}

/// The bench measures the cost of drawing each map, so no map is reused from the cache.
fn uncached(s: &ShadowSettings) -> ShadowSettings {
    ShadowSettings {
        shadow_cache: false,
        ..*s
    }
}

/// One block of timed frames of `renderer` (after its warm-up frames), each paired with a
/// frame of `plain` drawn just before it: load from elsewhere on the machine that lasts
/// longer than a frame falls on both and cancels in their difference.
fn time_block(
    renderer: &mut Renderer,
    plain: &mut Renderer,
    scene: &Scene,
    target: &RenderTarget,
    timer: &GpuPassTimes,
    opts: &BenchOptions,
) -> Result<Timings> {
    for _ in 0..opts.warmup {
        renderer.render(scene, Target::Offscreen(target))?;
    }
    renderer.finish();
    let mut t = Timings::default();
    for _ in 0..opts.frames.max(1) {
        let start = Instant::now();
        plain.render(scene, Target::Offscreen(target))?;
        plain.finish();
        t.plain.push(ms(start.elapsed()));
        time_passes(renderer, scene, target, timer, 1, &mut t)?;
    }
    Ok(t)
}

/// A configuration's row from its quieter block of timings and its scores.
fn timed_row(
    config: &BenchConfig,
    quieter: &Timings,
    metrics: Metrics,
    soft: SoftMetrics,
) -> BenchRow {
    BenchRow {
        config: config.clone(),
        wall_ms: Stat::of(&quieter.wall),
        overhead_ms: Stat::of(
            &quieter
                .wall
                .iter()
                .zip(&quieter.plain)
                .map(|(w, p)| w - p)
                .collect::<Vec<_>>(),
        )
        .median,
        depth_wall_ms: Stat::of(&quieter.depth_wall),
        scene_wall_ms: Stat::of(&quieter.scene_wall),
        depth_gpu_ms: Stat::of(&quieter.depth_gpu),
        scene_gpu_ms: Stat::of(&quieter.scene_gpu),
        volume_pixels: Stat::of(&quieter.volume_pixels).median.max(0.0) as u64,
        metrics,
        soft,
        transmittance: None,
        pareto: false,
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
        renderer.render_depth_map(scene)?;
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

/// Marks the rows no other row beats on both time and error.
pub fn mark_pareto(rows: &mut [BenchRow]) {
    let points: Vec<(f64, f64)> = rows.iter().map(|r| (r.wall_ms.median, r.error())).collect();
    for (i, row) in rows.iter_mut().enumerate() {
        let (t, e) = points[i];
        row.pareto = !points
            .iter()
            .any(|&(t2, e2)| t2 <= t && e2 <= e && (t2 < t || e2 < e));
    }
}

/// The fastest configuration whose error is at most `target`.
pub fn cheapest_under(rows: &[BenchRow], target: f64) -> Option<&BenchRow> {
    rows.iter()
        .filter(|r| r.error() <= target)
        .min_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median))
}

/// A Markdown table: the tutorials' configurations, then the Pareto front, fastest first,
/// then (for a light with a size) every soft filter's configuration, with the figures
/// against the area truth in three more columns.
pub fn to_markdown(rows: &[BenchRow]) -> String {
    let area = rows.iter().any(|r| r.soft.rays > 0);
    let mut header = vec![
        "configuration",
        "wall ms (median / p95)",
        "shadow overhead ms",
        "depth pass ms",
        "scene pass ms",
        "misclassified",
        "false shadow",
        "false light",
        "outside band",
        "MAE",
        "cost: taps / passes / map MiB",
    ];
    if area {
        header.extend([
            "MAE vs area light",
            "light bleeding",
            "penumbra width error px",
        ]);
    }
    // The delimiter row has as many cells as the header, or no viewer draws a table.
    let mut out = format!(
        "| {} |\n|{}\n",
        header.join(" | "),
        "---|".repeat(header.len())
    );
    let mut shown: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.config.tutorial.is_some())
        .collect();
    let mut front: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.pareto && r.config.tutorial.is_none())
        .collect();
    front.sort_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median));
    shown.extend(front);
    let mut soft: Vec<&BenchRow> = rows
        .iter()
        .filter(|r| r.config.family == Family::Soft && !r.pareto)
        .collect();
    soft.sort_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median));
    shown.extend(soft);
    for r in shown {
        let name = match (r.config.tutorial, r.pareto) {
            (Some(t), _) => format!("**{t}** ({})", r.label()),
            (None, true) => format!("{} (Pareto)", r.label()),
            (None, false) => format!("{} (soft)", r.label()),
        };
        let m = &r.metrics;
        let pct = |x: f64| format!("{:.3}%", x * 100.0);
        out.push_str(&format!(
            "| {name} | {:.2} / {:.2} | {:.2} | {:.2} | {:.2} | {} | {} | {} | {} | {} | {} |",
            r.wall_ms.median,
            r.wall_ms.p95,
            r.overhead_ms,
            r.depth_wall_ms.median,
            r.scene_wall_ms.median,
            pct(m.misclassified_rate),
            pct(m.false_shadow_rate),
            pct(m.false_light_rate),
            pct(m.misclassified_outside_band_rate),
            m.mae.map_or("n/a".into(), |v| format!("{v:.4}")),
            r.cost_label(),
        ));
        if area {
            let a = &r.soft;
            out.push_str(&format!(
                " {:.4} | {} | {:.2} |",
                a.mae,
                pct(a.light_bleed_rate),
                a.penumbra_width_error_px
            ));
        }
        out.push('\n');
    }
    out
}

/// How a configuration compares with a tutorial's on two terms, from one run:
/// the overhead at equal error and the error at equal overhead.
#[derive(Debug, Clone)]
pub struct AgainstTutorial<'a> {
    pub tutorial: &'a BenchRow,
    /// The least shadow overhead with an error no worse than the tutorial's.
    pub at_equal_error: Option<&'a BenchRow>,
    /// The lowest error with an overhead no larger than the tutorial's.
    pub at_equal_overhead: Option<&'a BenchRow>,
}

/// For each tutorial configuration in `rows`: the cheapest other configuration (by
/// overhead) at least as accurate, and the most accurate one at most as expensive.
pub fn against_tutorials(rows: &[BenchRow]) -> Vec<AgainstTutorial<'_>> {
    let others = || rows.iter().filter(|r| r.config.tutorial.is_none());
    rows.iter()
        .filter(|r| r.config.tutorial.is_some())
        .map(|t| AgainstTutorial {
            tutorial: t,
            at_equal_error: others()
                .filter(|r| r.error() <= t.error())
                .min_by(|a, b| a.overhead_ms.total_cmp(&b.overhead_ms)),
            at_equal_overhead: others().filter(|r| r.overhead_ms <= t.overhead_ms).min_by(
                |a, b| {
                    a.error()
                        .total_cmp(&b.error())
                        .then(a.overhead_ms.total_cmp(&b.overhead_ms))
                },
            ),
        })
        .collect()
}

/// The comparison as lines of text: overhead ratio at equal error and error ratio at
/// equal overhead.
pub fn against_tutorials_text(rows: &[BenchRow]) -> String {
    let mut out = String::new();
    for a in against_tutorials(rows) {
        let t = a.tutorial;
        let name = t.config.tutorial.unwrap_or_default();
        out.push_str(&format!(
            "against {name} ({}: overhead {:.2} ms, {}):\n",
            t.label(),
            t.overhead_ms,
            t.error_text()
        ));
        match a.at_equal_error {
            Some(r) => out.push_str(&format!(
                "  at equal error or better: {} with overhead {:.2} ms ({}): \
                 {:.2} of the tutorial's overhead\n",
                r.label(),
                r.overhead_ms,
                r.error_text(),
                r.overhead_ms / t.overhead_ms
            )),
            None => out.push_str("  at equal error or better: no other configuration\n"),
        }
        match a.at_equal_overhead {
            Some(r) => out.push_str(&format!(
                "  at equal overhead or less: {}, {} (overhead {:.2} ms): {}\n",
                r.label(),
                r.error_text(),
                r.overhead_ms,
                r.fewer_errors_than(t)
            )),
            None => out.push_str("  at equal overhead or less: no other configuration\n"),
        }
    }
    out
}

/// The `--quality` presets' rule, on the shadow overhead against LearnOpenGL's final
/// configuration's: `low` the configuration with the least overhead; `medium` the most
/// accurate with at most half the tutorial's overhead; `high` the most
/// accurate with no more than the tutorial's. A preset serves every kind of light, so only
/// one-map rows count. Absent where the sweep has no such row (or no tutorial row).
pub fn preset_choices(rows: &[BenchRow]) -> [(&'static str, Option<&BenchRow>); 3] {
    let one_map = || {
        rows.iter()
            .filter(|r| r.config.tutorial.is_none() && r.config.family == Family::OneMap)
    };
    let tutorial = rows
        .iter()
        .find(|r| r.config.tutorial == Some("learnopengl"));
    let most_accurate_within = |budget: f64| {
        one_map()
            .filter(|r| r.overhead_ms <= budget)
            .min_by(|a, b| {
                a.error()
                    .total_cmp(&b.error())
                    .then(a.overhead_ms.total_cmp(&b.overhead_ms))
            })
    };
    let low = one_map().min_by(|a, b| a.overhead_ms.total_cmp(&b.overhead_ms));
    let medium = tutorial.and_then(|t| most_accurate_within(0.5 * t.overhead_ms));
    let high = tutorial.and_then(|t| most_accurate_within(t.overhead_ms));
    [("low", low), ("medium", medium), ("high", high)]
}

#[cfg(test)]
mod tests {
    use super::*;

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
            depth_wall_ms: stat,
            scene_wall_ms: stat,
            depth_gpu_ms: stat,
            scene_gpu_ms: stat,
            metrics,
            pareto: false,
            volume_pixels: 0,
            soft: super::super::reference::compute_soft_metrics(0, 0, &[], &[], 0),
            transmittance: None,
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
