//! The chapters' technique: one 2D depth map per light ("Shadows", sections "Shadow
//! Mapping" and "Improving"; LearnOpenGL "Shadow Mapping").
//!
//! 1. The depth pass ([`Map2d::render_depth`], the book's `renderDepthMap`): bind the
//!    map's framebuffer, viewport to its size, clear depth, draw every caster with the
//!    light's view and its orthographic (or perspective) projection.
//! 2. The test: `calcShadow` in `shaders/lib/shadow_2d.glsl`, called once per fragment with
//!    the fragment's light-space position (`mlightviewVertexPos`, from scene.vert).
//!
//! The light's camera ([`camera`]) is the book's `OrthoCoords` box with its angle-built
//! view, LearnOpenGL's look-at, a perspective frustum (the slides, the blog), a spot's
//! frustum, or a box fitted to the scene ([`super::fitted`]).

use super::camera::{perspective_view, point_camera, Perspective};
use super::casters::{casters, depth_state, draw_casters, may_land};
use super::patch::Patch;
use super::{
    fitted, DepthPass, DepthViewKind, LightGlsl, Rays, ShadowKind, ShadowView, SlotTransform,
    Technique,
};
use crate::engine::{state, DepthPassGuard, DepthState, Gl, Sampling, ShadowMap, Texture};
use crate::error::Result;
use crate::scene::{Light, Scene};
use crate::settings::{Fit, LightProjection, ShadowSettings};

/// Its sampler in the scene shader, per light (GLSL 3.30 cannot index sampler arrays).
pub const SAMPLERS: [&str; crate::scene::MAX_LIGHTS] =
    ["shadowMap0", "shadowMap1", "shadowMap2", "shadowMap3"];

/// Light `i`'s part of the generated snippets: `calcShadow` (shaders/lib/shadow_2d.glsl),
/// its sampler and its call of `addLight2D` with its map slot `p`.
pub fn glsl(i: usize, p: usize, positional: bool, cone: bool, hardware: bool) -> LightGlsl {
    LightGlsl {
        snippet: "lib/shadow_2d.glsl",
        functions: &[
            "softTaps",
            "pcssDistance",
            "pcssPenumbra",
            "pcss",
            "calcShadow",
            "addLight2D",
        ],
        sampler_type: if hardware {
            "sampler2DShadow"
        } else {
            "sampler2D"
        },
        call: format!(
            "addLight2D_{i}({i}, {p}, {}, {positional}, {cone}, f);",
            SAMPLERS[i]
        ),
    }
}

/// A light's one 2D map: the book's `ShadowMap` (an FBO and its depth texture).
pub struct Map2d {
    map: ShadowMap,
}

impl Map2d {
    pub fn new(gl: &Gl, settings: &ShadowSettings) -> Result<Map2d> {
        Ok(Map2d {
            map: ShadowMap::new(gl, settings.map_size, settings.depth_format)?,
        })
    }

    /// The depth pass: the whole map, or with `patch` its region alone (scissored: the
    /// clear and the casters touch nothing else) with its casters.
    fn draw(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
        patch: Option<&Patch>,
    ) -> Result<ShadowView> {
        let (view, fitted_casters) = camera_and_casters(scene, index, pass.settings);
        // A fitted box's casters, of those the patch draws.
        let only = match (fitted_casters, patch) {
            (only, None) => only,
            (None, Some(p)) => Some(p.casters.clone()),
            (Some(f), Some(p)) => Some(f.into_iter().filter(|k| p.casters.contains(k)).collect()),
        };
        let program = pass.programs.flat(pass.gl)?;
        let depth = DepthState {
            scissor: patch.map(|p| p.region.pixels()),
            ..depth_state(pass.settings)
        };
        let _state = DepthPassGuard::begin(pass.gl, depth, &program);
        self.map.bind_for_writing();
        state::clear_depth(pass.gl);
        draw_map_casters(pass, scene, index, &view, &program, only.as_deref());
        Ok(view)
    }
}

impl Technique for Map2d {
    fn kind(&self) -> ShadowKind {
        ShadowKind::Map
    }

    fn fits(&self, s: &ShadowSettings) -> bool {
        self.map.size() == s.map_size && self.map.format() == s.depth_format
    }

    /// The book's `renderDepthMap`.
    fn render_depth(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
    ) -> Result<ShadowView> {
        self.draw(pass, scene, index, None)
    }

    fn patches(&self) -> bool {
        true
    }

    fn render_depth_patch(
        &mut self,
        pass: &mut DepthPass,
        scene: &Scene,
        index: usize,
        patch: &Patch,
    ) -> Result<ShadowView> {
        self.draw(pass, scene, index, Some(patch))
    }

    fn texture(&self) -> &Texture {
        self.map.depth_map_texture()
    }

    fn sampling(&self, settings: &ShadowSettings) -> Sampling {
        let s = settings.effective();
        Sampling {
            compare: s.filter.hardware(),
            linear: s.filter.hardware(),
            wrap: s.wrap,
        }
    }

