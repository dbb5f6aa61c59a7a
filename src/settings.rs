//! The shadow settings: every knob the chapters turn, as data. A chapter step is a preset of
//! these, never a copy of the renderer.

use serde::{Deserialize, Serialize};

use range::Range;

mod names;
mod range;

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
);

/// Which technique draws a light's shadow: the chapters' depth maps, or the slides' closing
/// stencil shadow volumes (exact hard shadows; `crate::shadows::volumes`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum ShadowTechnique {
    /// A depth map per light (2D, cube or cascades), tested per fragment.
    #[default]
    Maps,
    /// Stencil shadow volumes: silhouettes extruded in a geometry shader, counted z-fail.
    Volumes,
}

/// Depth precision of a shadow map. The book asks for plain `GL_DEPTH_COMPONENT`, which Mesa
/// stores as 24 bits; we name the size so the choice is explicit and measurable.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum DepthFormat {
    #[value(name = "16")]
    D16,
    #[default]
    #[value(name = "24")]
    D24,
    #[value(name = "32f")]
    D32F,
}

impl DepthFormat {
    pub const ALL: [DepthFormat; 3] = [DepthFormat::D16, DepthFormat::D24, DepthFormat::D32F];
}

/// How lookups outside [0, 1] behave. The book clamps to the edge; LearnOpenGL's first steps
/// REPEAT (showing over-sampling) and its final step clamps to a border of depth 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Wrap {
    #[default]
    ClampToEdge,
    ClampToBorder,
    Repeat,
}

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
    // Filterable maps (src/shadows/moments.rs): the map stores moments of depth, blurred,
    // and the test reconstructs a visibility from them.
    /// Variance shadow maps: (z, z^2), blurred, Chebyshev's upper bound.
    Vsm,
    /// Exponential variance shadow maps with the positive exponent only (2 components).
    Evsm2,
    /// Exponential variance shadow maps with both exponents (4 components).
    Evsm4,
    /// Moment shadow maps: (z, z^2, z^3, z^4), the Hamburger 4MSM reconstruction.
    Msm,
    // Soft shadows on summed-area tables of the moments (src/shadows/summed.rs).
    /// Variance soft shadow maps: a blocker search and a filter as wide as the penumbra,
    /// each one box of (z, z^2) read from a summed-area table.
    Vssm,
    /// Moment soft shadow maps: the same on four moments, with the 4MSM reconstruction.
    #[value(name = "msm-soft")]
    MsmSoft,
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
    /// [`Filter::works_with`].
    pub const SOFT: [Filter; 3] = [Filter::Pcf4x4Weighted, Filter::SoftPcf, Filter::Pcss];

    /// The moment maps' filters (a map of their own, `src/shadows/moments.rs`).
    pub const MOMENTS: [Filter; 4] = [Filter::Vsm, Filter::Evsm2, Filter::Evsm4, Filter::Msm];

    /// The soft filters on summed-area tables of a moment map (`src/shadows/summed.rs`).
    pub const SOFT_MOMENTS: [Filter; 2] = [Filter::Vssm, Filter::MsmSoft];

    /// Half the grid of lookups in texels (0 = one lookup); the soft filters have their
    /// own taps ([`Filter::kernel`]) and no grid.
    pub fn radius(self) -> u32 {
        match self {
            Filter::Single | Filter::Hardware2x2 => 0,
            Filter::Pcf3x3 | Filter::Hardware3x3 => 1,
            Filter::Pcf5x5 => 2,
            Filter::Pcf4x4Weighted | Filter::SoftPcf | Filter::Pcss => 0,
            // One filtered lookup: the blur did the averaging.
            Filter::Vsm | Filter::Evsm2 | Filter::Evsm4 | Filter::Msm => 0,
            // Boxes of a summed-area table, as wide as the penumbra.
            Filter::Vssm | Filter::MsmSoft => 0,
        }
    }

    /// The shader's kernel (which function a 2D map's test calls, `LAYER_TAPS` for a layered
    /// light): 0 = the grid of [`Filter::radius`], 1 = the
    /// playground's weighted 4 x 4, 2 = its soft PCF, 3 = PCSS.
    pub fn kernel(self) -> u32 {
        match self {
            Filter::Pcf4x4Weighted => 1,
            Filter::SoftPcf => 2,
            Filter::Pcss => 3,
            _ => 0,
        }
    }

    /// Shadow-map lookups per fragment of a 2D map under `settings` (PCSS: its blocker
    /// search and its filter; a hardware lookup reads 2 x 2 texels in one).
    pub fn lookups(self, settings: &ShadowSettings) -> u32 {
        match self {
            Filter::Pcf4x4Weighted | Filter::SoftPcf => 16,
            Filter::Pcss => settings.pcss_blocker_taps + settings.pcss_filter_taps,
            // One filtered lookup: the blur did the averaging.
            Filter::Vsm | Filter::Evsm2 | Filter::Evsm4 | Filter::Msm => 1,
            // Two boxes (blocker search, filter), each 4 x 4 texels of the table.
            Filter::Vssm | Filter::MsmSoft => 32,
            _ => (2 * self.radius() + 1).pow(2),
        }
    }

    /// Whether this is one of the soft filters ([`Filter::SOFT`]).
    pub fn soft(self) -> bool {
        Filter::SOFT.contains(&self)
    }

    /// Whether the map stores moments of depth (a float colour map, blurred) rather than
    /// depth: those filters need one 2D map (no cube maps, no cascades:
    /// [`crate::shadows::plan::filter_refusal`]).
    pub fn moments(self) -> bool {
        self.moment_components() > 0
    }

    /// The components of a moment map's texel (0: a depth map).
    pub fn moment_components(self) -> u32 {
        match self {
            Filter::Vsm | Filter::Evsm2 | Filter::Vssm => 2,
            Filter::Evsm4 | Filter::Msm | Filter::MsmSoft => 4,
            _ => 0,
        }
    }

    /// Whether lookups use the depth-compare hardware (`sampler2DShadow`, LINEAR).
    pub fn hardware(self) -> bool {
        matches!(self, Filter::Hardware2x2 | Filter::Hardware3x3)
    }
}

