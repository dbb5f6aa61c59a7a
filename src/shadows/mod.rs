//! Shadow techniques, one module each, behind one trait ([`Technique`]).
//!
//! - [`map2d`]: the chapters' technique: one 2D depth map drawn from the light, then
//!   `calcShadow` in `shaders/lib/shadow_2d.glsl` ("Shadows"; LearnOpenGL "Shadow Mapping").
//! - [`cube`]: a point light's depth cube map (LearnOpenGL "Point Shadows").
//! - [`cascades`]: cascaded shadow maps for a directional light.
//! - [`groups`]: a directional light's box fitted per group of casters.
//! - [`layers`]: the depth array with a box per layer, one [`Technique`] (`Layered`) for
//!   cascades and groups, each a `Layout` of its layers.
//! - [`moments`]: filterable maps (VSM, EVSM, MSM): depth's moments in a float colour
//!   map, blurred, for directional and spot lights.
//! - [`plan`]: which kind each light gets, under which settings, and what is refused: decided
//!   once, before any frame.
//! - [`volumetric`]: how translucent items cast (`volumetric = "off"` or `"solid"`).
//! - [`volumes`]: the slides' stencil shadow volumes, beside the maps rather than behind
//!   [`Technique`]: no storage, no depth pass; the renderer draws them per light into the
//!   stencil buffer (`renderer::volume_pass`).
//!
//! Beside the techniques:
//! - [`camera`]: the light cameras they share (a point light's, a perspective one, the box
//!   fitted to the scene), culling against them and where a box lands in a map's texels.
//! - [`casters`]: the depth programs and the one loop that draws the casters.
//! - [`cache`]: which map to keep, patch or draw again, beside the renderer's loop.
//! - [`program`]: the scene program: each light's slot, its texture unit ([`units`]) and the
//!   assembly of the techniques' GLSL into the generated snippets.
//!
//! A technique owns its storage (and says whether it still fits the settings), makes its
//! light camera, runs its depth pass, writes its part of the scene program (its `glsl`:
//! library files, sampler and call) and gives the scene pass its uniforms. Each kind's row
//! ([`kind::KindFacts`], in its technique's file) names its constructor, GLSL and samplers,
//! its HUD words, its storage, its idle rules and its bench family.

pub mod cache;
pub mod camera;
pub mod cascades;
pub mod casters;
pub mod cube;
pub mod groups;
pub mod kind;
pub mod layers;
pub mod map2d;
pub mod moment_mode;
pub mod moments;
pub mod plan;
pub mod program;
pub mod summed;
pub mod units;
pub mod volumes;
pub mod volumetric;

use glam::{DMat4, DVec3, Mat4, Vec3};

use crate::engine::{Gl, InstanceBuffer, Mesh, Sampling, ShaderProgram, ShadowMap, Texture};
use crate::error::Result;
use crate::scene::{Light, Scene};
use crate::settings::{
    glsl_float, BeyondFar, BiasMode, Filter, LightProjection, MapSize, ShadowSettings,
    TranslucentReceivers,
};
pub use kind::KindFacts;
use moments::MomentTest;
use volumetric::VolumetricKey;

/// What a light's shadow is stored in, and so which technique draws it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ShadowKind {
    /// The light does not cast: no map, no lookup.
    None,
    /// One 2D depth map (directional and spot lights; the chapters' case).
    Map,
    /// A depth cube map of distances (point lights).
    Cube,
    /// A depth texture array, one layer per cascade (directional lights with cascades).
    Cascades,
    /// A depth texture array, one layer per group of casters (directional lights with
    /// `caster_groups` > 1).
    Groups,
    /// No map: stencil shadow volumes ([`volumes`]), any kind of light.
    Volume,
    /// One 2D map of depth's moments, blurred (a moment filter: `Filter::MOMENTS` and
    /// `Filter::SOFT_MOMENTS`).
    Moments,
}