    fn slot_transform(
        &self,
        _light: &Light,
        view: &ShadowView,
        settings: &ShadowSettings,
    ) -> Option<SlotTransform> {
        Some(slot_transform(view, settings))
    }

    fn bytes(&self) -> u64 {
        self.map.size().texels() * 4
    }

    fn depth_view(&self) -> DepthViewKind {
        DepthViewKind::Flat
    }

    fn depth_map(&self) -> Option<&ShadowMap> {
        Some(&self.map)
    }
}

/// Draws light `index`'s casters into the bound 2D map with `program` (depth.vert's
/// uniforms), seen through `view`, and counts them: only casters that can land in the map,
/// the rest would be clipped anyway, and of those only the ones in `only` when given (the
/// casters a fitted box was fitted to).
pub fn draw_map_casters(
    pass: &mut DepthPass,
    scene: &Scene,
    index: usize,
    view: &ShadowView,
    program: &crate::engine::ShaderProgram,
    only: Option<&[usize]>,
) {
    program.set_mat4("orthoProjectionMatrix", &view.projection);
    let light = &scene.lights[index];
    let boxes = pass.boxes;
    let keep = |k: usize| {
        only.is_none_or(|o| o.contains(&k)) && may_land(light, view, boxes[k].0, boxes[k].1)
    };
    let drawn = draw_casters(
        pass.meshes,
        scene,
        program,
        "modelLightViewMatrix",
        view.view64,
        keep,
    );
    pass.casters.drawn += drawn as u64;
    pass.casters.total += casters(scene);
}

/// The light-space transform of a 2D map drawn through `view` (the chapter's map and a
/// moment map alike): world to the light's view, its projection, the normal offset in world
/// units.
pub fn slot_transform(view: &ShadowView, settings: &ShadowSettings) -> SlotTransform {
    SlotTransform {
        from: view.view64,
        projection: view.projection,
        normal_offset: settings.normal_offset * view.texel_world,
    }
}

/// Light `index`'s camera for its 2D map under `settings`: its own, or with
/// `fit = "scene"` an orthographic box fitted to this scene ([`fitted::fit_ortho`]).
pub fn camera(scene: &Scene, index: usize, settings: &ShadowSettings) -> ShadowView {
    camera_and_casters(scene, index, settings).0
}

/// [`camera`], with the casters a fitted box was fitted to: the only ones its depth pass
/// needs (`None`: the light's own camera, every caster that lands in it).
pub fn camera_and_casters(
    scene: &Scene,
    index: usize,
    settings: &ShadowSettings,
) -> (ShadowView, Option<Vec<usize>>) {
    let light = &scene.lights[index];
    match (light, settings.light_projection, settings.fit) {
        (Light::Directional(l), LightProjection::Ortho, Fit::Scene) => {
            let (fitted, casters) =
                fitted::fit_ortho_casters(scene, l.direction, settings.map_size, settings.snap);
            (fitted.shadow_view(l.direction), Some(casters))
        }
        _ => (own_camera(light, settings), None),
    }
}

/// The light's own camera. A directional light with `LightProjection::Perspective` becomes
/// a point-like light at its shadow position looking at the origin (LearnOpenGL's
/// "orthographic vs perspective" comparison).
fn own_camera(light: &Light, settings: &ShadowSettings) -> ShadowView {
    match (light, settings.light_projection) {
        (Light::Directional(l), LightProjection::Ortho) => {
            let o = &l.ortho;
            let view = l.view_matrix(settings.light_view);
            ShadowView {
                view,
                view64: view.as_dmat4(),
                projection: l.projection_matrix(),
                perspective: false,
                near: o.near,
                far: o.far,
                texel_world: ((o.right - o.left) / settings.map_size.width as f32)
                    .max((o.top - o.bottom) / settings.map_size.height as f32),
                rays: Rays::Parallel {
                    to_light: l.direction.normalize(),
                },
            }
        }
        (Light::Directional(l), LightProjection::Perspective) => {
            let eye = l.position();
            // The ortho box may start behind the light (the book's near is -1); a
            // perspective frustum needs a positive near, and at least 1 unit keeps its
            // depth precision usable (LearnOpenGL's comparison uses near 1).
            let near = l.ortho.near.max(1.0);
            let far = l.ortho.far.max(near * 2.0);
            let frustum = Perspective {
                fov: settings.perspective_fov,
                aspect: settings.map_size.aspect(),
                near,
                far,
            };
            perspective_view(
                eye,
                eye - l.direction.normalize() * l.shadow_pos_mult,
                None,
                frustum,
                settings.map_size,
            )
        }
        (Light::Spot(s), _) => {
            let frustum = Perspective {
                fov: s.fov,
                aspect: s.aspect,
                near: s.near,
                far: s.far,
            };
            perspective_view(s.position, s.target, s.up, frustum, settings.map_size)
        }
        // A point light's camera is its cube's.
        (Light::Point(p), _) => point_camera(p, settings),
    }
}
