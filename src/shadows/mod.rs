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
//! - [`fitted`]: a directional light's box fitted to the scene (a light camera, used by
//!   [`map2d`]).
//! - [`patch`]: the part of a cached 2D map that moved casters dirtied, drawn again alone.
//! - [`plan`]: which kind each light gets, under which settings, and what is refused: decided
//!   once, before any frame.
//! - [`volumetric`]: how translucent items cast (`volumetric = "off"` or `"solid"`).
//! - [`volumes`]: the slides' stencil shadow volumes, beside the maps rather than behind
//!   [`Technique`]: no storage, no depth pass; the renderer draws them per light into the
//!   stencil buffer (`renderer::volume_pass`).
//!
//! A technique owns its storage (and says whether it still fits the settings), makes its
//! light camera, runs its depth pass, names its shader snippet and sampler, and gives the
//! scene pass its uniforms. The renderer only asks; [`slots`] lays the lights out in the
//! scene shader and [`program`] turns what the shader is compiled for into `#define`s.

pub mod cache;
pub mod camera;
pub mod cascades;
pub mod casters;
pub mod cube;
pub mod fitted;
pub mod groups;
pub mod layers;
pub mod map2d;
pub mod moments;
pub mod patch;
pub mod plan;
pub mod program;
pub mod schedule;
pub mod slots;
pub mod summed;
pub mod volumes;
pub mod volumetric;

use glam::{DMat4, DVec3, Mat4, Vec3};

use crate::engine::{Gl, Mesh, Sampling, ShaderProgram, ShadowMap, Texture};
use crate::error::Result;
use crate::scene::{Light, Scene};
use crate::settings::ShadowSettings;

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
    /// One 2D map of depth's moments, blurred (a moment filter: vsm, evsm2, evsm4, msm).
    Moments,
}

impl ShadowKind {
    /// Whether the kind is a depth array with a box per layer ([`layers`]).
    pub fn layered(self) -> bool {
        matches!(self, ShadowKind::Cascades | ShadowKind::Groups)
    }

    /// Makes the storage of this kind for `settings` (`None` for a light that does not cast,
    /// and for volumes, which need none).
    pub fn create(self, gl: &Gl, settings: &ShadowSettings) -> Result<Option<Box<dyn Technique>>> {
        Ok(match self {
            ShadowKind::None | ShadowKind::Volume => None,
            ShadowKind::Map => Some(Box::new(map2d::Map2d::new(gl, settings)?)),
            ShadowKind::Cube => Some(Box::new(cube::Cube::new(gl, settings)?)),
            ShadowKind::Cascades => Some(Box::new(layers::Layered::<cascades::Cascades>::new(
                gl, settings,
            )?)),
            ShadowKind::Groups => Some(Box::new(layers::Layered::<groups::Groups>::new(
                gl, settings,
            )?)),
            ShadowKind::Moments => Some(Box::new(moments::Moments::new(gl, settings)?)),
        })
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
    /// A 2D map that stores exp(c (2 z - 1)) (EVSM's first moment): shown as the depth z.
    Exponential {
        exponent_bits: u32,
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
    pub snippets: &'static [&'static str],
    pub sampler_type: &'static str,
    pub test: String,
    pub defines: Vec<(&'static str, String)>,
}

/// What a depth pass draws with: the scene's meshes, the depth programs and the settings.
pub struct DepthPass<'a> {
    pub gl: &'a Gl,
    pub meshes: &'a [Mesh],
    pub programs: &'a mut casters::DepthPrograms,
    pub settings: &'a ShadowSettings,
    /// Every item's world box, in the scene's item order ([`fitted::item_world_boxes`],
    /// worked out once a frame for the cache's keys and every pass' culling).
    pub boxes: &'a [(DVec3, DVec3)],
    /// Casters drawn, and casters there were, over the passes so far.
    pub casters: &'a mut CasterCounts,
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
    /// Whether [`Technique::render_depth_patch`] draws part of the map ([`patch`]: only
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
        _patch: &patch::Patch,
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
        _ => map2d::camera(scene, index, settings),
    }
}
