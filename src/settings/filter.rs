//! The filters, each one whole in one table ([`Filter::facts`]): what its test reads and
//! costs, the GLSL it calls, where it is refused and how the HUD says it. A new filter is a
//! variant here, its row in the table and its GLSL function; the compiler asks for the row.
//!
//! The chapters' filters are the grid of "Shadow Mapping improvements" (3 x 3 PCF) and
//! LearnOpenGL's; the rest go past them (the shadow-playground's demos, PCSS, the moment
//! maps, opengl-tutorial.org's Poisson disk).

use super::ShadowSettings;

/// How the shadow map is sampled ("Shadow Mapping improvements": 3x3 PCF).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Filter {
    /// One depth comparison per fragment: hard, blocky edges.
    Single,
    /// The book's and LearnOpenGL's 3 x 3 average of comparisons, one texel apart.
    #[default]
    Pcf3x3,
    /// A 5 x 5 average.
    Pcf5x5,
    /// One `sampler2DShadow` lookup with LINEAR filtering: the GPU compares the 4 nearest
    /// texels and blends the results bilinearly (2 x 2 hardware PCF).
    #[value(name = "hw2x2")]
    Hardware2x2,
    /// A 3 x 3 grid of hardware 2 x 2 lookups, one texel apart.
    #[value(name = "hw3x3")]
    Hardware3x3,
    // The soft filters (past the chapters: the shadow-playground's demos, and PCSS).
    /// The shadow-playground's PCF: 16 taps at +-0.5 and +-1.5 texels, the inner 2 x 2
    /// weighing 0.6 / 4 each and the outer 12 0.4 / 12 each (its epsilon is the bias).
    #[value(name = "pcf4x4-weighted")]
    Pcf4x4Weighted,
    /// The same 16 weighted taps, each comparison through the playground's sigmoid
    /// 1 / (1 + exp(-1000 diff)) instead of a step.
    #[value(name = "soft-pcf")]
    SoftPcf,
    /// Percentage-closer soft shadows: a blocker search on a rotated Poisson disk, then a
    /// filter as wide as the penumbra a light of the light's `size` casts from that
    /// blocker depth (contact hardening). A zero-size light gives a hard test.
    #[value(name = "pcss")]
    Pcss,
    /// opengl-tutorial.org's Poisson-disk PCF: 16 taps of its fixed disk, spread over its
    /// 1 / 700 of a 1024-texel map (1.46 texels), averaged. A fixed pattern bands.
    #[value(name = "poisson")]
    Poisson,
    /// The same disk turned by a per-pixel angle (interleaved gradient noise), as the
    /// tutorial suggests: the bands become fine noise.
    #[value(name = "poisson-rotated")]
    PoissonRotated,
    // Filterable maps (src/shadows/moments/mod.rs): the map stores moments of depth, blurred,
    // and the test reconstructs a visibility from them.
    /// Variance shadow maps: (z, z^2), blurred, Chebyshev's upper bound.
    Vsm,
    /// Exponential variance shadow maps with the positive exponent only (2 components).
    Evsm2,
    /// Exponential variance shadow maps with both exponents (4 components).
    Evsm4,
    /// Moment shadow maps: (z, z^2, z^3, z^4), the Hamburger 4MSM reconstruction.
    Msm,
    /// Exponential shadow maps (Annen et al. 2008): exp(c z), blurred; a receiver at d is
    /// lit by exp(-c d) E[exp(c z)], clamped to 1.
    Esm,
    // Soft shadows on summed-area tables of the moments (src/shadows/summed.rs).
    /// Variance soft shadow maps: a blocker search and a filter as wide as the penumbra,
    /// each 4 x 4 cells of (z, z^2) read from a summed-area table (texel by texel where
    /// the box is narrow).
    Vssm,
    /// Moment soft shadow maps: the same on four moments, with the 4MSM reconstruction.
    #[value(name = "msm-soft")]
    MsmSoft,
}

