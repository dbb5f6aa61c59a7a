//! A plain, direct implementation of the frame LearnOpenGL's "Shadow Mapping" program (3.1.3)
//! draws, kept beside our renderer only as a yardstick.
//!
//! LearnOpenGL's own C++ binary cannot be built here, so to ask "is our `learnopengl` preset as
//! fast as the tutorial?" we time, in the same process and the same run, a minimal frame that
//! issues the same GL work the tutorial does: a depth pass into a 1024^2 map (floor and three
//! cubes, a trivial depth shader), then the textured Blinn-Phong pass with the 3x3 PCF shadow
//! test into an 800x600 RGBA8 + DEPTH24 framebuffer. One VAO per shape, uniforms looked up
//! once, no abstraction. The shaders are our own text of the tutorial's algorithm.

use glam::{Mat4, Vec3};
use glow::HasContext;
use glow::{TEXTURE_MAG_FILTER as MAG, TEXTURE_MIN_FILTER as MIN};
use glow::{TEXTURE_WRAP_S as WRAP_S, TEXTURE_WRAP_T as WRAP_T};

use super::render_target::read_rgba8;
use super::{check_gl, Gl};
use crate::error::{Error, Result};
use crate::image_data::ImageData;

const WIDTH: i32 = 800;
const HEIGHT: i32 = 600;
const MAP_SIZE: i32 = 1024;
const LIGHT_POS: Vec3 = Vec3::new(-2.0, 4.0, -1.0);
const CAMERA_POS: Vec3 = Vec3::new(0.0, 0.0, 3.0);

const DEPTH_VS: &str = "#version 330 core
layout (location = 0) in vec3 aPos;
uniform mat4 lightSpace;
uniform mat4 model;
void main() { gl_Position = lightSpace * model * vec4(aPos, 1.0); }
";

const DEPTH_FS: &str = "#version 330 core
void main() {}
";

const SCENE_VS: &str = "#version 330 core
layout (location = 0) in vec3 aPos;
layout (location = 1) in vec3 aNormal;
layout (location = 2) in vec2 aUv;
uniform mat4 projection;
uniform mat4 view;
uniform mat4 model;
uniform mat4 lightSpace;
out vec3 worldPos;
out vec3 worldNormal;
out vec2 uv;
out vec4 lightClip;
void main() {
    vec4 world = model * vec4(aPos, 1.0);
    worldPos = world.xyz;
    worldNormal = mat3(model) * aNormal;  // every scale here is uniform
    uv = aUv;
    lightClip = lightSpace * world;
    gl_Position = projection * view * world;
}
";

const SCENE_FS: &str = "#version 330 core
in vec3 worldPos;
in vec3 worldNormal;
in vec2 uv;
in vec4 lightClip;
out vec4 colour;
uniform sampler2D woodMap;
uniform sampler2D shadowMap;
uniform vec3 lightPos;
uniform vec3 viewPos;
void main() {
    vec3 albedo = texture(woodMap, uv).rgb;
    vec3 n = normalize(worldNormal);
    vec3 l = normalize(lightPos - worldPos);
    vec3 v = normalize(viewPos - worldPos);
    const vec3 lightColour = vec3(0.3);
    float diffuse = max(dot(n, l), 0.0);
    float specular = pow(max(dot(n, normalize(l + v)), 0.0), 64.0);

    // Shadow: light clip space to [0, 1], a slope-scaled bias, 3x3 comparisons averaged.
    vec3 p = lightClip.xyz / lightClip.w * 0.5 + 0.5;
    float reference = p.z - max(0.05 * (1.0 - dot(n, l)), 0.005);
    vec2 texel = 1.0 / vec2(textureSize(shadowMap, 0));
    float occluded = 0.0;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j)
            occluded += reference > texture(shadowMap, p.xy + vec2(i, j) * texel).r ? 1.0 : 0.0;
    occluded /= 9.0;
    if (p.z > 1.0)
        occluded = 0.0;  // beyond the light's far plane: lit

    vec3 light = 0.3 * lightColour + (1.0 - occluded) * (diffuse + specular) * lightColour;
    colour = vec4(light * albedo, 1.0);
}
";

