//! `Renderer`: the book's two-pass frame ("Shadows": `Renderer.render`).
//!
//! 1. [`Renderer::render_depth_map`]: each casting light's technique draws the scene from
//!    the light into its map (for the chapter's light, [`crate::shadows::map2d`]).
//! 2. [`Renderer::render_scene`]: the scene from the camera ([`scene_pass`]); each fragment
//!    asks each light's test whether it is lit (`calcShadow` in `shaders/lib/shadow_2d.glsl`).
//!
//! What is not the chapter's (the cache's [`DepthSchedule`], the shadow mask, the volumes,
//! the depth view, the counters) lives in the files beside this one.

mod access;
mod depth_view;
mod prepare;
mod programs;
mod scene_inputs;
mod scene_pass;
mod shadow_mask;
mod target;
mod translucent_maps;
mod translucent_pass;
mod vertex_light;
mod vertex_light_cache;
mod volume_pass;

pub use crate::shadows::cache::schedule::DepthPasses;
pub use access::{Pass, PassHooks};
pub use depth_view::DepthRange;
pub use shadow_mask::MaskUses;
pub use target::Target;
pub use vertex_light_cache::VertexLightCounts;

use std::rc::Rc;

use crate::engine::ShaderProgram;
use crate::engine::{check_gl, gl_limits, state, Gl, Outputs, Samplers, SamplesQuery};
use crate::error::Result;
use crate::scene::Scene;
use crate::settings::ShadowSettings;
use crate::shadows::cache::schedule::DepthSchedule;
use crate::shadows::casters::DepthPrograms;
use crate::shadows::plan::ShadowPlan;
use crate::shadows::program::slots::MaskMode;
use crate::shadows::program::ProgramKey;
use crate::shadows::volumes::Volumes;
use crate::shadows::{CasterCounts, DepthPass, ShadowView, Technique};
use scene_inputs::SceneGpu;

/// Owns the GL side of one scene: its meshes and textures, the programs, and one shadow
/// technique per casting light. Create it after the context and drop it before.
pub struct Renderer {
    gl: Gl,
    settings: ShadowSettings,
    /// Each light's kind and settings, decided when the settings or the lights change.
    plan: ShadowPlan,
    /// The scene's meshes and textures.
    gpu: SceneGpu,
    /// One per scene light, in the scene's order; `None` for a light that does not cast
    /// or has shadow volumes.
    shadows: Vec<Option<Box<dyn Technique>>>,
    /// Each light's camera in the last depth pass.
    views: Vec<Option<ShadowView>>,
    /// What each map holds, and which to keep, patch or draw this frame.
    schedule: DepthSchedule,
    depth_programs: DepthPrograms,
    /// Casters drawn into maps against casters offered, so far.
    casters: CasterCounts,
    /// Each light's translucent map, for the lights whose plan keeps one.
    volumetric: crate::shadows::volumetric::Maps,
    /// The translucent items' per-vertex light, kept with the maps.
    vertex_light: vertex_light_cache::VertexLight,
    /// Scene programs by what they were compiled for, the last used first.
    scene_programs: Vec<(ProgramKey, ShaderProgram)>,
    /// This frame's scene-program keys by outputs: worked out once a frame
    /// ([`Renderer::program_key`]), forgotten when a frame's depth pass begins or what
    /// they follow (the plan, the settings, the visibility light) changes.
    frame_keys: std::cell::RefCell<Vec<(Outputs, ProgramKey)>>,
    samplers: Samplers,
    /// Every pixel's shadow tests, kept while nothing changes ([`shadow_mask`]).
    mask: shadow_mask::ShadowMask,
    /// The meshes with adjacency and the extruding program, made when a light first
    /// needs them; a samples-passed query per light, and those the last frame read.
    volumes: Option<Volumes>,
    volume_queries: Vec<SamplesQuery>,
    volume_counted: Vec<usize>,
    depth_view: depth_view::DepthView,
    hooks: Option<Rc<dyn PassHooks>>,
    /// The driver's limit, for the lights' own settings.
    max_texture_size: u32,
    /// The light whose shadow test the visibility output carries.
    visibility_light: usize,
    /// The light whose map the depth view shows.
    depth_view_light: usize,
    /// The scene program's key, the target size and the cache setting
    /// [`Renderer::prepare_frame`] made everything for.
    prepared: Option<(ProgramKey, (u32, u32), bool)>,
}