/// Which taps a 2D depth map's test takes: the GLSL function its call names (for a layered
/// light, the `LAYER_TAPS_*` define its lookup is compiled with:
/// shaders/lib/shadow_layers.glsl). A moment filter's map has its own test ([`MomentMode`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Kernel {
    /// The book's grid of depth comparisons, [`Filter::radius`] texels each way.
    Grid,
    /// The same grid of hardware 2 x 2 comparisons (`sampler2DShadow`).
    HardwareGrid,
    /// The playground's weighted 4 x 4 taps.
    Weighted4x4,
    /// The playground's 4 x 4 taps through its sigmoid.
    SoftPcf,
    /// Percentage-closer soft shadows (no layered form: refused on cascades).
    Pcss,
    /// opengl-tutorial.org's fixed Poisson disk.
    Poisson,
    /// The same disk turned per pixel.
    PoissonRotated,
}

/// What a kernel's test is in GLSL: its library, its sampler, its function and the
/// arguments the function takes after the common four (map, position, bias, texel).
#[derive(Debug, Clone, Copy)]
pub struct KernelGlsl {
    pub library: &'static str,
    pub sampler_type: &'static str,
    pub function: &'static str,
    pub args: KernelArgs,
    /// The define a layered light's lookup is compiled with (none: refused on layers).
    pub layer_define: Option<&'static str>,
    /// Whether the test needs a fragment's own inputs (screen derivatives, its pixel),
    /// which a vertex shader has not.
    pub per_pixel: bool,
}

/// The arguments a kernel's function takes after (map, position, bias, texel), before
/// `beyondFarLit`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelArgs {
    /// None.
    Plain,
    /// The grid's radius.
    Radius,
    /// PCSS': the light's penumbra uniform, its taps and whether its map is perspective.
    Pcss,
    /// The fragment's pixel (`gl_FragCoord.xy`), which turns the taps.
    Pixel,
}

/// A kernel's test on a `sampler2D`, in `library`, that a vertex shader can run too.
const fn call(
    library: &'static str,
    function: &'static str,
    args: KernelArgs,
    layer_define: Option<&'static str>,
) -> KernelGlsl {
    KernelGlsl {
        library,
        sampler_type: "sampler2D",
        function,
        args,
        layer_define,
        per_pixel: false,
    }
}

impl Kernel {
    /// The kernel's test in GLSL.
    pub const fn glsl(self) -> KernelGlsl {
        const SOFT: &str = "lib/soft_filters.glsl";
        match self {
            Kernel::Grid => call(
                "lib/shadow_2d.glsl",
                "calcShadow",
                KernelArgs::Radius,
                Some("LAYER_TAPS_GRID"),
            ),
            Kernel::HardwareGrid => KernelGlsl {
                sampler_type: "sampler2DShadow",
                ..call(
                    "lib/hardware_pcf.glsl",
                    "calcShadowHardware",
                    KernelArgs::Radius,
                    Some("LAYER_TAPS_GRID"),
                )
            },
            Kernel::Weighted4x4 => call(
                SOFT,
                "pcf4x4Weighted",
                KernelArgs::Plain,
                Some("LAYER_TAPS_WEIGHTED_4X4"),
            ),
            Kernel::SoftPcf => call(
                SOFT,
                "softPcf",
                KernelArgs::Plain,
                Some("LAYER_TAPS_SOFT_PCF"),
            ),
            Kernel::Pcss => KernelGlsl {
                per_pixel: true,
                ..call("lib/pcss.glsl", "pcss", KernelArgs::Pcss, None)
            },
            Kernel::Poisson => call(SOFT, "poissonPcf", KernelArgs::Plain, None),
            Kernel::PoissonRotated => KernelGlsl {
                per_pixel: true,
                ..call(SOFT, "poissonPcfRotated", KernelArgs::Pixel, None)
            },
        }
    }
}

/// A moment filter, by name: which moments its depth pass stores, which function tests
/// them and which settings that test reads, in its row of [`MomentMode::facts`]
/// (`crate::shadows::moment_mode` names their defines).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MomentMode {
    Vsm,
    Evsm2,
    Evsm4,
    Msm,
    /// VSM's moments read from a summed-area table (src/shadows/summed.rs).
    Vssm,
    /// MSM's moments read from a summed-area table.
    MsmSoft,
    Esm,
}