/// Interleaved vertex: position, normal, texture coordinate.
type Vertex = [f32; 8];

/// The unit cube [-1, 1]^3 as 36 unindexed vertices, counter-clockwise outside: the
/// project's own cube (`MeshData::cube`), laid out the way the tutorial's arrays are.
fn cube_vertices() -> Vec<Vertex> {
    let cube = crate::geometry::MeshData::cube();
    cube.indices
        .iter()
        .map(|&i| {
            let (p, n, t) = (
                cube.positions[i as usize],
                cube.normals[i as usize],
                cube.tex_coords[i as usize],
            );
            [p[0], p[1], p[2], n[0], n[1], n[2], t[0], t[1]]
        })
        .collect()
}

/// The tutorial's 50 x 50 floor at y = -0.5 (`planeVertices` span -25..25), texture
/// coordinates 0..25 (u grows with x, v against z), wound clockwise from above as the
/// tutorial's is (no culling, so it only matters for consistency).
fn floor_vertices() -> Vec<Vertex> {
    const HALF: f32 = 25.0;
    const TILES: f32 = 25.0;
    let corner = |x: f32, z: f32| -> Vertex {
        let (u, v) = ((x + HALF) / (2.0 * HALF), (HALF - z) / (2.0 * HALF));
        [x, -0.5, z, 0.0, 1.0, 0.0, u * TILES, v * TILES]
    };
    let (a, b) = (corner(-HALF, HALF), corner(HALF, HALF));
    let (c, d) = (corner(HALF, -HALF), corner(-HALF, -HALF));
    vec![a, c, b, a, d, c]
}

/// One GL name of any kind the baseline owns.
enum Name {
    Program(glow::Program),
    VertexArray(glow::VertexArray),
    Buffer(glow::Buffer),
    Texture(glow::Texture),
    Renderbuffer(glow::Renderbuffer),
    Framebuffer(glow::Framebuffer),
}

/// Every GL name the baseline made; all freed on drop, also when `new` fails half-way.
struct Objects {
    gl: Gl,
    names: Vec<Name>,
}

impl Drop for Objects {
    fn drop(&mut self) {
        let gl = &self.gl;
        for name in self.names.drain(..).rev() {
            unsafe {
                match name {
                    Name::Program(p) => gl.delete_program(p),
                    Name::VertexArray(v) => gl.delete_vertex_array(v),
                    Name::Buffer(b) => gl.delete_buffer(b),
                    Name::Texture(t) => gl.delete_texture(t),
                    Name::Renderbuffer(r) => gl.delete_renderbuffer(r),
                    Name::Framebuffer(f) => gl.delete_framebuffer(f),
                }
            }
        }
    }
}

impl Objects {
    /// Records a freshly created name so `Drop` frees it.
    fn keep<T: Copy>(
        &mut self,
        made: std::result::Result<T, String>,
        kind: fn(T) -> Name,
    ) -> Result<T> {
        let name = made.map_err(|e| Error::Create(format!("baseline GL object: {e}")))?;
        self.names.push(kind(name));
        Ok(name)
    }

    fn program(&mut self, name: &str, vs: &str, fs: &str) -> Result<glow::Program> {
        let gl = self.gl.clone();
        unsafe {
            let program = self.keep(gl.create_program(), Name::Program)?;
            for (ty, text) in [(glow::VERTEX_SHADER, vs), (glow::FRAGMENT_SHADER, fs)] {
                let shader = gl.create_shader(ty).map_err(Error::Create)?;
                gl.shader_source(shader, text);
                gl.compile_shader(shader);
                let ok = gl.get_shader_compile_status(shader);
                let log = gl.get_shader_info_log(shader);
                gl.attach_shader(program, shader);
                gl.delete_shader(shader); // freed when the program goes
                if !ok {
                    return Err(Error::Shader {
                        file: format!("baseline {name}"),
                        log,
                    });
                }
            }
            gl.link_program(program);
            if !gl.get_program_link_status(program) {
                let log = gl.get_program_info_log(program);
                return Err(Error::Shader {
                    file: format!("baseline {name} (link)"),
                    log,
                });
            }
            Ok(program)
        }
    }