/// The Gaussian blur a moment map gets before it is read: separable, one horizontal and
/// one vertical pass. `playground3x3` is the shadow-playground's 3 x 3 kernel (corner /
/// edge / centre 0.045 / 0.122 / 0.332 = the outer product of (0.2118, 0.5762, 0.2118));
/// the others are Gaussians with sigma = taps / 6 (the kernel spans +-3 sigma),
/// normalised.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Blur {
    /// No blur: only the lookup's bilinear filtering.
    None,
    /// The shadow-playground's 3 x 3.
    #[default]
    #[value(name = "playground3x3")]
    Playground3x3,
    #[value(name = "gauss5")]
    Gauss5,
    #[value(name = "gauss7")]
    Gauss7,
    #[value(name = "gauss9")]
    Gauss9,
}

impl Blur {
    pub const ALL: [Blur; 5] = [
        Blur::None,
        Blur::Playground3x3,
        Blur::Gauss5,
        Blur::Gauss7,
        Blur::Gauss9,
    ];

    /// Taps of the 1D kernel (0: no blur).
    pub fn taps(self) -> u32 {
        match self {
            Blur::None => 0,
            Blur::Playground3x3 => 3,
            Blur::Gauss5 => 5,
            Blur::Gauss7 => 7,
            Blur::Gauss9 => 9,
        }
    }

    /// The 1D weights from the centre out (`weights[0]` the centre, then each side's),
    /// summing to 1 over the whole kernel.
    pub fn weights(self) -> Vec<f32> {
        if self == Blur::Playground3x3 {
            // The playground's 2D weights are this kernel's outer product: sqrt(0.332) in
            // the centre, 0.122 / sqrt(0.332) either side (0.045 ~ 0.2118^2 in the corners).
            let centre = 0.332f32.sqrt();
            let side = 0.122 / centre;
            let sum = centre + 2.0 * side;
            return vec![centre / sum, side / sum];
        }
        let radius = (self.taps() / 2) as i32;
        if radius == 0 {
            return vec![1.0];
        }
        let sigma = self.taps() as f32 / 6.0;
        let w: Vec<f32> = (0..=radius)
            .map(|i| (-((i * i) as f32) / (2.0 * sigma * sigma)).exp())
            .collect();
        let sum = w[0] + 2.0 * w[1..].iter().sum::<f32>();
        w.iter().map(|v| v / sum).collect()
    }
}

