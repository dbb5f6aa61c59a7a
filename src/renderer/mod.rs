//! `Renderer`: the book's two-pass frame ("Shadows": `Renderer.render`).
//!
//! 1. [`Renderer::render_depth_map`]: each casting light's technique draws the scene from
//!    the light into its map (for the chapter's light, [`crate::shadows::map2d`]).
//! 2. [`Renderer::render_scene`]: the scene from the camera; each fragment asks each
//!    light's test whether it is lit (`calcShadow` in `shaders/lib/shadow_2d.glsl`).
//!
//! The techniques live in [`crate::shadows`]; this file only orders the passes and feeds
//! the scene shader ([`scene_pass`]). With stencil shadow volumes the scene pass becomes
//! one pass per light ([`volume_pass`]). Measurement attaches through [`PassHooks`] and the
//! target's extra outputs; the renderer does not know who measures.

mod depth_view;
mod scene_pass;
mod shadow_mask;
mod volume_pass;

pub use shadow_mask::MaskUses;

use std::rc::Rc;

use crate::engine::{check_gl, gl_limits, state, Gl, Mesh, Outputs, RenderTarget, Samplers};
use crate::engine::{SamplesQuery, ShaderProgram, ShadowMap, Texture};
use crate::error::{Error, Result};
use crate::image_data::ImageData;
use crate::scene::Scene;
use crate::settings::ShadowSettings;
use crate::shadows::casters::DepthPrograms;
use crate::shadows::patch::{MapRecord, Patch};
use crate::shadows::plan::ShadowPlan;
use crate::shadows::program::ProgramKey;
use crate::shadows::slots::MaskMode;
use crate::shadows::volumes::Volumes;
use crate::shadows::{cache, fitted, CasterCounts, DepthPass, ShadowKind, ShadowView, Technique};

/// Where the main pass draws: the window's framebuffer (size in physical pixels) or an
/// offscreen [`RenderTarget`].
#[derive(Clone, Copy)]
pub enum Target<'a> {
    Window { width: u32, height: u32 },
    Offscreen(&'a RenderTarget),
}

impl Target<'_> {
    pub fn size(&self) -> (u32, u32) {
        match self {
            Target::Window { width, height } => (*width, *height),
            Target::Offscreen(t) => (t.width(), t.height()),
        }
    }

    /// The outputs besides colour (a window has none).
    pub fn outputs(&self) -> Outputs {
        match self {
            Target::Window { .. } => Outputs::default(),
            Target::Offscreen(t) => t.outputs(),
        }
    }

    /// Binds the target and sets the viewport to its size, keeping what is drawn there (to
    /// draw over a frame).
    fn bind(&self, gl: &Gl) {
        match self {
            Target::Offscreen(t) => t.bind(),
            Target::Window { width, height } => state::bind_window(gl, *width, *height),
        }
    }

    /// Binds the target, sets the viewport to its size in pixels (not the window's logical
    /// size) and clears it.
    fn bind_and_clear(&self, gl: &Gl, colour: [f32; 4]) {
        match self {
            Target::Offscreen(t) => t.bind_and_clear(colour),
            Target::Window { width, height } => {
                state::bind_window_and_clear(gl, *width, *height, colour)
            }
        }
    }
}

/// How many lights' depth passes were drawn whole, how many were skipped because the map
/// still held what the light sees, and how many drew only the part moved casters changed
/// (`shadow_cache`; [`crate::shadows::patch`]).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DepthPasses {
    pub drawn: u64,
    pub skipped: u64,
    pub patched: u64,
    /// The texels the patches cleared and drew again, summed.
    pub patched_texels: u64,
}

impl DepthPasses {
    /// Counts a pass drawn whole, or `patch`.
    fn count(&mut self, patch: Option<&Patch>) {
        match patch {
            Some(p) => {
                self.patched += 1;
                self.patched_texels += p.region.texels();
            }
            None => self.drawn += 1,
        }
    }
}

/// The passes of a frame, for [`PassHooks`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pass {
    Depth,
    Scene,
}