    /// One VAO and VBO for a non-indexed shape; attributes 0 position, 1 normal, 2 uv.
    fn shape(&mut self, vertices: &[Vertex]) -> Result<(glow::VertexArray, i32)> {
        let gl = self.gl.clone();
        unsafe {
            let vao = self.keep(gl.create_vertex_array(), Name::VertexArray)?;
            let vbo = self.keep(gl.create_buffer(), Name::Buffer)?;
            gl.bind_vertex_array(Some(vao));
            gl.bind_buffer(glow::ARRAY_BUFFER, Some(vbo));
            let bytes = std::slice::from_raw_parts(
                vertices.as_ptr().cast::<u8>(),
                std::mem::size_of_val(vertices),
            );
            gl.buffer_data_u8_slice(glow::ARRAY_BUFFER, bytes, glow::STATIC_DRAW);
            for (index, size, offset) in [(0, 3, 0), (1, 3, 3), (2, 2, 6)] {
                gl.enable_vertex_attrib_array(index);
                gl.vertex_attrib_pointer_f32(index, size, glow::FLOAT, false, 32, offset * 4);
            }
            gl.bind_vertex_array(None);
            Ok((vao, vertices.len() as i32))
        }
    }

    /// A 2D texture (RGBA8 from `pixels` with mipmaps, or empty): filters and wrap mode.
    fn texture(
        &mut self,
        internal: u32,
        size: i32,
        height: i32,
        pixels: Option<&[u8]>,
        (min, mag, wrap): (u32, u32, u32),
    ) -> Result<glow::Texture> {
        let gl = self.gl.clone();
        let (format, ty) = match internal {
            glow::DEPTH_COMPONENT24 => (glow::DEPTH_COMPONENT, glow::FLOAT),
            _ => (glow::RGBA, glow::UNSIGNED_BYTE),
        };
        unsafe {
            let t = self.keep(gl.create_texture(), Name::Texture)?;
            gl.bind_texture(glow::TEXTURE_2D, Some(t));
            gl.pixel_store_i32(glow::UNPACK_ALIGNMENT, 1);
            let data = glow::PixelUnpackData::Slice(pixels);
            let target = glow::TEXTURE_2D;
            gl.tex_image_2d(
                target,
                0,
                internal as i32,
                size,
                height,
                0,
                format,
                ty,
                data,
            );
            if pixels.is_some() {
                gl.generate_mipmap(target);
            }
            let params = [(MIN, min), (MAG, mag), (WRAP_S, wrap), (WRAP_T, wrap)];
            for (k, v) in params {
                gl.tex_parameter_i32(target, k, v as i32);
            }
            gl.bind_texture(target, None);
            Ok(t)
        }
    }
}

/// The tutorial's frame, drawn directly; owns every GL object it uses.
pub struct LearnOpenGlBaseline {
    gl: Gl,
    depth_program: glow::Program,
    scene_program: glow::Program,
    depth_light_space: Option<glow::UniformLocation>,
    depth_model: Option<glow::UniformLocation>,
    scene_model: Option<glow::UniformLocation>,
    /// projection, view, lightSpace, lightPos, viewPos
    scene_frame: [Option<glow::UniformLocation>; 5],
    floor: (glow::VertexArray, i32),
    cube: (glow::VertexArray, i32),
    wood: glow::Texture,
    depth_map: glow::Texture,
    shadow_fbo: glow::Framebuffer,
    scene_fbo: glow::Framebuffer,
    light_space: Mat4,
    projection: Mat4,
    view: Mat4,
    /// Floor first, then the three cubes.
    models: [Mat4; 4],
    /// Owns every GL name above; its `Drop` frees them (programs, VAOs, buffers, textures,
    /// renderbuffer, framebuffers).
    _objects: Objects,
}