/// The moment vector a moment shadow map's moments are pulled toward by `msm_bias`
/// (against the numerical failures of a nearly singular Hankel matrix).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum MsmToward {
    /// (0.5, 0.5, 0.5, 0.5): half the weight at depth 0 and half at 1 (for [0, 1] depth).
    #[default]
    Half,
    /// The shadow-playground's (0, 0.63, 0, 0.63).
    Playground,
}

impl MsmToward {
    pub fn vector(self) -> [f32; 4] {
        match self {
            MsmToward::Half => [0.5; 4],
            MsmToward::Playground => [0.0, 0.63, 0.0, 0.63],
        }
    }
}

/// How each lookup of a 2D depth map reads it: one texel, or (the shadow-playground, whose
/// depth is a colour map filtered LINEAR, `js/glh.js`) the depth interpolated between the
/// four nearest texels, compared as one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum DepthLookup {
    /// The nearest texel (the book's NEAREST depth texture).
    #[default]
    Nearest,
    /// A depth interpolated between four texels, then compared.
    Linear,
}

/// How the depth comparison is offset against acne.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum BiasMode {
    /// The plain comparison: acne everywhere a surface faces the light.
    None,
    /// `depth - bias` (the book's 0.05, LearnOpenGL's 0.005).
    #[default]
    Constant,
    /// LearnOpenGL's `max(bias * (1 - n.l), bias_min)`.
    Slope,
}

/// Which faces the depth pass culls.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Cull {
    /// The book's depth pass draws every face.
    #[default]
    None,
    Back,
    /// LearnOpenGL's peter-panning fix.
    Front,
}

/// How a light casts its translucent items (opacity below 1): the depth map holds one
/// depth per texel, so without a volumetric technique they cast all or nothing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Volumetric {
    /// They cast nothing (the chapters' depth map ignores them): one wrong.
    #[default]
    Off,
    /// They cast as if opaque, into the depth map: the other wrong.
    Solid,
    /// Opacity shadow maps (Kim and Neumann 2001): the optical depth of the crossings
    /// summed into `osm_slices` slices of the light's depth (`crate::shadows::volumetric`).
    Osm,
    /// Fourier opacity maps (Jansen and Bavoil 2010): the optical depth's density as
    /// `fom_coefficients` terms of a Fourier series along the light's depth.
    Fom,
    /// Adaptive volumetric shadow maps (Salvi et al. 2010): per texel a curve of
    /// transmittance against depth, `avsm_nodes` nodes, from `peel_layers` peeled layers.
    Avsm,
}

impl Volumetric {
    /// The next choice, after the last the first (the demo's T key).
    pub fn next(self) -> Volumetric {
        use clap::ValueEnum;
        let all = Volumetric::value_variants();
        let at = all.iter().position(|v| *v == self).unwrap_or(0);
        all[(at + 1) % all.len()]
    }
}

/// What a fragment beyond the light's far plane (z > 1) gets.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum BeyondFar {
    /// The book: the comparison runs anyway and says "shadowed".
    #[default]
    Shadowed,
    /// LearnOpenGL: treated as lit.
    Lit,
}

/// How the directional light's view matrix is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum LightView {
    /// The book: Euler angles from the direction (acos z, asin x). Right only while the
    /// direction has no x component (refused otherwise); the DummyGame's file asks for it.
    BookAngles,
    /// glm's `lookAt` from `direction * shadow_pos_mult` towards the origin with up +Y (a
    /// smooth turn to another up within a few degrees of the poles). The default: it works
    /// for every direction.
    #[default]
    LookAt,
}