/// What a moment map's depth pass stores (its `MOMENT_DEPTH_*` define in
/// shaders/moments_depth.frag); what its texels are cleared to and how the depth view
/// reads them back follow from it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MomentDepth {
    /// (z, z^2).
    Vsm,
    /// exp(c w) and -exp(-c w) of the warped depth w = 2 z - 1, and their squares.
    Evsm,
    /// (z, z^2, z^3, z^4).
    Msm,
    /// exp(c z).
    Esm,
}

/// The moment maps' settings, in the groups one test reads together.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MomentKnob {
    Blur,
    Variance,
    EvsmExponents,
    Msm,
    Cells,
    EsmExponent,
}

impl MomentKnob {
    /// Every group, for the idle rules and the descriptions.
    pub const ALL: [MomentKnob; 6] = [
        MomentKnob::Blur,
        MomentKnob::Variance,
        MomentKnob::EvsmExponents,
        MomentKnob::Msm,
        MomentKnob::Cells,
        MomentKnob::EsmExponent,
    ];

    /// The settings of the group, as the scene file names them.
    pub const fn settings(self) -> &'static [&'static str] {
        match self {
            MomentKnob::Blur => &["blur"],
            MomentKnob::Variance => &["min_variance", "bleed_reduction"],
            MomentKnob::EvsmExponents => &["evsm_exponents"],
            MomentKnob::Msm => &["msm_bias", "msm_toward"],
            MomentKnob::Cells => &["soft_search_cells", "soft_filter_cells"],
            MomentKnob::EsmExponent => &["esm_exponent"],
        }
    }

    /// Whether `filter`'s test reads the group.
    pub fn read_by(self, filter: Filter) -> bool {
        filter.facts().moments.is_some_and(|m| m.reads(self))
    }

    /// The filters whose test reads the group, in words ("vsm, evsm2 or evsm4"): worked
    /// out once, since the idle rules ask for every light of every plan.
    pub fn readers(self) -> &'static str {
        static WORDS: std::sync::OnceLock<Vec<String>> = std::sync::OnceLock::new();
        let words = WORDS.get_or_init(|| {
            let words = |knob: MomentKnob| {
                let names: Vec<&str> = (<Filter as clap::ValueEnum>::value_variants().iter())
                    .filter(|f| knob.read_by(**f))
                    .map(|f| f.name())
                    .collect();
                match names.split_last() {
                    Some((last, [])) => last.to_string(),
                    Some((last, rest)) => format!("{} or {last}", rest.join(", ")),
                    None => String::new(),
                }
            };
            MomentKnob::ALL.map(words).to_vec()
        });
        let index = MomentKnob::ALL.iter().position(|k| *k == self);
        index.map_or("", |i| &words[i])
    }
}

/// A moment filter's row: what its depth pass stores, its test and the settings it reads.
#[derive(Debug, Clone, Copy)]
pub struct MomentFacts {
    pub depth: MomentDepth,
    /// The test's GLSL function (shaders/lib/shadow_moments.glsl; a table's:
    /// shaders/lib/soft_moments.glsl).
    pub function: &'static str,
    /// Whether the test reads a summed-area table of the moments (src/shadows/summed.rs).
    pub table: bool,
    /// The settings it reads, in the order of the function's arguments.
    pub knobs: &'static [MomentKnob],
}

impl MomentMode {
    /// The mode's row: the one table a new moment filter joins.
    pub const fn facts(self) -> MomentFacts {
        use MomentKnob::{Blur, Cells, EsmExponent, EvsmExponents, Msm, Variance};
        const fn row(
            depth: MomentDepth,
            function: &'static str,
            knobs: &'static [MomentKnob],
        ) -> MomentFacts {
            MomentFacts {
                depth,
                function,
                table: false,
                knobs,
            }
        }
        const fn table(
            depth: MomentDepth,
            function: &'static str,
            knobs: &'static [MomentKnob],
        ) -> MomentFacts {
            MomentFacts {
                table: true,
                ..row(depth, function, knobs)
            }
        }
        const EVSM: &[MomentKnob] = &[Blur, Variance, EvsmExponents];
        match self {
            MomentMode::Vsm => row(MomentDepth::Vsm, "calcShadowVsm", &[Blur, Variance]),
            MomentMode::Evsm2 => row(MomentDepth::Evsm, "calcShadowEvsm", EVSM),
            MomentMode::Evsm4 => row(MomentDepth::Evsm, "calcShadowEvsm", EVSM),
            MomentMode::Msm => row(MomentDepth::Msm, "calcShadowMsm", &[Blur, Msm]),
            MomentMode::Vssm => table(MomentDepth::Vsm, "vssm", &[Variance, Cells]),
            MomentMode::MsmSoft => table(MomentDepth::Msm, "msmSoft", &[Msm, Cells]),
            MomentMode::Esm => row(MomentDepth::Esm, "calcShadowEsm", &[Blur, EsmExponent]),
        }
    }

