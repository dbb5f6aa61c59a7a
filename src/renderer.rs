//! `Renderer`: the book's two-pass frame. `render_depth_map` draws the scene from the light
//! into the shadow map; the main pass then draws it from the camera, sampling that map.

use glam::{DMat4, Mat3, Mat4, Vec3};
use glow::HasContext;

use crate::engine::mesh::FullScreenTriangle;
use crate::engine::{
    check_gl, gl_limits, CascadeShadowMap, CubeShadowMap, Gl, Mesh, Outputs, PassTimer,
    RenderTarget, ShaderProgram, ShadowMap, Texture,
};
use crate::error::{Error, Result};
use crate::image_data::ImageData;
use crate::light_slots::{self, LightSlot, ShadowKind};
use crate::scene::cascades::{camera_relative_matrix, fit_cascades, Cascade, CascadeSpec};
use crate::scene::fit::item_world_boxes;
use crate::scene::{Light, PointLight, Scene, Shading, ShadingModel, ShadowView};
use crate::settings::PointPass;
use crate::settings::{Cull, ShadowSettings, Wrap};
use crate::shaders;

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
}

/// A light's shadow storage, made when the light first casts and remade when the settings
/// change its size, format or kind.
enum LightShadow {
    None,
    Map(ShadowMap),
    Cube(CubeShadowMap),
    /// The array and the cascades of the last depth pass.
    Cascades(CascadeShadowMap, Vec<Cascade>),
}

impl LightShadow {
    fn kind(&self) -> ShadowKind {
        match self {
            LightShadow::None => ShadowKind::None,
            LightShadow::Map(_) => ShadowKind::Map,
            LightShadow::Cube(_) => ShadowKind::Cube,
            LightShadow::Cascades(..) => ShadowKind::Cascades,
        }
    }

    fn fits(&self, kind: ShadowKind, settings: &ShadowSettings) -> bool {
        let (size, format) = (settings.map_size, settings.depth_format);
        match self {
            LightShadow::None => kind == ShadowKind::None,
            LightShadow::Map(m) => {
                kind == ShadowKind::Map && m.size() == size && m.format() == format
            }
            LightShadow::Cube(c) => {
                kind == ShadowKind::Cube && c.size() == size && c.format() == format
            }
            LightShadow::Cascades(a, _) => {
                kind == ShadowKind::Cascades
                    && a.size() == size
                    && a.format() == format
                    && a.layers() == settings.cascades
            }
        }
    }

    fn new(gl: &Gl, kind: ShadowKind, settings: &ShadowSettings) -> Result<LightShadow> {
        let (size, format) = (settings.map_size, settings.depth_format);
        Ok(match kind {
            ShadowKind::None => LightShadow::None,
            ShadowKind::Map => LightShadow::Map(ShadowMap::new(gl, size, format)?),
            ShadowKind::Cube => LightShadow::Cube(CubeShadowMap::new(gl, size, format)?),
            ShadowKind::Cascades => LightShadow::Cascades(
                CascadeShadowMap::new(gl, size, settings.cascades, format)?,
                Vec::new(),
            ),
        })
    }

    /// The depth texture the scene pass samples.
    fn texture(&self) -> Option<&Texture> {
        match self {
            LightShadow::None => None,
            LightShadow::Map(m) => Some(m.depth_map_texture()),
            LightShadow::Cube(c) => Some(c.texture()),
            LightShadow::Cascades(a, _) => Some(a.texture()),
        }
    }
}

/// Owns the GL side of one scene: its meshes and textures, the programs and one shadow
/// map per casting light. Create it after the context and drop it before.
pub struct Renderer {
    gl: Gl,
    settings: ShadowSettings,
    depth_program: ShaderProgram,
    /// Scene programs by what they were compiled for, the last used first (a bench
    /// alternates a timed target without extra outputs and a scored one with them).
    scene_programs: Vec<(ProgramKey, ShaderProgram)>,
    /// One per scene light, in the scene's order.
    shadows: Vec<LightShadow>,
    /// Each light's camera in the last depth pass (`None` for lights that do not cast).
    shadow_views: Vec<Option<ShadowView>>,
    meshes: Vec<Mesh>,
    textures: Vec<Texture>,
    depth_view_program: ShaderProgram,
    full_screen: FullScreenTriangle,
    /// 1 x 1 white, for items without a texture.
    white: Texture,
    /// A point light's depth program, made when a point light first casts.
    point_depth_program: Option<ShaderProgram>,
    point_program_layered: bool,
    depth_view_cube: Option<ShaderProgram>,
    depth_view_array: Option<ShaderProgram>,
    /// GPU timers for the depth pass (0) and the scene pass (1), when enabled.
    timer: Option<PassTimer>,
    /// The light whose shadow test the visibility output carries.
    visibility_light: usize,
    /// The light whose map the depth view shows.
    depth_view_light: usize,
}