/// Measurement attached from outside (the bench's GPU timers): told when a pass begins and
/// ends.
pub trait PassHooks {
    fn begin(&self, pass: Pass);
    fn end(&self, pass: Pass);
}

/// Owns the GL side of one scene: its meshes and textures, the programs, and one shadow
/// technique per casting light. Create it after the context and drop it before.
pub struct Renderer {
    gl: Gl,
    settings: ShadowSettings,
    /// Each light's kind and settings, decided when the settings or the lights change.
    plan: ShadowPlan,
    meshes: Vec<Mesh>,
    textures: Vec<Texture>,
    /// 1 x 1 white, for items without a texture.
    white: Texture,
    /// One per scene light, in the scene's order; `None` for a light that does not cast
    /// or has shadow volumes.
    shadows: Vec<Option<Box<dyn Technique>>>,
    /// Each light's kind of shadow (a light with volumes has no technique above).
    kinds: Vec<ShadowKind>,
    /// The meshes with adjacency and the extruding program, made when a light first
    /// needs them.
    volumes: Option<Volumes>,
    /// One samples-passed query per light, for the volumes' fill.
    volume_queries: Vec<SamplesQuery>,
    /// The queries of the last frame's volume passes (read only when asked: a read waits
    /// for the frame).
    volume_counted: Vec<usize>,
    /// Each light's camera in the last depth pass.
    views: Vec<Option<ShadowView>>,
    /// What each light's map holds ([`cache::content_key`]); `None`: draw it again.
    drawn: Vec<Option<u64>>,
    /// What each patchable map was drawn with, to patch it when only casters move.
    records: Vec<Option<MapRecord>>,
    /// Depth passes drawn and skipped (the map was still right) so far.
    passes: DepthPasses,
    /// Casters drawn into maps against casters offered, so far.
    casters: CasterCounts,
    /// Every pixel's shadow tests, kept while nothing changes ([`shadow_mask`]).
    mask: shadow_mask::ShadowMask,
    depth_programs: DepthPrograms,
    /// Scene programs by what they were compiled for, the last used first (a bench
    /// alternates a timed target without extra outputs and a scored one with them).
    scene_programs: Vec<(ProgramKey, ShaderProgram)>,
    samplers: Samplers,
    depth_view: depth_view::DepthView,
    hooks: Option<Rc<dyn PassHooks>>,
    /// The driver's limit, for the lights' own settings.
    max_texture_size: u32,
    /// The light whose shadow test the visibility output carries.
    visibility_light: usize,
    /// The light whose map the depth view shows.
    depth_view_light: usize,
}

impl Renderer {
    /// Uploads the scene's meshes and textures and builds the pipeline for `settings`.
    pub fn new(gl: &Gl, scene: &Scene, settings: &ShadowSettings) -> Result<Renderer> {
        let max_texture_size = gl_limits(gl).max_texture_size;
        settings.validate(max_texture_size)?;
        let meshes = scene
            .meshes
            .iter()
            .map(|m| Mesh::new(gl, m))
            .collect::<Result<Vec<_>>>()?;
        let textures = scene
            .textures
            .iter()
            .map(|t| Texture::from_image(gl, t))
            .collect::<Result<Vec<_>>>()?;
        let white = ImageData {
            width: 1,
            height: 1,
            rgba: vec![255; 4],
        };
        state::enable_depth_test(gl);
        let mut renderer = Renderer {
            gl: gl.clone(),
            settings: *settings,
            plan: ShadowPlan::default(),
            meshes,
            textures,
            white: Texture::from_image(gl, &white)?,
            shadows: Vec::new(),
            kinds: Vec::new(),
            volumes: None,
            volume_queries: Vec::new(),
            volume_counted: Vec::new(),
            views: Vec::new(),
            drawn: Vec::new(),
            records: Vec::new(),
            passes: DepthPasses::default(),
            casters: CasterCounts::default(),
            mask: shadow_mask::ShadowMask::default(),
            depth_programs: DepthPrograms::default(),
            scene_programs: Vec::new(),
            samplers: Samplers::default(),
            depth_view: depth_view::DepthView::new(gl)?,
            hooks: None,
            max_texture_size,
            visibility_light: 0,
            depth_view_light: 0,
        };
        renderer.prepare_shadows(scene)?;
        // Compile the scene program now, so a shader error shows before the first frame.
        renderer.use_program(scene, Outputs::default(), MaskMode::Off)?;
        check_gl(gl, "renderer setup")?;
        Ok(renderer)
    }