impl ShadowKind {
    /// Every kind, in the order the idle rules ask them. A setting keeps the first reason
    /// given for it, so the volumes' row, which calls every map setting idle in a scene of
    /// volumes alone, comes after the rows that give their own settings their own reasons.
    pub const ALL: [ShadowKind; 7] = [
        ShadowKind::None,
        ShadowKind::Map,
        ShadowKind::Cube,
        ShadowKind::Cascades,
        ShadowKind::Groups,
        ShadowKind::Moments,
        ShadowKind::Volume,
    ];

    /// The kind's row, kept in its technique's file: the one table a new technique joins.
    pub fn facts(self) -> &'static KindFacts {
        match self {
            ShadowKind::None => &kind::NO_SHADOW,
            ShadowKind::Map => &map2d::KIND,
            ShadowKind::Cube => &cube::KIND,
            ShadowKind::Cascades => &cascades::KIND,
            ShadowKind::Groups => &groups::KIND,
            ShadowKind::Moments => &moments::KIND,
            ShadowKind::Volume => &volumes::KIND,
        }
    }

    /// Whether the kind is a depth array with a box per layer ([`layers`]).
    pub fn layered(self) -> bool {
        self.facts().layers.is_some()
    }

    /// Whether a light of this kind keeps a map (and a test in the scene shader).
    pub fn has_map(self) -> bool {
        self.facts().technique.is_some()
    }

    /// Makes the storage of this kind for `settings` (`None` for a light that does not cast,
    /// and for volumes, which need none).
    pub fn create(self, gl: &Gl, settings: &ShadowSettings) -> Result<Option<Box<dyn Technique>>> {
        let technique = self.facts().technique.as_ref();
        technique.map(|t| (t.create)(gl, settings)).transpose()
    }

    /// Light `i`'s test in the scene program, its light-space position (if any) in map slot
    /// `p`: the technique's library files, sampler type and call.
    pub fn glsl(self, i: usize, p: usize, test: &ShadowTest) -> Option<LightGlsl> {
        let technique = self.facts().technique.as_ref();
        technique.and_then(|t| (t.glsl)(i, p, test))
    }

    /// The sampler uniform of light `index`'s map, if it has one.
    pub fn sampler(self, index: usize) -> Option<&'static str> {
        let technique = self.facts().technique.as_ref();
        technique.and_then(|t| t.samplers.get(index).copied())
    }

    /// Whether the vertex shader gives the light a light-space position (a 2D or cube
    /// map's `mlightviewVertexPos` slot).
    pub fn map_slot(self) -> bool {
        self.facts().technique.as_ref().is_some_and(|t| t.map_slot)
    }
}

/// What a filter costs per frame: lookups per shaded pixel, passes over the map and the
/// bytes of its storage (the bench states these).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct FilterCost {
    /// Texture lookups per shaded fragment (a bilinear or hardware-compared lookup is one).
    pub taps: u32,
    /// Passes per map per frame: the depth pass, and a moment map's two blur passes.
    pub passes: u32,
    /// Texture reads per map texel in the blur (0 without one).
    pub blur_taps: u32,
    /// Bytes per map texel.
    pub bytes_per_texel: u32,
}

/// The cost of `settings`' filter on one 2D map.
pub fn filter_cost(settings: &ShadowSettings) -> FilterCost {
    let f = settings.filter;
    let components = f.moment_components();
    if components == 0 {
        return FilterCost {
            taps: f.lookups(settings),
            passes: 1,
            blur_taps: 0,
            bytes_per_texel: 4,
        };
    }
    if summed::reads_table(f) {
        let size = settings.map_size;
        let build = crate::engine::summed_area::axis_passes(size.width)
            + crate::engine::summed_area::axis_passes(size.height);
        return FilterCost {
            taps: f.lookups(settings),
            passes: 1 + build,
            blur_taps: crate::engine::summed_area::SAT_RADIX * build,
            // The moment map's two float textures and depth, and the table's two.
            bytes_per_texel: 2 * 4 * components + 4 + 2 * 4 * components,
        };
    }
    let blur = settings.blur.taps();
    FilterCost {
        taps: 1,
        passes: if blur > 0 { 3 } else { 1 },
        blur_taps: 2 * blur,
        bytes_per_texel: 2 * 4 * components + 4,
    }
}