/// Indices of the passes in [`Renderer::pass_times_ms`].
pub const DEPTH_PASS: usize = 0;
pub const SCENE_PASS: usize = 1;

impl Renderer {
    /// Uploads the scene's meshes and textures and builds the pipeline for `settings`.
    pub fn new(gl: &Gl, scene: &Scene, settings: &ShadowSettings) -> Result<Renderer> {
        settings.validate(gl_limits(gl).max_texture_size)?;
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
        let depth_program =
            ShaderProgram::new(gl, &shaders::depth_vert(), &shaders::depth_frag(), &[])?;
        let key = ProgramKey::of(scene, settings, 0, Outputs::default())?;
        let scene_program = scene_program(gl, &key)?;
        let depth_view_program = ShaderProgram::new(
            gl,
            &shaders::depth_view_vert(),
            &shaders::depth_view_frag(),
            &[("CUBE".into(), "0".into()), ("ARRAY".into(), "0".into())],
        )?;
        unsafe { gl.enable(glow::DEPTH_TEST) };
        check_gl(gl, "renderer setup")?;
        let mut renderer = Renderer {
            gl: gl.clone(),
            settings: *settings,
            depth_program,
            scene_programs: vec![(key, scene_program)],
            shadows: Vec::new(),
            shadow_views: Vec::new(),
            meshes,
            textures,
            depth_view_program,
            full_screen: FullScreenTriangle::new(gl)?,
            white: Texture::from_image(
                gl,
                &ImageData {
                    width: 1,
                    height: 1,
                    rgba: vec![255; 4],
                },
            )?,
            point_depth_program: None,
            point_program_layered: false,
            depth_view_cube: None,
            depth_view_array: None,
            timer: None,
            visibility_light: 0,
            depth_view_light: 0,
        };
        renderer.prepare_shadows(scene)?;
        Ok(renderer)
    }

    pub fn settings(&self) -> &ShadowSettings {
        &self.settings
    }

    /// Switches settings, rebuilding only what they change (the program for shader
    /// variants, shadow maps for their size, format or kind, on the next frame).
    pub fn set_settings(&mut self, settings: &ShadowSettings) -> Result<()> {
        settings.validate(gl_limits(&self.gl).max_texture_size)?;
        self.settings = *settings;
        for shadow in &self.shadows {
            configure_sampling(shadow, settings);
        }
        check_gl(&self.gl, "changing settings")
    }

    /// Which light's shadow test the visibility output carries (`compare` measures one
    /// light at a time); the program is rebuilt on the next frame.
    pub fn set_visibility_light(&mut self, index: usize) {
        self.visibility_light = index;
    }

    /// Which light's map the depth view shows.
    pub fn set_depth_view_light(&mut self, index: usize) {
        self.depth_view_light = index;
    }

    /// Times each pass on the GPU from now on (see [`Renderer::pass_times_ms`]).
    pub fn enable_timer(&mut self) -> Result<()> {
        self.timer = Some(PassTimer::new(&self.gl, 2)?);
        Ok(())
    }

    /// GPU milliseconds of the last frame's depth and scene passes (waits for them).
    pub fn pass_times_ms(&self) -> Option<[f64; 2]> {
        let t = self.timer.as_ref()?.read_ms();
        Some([t[DEPTH_PASS], t[SCENE_PASS]])
    }

    /// The first light's 2D shadow map, if it has one (the chapters' one map).
    pub fn shadow_map(&self) -> Option<&ShadowMap> {
        match self.shadows.first() {
            Some(LightShadow::Map(m)) => Some(m),
            _ => None,
        }
    }