    pub fn settings(&self) -> &ShadowSettings {
        &self.settings
    }

    /// Each light's shadow as the last frame drew it.
    pub fn plan(&self) -> &ShadowPlan {
        &self.plan
    }

    /// Switches settings; what they change (programs, maps) is rebuilt on the next frame.
    pub fn set_settings(&mut self, settings: &ShadowSettings) -> Result<()> {
        settings.validate(self.max_texture_size)?;
        self.settings = *settings;
        Ok(())
    }

    /// Which light's shadow test the visibility output carries (`compare` measures one
    /// light at a time).
    pub fn set_visibility_light(&mut self, index: usize) {
        self.visibility_light = index;
    }

    /// Which light's map the depth view shows.
    pub fn set_depth_view_light(&mut self, index: usize) {
        self.depth_view_light = index;
    }

    /// Attaches measurement: `hooks` is told when each pass begins and ends.
    pub fn set_hooks(&mut self, hooks: Rc<dyn PassHooks>) {
        self.hooks = Some(hooks);
    }

    /// The first light's 2D shadow map, if it has one (the chapters' one map).
    pub fn shadow_map(&self) -> Option<&ShadowMap> {
        self.shadows.first()?.as_deref()?.depth_map()
    }

    /// The first light's camera of the last depth pass.
    pub fn shadow_view(&self) -> Option<&ShadowView> {
        self.views.first()?.as_ref()
    }

    /// Depth passes drawn, skipped and patched so far ([`DepthPasses`]).
    pub fn depth_passes(&self) -> DepthPasses {
        self.passes
    }

    /// Frames that wrote the cached shadow mask and frames that read it, so far.
    pub fn mask_uses(&self) -> MaskUses {
        self.mask.uses
    }

    /// Casters drawn into maps against casters offered so far (culled per light volume;
    /// cascades cull per cascade and count only in the passes).
    pub fn caster_counts(&self) -> CasterCounts {
        self.casters
    }

    /// The pixels of shadow-volume faces that passed the depth test in the last frame
    /// (what z-fail counts: the fill the volumes cost); 0 without volumes.
    pub fn volume_pixels(&self) -> u64 {
        self.volume_counted
            .iter()
            .map(|&i| self.volume_queries[i].read())
            .sum()
    }

    /// Shadow maps in use and the bytes they take.
    pub fn shadow_memory(&self) -> (usize, u64) {
        let techniques = self.shadows.iter().flatten();
        (
            techniques.clone().count(),
            techniques.map(|t| t.bytes()).sum(),
        )
    }

    /// One frame: the depth maps first, then the scene (or, with `show_depth_map`, a map
    /// itself) into `target`.
    pub fn render(&mut self, scene: &Scene, target: Target) -> Result<()> {
        self.render_depth_map(scene)?;
        if self.settings.show_depth_map {
            self.render_depth_view(scene, target)
        } else {
            self.render_scene(scene, target)
        }
    }