    /// Whether the mode's test reads `knob`'s settings.
    pub fn reads(self, knob: MomentKnob) -> bool {
        self.facts().knobs.contains(&knob)
    }
}

/// How many lookups a filter's test takes per fragment.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Taps {
    /// The grid, (2 radius + 1)^2 (a hardware lookup reads 2 x 2 texels in one).
    Grid,
    /// A fixed number.
    Fixed(u32),
    /// PCSS: its blocker search's and its filter's, as the settings say.
    Pcss,
}

/// Everything about one filter that is not its GLSL body: its row of [`Filter::facts`].
#[derive(Debug, Clone, Copy)]
pub struct FilterFacts {
    /// Half the grid of lookups in texels (0 = one lookup, or taps of the filter's own).
    pub radius: u32,
    pub taps: Taps,
    /// The components of a moment map's texel (0: a depth map).
    pub components: u32,
    /// A depth map's taps (the moment filters: [`Kernel::Grid`], unused).
    pub kernel: Kernel,
    pub moments: Option<MomentMode>,
    /// What the filter does to each shaded pixel's test, for the HUD.
    pub words: &'static str,
    /// Why a point light's cube map cannot take it, if it cannot (the message names the
    /// filters of its family from their lists, so a new member is named too).
    pub on_cube: Option<fn() -> String>,
    /// Why cascades and caster groups cannot take it, if they cannot.
    pub on_layers: Option<fn() -> String>,
    /// The settings only this filter reads (idle under any other).
    pub exclusive: Exclusive,
}

/// Settings only one filter reads, as the scene file names them, and what they are in the
/// idle rules' words ("its counts").
#[derive(Debug, Clone, Copy)]
pub struct Exclusive {
    pub names: &'static [&'static str],
    pub what: &'static str,
}

/// A depth map's filter, on every kind of map.
const fn grid(radius: u32, kernel: Kernel, words: &'static str) -> FilterFacts {
    FilterFacts {
        radius,
        taps: Taps::Grid,
        components: 0,
        kernel,
        moments: None,
        words,
        on_cube: None,
        on_layers: None,
        exclusive: Exclusive {
            names: &[],
            what: "",
        },
    }
}

/// A soft filter: a 2D map's texel grid, which a cube map has not.
const fn soft(kernel: Kernel, taps: Taps, words: &'static str) -> FilterFacts {
    FilterFacts {
        taps,
        kernel,
        on_cube: Some(soft_on_cube),
        ..grid(0, kernel, words)
    }
}

/// A moment filter: one 2D map of `components` moments, blurred.
const fn moments(mode: MomentMode, components: u32, words: &'static str) -> FilterFacts {
    FilterFacts {
        taps: Taps::Fixed(1),
        components,
        moments: Some(mode),
        on_cube: Some(moments_on_cube),
        on_layers: Some(moments_on_layers),
        ..grid(0, Kernel::Grid, words)
    }
}

/// A soft moment filter: the blocker search and the filter, each a 5 x 5 lattice of a
/// summed-area table's corners.
const fn soft_moments(mode: MomentMode, components: u32, words: &'static str) -> FilterFacts {
    FilterFacts {
        taps: Taps::Fixed(50),
        on_cube: Some(soft_moments_on_cube),
        on_layers: Some(soft_moments_on_layers),
        ..moments(mode, components, words)
    }
}

/// Filters' names as a refusal lists them: "vsm, evsm2, evsm4" (`or`: "..., hw2x2 or hw3x3").
pub fn filter_names(filters: &[Filter], or: bool) -> String {
    let names: Vec<&str> = filters.iter().map(|f| f.name()).collect();
    match (or, names.split_last()) {
        (true, Some((last, rest))) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => names.join(", "),
    }
}