    /// The first light's camera of the last depth pass.
    pub fn shadow_view(&self) -> Option<&ShadowView> {
        self.shadow_views.first()?.as_ref()
    }

    /// Shadow maps in use and the bytes they take (a depth texel is 4 bytes on this
    /// driver whatever the format asks; reported as allocated, not as the format's size).
    pub fn shadow_memory(&self) -> (usize, u64) {
        let texel = |s: u32| u64::from(s) * u64::from(s) * 4;
        self.shadows.iter().fold((0, 0), |(n, bytes), s| match s {
            LightShadow::None => (n, bytes),
            LightShadow::Map(m) => (n + 1, bytes + texel(m.size())),
            LightShadow::Cube(c) => (n + 1, bytes + 6 * texel(c.size())),
            LightShadow::Cascades(a, _) => (n + 1, bytes + u64::from(a.layers()) * texel(a.size())),
        })
    }

    /// Makes each light's shadow storage match the scene's lights and the settings: only
    /// lights that cast get a map.
    fn prepare_shadows(&mut self, scene: &Scene) -> Result<()> {
        self.shadows
            .resize_with(scene.lights.len(), || LightShadow::None);
        self.shadow_views.resize(scene.lights.len(), None);
        let kinds = ShadowKind::for_lights(&scene.lights, &self.settings);
        for (kind, shadow) in kinds.into_iter().zip(self.shadows.iter_mut()) {
            if !shadow.fits(kind, &self.settings) {
                *shadow = LightShadow::new(&self.gl, kind, &self.settings)?;
                configure_sampling(shadow, &self.settings);
            }
        }
        Ok(())
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

    /// The shadow pass, once per casting light: bind its map's FBO, viewport to its size,
    /// clear depth, and draw every caster with the light's view and projection (ortho for
    /// the book's light).
    pub fn render_depth_map(&mut self, scene: &Scene) -> Result<()> {
        self.prepare_shadows(scene)?;
        if let Some(t) = &self.timer {
            t.begin(DEPTH_PASS);
        }
        for index in 0..scene.lights.len() {
            self.render_light_depth(scene, index)?;
        }
        if let Some(t) = &self.timer {
            t.end();
        }
        check_gl(&self.gl, "the depth-map pass")
    }

    fn render_light_depth(&mut self, scene: &Scene, index: usize) -> Result<()> {
        let light = scene.lights[index];
        if self.shadows[index].kind() == ShadowKind::None {
            self.shadow_views[index] = None;
            return Ok(());
        }
        let s = &self.settings;
        // Items' world boxes: cascades are fitted above them and culled by them.
        let boxes = match self.shadows[index] {
            LightShadow::Cascades(..) => item_world_boxes(scene),
            _ => Vec::new(),
        };
        let sv = match (&light, &mut self.shadows[index]) {
            (Light::Point(p), _) => {
                self.shadow_views[index] = Some(scene.shadow_view(index, s));
                return self.render_cube_depth_map(scene, index, p);
            }
            (Light::Directional(l), LightShadow::Cascades(_, c)) => {
                *c = fit_cascades(scene, &boxes, l.direction, &CascadeSpec::of(s));
                // The first cascade stands for the light's camera (reports, the depth
                // view's near and far); the one-map fit is not needed.
                match c.first() {
                    Some(first) => first.fitted.shadow_view(l.direction),
                    None => scene.shadow_view(index, s),
                }
            }
            _ => scene.shadow_view(index, s),
        };
        self.shadow_views[index] = Some(sv);
        self.begin_depth_state();
        let program = &self.depth_program;
        program.bind();
        match &self.shadows[index] {
            LightShadow::Map(map) => {
                map.bind_for_writing();
                unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
                program.set_mat4("orthoProjectionMatrix", &sv.projection);
                self.draw_casters(scene, program, "modelLightViewMatrix", sv.view64, &|_| true);
            }
            LightShadow::Cascades(array, cascades) => {
                for (layer, c) in cascades.iter().enumerate() {
                    array.bind_layer(layer as u32);
                    unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
                    let [l, r, b, t, n, f] = c.fitted.bounds;
                    let projection = DMat4::orthographic_rh_gl(l, r, b, t, n, f).as_mat4();
                    program.set_mat4("orthoProjectionMatrix", &projection);
                    let keep = |i: usize| c.may_hold(boxes[i].0, boxes[i].1);
                    self.draw_casters(scene, program, "modelLightViewMatrix", c.fitted.view, &keep);
                }
            }
            LightShadow::None | LightShadow::Cube(_) => {}
        }
        program.unbind();
        self.end_depth_state();
        Ok(())
    }

    /// A point light's depth pass: six faces of a cube map, each a 90-degree view from the
    /// light storing distance over `far` (LearnOpenGL's "Point Shadows").
    fn render_cube_depth_map(
        &mut self,
        scene: &Scene,
        index: usize,
        light: &PointLight,
    ) -> Result<()> {
        let layered = self.settings.point_pass == PointPass::Layered;
        if self.point_depth_program.is_none() || self.point_program_layered != layered {
            self.point_depth_program = Some(if layered {
                ShaderProgram::from_stages(
                    &self.gl,
                    &[
                        (glow::VERTEX_SHADER, &shaders::depth_point_layered_vert()),
                        (glow::GEOMETRY_SHADER, &shaders::depth_point_layered_geom()),
                        (glow::FRAGMENT_SHADER, &shaders::depth_point_frag()),
                    ],
                    &[],
                )?
            } else {
                ShaderProgram::new(
                    &self.gl,
                    &shaders::depth_point_vert(),
                    &shaders::depth_point_frag(),
                    &[],
                )?
            });
            self.point_program_layered = layered;
        }
        let (LightShadow::Cube(cube), Some(program)) =
            (&self.shadows[index], &self.point_depth_program)
        else {
            return Err(Error::Invalid(
                "the point light's cube map is missing".into(),
            ));
        };
        let projection = Mat4::perspective_rh_gl(90f32.to_radians(), 1.0, light.near, light.far);
        let to_light = DMat4::from_translation(-light.position.as_dvec3());
        self.begin_depth_state();
        program.bind();
        program.set_f32("farPlane", light.far);
        if layered {
            // One pass: the geometry shader draws every triangle into all six faces.
            cube.bind_layered()?;
            unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
            let faces = PointLight::face_views().map(|v| projection * v);
            program.set_mat4_array("faceProjections", &faces);
            self.draw_casters(scene, program, "modelLightMatrix", to_light, &|_| true);
        }
        for (face, view) in PointLight::face_views()
            .iter()
            .enumerate()
            .filter(|_| !layered)
        {
            cube.bind_face(face as u32);
            unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
            program.set_mat4("faceProjection", &(projection * *view));
            self.draw_casters(scene, program, "modelLightMatrix", to_light, &|_| true);
        }
        program.unbind();
        self.end_depth_state();
        check_gl(&self.gl, "the point light's depth pass")
    }

    /// Draws every shadow caster that `keep` (by item index) lets through, one mesh's items
    /// at a time, with `uniform` set to `light * model` (composed in double precision).
    fn draw_casters(
        &self,
        scene: &Scene,
        program: &ShaderProgram,
        uniform: &'static str,
        light: DMat4,
        keep: &dyn Fn(usize) -> bool,
    ) {
        for (mesh_id, mesh) in self.meshes.iter().enumerate() {
            let items = scene
                .items
                .iter()
                .enumerate()
                .filter(|(k, i)| i.mesh == mesh_id && i.casts_shadows && keep(*k))
                .map(|(_, i)| i);
            mesh.render_list(items, |item| {
                program.set_mat4(uniform, &(light * item.model_matrix64()).as_mat4());
            });
        }
    }

    /// Depth writes, polygon offset and culling as the settings ask, for a depth pass.
    fn begin_depth_state(&self) {
        let gl = &self.gl;
        let [factor, units] = self.settings.polygon_offset;
        unsafe {
            gl.depth_mask(true);
            if factor != 0.0 || units != 0.0 {
                gl.enable(glow::POLYGON_OFFSET_FILL);
                gl.polygon_offset(factor, units);
            }
            match self.settings.cull {
                Cull::None => gl.disable(glow::CULL_FACE),
                Cull::Back => {
                    gl.enable(glow::CULL_FACE);
                    gl.cull_face(glow::BACK);
                }
                Cull::Front => {
                    gl.enable(glow::CULL_FACE);
                    gl.cull_face(glow::FRONT);
                }
            }
        }
    }

    fn end_depth_state(&self) {
        unsafe {
            self.gl.disable(glow::CULL_FACE);
            self.gl.disable(glow::POLYGON_OFFSET_FILL);
            self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }

    /// Binds the target, sets the viewport to its size in pixels (not the window's logical
    /// size) and clears it.
    fn begin_target(&self, scene: &Scene, target: Target) -> (u32, u32) {
        let (width, height) = target.size();
        let c = scene.clear_colour;
        match target {
            Target::Offscreen(t) => t.bind_and_clear(c.to_array()),
            Target::Window { .. } => unsafe {
                self.gl.bind_framebuffer(glow::FRAMEBUFFER, None);
                self.gl.viewport(0, 0, width as i32, height as i32);
                self.gl.clear_color(c.x, c.y, c.z, c.w);
                self.gl
                    .clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            },
        }
        (width, height)
    }

    /// The main pass: draws the scene with each light's shadow map on its texture unit
    /// ([`light_slots::texture_unit`]). Call after [`Renderer::render_depth_map`].
    pub fn render_scene(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let key = ProgramKey::of(
            scene,
            &self.settings,
            self.visibility_light,
            target.outputs(),
        )?;
        self.use_program(key)?;
        if self.shadows.len() != scene.lights.len() {
            return Err(Error::Invalid(
                "render_scene before render_depth_map: there are no shadow maps yet".into(),
            ));
        }
        let (width, height) = self.begin_target(scene, target);
        if let Some(t) = &self.timer {
            t.begin(SCENE_PASS);
        }
        // View x model in double precision: far from the origin the two translations cancel,
        // and in single precision their difference would lose its digits.
        let view64 = scene.camera.view_matrix64();
        let view = view64.as_mat4();
        // World outputs are written relative to the camera for the same reason.
        let origin = DMat4::from_translation(-scene.camera.position.as_dvec3());
        let p = &self.scene_programs[0].1;
        p.bind();
        p.set_mat4(
            "projectionMatrix",
            &scene.camera.projection_matrix(width, height),
        );
        let kinds: Vec<ShadowKind> = self.shadows.iter().map(LightShadow::kind).collect();
        let u = LightUniforms::of(scene, &self.shadow_views, &kinds, &self.settings, view64);
        p.set_vec3_array("lightPositionOrDirection", &u.position_or_direction);
        p.set_f32_array("lightConeCos", &u.cone_cos);
        p.set_vec3_array("lightConeAxis", &u.cone_axis);
        p.set_f32_array("lightFar", &u.far);
        p.set_f32_array("normalOffset", &u.normal_offset);
        p.set_mat3_array("lightRotation", &u.rotation);
        // The view is rigid: the transpose of its rotation undoes it (G-buffer outputs).
        p.set_mat3("viewToWorld", &Mat3::from_mat4(view).transpose());
        p.set_mat4_array("orthoProjectionMatrix", &u.projection);
        self.set_cascade_uniforms(scene);
        p.set_i32("textureSampler", light_slots::MATERIAL_UNIT as i32);
        for (i, shadow) in self.shadows.iter().enumerate() {
            if let (Some(name), Some(texture)) = (
                light_slots::sampler_name(i, shadow.kind()),
                shadow.texture(),
            ) {
                let unit = light_slots::texture_unit(i);
                p.set_i32(name, unit as i32);
                texture.bind(unit);
            }
        }
        let mut light_matrices = vec![Mat4::IDENTITY; u.light_from.len()];
        let mut diffuse = vec![Vec3::ZERO; u.colour.len()];
        for (mesh_id, mesh) in self.meshes.iter().enumerate() {
            let items = scene.items.iter().filter(|i| i.mesh == mesh_id);
            mesh.render_list(items, |item| {
                let model = item.model_matrix64();
                let model_view = (view64 * model).as_mat4();
                p.set_mat4("modelOriginMatrix", &(origin * model).as_mat4());
                p.set_mat4("modelViewMatrix", &model_view);
                p.set_mat3("normalMatrix", &normal_matrix(&model_view));
                p.set_mat3("worldNormalMatrix", &normal_matrix(&model.as_mat4()));
                for (m, from) in light_matrices.iter_mut().zip(&u.light_from) {
                    *m = (*from * model).as_mat4();
                }
                p.set_mat4_array("modelLightViewMatrix", &light_matrices);
                let m = &item.material;
                let colour = m.colour.truncate();
                p.set_vec4(
                    "material.ambient",
                    (scene.ambient * colour).extend(m.reflectance),
                );
                for (d, light) in diffuse.iter_mut().zip(&u.colour) {
                    *d = *light * colour;
                }
                p.set_vec3_array("material.diffuse", &diffuse);
                m.texture
                    .and_then(|t| self.textures.get(t))
                    .unwrap_or(&self.white)
                    .bind(light_slots::MATERIAL_UNIT);
            });
        }
        p.unbind();
        if let Some(t) = &self.timer {
            t.end();
        }
        check_gl(&self.gl, "the scene pass")
    }

    /// Moves the program compiled for `key` to the front of the cache, compiling it if it is
    /// not there (the cache keeps the last few).
    fn use_program(&mut self, key: ProgramKey) -> Result<()> {
        const KEEP: usize = 4;
        match self.scene_programs.iter().position(|(k, _)| *k == key) {
            Some(0) => {}
            Some(i) => {
                let entry = self.scene_programs.remove(i);
                self.scene_programs.insert(0, entry);
            }
            None => {
                let program = scene_program(&self.gl, &key)?;
                self.scene_programs.insert(0, (key, program));
                self.scene_programs.truncate(KEEP);
            }
        }
        Ok(())
    }

    /// The cascaded light's matrices (camera-relative world to each cascade's clip space),
    /// split depths and normal offsets.
    fn set_cascade_uniforms(&self, scene: &Scene) {
        let p = &self.scene_programs[0].1;
        for shadow in &self.shadows {
            let LightShadow::Cascades(_, cascades) = shadow else {
                continue;
            };
            let matrices: Vec<Mat4> = cascades
                .iter()
                .map(|c| camera_relative_matrix(c, scene.camera.position).as_mat4())
                .collect();
            let mut splits: Vec<f32> = cascades.iter().map(|c| c.near as f32).collect();
            splits.extend(cascades.last().map(|c| c.far as f32));
            let offsets: Vec<f32> = cascades
                .iter()
                .map(|c| self.settings.normal_offset * c.fitted.texel as f32)
                .collect();
            p.set_mat4_array("cascadeMatrix", &matrices);
            p.set_f32_array("cascadeSplit", &splits);
            p.set_f32_array("cascadeNormalOffset", &offsets);
        }
    }

    /// The chapters' debug quad: a light's shadow map on the whole target, linearised for a
    /// perspective light (LearnOpenGL's `LinearizeDepth`), raw for an orthographic one; a
    /// cube map as a panorama, cascades side by side.
    pub fn render_depth_view(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let index = self
            .depth_view_light
            .min(self.shadows.len().saturating_sub(1));
        let Some(shadow) = self.shadows.get(index) else {
            return Err(Error::Invalid(
                "render_depth_view before render_depth_map: there is no shadow map yet".into(),
            ));
        };
        self.begin_target(scene, target);
        let (cube, array) = match shadow {
            LightShadow::None => {
                // A light without a map: the cleared target says so.
                return check_gl(&self.gl, "the depth-map view");
            }
            LightShadow::Map(_) => (false, false),
            LightShadow::Cube(_) => (true, false),
            LightShadow::Cascades(..) => (false, true),
        };
        let slot = match (cube, array) {
            (true, _) => Some(&mut self.depth_view_cube),
            (_, true) => Some(&mut self.depth_view_array),
            _ => None,
        };
        if let Some(slot) = slot {
            if slot.is_none() {
                *slot = Some(ShaderProgram::new(
                    &self.gl,
                    &shaders::depth_view_vert(),
                    &shaders::depth_view_frag(),
                    &[
                        ("CUBE".into(), u32::from(cube).to_string()),
                        ("ARRAY".into(), u32::from(array).to_string()),
                    ],
                )?);
            }
        }
        let p = match (cube, array) {
            (true, _) => self.depth_view_cube.as_ref(),
            (_, true) => self.depth_view_array.as_ref(),
            _ => Some(&self.depth_view_program),
        };
        let (Some(p), Some(texture)) = (p, self.shadows[index].texture()) else {
            return Err(Error::Invalid("the depth view has no program".into()));
        };
        // A plain sampler must not read a texture in compare mode.
        texture.set_compare(false, false);
        p.bind();
        p.set_i32("depthMap", 0);
        if let Some(sv) = &self.shadow_views[index] {
            p.set_i32("linearize", i32::from(sv.perspective && !cube));
            p.set_f32("nearPlane", sv.near);
            p.set_f32("farPlane", sv.far);
        }
        p.set_i32("layers", self.settings.cascades as i32);
        texture.bind(0);
        unsafe { self.gl.disable(glow::DEPTH_TEST) };
        self.full_screen.draw();
        unsafe { self.gl.enable(glow::DEPTH_TEST) };
        p.unbind();
        configure_sampling(&self.shadows[index], &self.settings);
        check_gl(&self.gl, "the depth-map view")
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        unsafe { self.gl.finish() };
    }
}

/// Everything a scene program is compiled for: branches on these would run for every pixel
/// on a software rasteriser, so they are `#define`s.
#[derive(Debug, Clone, PartialEq)]
struct ProgramKey {
    /// The shadow settings' defines.
    settings: Vec<(String, String)>,
    slots: Vec<LightSlot>,
    blinn: bool,
    specular_power_bits: u32,
    visibility_light: usize,
    /// The outputs the target has: the others are not computed.
    outputs: Outputs,
}

impl ProgramKey {
    fn of(
        scene: &Scene,
        settings: &ShadowSettings,
        visibility_light: usize,
        outputs: Outputs,
    ) -> Result<ProgramKey> {
        if scene.lights.is_empty() || scene.lights.len() > light_slots::MAX_LIGHTS {
            return Err(Error::Invalid(format!(
                "{}: {} lights: expected 1 to {}",
                scene.source.display(),
                scene.lights.len(),
                light_slots::MAX_LIGHTS
            )));
        }
        let kinds = ShadowKind::for_lights(&scene.lights, settings);
        let slots = scene
            .lights
            .iter()
            .zip(kinds)
            .map(|(light, shadow)| {
                let (positional, cone) = match light.shading() {
                    Shading::Direction(_) => (false, false),
                    Shading::Position { cone, .. } => (true, cone.is_some()),
                };
                LightSlot {
                    shadow,
                    positional,
                    cone,
                }
            })
            .collect();
        Ok(ProgramKey {
            settings: settings.shader_defines(),
            slots,
            blinn: scene.shading == ShadingModel::BlinnPhong,
            specular_power_bits: scene.specular_power.to_bits(),
            visibility_light,
            outputs,
        })
    }
}

/// The per-light uniform arrays of the scene pass (view space), and the per-slot ones of
/// the lights with a 2D or cube map ([`light_slots::map_slots`]).
struct LightUniforms {
    colour: Vec<Vec3>,
    /// A positional light's position, or the direction towards a directional one.
    position_or_direction: Vec<Vec3>,
    cone_cos: Vec<f32>,
    cone_axis: Vec<Vec3>,
    far: Vec<f32>,
    /// Per map slot.
    normal_offset: Vec<f32>,
    projection: Vec<Mat4>,
    /// World to the light's view (a point light: to the light's position), per map slot.
    light_from: Vec<DMat4>,
    /// Its rotation (for normal offsets), per map slot.
    rotation: Vec<Mat3>,
}

impl LightUniforms {
    fn of(
        scene: &Scene,
        views: &[Option<ShadowView>],
        kinds: &[ShadowKind],
        settings: &ShadowSettings,
        view64: DMat4,
    ) -> LightUniforms {
        let view = view64.as_mat4();
        let n = scene.lights.len();
        let slots = light_slots::map_slots(kinds.iter().copied());
        let mapped = slots.iter().flatten().count().max(1);
        let mut u = LightUniforms {
            colour: Vec::with_capacity(n),
            position_or_direction: vec![Vec3::Z; n],
            cone_cos: vec![-2.0; n],
            cone_axis: vec![Vec3::Z; n],
            far: vec![1.0; n],
            normal_offset: vec![0.0; mapped],
            projection: vec![Mat4::IDENTITY; mapped],
            light_from: vec![DMat4::IDENTITY; mapped],
            rotation: vec![Mat3::IDENTITY; mapped],
        };
        for (i, light) in scene.lights.iter().enumerate() {
            u.colour.push(light.colour() * light.intensity());
            match light.shading() {
                Shading::Direction(d) => u.position_or_direction[i] = view.transform_vector3(d),
                Shading::Position { position, cone } => {
                    u.position_or_direction[i] =
                        view64.transform_point3(position.as_dvec3()).as_vec3();
                    if let Some((cos, axis)) = cone {
                        u.cone_cos[i] = cos;
                        u.cone_axis[i] = view.transform_vector3(axis);
                    }
                }
            }
            if let Light::Point(l) = light {
                u.far[i] = l.far;
            }
            let (Some(p), Some(sv)) = (slots[i], views.get(i).copied().flatten()) else {
                continue;
            };
            u.normal_offset[p] = settings.normal_offset * sv.texel_world;
            // A point light's test works on the fragment relative to the light.
            let from = match light {
                Light::Point(l) => DMat4::from_translation(-l.position.as_dvec3()),
                _ => {
                    u.projection[p] = sv.projection;
                    sv.view64
                }
            };
            u.light_from[p] = from;
            u.rotation[p] = Mat3::from_mat4(from.as_mat4());
        }
        u
    }
}

fn scene_program(gl: &Gl, key: &ProgramKey) -> Result<ShaderProgram> {
    let cascades = key
        .settings
        .iter()
        .find(|(k, _)| k == "CASCADES")
        .and_then(|(_, v)| v.parse().ok())
        .unwrap_or(1);
    let needed = light_slots::vertex_outputs(&key.slots, cascades);
    let allowed = gl_limits(gl).max_vertex_output_components as usize;
    if needed > allowed {
        return Err(Error::Invalid(format!(
            "{} lights with {cascades} cascades need {needed} vertex shader outputs and this \
             driver allows {allowed}: use fewer lights or fewer cascades",
            key.slots.len()
        )));
    }
    let mut defines = key.settings.clone();
    for (name, on) in [
        ("OUTPUT_VISIBILITY", key.outputs.visibility),
        ("OUTPUT_GBUFFER", key.outputs.gbuffer),
    ] {
        defines.push((name.into(), u32::from(on).to_string()));
    }
    defines.push(("BLINN".into(), u32::from(key.blinn).to_string()));
    defines.push((
        "SPECULAR_POWER".into(),
        crate::settings::glsl_float(f32::from_bits(key.specular_power_bits)),
    ));
    defines.extend(light_slots::defines(&key.slots, key.visibility_light));
    ShaderProgram::new(gl, &shaders::scene_vert(), &shaders::scene_frag(), &defines)
}

/// The matrix that carries normals: the inverse transpose of the upper 3 x 3, so normals
/// stay perpendicular under non-uniform scale.
fn normal_matrix(m: &Mat4) -> Mat3 {
    Mat3::from_mat4(*m).inverse().transpose()
}

/// Wrap mode and compare mode of a 2D or array shadow map for the settings' filter (a cube
/// map keeps plain NEAREST reads).
fn configure_sampling(shadow: &LightShadow, settings: &ShadowSettings) {
    let settings = settings.effective();
    // A cascade covers exactly its slice and the casters that reach it: outside it is lit.
    let (texture, wrap) = match shadow {
        LightShadow::Map(m) => (m.depth_map_texture(), settings.wrap),
        LightShadow::Cascades(a, _) => (a.texture(), Wrap::ClampToBorder),
        LightShadow::None | LightShadow::Cube(_) => return,
    };
    texture.set_wrap(wrap);
    texture.set_compare(settings.filter.hardware(), settings.filter.hardware());
}