    /// The shadow pass: each casting light's technique draws the casters into its map
    /// (the book's `renderDepthMap`: bind the map's FBO, viewport to its size, clear depth,
    /// draw with the light's view and projection).
    pub fn render_depth_map(&mut self, scene: &Scene) -> Result<()> {
        self.prepare_shadows(scene)?;
        self.hook(Pass::Depth, true);
        let boxes = match self.shadows.iter().any(Option::is_some) {
            true => fitted::item_world_boxes(scene),
            false => Vec::new(),
        };
        // Each item's placement, once for every light's cache key and patch record.
        let placements = match self.settings.shadow_cache && !boxes.is_empty() {
            true => cache::placements(scene),
            false => Vec::new(),
        };
        for (index, (shadow, view)) in self.shadows.iter_mut().zip(&mut self.views).enumerate() {
            let light = &scene.lights[index];
            let settings = self.plan.lights[index].settings;
            let Some(technique) = shadow else {
                *view = None;
                continue;
            };
            let follows = cache::follows_camera(light, technique.kind(), &settings);
            let facts = settings
                .shadow_cache
                .then(|| cache::LightFacts::of(scene, index, &settings, follows));
            let key = facts
                .as_ref()
                .map(|f| cache::content_key(scene, &boxes, &placements, index, f));
            if key.is_some() && key == self.drawn[index] && view.is_some() {
                self.passes.skipped += 1;
                continue;
            }
            // A kept map of a fixed camera can be patched where only casters moved.
            let record = facts
                .filter(|_| technique.patches())
                .and_then(|f| MapRecord::of(scene, &boxes, &placements, &f, settings.map_size));
            let kept = self.drawn[index].is_some() && view.is_some();
            let patch = match (&self.records[index], &record) {
                (Some(old), Some(now)) if kept => old.patch_to(now),
                _ => None,
            };
            let mut pass = DepthPass {
                gl: &self.gl,
                meshes: &self.meshes,
                programs: &mut self.depth_programs,
                settings: &settings,
                boxes: &boxes,
                casters: &mut self.casters,
            };
            // Forget the key first: a failed pass leaves the map to be drawn again.
            self.drawn[index] = None;
            self.records[index] = None;
            *view = Some(match &patch {
                Some(p) => technique.render_depth_patch(&mut pass, scene, index, p)?,
                None => technique.render_depth(&mut pass, scene, index)?,
            });
            self.drawn[index] = key;
            self.records[index] = record;
            self.passes.count(patch.as_ref());
        }
        self.hook(Pass::Depth, false);
        check_gl(&self.gl, "the depth-map pass")
    }

    /// The main pass: the scene from the camera, each light's map on its texture unit. Call
    /// after [`Renderer::render_depth_map`].
    pub fn render_scene(&mut self, scene: &Scene, target: Target) -> Result<()> {
        if self.shadows.len() != scene.lights.len() {
            return Err(Error::Invalid(
                "render_scene before render_depth_map: there are no shadow maps yet".into(),
            ));
        }
        let uses_volumes = self.volumes.is_some() && self.kinds.contains(&ShadowKind::Volume);
        let plan = match uses_volumes {
            true => shadow_mask::Plan::Test,
            false => {
                let key = self.mask_key(scene, target.size())?;
                self.mask.plan(key)
            }
        };
        self.hook(Pass::Scene, true);
        // The samplers leave the renderer for the pass, so the inputs can borrow the rest.
        let mut samplers = std::mem::take(&mut self.samplers);
        let result = self.draw_scene(scene, target, plan, &mut samplers);
        self.samplers = samplers;
        self.hook(Pass::Scene, false);
        result?;
        check_gl(&self.gl, "the scene pass")
    }

    /// The scene pass into `target`, after writing the shadow mask if `plan` says so.
    fn draw_scene(
        &mut self,
        scene: &Scene,
        target: Target,
        plan: shadow_mask::Plan,
        samplers: &mut Samplers,
    ) -> Result<()> {
        if let shadow_mask::Plan::Write(key) = plan {
            self.write_mask(scene, target.size(), key, samplers)?;
        }
        let mode = match plan {
            shadow_mask::Plan::Test => MaskMode::Off,
            _ => MaskMode::Read,
        };
        self.use_program(scene, target.outputs(), mode)?;
        target.bind_and_clear(&self.gl, scene.clear_colour.to_array());
        let inputs = self.scene_inputs(mode);
        let (gl, size) = (&self.gl, target.size());
        match &self.volumes {
            Some(volumes) if self.kinds.contains(&ShadowKind::Volume) => {
                let counted = volume_pass::draw(
                    &inputs,
                    volumes,
                    &self.kinds,
                    self.visibility_light,
                    &self.volume_queries,
                    samplers,
                    gl,
                    scene,
                    size,
                )?;
                if self.settings.show_volumes {
                    volume_pass::draw_debug(volumes, &self.plan, gl, scene, size);
                }
                self.volume_counted = counted;
                Ok(())
            }
            _ => {
                scene_pass::draw(&inputs, samplers, gl, scene, size)?;
                self.volume_counted.clear();
                Ok(())
            }
        }
    }