/// The rays a light's map stands for: what the exact reference traces.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rays {
    /// Parallel, towards the light (an orthographic map).
    Parallel { to_light: Vec3 },
    /// From a point (a perspective or cube map: the light's eye).
    FromPoint { position: Vec3 },
}

/// A light's camera in a depth pass.
#[derive(Debug, Clone, Copy)]
pub struct ShadowView {
    pub view: Mat4,
    /// The same view in double precision, for view x model far from the origin.
    pub view64: DMat4,
    pub projection: Mat4,
    /// Perspective projections need the divide by w (and linearising for display).
    pub perspective: bool,
    /// A perspective 2D map that stores linear depth, near (0) to far (1), rather than its
    /// projection's z / w ([`map2d::stores_linear_depth`]).
    pub linear_depth: bool,
    pub near: f32,
    pub far: f32,
    /// The size of one shadow-map texel in world units, at the target for perspective maps.
    pub texel_world: f32,
    pub rays: Rays,
}

/// How a depth view shows a technique's texture.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DepthViewKind {
    Flat,
    /// A 2D map that stores exp(c w), `w` the depth z or, `warped`, 2 z - 1 (EVSM's first
    /// moment): shown as the depth z.
    Exponential {
        exponent_bits: u32,
        warped: bool,
    },
    /// A cube map, as a panorama.
    Cube,
    /// A texture array, its layers side by side.
    Array {
        layers: u32,
    },
}

/// Where a light with a 2D or cube map finds its fragment's light-space position: the
/// scene pass sets `modelLightViewMatrix[slot] = from * model` per item.
#[derive(Debug, Clone, Copy)]
pub struct SlotTransform {
    /// World to the light's view (a point light: to its position).
    pub from: DMat4,
    pub projection: Mat4,
    /// The normal offset in world units.
    pub normal_offset: f32,
}

/// A technique's part of the generated snippet for light `i`: the library files its test
/// needs, its sampler's GLSL type, and its test: a call of the library function its filter
/// chose, with the light's settings as arguments (1 = lit). A layered light's filter is
/// the program's, so it comes as `defines`.
pub struct LightGlsl {
    pub snippets: Vec<&'static str>,
    pub sampler_type: &'static str,
    pub test: String,
    pub defines: Vec<(&'static str, String)>,
}

/// The shadow test's settings, which the generated call passes as arguments: those every
/// map's test takes, then its own kind's ([`OwnTest`]), so that a program's key holds no
/// constant its test does not read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ShadowTest {
    pub bias_mode: BiasMode,
    pub bias_bits: u32,
    pub bias_min_bits: u32,
    pub beyond_far_lit: bool,
    pub normal_offset: bool,
    /// The map's size: the PCF grid steps one texel, 1 / width across and 1 / height up.
    pub map_size: MapSize,
    /// PCSS and the soft moment filters: the light's map is a perspective one (its depth
    /// is not linear).
    pub pcss_perspective: bool,
    /// The light's translucent map, whose transmittance multiplies the test
    /// ([`crate::shadows::volumetric`]).
    pub volumetric: Option<VolumetricKey>,
    /// `translucent_receivers = "vertex"`: translucent items take this test per vertex
    /// where it can run there ([`program::vertex`]).
    pub vertex_receivers: bool,
    pub own: OwnTest,
}

/// What only one kind of map's test takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum OwnTest {
    /// A depth map's (2D, cube, layers).
    Depth(DepthTest),
    /// A moment map's constants ([`moments`], [`summed`]).
    Moments(MomentTest),
}

/// A depth map's test: its filter's taps, PCSS's counts and how the map stores depth.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct DepthTest {
    pub pcf_radius: u32,
    pub hardware: bool,
    /// The grid, or a soft filter's taps (shaders/lib/soft_filters.glsl).
    pub kernel: map2d::Kernel,
    /// PCSS's taps (0 for the other filters, so their key ignores them).
    pub pcss_blocker_taps: u32,
    pub pcss_filter_taps: u32,
    /// How the light's 2D map stores and tests depth ([`map2d::map_depth`]).
    pub map_depth: map2d::MapDepth,
}

