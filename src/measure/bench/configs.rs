//! The configurations the bench sweeps: the bias presets, the families of shadow, the
//! tutorials' own configurations and the grid around them.

use glam::Vec3;
use serde::Serialize;

use crate::scene::refusals::Refusal;
use crate::scene::{DirectionalLight, Light, OrthoCoords, PointLight, SpotLight};
use crate::settings::{
    BiasMode, Cull, DepthFormat, Filter, Fit, MapSize, PointPass, ShadowPatch, ShadowSettings,
    ShadowTechnique,
};
pub use crate::shadows::kind::Family;
use crate::shadows::plan::ShadowPlan;

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
        (own.kind.facts().family)(&own.settings)
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
    let extra: Vec<BenchConfig> = out
        .iter()
        .flat_map(|c| {
            variants(light, c, quick)
                .into_iter()
                .map(|settings| BenchConfig {
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

/// The variants of a one-map row the sweep adds: cascades and caster groups of the same
/// memory for a directional light's layered kinds, six passes for a point light's layered
/// cube.
fn variants(light: &Light, c: &BenchConfig, quick: bool) -> Vec<ShadowSettings> {
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
        (Family::PointLayered, _) if s.cull == Cull::None && s.depth_format == DepthFormat::D24 => {
            vec![ShadowSettings {
                point_pass: PointPass::SixPasses,
                ..s
            }]
        }
        // Every other row is its own only variant (a new family answers here).
        (Family::OneMap | Family::PointLayered, _) => Vec::new(),
        (Family::Cascades | Family::Groups | Family::PointSixPasses, _) => Vec::new(),
        (Family::Volumes | Family::Soft, _) => Vec::new(),
    }
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
    for (s, b) in cull_and_format_rows(base) {
        push(s, b);
    }
    if max_texture_size > 8192 {
        let mut s = tutorial_configs(base)[0].settings;
        s.map_size = MapSize::square(max_texture_size);
        push(s, BiasPreset::Book);
    }
    out
}

/// The full sweep's rows at 1024^2 and pcf3x3 that vary what the depth pass draws and
/// stores: each culled face at each depth format, then D16 and D32F with no culling, at
/// every bias preset.
fn cull_and_format_rows(base: &ShadowSettings) -> Vec<(ShadowSettings, BiasPreset)> {
    let culled = [Cull::Back, Cull::Front]
        .into_iter()
        .flat_map(|cull| DepthFormat::ALL.into_iter().map(move |f| (cull, f)));
    let formats = [DepthFormat::D16, DepthFormat::D32F].map(|f| (Cull::None, f));
    culled
        .chain(formats)
        .flat_map(|(cull, format)| {
            BiasPreset::ALL.into_iter().map(move |bias| {
                let mut s = *base;
                s.map_size = MapSize::square(1024);
                s.filter = Filter::Pcf3x3;
                s.cull = cull;
                s.depth_format = format;
                bias.apply(&mut s);
                (s, bias)
            })
        })
        .collect()
}