/// The projection of a directional light's shadow camera.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum LightProjection {
    /// The book's: parallel rays, the `OrthoCoords` box.
    #[default]
    Ortho,
    /// A frustum from the shadow position towards the origin (`perspective_fov`), as if the
    /// light were a nearby point; spot lights always use their own frustum.
    Perspective,
}

/// What a perspective map (a spot light's, a directional light's `perspective` one) stores.
/// Its projection's z / w crowds every depth past the near plane towards 1 (at near 0.01
/// and far 30 the last 99.9% of the range gets 0.03% of the values), so a bias in those
/// units spans a distance that depends on the near plane: docs/techniques/perspective-depth.md.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum PerspectiveDepth {
    /// The depth along the light's axis, linear from its near plane (0) to its far plane
    /// (1), written per fragment: a bias is the same fraction of the light's range, the
    /// same world distance, at any near plane (as in an orthographic map).
    #[default]
    Linear,
    /// The projection's own depth, as the chapters store it (LearnOpenGL linearises it only
    /// to show it).
    Hyperbolic,
    /// The projection's depth stored, the bias taken off the fragment's linear depth before
    /// it is compared: the same reach as `linear` with the depth pass untouched, as long as
    /// the stored depth resolves it (not 16 bits at small near planes).
    HyperbolicLinearBias,
}

/// Where a directional light's orthographic box comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum Fit {
    /// The light's `OrthoCoords`, as the book sets them by hand.
    #[default]
    Manual,
    /// Computed each frame from the casters and the receivers the camera can see.
    Scene,
}

/// How a point light's six cube faces are drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum PointPass {
    /// One pass per face, the face attached in turn.
    SixPasses,
    /// One pass: a geometry shader sends each triangle to every face with gl_Layer. The
    /// default: one draw per caster instead of six; on llvmpipe both cost the same within
    /// 0.3% of instructions (docs/techniques/point-lights.md).
    #[default]
    Layered,
}

/// A shadow map's size in texels. Square in the chapters (`map_size = 1024`, `--map-size
/// 1024`); the shadow-playground's maps have its canvas' shape (`map_size = [400, 300]`,
/// `--map-size 400x300`). Cube maps and cascade arrays are square and refuse other sizes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct MapSize {
    pub width: u32,
    pub height: u32,
}

impl MapSize {
    /// A `side` x `side` map.
    pub const fn square(side: u32) -> MapSize {
        MapSize {
            width: side,
            height: side,
        }
    }

    pub fn is_square(self) -> bool {
        self.width == self.height
    }

    /// The smaller side: the coarser texels are along it.
    pub fn min_side(self) -> u32 {
        self.width.min(self.height)
    }

    /// The larger side.
    pub fn max_side(self) -> u32 {
        self.width.max(self.height)
    }

    /// Texels in the map.
    pub fn texels(self) -> u64 {
        u64::from(self.width) * u64::from(self.height)
    }

    /// Width over height.
    pub fn aspect(self) -> f32 {
        self.width as f32 / self.height.max(1) as f32
    }

    /// At least `side` texels on each side (the `hi-res` step).
    pub fn at_least(self, side: u32) -> MapSize {
        MapSize {
            width: self.width.max(side),
            height: self.height.max(side),
        }
    }

    /// The side of a square map, or an error saying that `what` (a cube map, cascades)
    /// needs one: its faces and layers are square.
    pub fn square_side(self, what: &str) -> crate::Result<u32> {
        match self.is_square() {
            true => Ok(self.width),
            false => Err(crate::Error::Invalid(format!(
                "shadow.map_size = {self}: {what} needs a square map (its faces or layers are \
                 square); expected one number, like {}",
                self.max_side()
            ))),
        }
    }
}

impl MapSize {
    /// `1024^2` for a square map, `400x300` otherwise (for summaries).
    pub fn label(&self) -> String {
        match self.is_square() {
            true => format!("{}^2", self.width),
            false => self.to_string(),
        }
    }
}

