//! `Renderer`: the book's two-pass frame. `render_depth_map` draws the scene from the light
//! into the shadow map; the main pass then draws it from the camera, sampling that map.

use glam::{DMat4, Mat3, Mat4, Vec3};
use glow::HasContext;

use crate::engine::mesh::FullScreenTriangle;
use crate::engine::{
    check_gl, gl_limits, CubeShadowMap, Gl, Mesh, PassTimer, RenderTarget, ShaderProgram,
    ShadowMap, Texture,
};
use crate::error::{Error, Result};
use crate::image_data::ImageData;
use crate::scene::{Light, PointLight, Scene, Shading, ShadingModel, ShadowView};
use crate::settings::PointPass;
use crate::settings::{Cull, ShadowSettings};
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
}

/// Owns the GL side of one scene: its meshes and textures, the two programs and the shadow
/// map. Create it after the context and drop it before.
pub struct Renderer {
    gl: Gl,
    settings: ShadowSettings,
    depth_program: ShaderProgram,
    scene_program: ShaderProgram,
    /// The lighting the scene program was compiled for.
    lighting: LightingKey,
    shadow_map: ShadowMap,
    meshes: Vec<Mesh>,
    textures: Vec<Texture>,
    depth_view_program: ShaderProgram,
    full_screen: FullScreenTriangle,
    /// The light's camera used by the last depth pass.
    shadow_view: Option<ShadowView>,
    /// A point light's cube map and depth program, made when a point light first casts.
    cube_map: Option<CubeShadowMap>,
    /// 1 x 1 white, for items without a texture.
    white: Texture,
    point_depth_program: Option<ShaderProgram>,
    point_program_layered: bool,
    depth_view_cube: Option<ShaderProgram>,
    /// GPU timers for the depth pass (0) and the scene pass (1), when enabled.
    timer: Option<PassTimer>,
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
        let lighting = LightingKey::of(scene);
        let scene_program = scene_program(gl, settings, lighting)?;
        let depth_view_program = ShaderProgram::new(
            gl,
            &shaders::depth_view_vert(),
            &shaders::depth_view_frag(),
            &[("CUBE".into(), "0".into())],
        )?;
        let shadow_map = ShadowMap::new(gl, settings.map_size, settings.depth_format)?;
        configure_sampling(&shadow_map, settings);
        unsafe { gl.enable(glow::DEPTH_TEST) };
        check_gl(gl, "renderer setup")?;
        Ok(Renderer {
            gl: gl.clone(),
            settings: *settings,
            depth_program,
            scene_program,
            lighting,
            shadow_map,
            meshes,
            textures,
            depth_view_program,
            full_screen: FullScreenTriangle::new(gl)?,
            shadow_view: None,
            cube_map: None,
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
            timer: None,
        })
    }

    pub fn settings(&self) -> &ShadowSettings {
        &self.settings
    }

    /// Switches settings, rebuilding only what they change (the program for shader
    /// variants, the shadow map for its size or format).
    pub fn set_settings(&mut self, settings: &ShadowSettings) -> Result<()> {
        settings.validate(gl_limits(&self.gl).max_texture_size)?;
        if settings.shader_defines() != self.settings.shader_defines() {
            self.scene_program = scene_program(&self.gl, settings, self.lighting)?;
        }
        if settings.map_size != self.settings.map_size
            || settings.depth_format != self.settings.depth_format
        {
            self.shadow_map = ShadowMap::new(&self.gl, settings.map_size, settings.depth_format)?;
        }
        configure_sampling(&self.shadow_map, settings);
        self.settings = *settings;
        check_gl(&self.gl, "changing settings")
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

    pub fn shadow_map(&self) -> &ShadowMap {
        &self.shadow_map
    }

    /// The light's camera of the last depth pass.
    pub fn shadow_view(&self) -> Option<&ShadowView> {
        self.shadow_view.as_ref()
    }

    /// One frame: the depth map first, then the scene (or, with `show_depth_map`, the map
    /// itself) into `target`.
    pub fn render(&mut self, scene: &Scene, target: Target) -> Result<()> {
        self.render_depth_map(scene)?;
        if self.settings.show_depth_map {
            self.render_depth_view(scene, target)
        } else {
            self.render_scene(scene, target)
        }
    }

    /// The shadow pass: bind the map's FBO, viewport to its size, clear depth, and draw every
    /// caster with the light's view and projection (ortho for the book's light).
    pub fn render_depth_map(&mut self, scene: &Scene) -> Result<()> {
        let sv = scene.shadow_view(&self.settings);
        self.shadow_view = Some(sv);
        if let Light::Point(p) = &scene.light {
            return self.render_cube_depth_map(scene, p);
        }
        let gl = &self.gl;
        self.shadow_map.bind_for_writing();
        self.begin_depth_state();
        unsafe {
            gl.clear(glow::DEPTH_BUFFER_BIT);
        }
        if let Some(t) = &self.timer {
            t.begin(DEPTH_PASS);
        }
        let program = &self.depth_program;
        program.bind();
        program.set_mat4("orthoProjectionMatrix", &sv.projection);
        self.draw_casters(scene, program, "modelLightViewMatrix", sv.view64);
        program.unbind();
        if let Some(t) = &self.timer {
            t.end();
        }
        self.end_depth_state();
        check_gl(gl, "the depth-map pass")
    }

    /// A point light's depth pass: six faces of a cube map, each a 90-degree view from the
    /// light storing distance over `far` (LearnOpenGL's "Point Shadows").
    fn render_cube_depth_map(&mut self, scene: &Scene, light: &PointLight) -> Result<()> {
        let (size, format) = (self.settings.map_size, self.settings.depth_format);
        let stale = self
            .cube_map
            .as_ref()
            .is_none_or(|c| c.size() != size || c.format() != format);
        if stale {
            self.cube_map = Some(CubeShadowMap::new(&self.gl, size, format)?);
        }
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
        let (Some(cube), Some(program)) = (&self.cube_map, &self.point_depth_program) else {
            return Err(Error::Invalid(
                "the point light's cube map is missing".into(),
            ));
        };
        let projection = Mat4::perspective_rh_gl(90f32.to_radians(), 1.0, light.near, light.far);
        let to_light = DMat4::from_translation(-light.position.as_dvec3());
        self.begin_depth_state();
        if let Some(t) = &self.timer {
            t.begin(DEPTH_PASS);
        }
        program.bind();
        program.set_f32("farPlane", light.far);
        if layered {
            // One pass: the geometry shader draws every triangle into all six faces.
            cube.bind_layered()?;
            unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
            let faces = PointLight::face_views().map(|v| projection * v);
            program.set_mat4_array("faceProjections", &faces);
            self.draw_casters(scene, program, "modelLightMatrix", to_light);
        }
        for (face, view) in PointLight::face_views()
            .iter()
            .enumerate()
            .filter(|_| !layered)
        {
            cube.bind_face(face as u32);
            unsafe { self.gl.clear(glow::DEPTH_BUFFER_BIT) };
            program.set_mat4("faceProjection", &(projection * *view));
            self.draw_casters(scene, program, "modelLightMatrix", to_light);
        }
        program.unbind();
        if let Some(t) = &self.timer {
            t.end();
        }
        self.end_depth_state();
        check_gl(&self.gl, "the point light's depth pass")
    }

    /// Draws every shadow caster, one mesh's items at a time, with `uniform` set to
    /// `light * model` (composed in double precision).
    fn draw_casters(
        &self,
        scene: &Scene,
        program: &ShaderProgram,
        uniform: &'static str,
        light: DMat4,
    ) {
        for (mesh_id, mesh) in self.meshes.iter().enumerate() {
            let items = scene
                .items
                .iter()
                .filter(|i| i.mesh == mesh_id && i.casts_shadows);
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

    /// The main pass: draws the scene with the shadow map on texture unit 1. Call after
    /// [`Renderer::render_depth_map`].
    pub fn render_scene(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let lighting = LightingKey::of(scene);
        if lighting != self.lighting {
            self.scene_program = scene_program(&self.gl, &self.settings, lighting)?;
            self.lighting = lighting;
        }
        let Some(sv) = self.shadow_view else {
            return Err(Error::Invalid(
                "render_scene before render_depth_map: there is no shadow map yet".into(),
            ));
        };
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
        let p = &self.scene_program;
        p.bind();
        p.set_mat4(
            "projectionMatrix",
            &scene.camera.projection_matrix(width, height),
        );
        // A point light's test works on the fragment relative to the light (no projection).
        let point = match &scene.light {
            Light::Point(l) => Some(l),
            _ => None,
        };
        let light_from = match point {
            Some(l) => DMat4::from_translation(-l.position.as_dvec3()),
            None => sv.view64,
        };
        p.set_mat4(
            "orthoProjectionMatrix",
            &point.map_or(sv.projection, |_| Mat4::IDENTITY),
        );
        if let Some(l) = point {
            p.set_f32("farPlane", l.far);
        }
        p.set_vec3("ambientLight", scene.ambient);
        p.set_i32(
            "blinn",
            i32::from(scene.shading == ShadingModel::BlinnPhong),
        );
        p.set_f32("normalOffset", self.settings.normal_offset * sv.texel_world);
        let light = &scene.light;
        let light_colour = light.colour() * light.intensity();
        p.set_vec3("light.colour", light_colour);
        match light.shading() {
            Shading::Direction(d) => p.set_vec3("light.direction", view.transform_vector3(d)),
            Shading::Position { position, cone } => {
                let position = view64.transform_point3(position.as_dvec3()).as_vec3();
                p.set_vec3("light.position", position);
                let (cos, axis) = cone.unwrap_or((-2.0, Vec3::Z));
                p.set_f32("light.coneCos", cos);
                p.set_vec3("light.coneAxis", view.transform_vector3(axis));
            }
        }
        p.set_i32("textureSampler", 0);
        p.set_i32("shadowMap", 1);
        match (&self.cube_map, point) {
            (Some(cube), Some(_)) => cube.texture().bind_cube(1),
            _ => self.shadow_map.depth_map_texture().bind(1),
        }
        for (mesh_id, mesh) in self.meshes.iter().enumerate() {
            let items = scene.items.iter().filter(|i| i.mesh == mesh_id);
            mesh.render_list(items, |item| {
                let model = item.model_matrix64();
                let model_view = (view64 * model).as_mat4();
                p.set_mat4("modelOriginMatrix", &(origin * model).as_mat4());
                p.set_mat4("modelViewMatrix", &model_view);
                p.set_mat3("normalMatrix", &normal_matrix(&model_view));
                p.set_mat3("worldNormalMatrix", &normal_matrix(&model.as_mat4()));
                p.set_mat4("modelLightViewMatrix", &(light_from * model).as_mat4());
                let m = &item.material;
                p.set_vec4("material.colour", m.colour);
                p.set_vec3("material.specular", light_colour * m.reflectance);
                m.texture
                    .and_then(|t| self.textures.get(t))
                    .unwrap_or(&self.white)
                    .bind(0);
            });
        }
        p.unbind();
        if let Some(t) = &self.timer {
            t.end();
        }
        check_gl(&self.gl, "the scene pass")
    }

    /// The chapters' debug quad: the shadow map on the whole target, linearised for a
    /// perspective light (LearnOpenGL's `LinearizeDepth`), raw for an orthographic one.
    pub fn render_depth_view(&mut self, scene: &Scene, target: Target) -> Result<()> {
        let Some(sv) = self.shadow_view else {
            return Err(Error::Invalid(
                "render_depth_view before render_depth_map: there is no shadow map yet".into(),
            ));
        };
        self.begin_target(scene, target);
        if let (Light::Point(_), Some(cube)) = (&scene.light, &self.cube_map) {
            // A point light's six faces as one panorama of directions from the light.
            if self.depth_view_cube.is_none() {
                self.depth_view_cube = Some(ShaderProgram::new(
                    &self.gl,
                    &shaders::depth_view_vert(),
                    &shaders::depth_view_frag(),
                    &[("CUBE".into(), "1".into())],
                )?);
            }
            if let Some(p) = &self.depth_view_cube {
                p.bind();
                p.set_i32("depthMap", 0);
                cube.texture().bind_cube(0);
                unsafe { self.gl.disable(glow::DEPTH_TEST) };
                self.full_screen.draw();
                unsafe { self.gl.enable(glow::DEPTH_TEST) };
                p.unbind();
            }
            return check_gl(&self.gl, "the cube depth-map view");
        }
        let texture = self.shadow_map.depth_map_texture();
        // A plain sampler2D must not read a texture in compare mode.
        texture.set_compare(false, false);
        let p = &self.depth_view_program;
        p.bind();
        p.set_i32("depthMap", 0);
        p.set_i32("linearize", i32::from(sv.perspective));
        p.set_f32("nearPlane", sv.near);
        p.set_f32("farPlane", sv.far);
        texture.bind(0);
        unsafe { self.gl.disable(glow::DEPTH_TEST) };
        self.full_screen.draw();
        unsafe { self.gl.enable(glow::DEPTH_TEST) };
        p.unbind();
        configure_sampling(&self.shadow_map, &self.settings);
        check_gl(&self.gl, "the depth-map view")
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        unsafe { self.gl.finish() };
    }
}

/// What the scene program is specialised for besides the shadow settings: branches on these
/// would run for every pixel on a software rasteriser, so they are `#define`s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct LightingKey {
    positional: bool,
    cone: bool,
    blinn: bool,
    point: bool,
    specular_power_bits: u32,
}

impl LightingKey {
    fn of(scene: &Scene) -> LightingKey {
        let (positional, cone) = match scene.light.shading() {
            Shading::Direction(_) => (false, false),
            Shading::Position { cone, .. } => (true, cone.is_some()),
        };
        LightingKey {
            positional,
            cone,
            blinn: scene.shading == ShadingModel::BlinnPhong,
            point: matches!(scene.light, Light::Point(_)),
            specular_power_bits: scene.specular_power.to_bits(),
        }
    }
}

fn scene_program(gl: &Gl, settings: &ShadowSettings, key: LightingKey) -> Result<ShaderProgram> {
    let mut defines = settings.shader_defines();
    for (name, on) in [
        ("LIGHT_POSITIONAL", key.positional),
        ("SPOT_CONE", key.cone),
        ("BLINN", key.blinn),
        ("POINT_SHADOW", key.point),
    ] {
        defines.push((name.into(), u32::from(on).to_string()));
    }
    defines.push((
        "SPECULAR_POWER".into(),
        crate::settings::glsl_float(f32::from_bits(key.specular_power_bits)),
    ));
    ShaderProgram::new(gl, &shaders::scene_vert(), &shaders::scene_frag(), &defines)
}

/// The matrix that carries normals: the inverse transpose of the upper 3 x 3, so normals
/// stay perpendicular under non-uniform scale.
fn normal_matrix(m: &Mat4) -> Mat3 {
    Mat3::from_mat4(*m).inverse().transpose()
}

/// Wrap mode and compare mode of the shadow map for the settings' filter.
fn configure_sampling(shadow_map: &ShadowMap, settings: &ShadowSettings) {
    let settings = settings.effective();
    let texture = shadow_map.depth_map_texture();
    texture.set_wrap(settings.wrap);
    texture.set_compare(settings.filter.hardware(), settings.filter.hardware());
}
