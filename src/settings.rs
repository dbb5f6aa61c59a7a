//! The shadow settings: every knob the chapters turn, as data. A chapter step is a preset of
//! these, never a copy of the renderer.

use serde::{Deserialize, Serialize};

use range::Range;

mod choices;
mod describe;
mod filter;
mod map_size;
mod names;
mod range;
pub mod suggest;

pub use choices::{
    BeyondFar, BiasMode, Blur, Cull, DepthFormat, DepthLookup, Fit, LightProjection, LightView,
    MsmToward, OpaqueReceivers, PerspectiveDepth, PointPass, ShadowTechnique, TranslucentReceivers,
    Volumetric, Wrap,
};
pub use filter::{
    filter_names, Exclusive, Filter, FilterFacts, Kernel, KernelArgs, KernelGlsl, MomentDepth,
    MomentFacts, MomentKnob, MomentMode, Taps,
};
pub use map_size::{parse_map_size, MapSize};

names::named_by_clap!(
    ShadowTechnique,
    DepthFormat,
    Wrap,
    Filter,
    Blur,
    MsmToward,
    DepthLookup,
    BiasMode,
    Cull,
    BeyondFar,
    LightView,
    LightProjection,
    PerspectiveDepth,
    Fit,
    PointPass,
    Volumetric,
    TranslucentReceivers,
    OpaqueReceivers,
);

/// The points of PCSS's Poisson disk (shaders/lib/pcss.glsl): the most taps each
/// of its two stages can take.
pub const PCSS_MAX_TAPS: u32 = 32;
/// EVSM's largest exponent: exp(2 x 42) ~ 3e36 stays below 32-bit floats' 3.4e38, so
/// the warped depth's square cannot overflow.
pub const EVSM_MAX_EXPONENT: f32 = 42.0;
/// ESM's largest exponent: exp(88 x 1) ~ 1.7e38 at depth 1 stays below 32-bit floats'
/// 3.4e38 (ln 3.4e38 = 88.7), and a blur's weighted sums stay below their largest texel.
pub const ESM_MAX_EXPONENT: f32 = 88.0;

/// PCSS's taps per stage: 1 to [`PCSS_MAX_TAPS`].
fn poisson_taps() -> Range<u32> {
    Range::from_to(1, PCSS_MAX_TAPS).note("the Poisson disk's points")
}

/// The most cells a side of a soft moment filter's stage (`soft_search_cells`,
/// `soft_filter_cells`): `SOFT_MAX_CELLS` of shaders/lib/soft_moments.glsl.
pub const MAX_SOFT_CELLS: u32 = 4;

/// Cascades per light: the layers of one depth texture array, and slots in the shader's
/// uniform arrays.
pub const MAX_CASCADES: u32 = 4;

/// The most floats a texel of a translucent map holds: four to a layer, eight layers
/// (`crate::engine::translucent_map::MAX_LAYERS`).
pub const MAX_TRANSLUCENT_CHANNELS: u32 = 32;

/// The most Fourier opacity terms: the mean and a cosine and a sine per term fit in
/// [`MAX_TRANSLUCENT_CHANNELS`].
pub const MAX_FOURIER_TERMS: u32 = (MAX_TRANSLUCENT_CHANNELS - 1) / 2;

/// The most AVSM nodes a texel: two to a layer of a translucent map.
pub const MAX_AVSM_NODES: u32 = MAX_TRANSLUCENT_CHANNELS / 2;

/// The most layers AVSM peels.
pub const MAX_PEEL_LAYERS: u32 = 64;

/// The most shadow-map texels a normal offset moves a lookup: a few texels keep acne away,
/// and far more moves the lookup off its receiver altogether.
pub const MAX_NORMAL_OFFSET: f32 = 16.0;

/// The largest factor or units of `glPolygonOffset`: the chapters' offsets are a few units
/// (1.1, 4), and far larger ones push every caster past its receivers.
pub const MAX_POLYGON_OFFSET: f32 = 1000.0;