impl std::fmt::Display for MapSize {
    /// `1024` for a square map, `400x300` otherwise (as `--map-size` takes it).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self.is_square() {
            true => write!(f, "{}", self.width),
            false => write!(f, "{}x{}", self.width, self.height),
        }
    }
}

impl From<u32> for MapSize {
    fn from(side: u32) -> MapSize {
        MapSize::square(side)
    }
}

/// A square map's side equals the size of that square (the cube and cascade maps, square
/// by construction, compare their side with the settings' size).
impl PartialEq<MapSize> for u32 {
    fn eq(&self, size: &MapSize) -> bool {
        size.width == *self && size.height == *self
    }
}

impl Serialize for MapSize {
    /// A number for a square map, `[width, height]` otherwise.
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.is_square() {
            true => s.serialize_u32(self.width),
            false => [self.width, self.height].serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for MapSize {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<MapSize, D::Error> {
        struct V;
        const EXPECTED: &str = "a side in texels (like 1024) or [width, height] (like [400, 300])";
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = MapSize;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str(EXPECTED)
            }
            fn visit_u64<E: serde::de::Error>(self, v: u64) -> Result<MapSize, E> {
                u32::try_from(v)
                    .map(MapSize::square)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Unsigned(v), &self))
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<MapSize, E> {
                u64::try_from(v)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Signed(v), &self))
                    .and_then(|v| self.visit_u64(v))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut a: A,
            ) -> Result<MapSize, A::Error> {
                let side = |v: Option<u32>, i| {
                    v.ok_or_else(|| serde::de::Error::invalid_length(i, &"[width, height]"))
                };
                let width = side(a.next_element::<u32>()?, 0)?;
                let height = side(a.next_element::<u32>()?, 1)?;
                if a.next_element::<serde::de::IgnoredAny>()?.is_some() {
                    return Err(serde::de::Error::invalid_length(3, &"[width, height]"));
                }
                Ok(MapSize { width, height })
            }
        }
        d.deserialize_any(V)
    }
}

/// Parses `--map-size`: `N` (a square map) or `WxH`, e.g. `1024` or `400x300`.
pub fn parse_map_size(s: &str) -> Result<MapSize, String> {
    let err =
        || format!("'{s}': expected a side in texels like 1024, or WIDTHxHEIGHT like 400x300");
    let side = |t: &str| t.trim().parse::<u32>().map_err(|_| err());
    match s.split_once(['x', 'X']) {
        Some((w, h)) => Ok(MapSize {
            width: side(w)?,
            height: side(h)?,
        }),
        None => side(s).map(MapSize::square),
    }
}

/// The points of PCSS's Poisson disk (shaders/lib/soft_filters.glsl): the most taps each
/// of its two stages can take.
pub const PCSS_MAX_TAPS: u32 = 32;
/// EVSM's largest exponent: exp(2 x 42) ~ 3e36 stays below 32-bit floats' 3.4e38, so
/// the warped depth's square cannot overflow.
pub const EVSM_MAX_EXPONENT: f32 = 42.0;

/// PCSS's taps per stage: 1 to [`PCSS_MAX_TAPS`].
fn poisson_taps() -> Range<u32> {
    Range::from_to(1, PCSS_MAX_TAPS).note("the Poisson disk's points")
}

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