    /// The scene pass' inputs: the program in front of the cache, the lights' techniques
    /// and views, the mask when the program reads it.
    fn scene_inputs(&self, mode: MaskMode) -> scene_pass::Inputs<'_> {
        scene_pass::Inputs {
            program: &self.scene_programs[0].1,
            shadows: &self.shadows,
            views: &self.views,
            plan: &self.plan,
            meshes: &self.meshes,
            textures: &self.textures,
            white: &self.white,
            pass_light: -1,
            mask: match mode {
                MaskMode::Read => self.mask.texture(),
                _ => None,
            },
        }
    }

    /// The chapters' debug quad: a light's shadow map on the whole target (see
    /// [`depth_view`]).
    pub fn render_depth_view(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let index = self
            .depth_view_light
            .min(self.shadows.len().saturating_sub(1));
        if self.shadows.is_empty() {
            return Err(Error::Invalid(
                "render_depth_view before render_depth_map: there is no shadow map yet".into(),
            ));
        }
        target.bind_and_clear(&self.gl, scene.clear_colour.to_array());
        // A light without a map: the cleared target says so.
        if let Some(technique) = self.shadows[index].as_deref() {
            self.depth_view.draw(
                &self.gl,
                &mut self.samplers,
                technique,
                self.views[index].as_ref(),
            )?;
        }
        check_gl(&self.gl, "the depth-map view")
    }

    /// The shadow-map inset: the depth view (LearnOpenGL's debug quad, [`depth_view`]) drawn
    /// into `rect` of `target` over the frame already there, so the map and the shadows it
    /// makes are seen together. Shows the light the depth view is set to
    /// ([`Renderer::set_depth_view_light`]) or, if that one has no map, the first light
    /// with one; with no map at all it draws nothing. Writes colour only; call after
    /// [`Renderer::render`] (it needs this frame's maps).
    pub fn render_depth_inset(
        &mut self,
        scene: &Scene,
        target: Target,
        rect: state::PixelRect,
    ) -> Result<()> {
        if self.shadows.len() != scene.lights.len() {
            return Err(Error::Invalid(
                "render_depth_inset before render_depth_map: there are no shadow maps yet".into(),
            ));
        }
        let (width, height) = target.size();
        let inside = rect.width > 0
            && rect.height > 0
            && u64::from(rect.x) + u64::from(rect.width) <= u64::from(width)
            && u64::from(rect.y) + u64::from(rect.height) <= u64::from(height);
        if !inside {
            return Err(Error::Invalid(format!(
                "shadow-map inset {rect:?}: expected a non-empty rectangle inside the \
                 {width}x{height} frame"
            )));
        }
        let has_map = |i: &usize| self.shadows.get(*i).is_some_and(Option::is_some);
        let Some(index) = std::iter::once(self.depth_view_light)
            .chain(0..self.shadows.len())
            .find(has_map)
        else {
            return Ok(());
        };
        target.bind(&self.gl);
        if let Some(technique) = self.shadows[index].as_deref() {
            let _overlay = state::OverlayViewport::begin(&self.gl, rect);
            self.depth_view.draw(
                &self.gl,
                &mut self.samplers,
                technique,
                self.views[index].as_ref(),
            )?;
        }
        check_gl(&self.gl, "the shadow-map inset")
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        state::finish(&self.gl);
    }

    /// Makes each light's technique match the plan (resolved again when the settings or the
    /// lights changed): only lights that cast get one, remade when its kind or storage
    /// changes.
    fn prepare_shadows(&mut self, scene: &Scene) -> Result<()> {
        if !self.plan.fits(&scene.lights, &self.settings) {
            let max = Some(self.max_texture_size);
            self.plan = ShadowPlan::resolve(&scene.lights, &self.settings, max)?;
        }
        let plan = &self.plan;
        if plan.has(ShadowKind::Volume) {
            if !self.volumes.as_ref().is_some_and(|v| v.fits(scene)) {
                self.volumes = Some(Volumes::new(&self.gl, scene)?);
            }
            while self.volume_queries.len() < plan.lights.len() {
                self.volume_queries.push(SamplesQuery::new(&self.gl)?);
            }
        }
        let n = plan.lights.len();
        self.kinds.clear();
        self.kinds.extend(plan.lights.iter().map(|l| l.kind));
        self.shadows.resize_with(n, || None);
        self.views.resize(n, None);
        self.drawn.resize(n, None);
        self.records.resize(n, None);
        for (i, (own, shadow)) in plan.lights.iter().zip(&mut self.shadows).enumerate() {
            let (kind, settings) = (own.kind, &own.settings);
            let fits = match shadow {
                Some(t) => t.kind() == kind && t.fits(settings),
                None => matches!(kind, ShadowKind::None | ShadowKind::Volume),
            };
            if !fits {
                *shadow = kind.create(&self.gl, settings)?;
                self.drawn[i] = None;
                self.records[i] = None;
            }
        }
        Ok(())
    }

    /// Moves the program for this frame's key to the front of the cache, compiling it if it
    /// is not there (the cache keeps the last few).
    fn use_program(&mut self, scene: &Scene, outputs: Outputs, mask: MaskMode) -> Result<()> {
        // A bench alternates a timed target and a scored one, each maybe with the mask
        // written and read.
        const KEEP: usize = 6;
        let key = self.program_key(scene, outputs)?.with_mask(mask);
        match self.scene_programs.iter().position(|(k, _)| *k == key) {
            Some(0) => {}
            Some(i) => {
                let entry = self.scene_programs.remove(i);
                self.scene_programs.insert(0, entry);
            }
            None => {
                let program = key.compile(&self.gl)?;
                self.scene_programs.insert(0, (key, program));
                self.scene_programs.truncate(KEEP);
            }
        }
        Ok(())
    }

    /// The scene program's key for this frame's lights and `outputs`, before the mask.
    fn program_key(&self, scene: &Scene, outputs: Outputs) -> Result<ProgramKey> {
        ProgramKey::of(scene, &self.plan, self.visibility_light, outputs)
    }

    /// What this frame's shadow tests depend on ([`shadow_mask::frame_key`]); `None` when
    /// the mask cannot stand for them: no light with a map, a map drawn every frame
    /// (`shadow_cache` off), or a program the mask cannot serve.
    fn mask_key(&self, scene: &Scene, size: (u32, u32)) -> Result<Option<u64>> {
        let program = self.program_key(scene, Outputs::default())?;
        let maps: Vec<Option<u64>> = self
            .shadows
            .iter()
            .zip(&self.drawn)
            .filter(|(t, _)| t.is_some())
            .map(|(_, key)| *key)
            .collect();
        if maps.is_empty() || !program.maskable() {
            return Ok(None);
        }
        Ok(shadow_mask::frame_key(scene, size, &program, &maps))
    }

    /// Draws every pixel's shadow tests into the mask (the scene pass with
    /// `SHADOW_MASK_WRITE`, into the mask's own float target of the frame's size), as the
    /// tests of the frame `key`.
    fn write_mask(
        &mut self,
        scene: &Scene,
        (width, height): (u32, u32),
        key: u64,
        samplers: &mut Samplers,
    ) -> Result<()> {
        self.use_program(scene, Outputs::default(), MaskMode::Write)?;
        let channels = 1 + self.shadows.iter().rposition(Option::is_some).unwrap_or(0);
        self.mask
            .begin_write(&self.gl, (width, height), channels)?
            .bind_and_clear([1.0; 4]);
        let inputs = self.scene_inputs(MaskMode::Write);
        scene_pass::draw(&inputs, samplers, &self.gl, scene, (width, height))?;
        self.mask.written(key);
        Ok(())
    }

    fn hook(&self, pass: Pass, begin: bool) {
        if let Some(h) = &self.hooks {
            match begin {
                true => h.begin(pass),
                false => h.end(pass),
            }
        }
    }
}
