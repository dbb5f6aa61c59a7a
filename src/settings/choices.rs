//! The values the enum settings take: techniques, blurs, biases, culling, the light
//! camera's views and projections (the filters have a file of their own, `filter.rs`).

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

/// Where a translucent item's fragments take a light's shadow test (opacity below 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum TranslucentReceivers {
    /// Per pixel, as the opaque items: the light's filter and translucent lookup at every
    /// fragment of every translucent layer.
    #[default]
    Pixel,
    /// Per vertex, interpolated across the triangle, as engines light particles: the test
    /// (a 2D depth or moment map's, not PCSS's or the soft moment filters') runs once a
    /// vertex.
    Vertex,
}

/// What an opaque receiver reads from a light's translucent map (`volumetric` osm, fom or
/// avsm).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, clap::ValueEnum)]
pub enum OpaqueReceivers {
    /// The curve at the receiver's own depth: the technique's lookup at every pixel.
    #[default]
    Curve,
    /// One filtered fetch of a map resolved beside the two maps: the curve read at the
    /// depth map's own depth, where a lit opaque receiver lies.
    Resolved,
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