/// Declares every setting once: its group, its type, its default, its documentation, the
/// numbers it takes ([`range::Range`]) and any flag options. From that one list come [`ShadowSettings`] (the scene file's
/// `[shadow]` table), [`ShadowPatch`] (the same fields, each optional: a light's own
/// `shadow` table and the command line's flags, with the groups as `--help` headings) and
/// [`SETTING_GROUPS`].
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
                #[arg(long, help_heading = $group $(, $($arg)*)?)]
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
        /// Constant bias, or the slope bias' maximum, in [0, 1] depth units (a cube map:
        /// world units).
        bias: f32 = 0.05, range(Range::at_least(0.0)),
            arg(value_name = "B", value_parser = parse_finite, allow_negative_numbers = true);
        /// The slope bias' floor (LearnOpenGL: 0.005).
        bias_min: f32 = 0.005, range(Range::at_least(0.0)),
            arg(value_name = "B", value_parser = parse_finite, allow_negative_numbers = true);
        /// Normal-offset bias: the lookup moves this many shadow-map texels along the
        /// surface normal (0 = off); the same meaning for 2D, cube and cascade maps.
        normal_offset: f32 = 0.0, range(Range::at_least(0.0)),
            arg(value_name = "TEXELS", value_parser = parse_finite, allow_negative_numbers = true);
        /// PCSS: lookups of the blocker search (on a rotated Poisson disk, 1 to 32).
        pcss_blocker_taps: u32 = 16, range(poisson_taps()),
            arg(value_name = "N", allow_negative_numbers = true);
        /// PCSS: lookups of the filter that follows the penumbra (1 to 32).
        pcss_filter_taps: u32 = 16, range(poisson_taps()),
            arg(value_name = "N", allow_negative_numbers = true);
        /// Shadow-map wrap mode for lookups outside [0, 1].
        wrap: Wrap = Wrap::ClampToEdge;
        /// What fragments beyond the light's far plane get.
        beyond_far: BeyondFar = BeyondFar::Shadowed;
    }
    /// The filterable maps (`filter = "vsm"`, `"evsm2"`, `"evsm4"`, `"msm"`): a float
    /// colour map of depth's moments, blurred, read with one filtered lookup.
    "Moment maps" {
        /// The blur before the lookup: the playground's 3 x 3, a wider Gaussian, or none.
        blur: Blur = Blur::Playground3x3;
        /// The least variance Chebyshev's bound assumes (VSM; EVSM scales it by each
        /// exponent's slope), against acne where the map is flat.
        min_variance: f32 = 1e-6, range(Range::at_least(0.0)),
            arg(value_name = "V", value_parser = parse_finite, allow_negative_numbers = true);
        /// Light-bleeding reduction (VSM, EVSM): bounds below this read as shadow, the rest
        /// stretch to [0, 1] (0 = off; Filament's default 0.15, MJP's comparisons 0.25).
        bleed_reduction: f32 = 0.15, range(Range::from_below(0.0, 1.0).low_means("off")),
            arg(value_name = "AMOUNT", value_parser = parse_finite, allow_negative_numbers = true);
        /// EVSM's exponents [positive, negative] (40 and 5 by default); each is clamped to
        /// 42 so exp(2c) stays inside 32-bit floats.
        evsm_exponents: [f32; 2] = [40.0, 5.0],
            range(Range::above(0.0)
                .note(format!("each is clamped to {EVSM_MAX_EXPONENT}"))
                .pair("[positive, negative], like [40, 5]")),
            arg(value_name = "POS,NEG", value_parser = parse_pair, allow_hyphen_values = true);
        /// MSM's moment bias alpha: the moments move this far toward `msm_toward` (3e-5
        /// for [0, 1] depth; the playground's preset: 9e-4 toward "playground").
        msm_bias: f32 = 3e-5, range(Range::from_to(0.0, 1.0).note("3e-5 for [0, 1] depth")),
            arg(value_name = "ALPHA", value_parser = parse_finite, allow_negative_numbers = true);
        /// What MSM's moment bias pulls toward.
        msm_toward: MsmToward = MsmToward::Half;
    }
    /// How the map is drawn.
    "Depth pass" {
        /// Faces culled in the depth pass.
        cull: Cull = Cull::None;
        /// `glPolygonOffset(factor, units)` in the depth pass, e.g. 1.1,4 ([0, 0] = off).
        polygon_offset: [f32; 2] = [0.0, 0.0], range(Range::any().pair("[factor, units]")),
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
        /// (0 = a hard seam at the split, at most 0.5).
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
            _ if self.cascades > 1 => Some(DirectionalLayers::Cascades),
            _ if self.caster_groups > 1 => Some(DirectionalLayers::CasterGroups),
            _ => None,
        }
    }

    /// A short human summary, for window titles and reports: the map and its test, then
    /// every other field that differs from the defaults (the book's final configuration),
    /// so two settings that render differently never read the same. Fields that do nothing
    /// with the others (the fov of an orthographic light, the cascades' split of one map)
    /// are left out.
    pub fn summary(&self) -> String {
        if !self.shadows {
            return "no shadows".to_string();
        }
        if self.technique == ShadowTechnique::Volumes {
            let shown = if self.show_volumes {
                ", volumes shown"
            } else {
                ""
            };
            return format!("stencil shadow volumes (z-fail, depth clamp){shown}");
        }
        let bias = match self.bias_mode {
            BiasMode::None => "no bias".to_string(),
            BiasMode::Constant => format!("bias {}", self.bias),
            BiasMode::Slope => format!("slope bias {}..{}", self.bias_min, self.bias),
        };
        let size = self.map_size.label();
        let mut line = format!(
            "{size} {} {}, {}{}, cull {}",
            self.depth_format.name(),
            self.filter.name(),
            bias,
            self.offsets_and_layers(),
            self.cull.name()
        );
        // The rest by their serialised names and values, alphabetically (a new field shows
        // up here without being listed).
        let (Ok(serde_json::Value::Object(mine)), Ok(serde_json::Value::Object(base))) = (
            serde_json::to_value(self),
            serde_json::to_value(ShadowSettings::default()),
        ) else {
            return line;
        };
        for (key, value) in &mine {
            if base.get(key) == Some(value) {
                continue;
            }
            if let Some(part) = self.summary_part(key, value) {
                line.push_str(", ");
                line.push_str(&part);
            }
        }
        line
    }

    /// The summary's offsets and the split of a directional light's map (cascades or
    /// caster groups), each led by ", ".
    fn offsets_and_layers(&self) -> String {
        let mut extra = String::new();
        if self.normal_offset != 0.0 {
            extra.push_str(&format!(", normal offset {} texels", self.normal_offset));
        }
        if self.polygon_offset != [0.0, 0.0] {
            extra.push_str(&format!(
                ", polygon offset {}/{}",
                self.polygon_offset[0], self.polygon_offset[1]
            ));
        }
        let defaults = ShadowSettings::default();
        if self.cascades > 1 {
            extra.push_str(&format!(
                ", {} cascades (lambda {}",
                self.cascades, self.cascade_lambda
            ));
            if self.cascade_blend != defaults.cascade_blend {
                extra.push_str(&format!(", blend {}", self.cascade_blend));
            }
            if self.shadow_distance != defaults.shadow_distance {
                extra.push_str(&format!(", to depth {}", self.shadow_distance));
            }
            extra.push(')');
        } else if self.caster_groups > 1 {
            extra.push_str(&format!(", {} caster groups", self.caster_groups));
        }
        extra
    }

    /// How the summary names a field that differs from the default (by its serialised
    /// name); `None` for the fields shown before it or that do nothing with the others.
    fn summary_part(&self, key: &str, value: &serde_json::Value) -> Option<String> {
        let perspective = self.light_projection == LightProjection::Perspective;
        let fitted = self.fit == Fit::Scene || self.cascades > 1 || self.caster_groups > 1;
        let v = match value {
            serde_json::Value::String(s) => s.clone(),
            // Switches read as the flags spell them.
            serde_json::Value::Bool(b) => if *b { "on" } else { "off" }.to_string(),
            // Settings are f32: shown as f32 (0.4, not 0.4000000059604645).
            serde_json::Value::Number(n) if n.is_f64() => {
                (n.as_f64().unwrap_or_default() as f32).to_string()
            }
            other => other.to_string(),
        };
        Some(match key {
            "map_size" | "depth_format" | "filter" | "bias_mode" | "bias" | "bias_min"
            | "normal_offset" | "polygon_offset" | "cull" | "cascades" | "caster_groups"
            | "cascade_lambda" | "cascade_blend" | "shadow_distance" => return None,
            "perspective_fov" => return None,
            "pcss_blocker_taps" | "pcss_filter_taps" if self.filter != Filter::Pcss => return None,
            "depth_lookup" if self.filter.hardware() || self.filter.moments() => return None,
            // The moment maps' knobs do nothing for a depth map.
            "blur" | "min_variance" | "bleed_reduction" | "evsm_exponents" | "msm_bias"
            | "msm_toward"
                if !self.filter.moments() =>
            {
                return None
            }
            "osm_slices" if self.volumetric != Volumetric::Osm => return None,
            "fom_coefficients" if self.volumetric != Volumetric::Fom => return None,
            "avsm_nodes" | "peel_layers" if self.volumetric != Volumetric::Avsm => return None,
            "volumetric_size" if matches!(self.volumetric, Volumetric::Off | Volumetric::Solid) => {
                return None
            }
            "volumetric_size" => format!("translucent map {}", self.volumetric_size),
            "light_projection" if perspective => {
                format!("perspective light, fov {}", self.perspective_fov)
            }
            "light_projection" => format!("{v} light"),
            "light_view" => format!("{v} view"),
            "wrap" => format!("wrap {v}"),
            "beyond_far" => format!("beyond far {v}"),
            "fit" => format!("box fitted to the {v}"),
            "snap" if !fitted => return None,
            "snap" => "unsnapped".to_string(),
            "point_pass" => format!("point pass {v}"),
            "show_depth_map" => "showing the depth map".to_string(),
            "show_cascades" => "cascades tinted".to_string(),
            "show_volumes" => "volumes shown".to_string(),
            _ => format!("{} {v}", key.replace('_', " ")),
        })
    }

    /// Checks values against each other and the driver's maximum texture size.
    pub fn validate(&self, max_texture_size: u32) -> crate::Result<()> {
        check_size("map_size", self.map_size, max_texture_size)?;
        check_size("volumetric_size", self.volumetric_size, max_texture_size)?;
        self.validate_values()
    }

    /// Checks everything that needs no driver: each setting against its declared range.
    pub fn validate_values(&self) -> crate::Result<()> {
        self.check_ranges()
    }

    /// The settings as the renderer applies them: a fitted box covers exactly what can be
    /// shadowed, so lookups outside it (a border of depth 1) and beyond its far plane are
    /// lit. (Cascades always work that way, whatever the other maps do: see
    /// `crate::shadows::cascades`.)
    pub fn effective(&self) -> ShadowSettings {
        match self.fit {
            Fit::Manual => *self,
            _ => ShadowSettings {
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

    #[test]
    fn map_sizes_read_as_one_number_or_two() {
        let wide = MapSize {
            width: 400,
            height: 300,
        };
        assert_eq!(parse_map_size("1024"), Ok(MapSize::square(1024)));
        assert_eq!(parse_map_size("400x300"), Ok(wide));
        for bad in ["", "x", "400x", "-1", "400x300x2", "1.5"] {
            let e = parse_map_size(bad).unwrap_err();
            assert!(
                e.contains("expected a side in texels like 1024"),
                "{bad}: {e}"
            );
        }
        let read = |t: &str| toml::from_str::<ShadowSettings>(t).map(|s| s.map_size);
        assert_eq!(read("map_size = 512").unwrap(), MapSize::square(512));
        assert_eq!(read("map_size = [400, 300]").unwrap(), wide);
        for bad in [
            "map_size = [400]",
            "map_size = [1, 2, 3]",
            "map_size = -4",
            "map_size = \"big\"",
        ] {
            let e = read(bad).unwrap_err().to_string();
            assert!(e.contains("map_size"), "{bad}: {e}");
        }
        // Written back as they were read; shown as the flag takes them.
        assert_eq!(serde_json::to_string(&wide).unwrap(), "[400,300]");
        assert_eq!(serde_json::to_string(&MapSize::square(64)).unwrap(), "64");
        assert_eq!(
            (wide.to_string(), MapSize::square(64).to_string()),
            ("400x300".into(), "64".into())
        );
        assert!(wide
            .square_side("cascades")
            .unwrap_err()
            .to_string()
            .contains("needs a square map"));
    }
}