impl Renderer {
    /// Uploads the scene's meshes and textures and builds the pipeline for `settings`.
    pub fn new(gl: &Gl, scene: &Scene, settings: &ShadowSettings) -> Result<Renderer> {
        let max_texture_size = gl_limits(gl).max_texture_size;
        settings.validate(max_texture_size)?;
        let gpu = SceneGpu::upload(gl, scene)?;
        state::enable_depth_test(gl);
        let mut renderer = Renderer {
            gl: gl.clone(),
            settings: *settings,
            plan: ShadowPlan::default(),
            gpu,
            shadows: Vec::new(),
            views: Vec::new(),
            schedule: DepthSchedule::default(),
            depth_programs: DepthPrograms::default(),
            casters: CasterCounts::default(),
            volumetric: Default::default(),
            vertex_light: Default::default(),
            scene_programs: Vec::new(),
            frame_keys: Default::default(),
            samplers: Samplers::default(),
            mask: shadow_mask::ShadowMask::default(),
            volumes: None,
            volume_queries: Vec::new(),
            volume_counted: Vec::new(),
            depth_view: depth_view::DepthView::new(gl)?,
            hooks: None,
            max_texture_size,
            visibility_light: 0,
            depth_view_light: 0,
            prepared: None,
        };
        renderer.prepare_shadows(scene)?;
        // Compile the scene program now, so a shader error shows before the first frame.
        renderer.use_program(scene, Outputs::default(), MaskMode::Off)?;
        check_gl(gl, "renderer setup")?;
        Ok(renderer)
    }

    /// One frame: the shadows first (the depth maps and what is drawn beside them), then
    /// the scene (or, with `show_depth_map`, a map itself) into `target`.
    pub fn render(&mut self, scene: &Scene, target: Target) -> Result<()> {
        self.render_shadows(scene)?;
        if self.settings.show_depth_map {
            self.render_depth_view(scene, target)
        } else {
            self.render_scene(scene, target)
        }
    }

    /// The shadow pass as measurement sees it: the chapter's depth maps, then the
    /// translucent maps and the per-vertex light drawn from them ([`translucent_maps`]).
    pub fn render_shadows(&mut self, scene: &Scene) -> Result<()> {
        self.hook(Pass::Depth, true);
        let result = self.draw_shadows(scene);
        self.hook(Pass::Depth, false);
        result?;
        check_gl(&self.gl, "the depth-map pass")
    }

    fn draw_shadows(&mut self, scene: &Scene) -> Result<()> {
        self.render_depth_map(scene)?;
        self.render_translucent_maps(scene)?;
        self.capture_vertex_light(scene)
    }

    /// The shadow pass (the book's `renderDepthMap`): each casting light's technique binds
    /// its map's FBO, sets the viewport to its size, clears depth and draws the casters with
    /// the light's view and projection. The schedule keeps a map that still holds what its
    /// light sees, or has only a patch of it drawn again.
    pub fn render_depth_map(&mut self, scene: &Scene) -> Result<()> {
        self.prepare_shadows(scene)?;
        self.frame_keys.get_mut().clear();
        self.schedule
            .begin(scene, &self.shadows, self.settings.shadow_cache);
        for (index, shadow) in self.shadows.iter_mut().enumerate() {
            let view = &mut self.views[index];
            let Some(technique) = shadow else {
                *view = None;
                continue;
            };
            let settings = self.plan.lights[index].settings;
            let step = self
                .schedule
                .step(scene, index, &**technique, &settings, view.is_some());
            let Some(step) = step else { continue };
            let mut pass = DepthPass {
                gl: &self.gl,
                meshes: &self.gpu.meshes,
                programs: &mut self.depth_programs,
                settings: &settings,
                boxes: self.schedule.boxes(),
                casters: &mut self.casters,
                instances: &self.gpu.instances,
            };
            *view = Some(match &step.patch {
                Some(patch) => technique.render_depth_patch(&mut pass, scene, index, patch)?,
                None => technique.render_depth(&mut pass, scene, index)?,
            });
            self.schedule.drawn(index, step);
        }
        Ok(())
    }

    /// The main pass (the book's `renderScene`): the scene from the camera, each light's map
    /// on its texture unit. Call after [`Renderer::render_depth_map`].
    pub fn render_scene(&mut self, scene: &Scene, target: Target) -> Result<()> {
        self.after_depth_map(scene, "render_scene")?;
        self.prepare_frame(scene, target)?;
        let plan = self.plan_scene(scene, target)?;
        self.hook(Pass::Scene, true);
        // The samplers leave the renderer for the pass, so the inputs can borrow the rest.
        let mut samplers = std::mem::take(&mut self.samplers);
        let result = self.draw_scene(scene, target, &plan, &mut samplers);
        self.samplers = samplers;
        self.hook(Pass::Scene, false);
        result?;
        check_gl(&self.gl, "the scene pass")
    }
}