impl LearnOpenGlBaseline {
    pub fn new(gl: &Gl) -> Result<Self> {
        let mut o = Objects {
            gl: gl.clone(),
            names: Vec::new(),
        };
        let depth_program = o.program("depth", DEPTH_VS, DEPTH_FS)?;
        let scene_program = o.program("scene", SCENE_VS, SCENE_FS)?;
        let floor = o.shape(&floor_vertices())?;
        let cube = o.shape(&cube_vertices())?;
        let wood = ImageData::wood(256);
        let wood_params = (glow::LINEAR_MIPMAP_LINEAR, glow::LINEAR, glow::REPEAT);
        let wood = o.texture(glow::RGBA8, 256, 256, Some(&wood.rgba), wood_params)?;
        let (depth24, nearest) = (glow::DEPTH_COMPONENT24, glow::NEAREST);
        let map_params = (nearest, nearest, glow::CLAMP_TO_BORDER);
        let depth_map = o.texture(depth24, MAP_SIZE, MAP_SIZE, None, map_params)?;
        let target_params = (nearest, nearest, glow::CLAMP_TO_EDGE);
        let colour = o.texture(glow::RGBA8, WIDTH, HEIGHT, None, target_params)?;
        unsafe {
            let uniform = |p, name| gl.get_uniform_location(p, name);
            let scene_frame = ["projection", "view", "lightSpace", "lightPos", "viewPos"]
                .map(|n| uniform(scene_program, n));
            gl.use_program(Some(scene_program));
            gl.uniform_1_i32(uniform(scene_program, "woodMap").as_ref(), 0);
            gl.uniform_1_i32(uniform(scene_program, "shadowMap").as_ref(), 1);
            gl.use_program(None);
            gl.bind_texture(glow::TEXTURE_2D, Some(depth_map));
            gl.tex_parameter_f32_slice(glow::TEXTURE_2D, glow::TEXTURE_BORDER_COLOR, &[1.0; 4]);
            gl.bind_texture(glow::TEXTURE_2D, None);

            let depth_rb = o.keep(gl.create_renderbuffer(), Name::Renderbuffer)?;
            gl.bind_renderbuffer(glow::RENDERBUFFER, Some(depth_rb));
            gl.renderbuffer_storage(glow::RENDERBUFFER, glow::DEPTH_COMPONENT24, WIDTH, HEIGHT);
            gl.bind_renderbuffer(glow::RENDERBUFFER, None);

            let shadow_fbo = o.keep(gl.create_framebuffer(), Name::Framebuffer)?;
            let scene_fbo = o.keep(gl.create_framebuffer(), Name::Framebuffer)?;
            let attach = |fbo, attachment, texture| {
                gl.bind_framebuffer(glow::FRAMEBUFFER, Some(fbo));
                gl.framebuffer_texture_2d(
                    glow::FRAMEBUFFER,
                    attachment,
                    glow::TEXTURE_2D,
                    Some(texture),
                    0,
                );
            };
            attach(shadow_fbo, glow::DEPTH_ATTACHMENT, depth_map);
            gl.draw_buffer(glow::NONE);
            gl.read_buffer(glow::NONE);
            super::check::check_framebuffer(gl, "baseline shadow map")?;
            attach(scene_fbo, glow::COLOR_ATTACHMENT0, colour);
            gl.framebuffer_renderbuffer(
                glow::FRAMEBUFFER,
                glow::DEPTH_ATTACHMENT,
                glow::RENDERBUFFER,
                Some(depth_rb),
            );
            super::check::check_framebuffer(gl, "baseline scene target")?;
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);

            let tilted =
                Mat4::from_axis_angle(Vec3::new(1.0, 0.0, 1.0).normalize(), 60f32.to_radians());
            let at = |x, y, z, s| {
                Mat4::from_translation(Vec3::new(x, y, z)) * Mat4::from_scale(Vec3::splat(s))
            };
            let baseline = LearnOpenGlBaseline {
                gl: gl.clone(),
                depth_program,
                scene_program,
                depth_light_space: uniform(depth_program, "lightSpace"),
                depth_model: uniform(depth_program, "model"),
                scene_model: uniform(scene_program, "model"),
                scene_frame,
                floor,
                cube,
                wood,
                depth_map,
                shadow_fbo,
                scene_fbo,
                light_space: Mat4::orthographic_rh_gl(-10.0, 10.0, -10.0, 10.0, 1.0, 7.5)
                    * Mat4::look_at_rh(LIGHT_POS, Vec3::ZERO, Vec3::Y),
                projection: Mat4::perspective_rh_gl(45f32.to_radians(), 800.0 / 600.0, 0.1, 100.0),
                view: Mat4::look_at_rh(CAMERA_POS, CAMERA_POS - Vec3::Z, Vec3::Y),
                models: [
                    Mat4::IDENTITY,
                    at(0.0, 1.5, 0.0, 0.5),
                    at(2.0, 0.0, 1.0, 0.5),
                    Mat4::from_translation(Vec3::new(-1.0, 0.0, 2.0))
                        * tilted
                        * Mat4::from_scale(Vec3::splat(0.25)),
                ],
                _objects: o,
            };
            check_gl(gl, "baseline setup")?;
            Ok(baseline)
        }
    }

    /// Floor and cubes with the bound program, its model uniform at `model`.
    fn draw_scene(&self, model: Option<&glow::UniformLocation>) {
        let gl = &self.gl;
        for (i, m) in self.models.iter().enumerate() {
            let (vao, count) = if i == 0 { self.floor } else { self.cube };
            unsafe {
                gl.uniform_matrix_4_f32_slice(model, false, &m.to_cols_array());
                gl.bind_vertex_array(Some(vao));
                gl.draw_arrays(glow::TRIANGLES, 0, count);
            }
        }
        unsafe { gl.bind_vertex_array(None) };
    }

    /// One frame: the depth pass, then the lit scene into the 800x600 target (no glFinish).
    pub fn render_frame(&self) {
        let gl = &self.gl;
        let m4 = |loc: &Option<glow::UniformLocation>, m: &Mat4| unsafe {
            gl.uniform_matrix_4_f32_slice(loc.as_ref(), false, &m.to_cols_array())
        };
        unsafe {
            gl.enable(glow::DEPTH_TEST);
            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.shadow_fbo));
            gl.viewport(0, 0, MAP_SIZE, MAP_SIZE);
            gl.clear(glow::DEPTH_BUFFER_BIT);
            gl.use_program(Some(self.depth_program));
            m4(&self.depth_light_space, &self.light_space);
            self.draw_scene(self.depth_model.as_ref());

            gl.bind_framebuffer(glow::FRAMEBUFFER, Some(self.scene_fbo));
            gl.viewport(0, 0, WIDTH, HEIGHT);
            gl.clear_color(0.1, 0.1, 0.1, 1.0);
            gl.clear(glow::COLOR_BUFFER_BIT | glow::DEPTH_BUFFER_BIT);
            gl.use_program(Some(self.scene_program));
            let [projection, view, light_space, light_pos, view_pos] = &self.scene_frame;
            m4(projection, &self.projection);
            m4(view, &self.view);
            m4(light_space, &self.light_space);
            gl.uniform_3_f32_slice(light_pos.as_ref(), &LIGHT_POS.to_array());
            gl.uniform_3_f32_slice(view_pos.as_ref(), &CAMERA_POS.to_array());
            gl.active_texture(glow::TEXTURE0);
            gl.bind_texture(glow::TEXTURE_2D, Some(self.wood));
            gl.active_texture(glow::TEXTURE1);
            gl.bind_texture(glow::TEXTURE_2D, Some(self.depth_map));
            self.draw_scene(self.scene_model.as_ref());
            gl.bind_framebuffer(glow::FRAMEBUFFER, None);
        }
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        unsafe { self.gl.finish() };
    }

    /// The 800x600 image as RGBA8, rows top to bottom.
    pub fn read_colour(&self) -> Vec<u8> {
        let (w, h) = (WIDTH as u32, HEIGHT as u32);
        read_rgba8(&self.gl, Some(self.scene_fbo), 0, w, h)
    }
}