fn soft_on_cube() -> String {
    format!(
        "a point light's cube map takes {} (the soft filters read a 2D map's texel grid)",
        filter_names(&Filter::ALL, true)
    )
}

fn pcss_on_layers() -> String {
    "cascades and caster groups do not take pcss (its penumbra is measured in one light \
     camera's units, and each layer has its own box)"
        .to_string()
}

fn poisson_on_layers() -> String {
    format!(
        "cascades and caster groups do not take the Poisson disk ({}: it is a 2D map's \
         filter); use pcf3x3 or pcf4x4-weighted",
        filter_names(&[Filter::Poisson, Filter::PoissonRotated], false)
    )
}

fn moments_on_cube() -> String {
    format!(
        "the moment maps ({}) need one 2D map and a point light's shadow is a cube map; give \
         the light a depth filter of its own (shadow = {{ filter = \"pcf3x3\" }}) or use one \
         for the scene",
        filter_names(&Filter::MOMENTS, false)
    )
}

fn moments_on_layers() -> String {
    format!(
        "the moment maps ({}) need one 2D map and cascades and caster groups have a layer \
         each; use cascades = 1 and caster_groups = 1, or a depth filter (pcf3x3) for the light",
        filter_names(&Filter::MOMENTS, false)
    )
}

fn soft_moments_on_cube() -> String {
    format!(
        "the soft moment filters ({}) read summed-area tables of one 2D map and a point \
         light's shadow is a cube map; give the light a depth filter of its own (shadow = {{ \
         filter = \"pcf3x3\" }}) or use one for the scene",
        filter_names(&Filter::SOFT_MOMENTS, false)
    )
}

fn soft_moments_on_layers() -> String {
    format!(
        "the soft moment filters ({}) measure the penumbra in one light camera's units and \
         cascades and caster groups have a box each; use cascades = 1 and caster_groups = 1, \
         or a depth filter (pcf3x3) for the light",
        filter_names(&Filter::SOFT_MOMENTS, false)
    )
}

impl Filter {
    /// The chapters' filters (hard tests; the bench's full grid); the soft ones are
    /// [`Filter::SOFT`], the moment maps' [`Filter::MOMENTS`].
    pub const ALL: [Filter; 5] = [
        Filter::Single,
        Filter::Pcf3x3,
        Filter::Pcf5x5,
        Filter::Hardware2x2,
        Filter::Hardware3x3,
    ];

    /// The soft filters, for the 2D map (and, but for PCSS, cascades): see
    /// [`Filter::facts`]' refusals.
    pub const SOFT: [Filter; 5] = [
        Filter::Pcf4x4Weighted,
        Filter::SoftPcf,
        Filter::Pcss,
        Filter::Poisson,
        Filter::PoissonRotated,
    ];

    /// The moment maps' filters (a map of their own, `src/shadows/moments/mod.rs`).
    pub const MOMENTS: [Filter; 5] = [
        Filter::Vsm,
        Filter::Evsm2,
        Filter::Evsm4,
        Filter::Msm,
        Filter::Esm,
    ];

    /// The soft filters on summed-area tables of a moment map (`src/shadows/summed.rs`).
    pub const SOFT_MOMENTS: [Filter; 2] = [Filter::Vssm, Filter::MsmSoft];