impl DepthTest {
    fn of(s: &ShadowSettings) -> DepthTest {
        let pcss = s.filter == Filter::Pcss;
        DepthTest {
            pcf_radius: s.filter.radius(),
            hardware: s.filter.hardware(),
            kernel: s.filter.facts().kernel,
            pcss_blocker_taps: if pcss { s.pcss_blocker_taps } else { 0 },
            pcss_filter_taps: if pcss { s.pcss_filter_taps } else { 0 },
            map_depth: map2d::MapDepth::Projected,
        }
    }
}

impl ShadowTest {
    /// The test as the settings apply it ([`ShadowSettings::effective`]).
    pub fn of(settings: &ShadowSettings) -> ShadowTest {
        let s = settings.effective();
        ShadowTest {
            bias_mode: s.bias_mode,
            bias_bits: s.bias.to_bits(),
            bias_min_bits: s.bias_min.to_bits(),
            beyond_far_lit: s.beyond_far == BeyondFar::Lit,
            normal_offset: s.normal_offset != 0.0,
            map_size: s.map_size,
            pcss_perspective: false,
            volumetric: None,
            vertex_receivers: s.translucent_receivers == TranslucentReceivers::Vertex,
            own: match MomentTest::of(&s) {
                Some(moments) => OwnTest::Moments(moments),
                None => OwnTest::Depth(DepthTest::of(&s)),
            },
        }
    }

    /// The test of `light` under its own settings: as [`ShadowTest::of`], knowing whether
    /// PCSS reads a perspective map (a spot's, or a directional light's perspective one).
    pub fn for_light(light: &Light, settings: &ShadowSettings) -> ShadowTest {
        let perspective = match light {
            Light::Spot(_) => true,
            Light::Directional(_) => settings.light_projection == LightProjection::Perspective,
            Light::Point(_) => false,
        };
        let mut test = ShadowTest {
            pcss_perspective: perspective
                && (settings.filter == Filter::Pcss || summed::reads_table(settings.filter)),
            ..ShadowTest::of(settings)
        };
        if let OwnTest::Depth(depth) = &mut test.own {
            depth.map_depth = map2d::map_depth(perspective, settings);
        }
        test
    }

    /// A depth map's own constants, if the test is a depth map's.
    pub fn depth(&self) -> Option<&DepthTest> {
        match &self.own {
            OwnTest::Depth(d) => Some(d),
            OwnTest::Moments(_) => None,
        }
    }

    /// A moment map's own constants, if the test is a moment map's.
    pub fn moments(&self) -> Option<&MomentTest> {
        match &self.own {
            OwnTest::Moments(m) => Some(m),
            OwnTest::Depth(_) => None,
        }
    }
}

impl ShadowTest {
    /// Whether this test can run in a vertex shader (translucent receivers per vertex): a
    /// 2D depth or moment map's, not PCSS's nor the soft moment filters' (they turn their
    /// taps by the pixel and size them by screen derivatives, which a vertex shader has
    /// not).
    pub fn runs_per_vertex(&self, kind: ShadowKind) -> bool {
        (kind.facts().per_vertex)(self)
    }

    /// The bias argument of light `i`'s test (shaders/lib/bias.glsl): a number, or the
    /// slope bias of the fragment's normal and `toLight{i}`, the direction to the light.
    pub fn bias_glsl(&self, i: usize) -> String {
        let bias = glsl_float(f32::from_bits(self.bias_bits));
        match self.bias_mode {
            BiasMode::None => "0.0".into(),
            BiasMode::Constant => bias,
            BiasMode::Slope => format!(
                "slopeBias(f.normal, toLight{i}, {bias}, {})",
                glsl_float(f32::from_bits(self.bias_min_bits))
            ),
        }
    }