/// The constant bias and the slope bias' ends: [0, 1] depth units (a cube map's: world
/// units), for the `[shadow]` table, a light's own, the flags and the `[steps]` table alike.
fn bias_range() -> Range<f32> {
    Range::from_to(0.0, 1.0)
}

/// Why `bias` cannot be a bias ("7: expected 0 to 1"), or `None` where it can: for a table
/// other than `[shadow]` that gives one (`[steps] bias`).
pub fn bias_problem(bias: f32) -> Option<String> {
    use range::Bounds;
    let range = bias_range();
    (!range.admits(bias)).then(|| format!("{bias}: expected {}", range.expected()))
}

/// A setting's `--help` text from its documentation lines and, where it has one, its
/// range (what [`range::check`] refuses outside).
macro_rules! setting_help {
    ([$($doc:literal),*]) => {
        range::help(&[$($doc),*], None)
    };
    ([$($doc:literal),*], $range:expr) => {
        range::help(&[$($doc),*], Some(range::Bounds::expected(&$range)))
    };
}

/// Declares every setting once: its group, its type, its default, its documentation, the
/// numbers it takes ([`range::Range`]) and any flag options. From that one list come
/// [`ShadowSettings`] (the scene file's `[shadow]` table), [`ShadowPatch`] (the same fields,
/// each optional: a light's own `shadow` table and the command line's flags, with the groups
/// as `--help` headings and each range in its flag's help) and [`SETTING_GROUPS`].
macro_rules! shadow_settings {
    ($(
        $(#[doc = $gdoc:literal])*
        $group:literal {
            $(
                $(#[doc = $doc:literal])*
                $field:ident : $ty:ty = $default:expr
                    $(, range($range:expr))? $(, arg($($arg:tt)*))? ;
            )*
        }
    )*) => {
        /// Every setting of the shadow pipeline. The defaults are the book's final
        /// configuration.
        #[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
        #[serde(default, deny_unknown_fields)]
        pub struct ShadowSettings {
            $($( $(#[doc = $doc])* pub $field: $ty, )*)*
        }

        impl Default for ShadowSettings {
            fn default() -> Self {
                ShadowSettings { $($( $field: $default, )*)* }
            }
        }

        /// Settings that replace some of another's: a light's own `shadow` table over the
        /// scene's `[shadow]`, and the command line's flags over both.
        #[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, clap::Args)]
        #[serde(deny_unknown_fields)]
        pub struct ShadowPatch {
            $($(
                $(#[doc = $doc])*
                #[arg(long, help_heading = $group,
                      help = setting_help!([$($doc),*] $(, $range)?) $(, $($arg)*)?)]
                #[serde(default, skip_serializing_if = "Option::is_none")]
                pub $field: Option<$ty>,
            )*)*
        }

        impl ShadowPatch {
            /// Writes every given field into `settings`.
            pub fn apply_to(&self, settings: &mut ShadowSettings) {
                $($( if let Some(v) = self.$field { settings.$field = v; } )*)*
            }

            /// This patch without the fields `other` gives (so flags win over a light's
            /// own table).
            pub fn without(&self, other: &ShadowPatch) -> ShadowPatch {
                ShadowPatch {
                    $($( $field: if other.$field.is_some() { None } else { self.$field }, )*)*
                }
            }

            /// This patch over `under`: its own fields, and `under`'s where it gives none
            /// (the flags over a `--quality` preset).
            pub fn or(&self, under: &ShadowPatch) -> ShadowPatch {
                ShadowPatch {
                    $($( $field: self.$field.or(under.$field), )*)*
                }
            }

            /// The names (as the scene file spells them) of the fields it gives.
            pub fn given(&self) -> Vec<&'static str> {
                let mut names = Vec::new();
                $($( if self.$field.is_some() { names.push(stringify!($field)); } )*)*
                names
            }
        }

        impl ShadowSettings {
            /// Checks every setting against the range declared beside it.
            fn check_ranges(&self) -> crate::Result<()> {
                $($($( range::check(stringify!($field), self.$field, &$range)?; )?)*)*
                Ok(())
            }
        }

        /// The settings by what they govern, in `--help`'s order.
        pub const SETTING_GROUPS: &[(&str, &[&str])] = &[
            $( ($group, &[ $( stringify!($field), )* ]), )*
        ];
    };
}

shadow_settings! {
    /// What draws the shadows.
    "Technique" {
        /// `maps` (the chapters' depth maps) or `volumes` (the slides' stencil shadow
        /// volumes: exact, no map, no bias; the map and test settings do not apply).
        technique: ShadowTechnique = ShadowTechnique::Maps, arg(value_name = "maps|volumes");
    }
    /// The map itself.
    "Shadow map" {
        /// Shadows at all: `off` lets every light light all it faces, the frame a shadow
        /// technique's cost (its overhead) is measured against.
        shadows: bool = true,
            arg(value_name = "on|off", hide_possible_values = true, value_parser = clap::builder::BoolishValueParser::new());
        /// The shadow map's size in texels: N for N x N (the book: 1024), or WxH (the
        /// shadow-playground's 400x300); each side at most the driver's maximum texture
        /// size. Cube maps and cascades need a square size.
        map_size: MapSize = MapSize::square(1024),
            arg(value_name = "SIZE", value_parser = parse_map_size, allow_negative_numbers = true);
        /// Depth-map precision.
        depth_format: DepthFormat = DepthFormat::D24;
        /// What a perspective map stores: `linear` (depth from the light's near plane to its
        /// far plane: the bias means the same at any near plane) or `hyperbolic` (the
        /// projection's z / w, the chapters'). Depth maps only; a moment map and PCSS keep
        /// the projection's depth.
        perspective_depth: PerspectiveDepth = PerspectiveDepth::Linear;
        /// Cascaded shadow maps for directional lights: 1 = one map (the chapters), 2 to 4
        /// = that many `map_size` layers of a depth texture array, one per slice of the view.
        cascades: u32 = 1, range(Range::from_to(1, MAX_CASCADES).low_means("one map")),
            arg(value_name = "N", allow_negative_numbers = true);
        /// Caster groups for a directional light with one cascade: 1 = one box (the
        /// chapters, or with `fit = "scene"` one box fitted to the view), 2 to 4 = the
        /// casters whose shadow is in view split into up to that many groups, each with its
        /// own box fitted to it in a `map_size` layer of a depth array (casters far apart
        /// keep fine texels). Always fitted to the view.
        caster_groups: u32 = 1, range(Range::from_to(1, MAX_CASCADES).low_means("one box")),
            arg(value_name = "N", allow_negative_numbers = true);
    }
    /// How a fragment is tested against the map.
    "Shadow test" {
        /// How the shadow map is sampled.
        filter: Filter = Filter::Pcf3x3;
        /// How each lookup reads a 2D depth map: `nearest` (one texel) or `linear` (a depth
        /// interpolated between four texels, then compared, as the shadow-playground reads
        /// its colour map); the hardware and moment filters filter on their own.
        depth_lookup: DepthLookup = DepthLookup::Nearest;
        /// How the depth comparison is offset against acne.
        bias_mode: BiasMode = BiasMode::Constant;
        /// Constant bias, or the slope bias' ceiling (its most, at grazing light), in depth
        /// units (a cube map: world units).
        bias: f32 = 0.05, range(bias_range()),
            arg(value_name = "B", value_parser = parse_finite, allow_negative_numbers = true);
        /// The slope bias' floor (LearnOpenGL: 0.005), at most `bias`, its ceiling.
        bias_min: f32 = 0.005, range(bias_range()),
            arg(value_name = "B", value_parser = parse_finite, allow_negative_numbers = true);
        /// Normal-offset bias: the lookup moves this many shadow-map texels along the
        /// surface normal (0 = off); the same meaning for 2D, cube and cascade maps.
        normal_offset: f32 = 0.0,
            range(Range::from_to(0.0, MAX_NORMAL_OFFSET).low_means("off").note("texels")),
            arg(value_name = "TEXELS", value_parser = parse_finite, allow_negative_numbers = true);
        /// PCSS: lookups of the blocker search (on a rotated Poisson disk).
        pcss_blocker_taps: u32 = 16, range(poisson_taps()),
            arg(value_name = "N", allow_negative_numbers = true);
        /// PCSS: lookups of the filter that follows the penumbra.
        pcss_filter_taps: u32 = 16, range(poisson_taps()),
            arg(value_name = "N", allow_negative_numbers = true);
        /// Shadow-map wrap mode for lookups outside [0, 1].
        wrap: Wrap = Wrap::ClampToEdge;
        /// What fragments beyond the light's far plane get.
        beyond_far: BeyondFar = BeyondFar::Shadowed;
    }
    /// The filterable maps (`filter = "vsm"`, `"evsm2"`, `"evsm4"`, `"msm"`, `"esm"`): a float
    /// colour map of depth's moments, blurred, read with one filtered lookup.
    "Moment maps" {
        /// The blur before the lookup: the playground's 3 x 3, a wider Gaussian, or none.
        blur: Blur = Blur::Playground3x3;
        /// The least variance Chebyshev's bound assumes (VSM; EVSM scales it by each
        /// exponent's slope), against acne where the map is flat.
        min_variance: f32 = 1e-6,
            range(Range::from_to(0.0, 0.25).note("a depth in [0, 1] varies at most 0.25")),
            arg(value_name = "V", value_parser = parse_finite, allow_negative_numbers = true);
        /// Light-bleeding reduction (VSM, EVSM): bounds below this read as shadow, the rest
        /// stretch to [0, 1] (0 = off; Filament's default 0.15, MJP's comparisons 0.25).
        bleed_reduction: f32 = 0.15, range(Range::from_below(0.0, 1.0).low_means("off")),
            arg(value_name = "AMOUNT", value_parser = parse_finite, allow_negative_numbers = true);
        /// EVSM's exponents [positive, negative] (40 and 5 by default).
        evsm_exponents: [f32; 2] = [40.0, 5.0],
            range(Range::above_to(0.0, EVSM_MAX_EXPONENT)
                .note(format!("exp(2 x {EVSM_MAX_EXPONENT}) stays inside 32-bit floats"))
                .pair("[positive, negative], like [40, 5]")),
            arg(value_name = "POS,NEG", value_parser = parse_pair, allow_hyphen_values = true);
        /// MSM's moment bias alpha: the moments move this far toward `msm_toward` (3e-5
        /// for [0, 1] depth; the playground's preset: 9e-4 toward "playground").
        msm_bias: f32 = 3e-5, range(Range::from_to(0.0, 1.0).note("3e-5 for [0, 1] depth")),
            arg(value_name = "ALPHA", value_parser = parse_finite, allow_negative_numbers = true);
        /// What MSM's moment bias pulls toward.
        msm_toward: MsmToward = MsmToward::Half;
        /// vssm, msm-soft: cells a side of the blocker search's box; (n + 1)^2 reads of the
        /// summed-area table a pixel (4: 25 reads; 1: one box of 4 corners).
        soft_search_cells: u32 = 4, range(Range::from_to(1, MAX_SOFT_CELLS)),
            arg(value_name = "N", allow_negative_numbers = true);
        /// vssm, msm-soft: cells a side of the filter's box, as `soft_search_cells`.
        soft_filter_cells: u32 = 4, range(Range::from_to(1, MAX_SOFT_CELLS)),
            arg(value_name = "N", allow_negative_numbers = true);
        /// ESM's exponent c: the map stores exp(c z); larger is sharper and leaks less light
        /// near contact (80 by default, Annen et al.'s; its map is 32-bit float).
        esm_exponent: f32 = 80.0,
            range(Range::above_to(0.0, ESM_MAX_EXPONENT)
                .note(format!("exp({ESM_MAX_EXPONENT} x 1) stays inside 32-bit floats"))),
            arg(value_name = "C", value_parser = parse_finite, allow_negative_numbers = true);
    }
    /// How the map is drawn.
    "Depth pass" {
        /// Faces culled in the depth pass.
        cull: Cull = Cull::None;
        /// `glPolygonOffset(factor, units)` in the depth pass, e.g. 1.1,4 ([0, 0] = off).
        polygon_offset: [f32; 2] = [0.0, 0.0],
            range(Range::from_to(-MAX_POLYGON_OFFSET, MAX_POLYGON_OFFSET).pair("[factor, units]")),
            arg(value_name = "FACTOR,UNITS", value_parser = parse_pair, allow_hyphen_values = true);
        /// How a point light's six cube faces are drawn.
        point_pass: PointPass = PointPass::Layered;
        /// Draw a light's map again only when what it sees changed (the light, its settings,
        /// a caster, and for a box fitted to the view the camera); `off` draws every map every
        /// frame, as the chapters do. A cached frame is the same, pixel for pixel.
        shadow_cache: bool = true,
            arg(value_name = "on|off", hide_possible_values = true, value_parser = clap::builder::BoolishValueParser::new());
    }
    /// Where the light's camera looks from and what it covers.
    "Light camera" {
        /// How a directional light's view matrix is built (scene files without it get
        /// look-at; the DummyGame's asks for the book's angles).
        light_view: LightView = LightView::LookAt;
        /// A directional light's shadow projection.
        light_projection: LightProjection = LightProjection::Ortho;
        /// Field of view of a perspective shadow camera for a directional light, degrees.
        perspective_fov: f32 = 45.0, range(Range::between(0.0, 180.0).unit("degrees")),
            arg(value_name = "DEG", value_parser = parse_finite, allow_negative_numbers = true);
        /// A directional light's box: by hand (`OrthoCoords`) or fitted to the scene each
        /// frame.
        fit: Fit = Fit::Manual;
        /// With `fit = "scene"`, cascades or caster groups: snap the boxes to whole texels so
        /// shadows hold still as the camera moves.
        snap: bool = true,
            arg(value_name = "on|off", hide_possible_values = true, value_parser = clap::builder::BoolishValueParser::new());
        /// Where the cascades split: 0 = uniform slices, 1 = logarithmic (the practical
        /// scheme).
        cascade_lambda: f32 = 0.75, range(Range::from_to(0.0, 1.0)),
            arg(value_name = "LAMBDA", value_parser = parse_finite, allow_negative_numbers = true);
        /// The last fraction of each cascade's depth range that fades into the next
        /// (0 = a hard seam at the split).
        cascade_blend: f32 = 0.1, range(Range::from_to(0.0, 0.5)),
            arg(value_name = "FRACTION", value_parser = parse_finite, allow_negative_numbers = true);
        /// Where cascaded shadows end, in view depth (0 = the camera's far plane).
        shadow_distance: f32 = 0.0,
            range(Range::at_least(0.0).note("0 = the camera's far plane")),
            arg(value_name = "DEPTH", value_parser = parse_finite, allow_negative_numbers = true);
    }
    /// Translucent casters (items with `opacity` below 1).
    "Translucent casters" {
        /// How a light casts its translucent items: `off` (not at all), `solid` (as
        /// opaque, in the depth map), or a translucent map beside the depth map (`osm`
        /// opacity slices, `fom` Fourier opacity, `avsm` adaptive volumetric shadow maps); a
        /// directional or spot light's 2D map only.
        volumetric: Volumetric = Volumetric::Off, arg(value_name = "off|solid|osm|fom|avsm");
        /// The translucent map's size in texels, N or WxH like `map_size` (its texels cover
        /// the depth map's box): smaller costs less and blurs the translucent shadows' edges.
        volumetric_size: MapSize = MapSize::square(1024),
            arg(value_name = "SIZE", value_parser = parse_map_size, allow_negative_numbers = true);
        /// `volumetric = "osm"`: slices between the nearest and farthest translucent
        /// caster, four to a float target.
        osm_slices: u32 = 16, range(Range::from_to(1, MAX_TRANSLUCENT_CHANNELS)),
            arg(value_name = "K", allow_negative_numbers = true);
        /// `volumetric = "fom"`: Fourier terms (cosine and sine each) besides the mean;
        /// 1 + 2 N floats a texel.
        fom_coefficients: u32 = 7, range(Range::from_to(1, MAX_FOURIER_TERMS)),
            arg(value_name = "N", allow_negative_numbers = true);
        /// `volumetric = "avsm"`: nodes of the curve a texel, two to a float target at
        /// 32-bit; the first and the last are always kept.
        avsm_nodes: u32 = 8, range(Range::from_to(2, MAX_AVSM_NODES)),
            arg(value_name = "N", allow_negative_numbers = true);
        /// `volumetric = "avsm"`: the most layers of translucent fragments peeled from the
        /// light (peeling stops sooner at an empty layer); crossings past them are lost.
        peel_layers: u32 = 16, range(Range::from_to(1, MAX_PEEL_LAYERS)),
            arg(value_name = "K", allow_negative_numbers = true);
        /// Where translucent items take each light's shadow test: `pixel` (every fragment
        /// of every layer) or `vertex` (once a vertex, interpolated: a 2D depth or moment
        /// map's test, not PCSS's or the soft moment filters'); opaque items always per pixel.
        translucent_receivers: TranslucentReceivers = TranslucentReceivers::Pixel,
            arg(value_name = "pixel|vertex");
        /// What opaque receivers read from a translucent map: `curve` (the technique's lookup
        /// at the receiver's depth, every pixel) or `resolved` (one filtered fetch of the
        /// curve read at the depth map's depth, resolved whenever either map is drawn).
        opaque_receivers: OpaqueReceivers = OpaqueReceivers::Curve,
            arg(value_name = "curve|resolved");
    }
    /// Pictures instead of, or over, the scene.
    "Debug views" {
        /// Draw the shadow map on the whole frame instead of the scene (the chapters' debug
        /// quad; a cube map as a panorama, cascades side by side), linearised when the
        /// projection is perspective.
        show_depth_map: bool = false,
            arg(value_name = "BOOL", num_args = 0..=1, default_missing_value = "true", value_parser = clap::builder::BoolishValueParser::new());
        /// Draw the shadow volumes' faces over the frame (technique = volumes), each light's
        /// in its own colour.
        show_volumes: bool = false,
            arg(value_name = "BOOL", num_args = 0..=1, default_missing_value = "true", value_parser = clap::builder::BoolishValueParser::new());
        /// Tint each cascade's part of the frame (red, green, blue, yellow from the camera
        /// out).
        show_cascades: bool = false,
            arg(value_name = "BOOL", num_args = 0..=1, default_missing_value = "true", value_parser = clap::builder::BoolishValueParser::new());
    }
}

/// Checks a map's size (setting `name`) against the driver's maximum texture size.
fn check_size(name: &str, size: MapSize, max_texture_size: u32) -> crate::Result<()> {
    let sides = [size.width, size.height];
    if sides.iter().all(|&n| n > 0 && n <= max_texture_size) {
        return Ok(());
    }
    let each = if size.is_square() { "" } else { "each side " };
    Err(crate::Error::Invalid(format!(
        "shadow.{name} = {size}: expected {each}1 to {max_texture_size} (the driver's maximum texture size)"
    )))
}

/// Parses a finite number (NaN and infinities would reach the shaders as garbage).
pub fn parse_finite(s: &str) -> Result<f32, String> {
    match s.trim().parse::<f32>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(format!("'{s}': expected a finite number, like 0.05")),
    }
}

/// Parses `A,B` into two finite numbers, e.g. `1.1,4` or `-1,-4`.
pub fn parse_pair(s: &str) -> Result<[f32; 2], String> {
    let err = || format!("'{s}': expected two numbers separated by a comma, like 1.1,4");
    let (a, b) = s.split_once(',').ok_or_else(err)?;
    let a: f32 = a.trim().parse().map_err(|_| err())?;
    let b: f32 = b.trim().parse().map_err(|_| err())?;
    if !(a.is_finite() && b.is_finite()) {
        return Err(err());
    }
    Ok([a, b])
}

/// The layers a directional light's map gets ([`ShadowSettings::directional_layers`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DirectionalLayers {
    /// A layer per slice of the view (`cascades` > 1).
    Cascades,
    /// A layer per group of casters (`caster_groups` > 1).
    CasterGroups,
}

impl ShadowSettings {
    /// The layers a directional light's map is split into under these settings, if any:
    /// cascades, or else caster groups; both need an orthographic light projection.
    pub fn directional_layers(&self) -> Option<DirectionalLayers> {
        match self.light_projection {
            LightProjection::Perspective => None,
            LightProjection::Ortho if self.cascades > 1 => Some(DirectionalLayers::Cascades),
            LightProjection::Ortho if self.caster_groups > 1 => {
                Some(DirectionalLayers::CasterGroups)
            }
            LightProjection::Ortho => None,
        }
    }

    /// Checks values against each other and the driver's maximum texture size.
    pub fn validate(&self, max_texture_size: u32) -> crate::Result<()> {
        check_size("map_size", self.map_size, max_texture_size)?;
        check_size("volumetric_size", self.volumetric_size, max_texture_size)?;
        self.validate_values()
    }

    /// Checks everything that needs no driver: each setting against its declared range,
    /// then the settings that must be ordered against each other.
    pub fn validate_values(&self) -> crate::Result<()> {
        self.check_ranges()?;
        self.check_order()
    }

    /// The ends of one range given as two settings: the slope bias grows from its floor
    /// (`bias_min`) to its ceiling (`bias`), so a floor above the ceiling is no slope bias.
    /// The message names every setting involved, so a flag among them is named.
    fn check_order(&self) -> crate::Result<()> {
        let slope = match self.bias_mode {
            BiasMode::Slope => true,
            BiasMode::None | BiasMode::Constant => false,
        };
        if slope && self.bias_min > self.bias {
            return Err(crate::Error::Invalid(format!(
                "shadow.bias_min = {} is above shadow.bias = {} with shadow.bias_mode = slope \
                 (the slope bias grows from bias_min, its floor, to bias, its ceiling): \
                 expected bias_min from 0 to {}, or bias from {} to 1",
                self.bias_min, self.bias, self.bias, self.bias_min
            )));
        }
        Ok(())
    }

    /// The settings as the renderer applies them: a fitted box covers exactly what can be
    /// shadowed, so lookups outside it (a border of depth 1) and beyond its far plane are
    /// lit. (Cascades always work that way, whatever the other maps do: see
    /// `crate::shadows::cascades`.)
    pub fn effective(&self) -> ShadowSettings {
        match self.fit {
            Fit::Manual => *self,
            Fit::Scene => ShadowSettings {
                wrap: Wrap::ClampToBorder,
                beyond_far: BeyondFar::Lit,
                ..*self
            },
        }
    }
}

/// A float as a GLSL literal that keeps every bit (`{:?}` prints the shortest exact form).
pub fn glsl_float(v: f32) -> String {
    let t = format!("{v:?}");
    if t.contains(['.', 'e', 'E']) {
        t
    } else {
        format!("{t}.0")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_patch_gives_only_its_fields_and_yields_to_another() {
        let own = ShadowPatch {
            filter: Some(Filter::Single),
            bias: Some(0.2),
            ..ShadowPatch::default()
        };
        let flags = ShadowPatch {
            bias: Some(0.01),
            ..ShadowPatch::default()
        };
        let mut s = ShadowSettings::default();
        own.without(&flags).apply_to(&mut s);
        flags.apply_to(&mut s);
        assert_eq!((s.filter, s.bias), (Filter::Single, 0.01));
        assert_eq!(s.map_size, ShadowSettings::default().map_size);
        assert_eq!(own.given(), ["filter", "bias"]);
        // Every setting is in exactly one group.
        let grouped: Vec<&str> = SETTING_GROUPS
            .iter()
            .flat_map(|(_, f)| f.iter().copied())
            .collect();
        let all = serde_json::to_value(ShadowSettings::default()).unwrap();
        let names: Vec<&str> = all
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        assert_eq!(grouped.len(), names.len());
        assert!(
            names.iter().all(|n| grouped.contains(n)),
            "{names:?} vs {grouped:?}"
        );
    }
}