    /// The filter's row: the one table a new filter joins.
    pub const fn facts(self) -> FilterFacts {
        use Kernel::{Grid, HardwareGrid};
        match self {
            Filter::Single => grid(0, Grid, "one depth test (hard edges)"),
            Filter::Pcf3x3 => grid(1, Grid, "PCF, 3 x 3 depth tests averaged"),
            Filter::Pcf5x5 => grid(2, Grid, "PCF, 5 x 5 depth tests averaged"),
            Filter::Hardware2x2 => grid(0, HardwareGrid, "the GPU's depth compare, 2 x 2 blended"),
            Filter::Hardware3x3 => grid(
                1,
                HardwareGrid,
                "the GPU's depth compare over 3 x 3 lookups",
            ),
            Filter::Pcf4x4Weighted => soft(
                Kernel::Weighted4x4,
                Taps::Fixed(16),
                "PCF, 4 x 4 depth tests weighted",
            ),
            Filter::SoftPcf => soft(Kernel::SoftPcf, Taps::Fixed(16), "soft PCF, 16 depth tests"),
            Filter::Pcss => FilterFacts {
                on_layers: Some(pcss_on_layers),
                exclusive: Exclusive {
                    names: &["pcss_blocker_taps", "pcss_filter_taps"],
                    what: "its counts",
                },
                ..soft(
                    Kernel::Pcss,
                    Taps::Pcss,
                    "PCSS, softer the farther from the caster",
                )
            },
            Filter::Poisson => FilterFacts {
                on_layers: Some(poisson_on_layers),
                ..soft(
                    Kernel::Poisson,
                    Taps::Fixed(16),
                    "Poisson-disk PCF, 16 depth tests",
                )
            },
            Filter::PoissonRotated => FilterFacts {
                on_layers: Some(poisson_on_layers),
                ..soft(
                    Kernel::PoissonRotated,
                    Taps::Fixed(16),
                    "Poisson-disk PCF turned per pixel, 16 depth tests",
                )
            },
            Filter::Vsm => moments(MomentMode::Vsm, 2, "VSM, variance of depth"),
            Filter::Evsm2 => moments(
                MomentMode::Evsm2,
                2,
                "EVSM, exponential variance (2 moments)",
            ),
            Filter::Evsm4 => moments(
                MomentMode::Evsm4,
                4,
                "EVSM, exponential variance (4 moments)",
            ),
            Filter::Msm => moments(MomentMode::Msm, 4, "MSM, 4 moments of depth"),
            Filter::Esm => moments(MomentMode::Esm, 1, "ESM, exponential of depth"),
            Filter::Vssm => soft_moments(
                MomentMode::Vssm,
                2,
                "VSSM, variance soft shadows on summed-area tables",
            ),
            Filter::MsmSoft => soft_moments(
                MomentMode::MsmSoft,
                4,
                "moment soft shadows on summed-area tables",
            ),
        }
    }

    /// Half the grid of lookups in texels (0 = one lookup); the soft filters have their
    /// own taps ([`Kernel`]) and no grid.
    pub fn radius(self) -> u32 {
        self.facts().radius
    }

    /// Shadow-map lookups per fragment of a 2D map under `settings` (PCSS: its blocker
    /// search and its filter; a hardware lookup reads 2 x 2 texels in one).
    pub fn lookups(self, settings: &ShadowSettings) -> u32 {
        match self.facts().taps {
            Taps::Grid => (2 * self.radius() + 1).pow(2),
            Taps::Fixed(n) => n,
            Taps::Pcss => settings.pcss_blocker_taps + settings.pcss_filter_taps,
        }
    }

    /// Whether this is one of the soft filters ([`Filter::SOFT`]).
    pub fn soft(self) -> bool {
        Filter::SOFT.contains(&self)
    }

    /// Whether the map stores moments of depth (a float colour map, blurred) rather than
    /// depth: those filters need one 2D map (no cube maps, no cascades: their refusals).
    pub fn moments(self) -> bool {
        self.moment_components() > 0
    }

    /// The components of a moment map's texel (0: a depth map).
    pub fn moment_components(self) -> u32 {
        self.facts().components
    }

    /// Whether lookups use the depth-compare hardware (`sampler2DShadow`, LINEAR).
    pub fn hardware(self) -> bool {
        self.facts().kernel == Kernel::HardwareGrid
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::ValueEnum;

    #[test]
    fn every_knob_a_moment_row_reads_is_listed_and_named_once() {
        for f in Filter::value_variants() {
            let Some(mode) = f.facts().moments else {
                continue;
            };
            for knob in mode.facts().knobs {
                assert!(MomentKnob::ALL.contains(knob), "{}: {knob:?}", f.name());
                assert!(!knob.readers().is_empty(), "{knob:?}");
            }
        }
        let mut names: Vec<&str> = MomentKnob::ALL
            .iter()
            .flat_map(|k| k.settings())
            .copied()
            .collect();
        let all = names.len();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), all, "a setting in two groups");
        assert_eq!(MomentKnob::Variance.readers(), "vsm, evsm2, evsm4 or vssm");
        assert_eq!(MomentKnob::EsmExponent.readers(), "esm");
    }
}