    /// One texel of the map, `vec2(1 / width, 1 / height)`: a constant the compiler folds,
    /// not a `textureSize` query per pixel.
    pub fn texel_glsl(&self) -> String {
        format!(
            "vec2({}, {})",
            glsl_float(1.0 / self.map_size.width as f32),
            glsl_float(1.0 / self.map_size.height as f32)
        )
    }
}

/// What a depth pass draws with: the scene's meshes, the depth programs and the settings.
pub struct DepthPass<'a> {
    pub gl: &'a Gl,
    pub meshes: &'a [Mesh],
    pub programs: &'a mut casters::DepthPrograms,
    pub settings: &'a ShadowSettings,
    /// Every item's world box, in the scene's item order ([`camera::fitted::item_world_boxes`],
    /// worked out once a frame for the cache's keys and every pass' culling).
    pub boxes: &'a [(DVec3, DVec3)],
    /// Casters drawn, and casters there were, over the passes so far.
    pub casters: &'a mut CasterCounts,
    /// The per-instance values of the casters' instanced draws.
    pub instances: &'a InstanceBuffer,
}

impl<'a> DepthPass<'a> {
    /// What a caster draw reads beside its program: the meshes and the instance buffer.
    pub fn gpu(&self) -> (&'a [Mesh], &'a InstanceBuffer) {
        (self.meshes, self.instances)
    }
}

/// Casters drawn into maps against casters offered (those outside a light's volume are
/// culled), summed over depth passes.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct CasterCounts {
    pub drawn: u64,
    pub total: u64,
}

/// One shadow technique for one light.
pub trait Technique {
    fn kind(&self) -> ShadowKind;
    /// Whether the storage still matches `settings` (size, format, layers).
    fn fits(&self, settings: &ShadowSettings) -> bool;
    /// The depth pass for light `index` of `scene`: draws its casters into the storage and
    /// returns the light's camera.
    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView>;
    /// Whether [`Technique::render_depth_patch`] draws part of the map ([`cache::patch`]: only
    /// the chapter's 2D depth map).
    fn patches(&self) -> bool {
        false
    }
    /// [`Technique::render_depth`] into `patch.region` of the map alone, drawing only
    /// `patch.casters` (the map keeps the rest). Without [`Technique::patches`]: the whole
    /// pass.
    fn render_depth_patch(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
        _patch: &cache::patch::Patch,
    ) -> Result<ShadowView> {
        self.render_depth(pass, scene, index)
    }
    /// The texture the scene pass samples: a depth texture, or a moment map's float colour
    /// texture (its `sampling` says how it is read).
    fn texture(&self) -> &Texture;
    /// The texture the depth view shows (a summed-area table's moment map).
    fn view_texture(&self) -> &Texture {
        self.texture()
    }
    /// How the scene pass samples it under `settings`.
    fn sampling(&self, settings: &ShadowSettings) -> Sampling;
    /// The light-space transform of a technique with a map slot (2D and cube maps).
    fn slot_transform(
        &self,
        light: &Light,
        view: &ShadowView,
        settings: &ShadowSettings,
    ) -> Option<SlotTransform>;
    /// Uniforms of the scene program that are the technique's own (cascades' matrices).
    fn set_scene_uniforms(&self, _program: &ShaderProgram, _scene: &Scene, _s: &ShadowSettings) {}
    /// Bytes of GPU memory it holds (a depth texel is 4 bytes on this driver whatever the
    /// format asks; reported as allocated).
    fn bytes(&self) -> u64;
    fn depth_view(&self) -> DepthViewKind;
    /// The chapters' one 2D map, for reading it back (`--depth-out`); other kinds have none.
    fn depth_map(&self) -> Option<&ShadowMap> {
        None
    }
}

/// Light `index`'s camera for a depth pass under `settings`, without GL: the chapter's
/// light camera (fitted to the scene with `fit = "scene"`) or a point light's. The exact
/// reference traces its [`Rays`].
pub fn light_camera(scene: &Scene, index: usize, settings: &ShadowSettings) -> ShadowView {
    match &scene.lights[index] {
        Light::Point(p) => camera::point_camera(p, settings),
        Light::Directional(_) | Light::Spot(_) => map2d::camera(scene, index, settings),
    }
}
