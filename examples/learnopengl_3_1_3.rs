//! LearnOpenGL "Shadow Mapping", program 3.1.3 (`shadow_mapping.cpp`, the improved final
//! step) as one file, to read beside the chapter: a depth pass from the light into a 1024^2
//! map, then the wooden floor and three cubes lit with Blinn-Phong, a slope-scaled bias and
//! 3 x 3 PCF, the map clamped to a border of depth 1 and z > 1 lit.
//!
//! ```sh
//! cargo run --release --example learnopengl_3_1_3 -- out.png
//! ```
//!
//! It renders headless (EGL, no display) into an 800 x 600 target and writes a PNG. The GL
//! work goes through the engine's book-named owners (`ShaderProgram`, `Mesh`, `Texture`,
//! `ShadowMap`, `RenderTarget`); the shaders below are this file's own text of the
//! tutorial's. The benchmark `learnopengl_baseline` and `tests/baseline.rs` use
//! [`ShadowMapping`] as a yardstick for the renderer's `learnopengl` scene.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use glam::{Mat4, Vec3};
use shadowmap::engine::{self, state, DepthPassGuard, DepthState, Gl, HeadlessContext, Mesh};
use shadowmap::engine::{Outputs, RenderTarget, Sampler, Sampling, ShaderProgram, ShaderSource};
use shadowmap::engine::{ShadowMap, Texture};
use shadowmap::geometry::MeshData;
use shadowmap::image_data::ImageData;
use shadowmap::settings::{Cull, DepthFormat, Wrap};
use shadowmap::transformation::Transformation;
use shadowmap::Result;

/// The window's size (`SCR_WIDTH`, `SCR_HEIGHT`).
pub const SCR_WIDTH: u32 = 800;
pub const SCR_HEIGHT: u32 = 600;
/// The depth map's size (`SHADOW_WIDTH`, `SHADOW_HEIGHT`).
pub const SHADOW_SIZE: u32 = 1024;
/// `lightPos`: the light's camera sits here and looks at the origin.
pub const LIGHT_POS: Vec3 = Vec3::new(-2.0, 4.0, -1.0);
/// `glClearColor(0.1, 0.1, 0.1, 1.0)`.
const CLEAR: [f32; 4] = [0.1, 0.1, 0.1, 1.0];

/// `shadow_mapping_depth.vs`: the scene in the light's clip space. The engine's meshes
/// carry position, texture coordinate and normal at locations 0, 1, 2.
const DEPTH_VS: &str = "#version 330 core
layout (location = 0) in vec3 aPos;

uniform mat4 lightSpaceMatrix;
uniform mat4 model;

void main()
{
    gl_Position = lightSpaceMatrix * model * vec4(aPos, 1.0);
}
";

/// `shadow_mapping_depth.fs`: nothing to write, the depth buffer is the output.
const DEPTH_FS: &str = "#version 330 core
void main()
{
}
";

/// `shadow_mapping.vs`: world position, normal and the position in the light's clip space.
const SCENE_VS: &str = "#version 330 core
layout (location = 0) in vec3 aPos;
layout (location = 1) in vec2 aTexCoords;
layout (location = 2) in vec3 aNormal;

out VS_OUT {
    vec3 FragPos;
    vec3 Normal;
    vec2 TexCoords;
    vec4 FragPosLightSpace;
} vs_out;

uniform mat4 projection;
uniform mat4 view;
uniform mat4 model;
uniform mat4 lightSpaceMatrix;

void main()
{
    vs_out.FragPos = vec3(model * vec4(aPos, 1.0));
    vs_out.Normal = transpose(inverse(mat3(model))) * aNormal;
    vs_out.TexCoords = aTexCoords;
    vs_out.FragPosLightSpace = lightSpaceMatrix * vec4(vs_out.FragPos, 1.0);
    gl_Position = projection * view * model * vec4(aPos, 1.0);
}
";

/// `shadow_mapping.fs`: Blinn-Phong with light colour 0.3 and ambient 0.3 x the light
/// colour (the `learnopengl` scene's reading of the repository), and `ShadowCalculation`:
/// the slope-scaled bias, 3 x 3 PCF, and no shadow beyond the light's far plane.
const SCENE_FS: &str = "#version 330 core
out vec4 FragColor;

in VS_OUT {
    vec3 FragPos;
    vec3 Normal;
    vec2 TexCoords;
    vec4 FragPosLightSpace;
} fs_in;

uniform sampler2D diffuseTexture;
uniform sampler2D shadowMap;

uniform vec3 lightPos;
uniform vec3 viewPos;

float ShadowCalculation(vec4 fragPosLightSpace)
{
    // Perspective divide (w = 1 for the orthographic light), then [-1, 1] to [0, 1].
    vec3 projCoords = fragPosLightSpace.xyz / fragPosLightSpace.w;
    projCoords = projCoords * 0.5 + 0.5;
    float currentDepth = projCoords.z;
    // The bias grows as the surface turns away from the light.
    vec3 normal = normalize(fs_in.Normal);
    vec3 lightDir = normalize(lightPos - fs_in.FragPos);
    float bias = max(0.05 * (1.0 - dot(normal, lightDir)), 0.005);
    // PCF: the shadowed share of the 3 x 3 texels around the lookup.
    float shadow = 0.0;
    vec2 texelSize = 1.0 / textureSize(shadowMap, 0);
    for (int x = -1; x <= 1; ++x)
    {
        for (int y = -1; y <= 1; ++y)
        {
            float pcfDepth = texture(shadowMap, projCoords.xy + vec2(x, y) * texelSize).r;
            shadow += currentDepth - bias > pcfDepth ? 1.0 : 0.0;
        }
    }
    shadow /= 9.0;
    // Beyond the light's far plane nothing is known: lit.
    if (projCoords.z > 1.0)
        shadow = 0.0;
    return shadow;
}

void main()
{
    vec3 color = texture(diffuseTexture, fs_in.TexCoords).rgb;
    vec3 normal = normalize(fs_in.Normal);
    vec3 lightColor = vec3(0.3);
    vec3 ambient = 0.3 * lightColor;
    vec3 lightDir = normalize(lightPos - fs_in.FragPos);
    float diff = max(dot(lightDir, normal), 0.0);
    vec3 diffuse = diff * lightColor;
    vec3 viewDir = normalize(viewPos - fs_in.FragPos);
    vec3 halfwayDir = normalize(lightDir + viewDir);
    float spec = pow(max(dot(normal, halfwayDir), 0.0), 64.0);
    vec3 specular = spec * lightColor;
    float shadow = ShadowCalculation(fs_in.FragPosLightSpace);
    vec3 lighting = (ambient + (1.0 - shadow) * (diffuse + specular)) * color;
    FragColor = vec4(lighting, 1.0);
}
";

/// `planeVertices`: the 50 x 50 floor at y = -0.5, the wood repeating 25 times across it,
/// wound clockwise seen from above as in the tutorial.
fn plane_vertices() -> MeshData {
    let corners = [
        ([25.0, 25.0], [25.0, 0.0]),
        ([-25.0, 25.0], [0.0, 0.0]),
        ([-25.0, -25.0], [0.0, 25.0]),
        ([25.0, 25.0], [25.0, 0.0]),
        ([-25.0, -25.0], [0.0, 25.0]),
        ([25.0, -25.0], [25.0, 25.0]),
    ];
    MeshData {
        name: "planeVertices".into(),
        positions: corners.iter().map(|([x, z], _)| [*x, -0.5, *z]).collect(),
        tex_coords: corners.iter().map(|(_, uv)| *uv).collect(),
        normals: vec![[0.0, 1.0, 0.0]; 6],
        indices: (0..6).collect(),
    }
}

/// `renderScene`'s model matrices: the floor, then the three cubes (`renderCube` spans
/// [-1, 1]).
fn models() -> [Mat4; 4] {
    let scaled = |at: Vec3, s: f32| Mat4::from_translation(at) * Mat4::from_scale(Vec3::splat(s));
    let axis = Vec3::new(1.0, 0.0, 1.0).normalize();
    [
        Mat4::IDENTITY,
        scaled(Vec3::new(0.0, 1.5, 0.0), 0.5),
        scaled(Vec3::new(2.0, 0.0, 1.0), 0.5),
        Mat4::from_translation(Vec3::new(-1.0, 0.0, 2.0))
            * Mat4::from_axis_angle(axis, 60f32.to_radians())
            * Mat4::from_scale(Vec3::splat(0.25)),
    ]
}

/// `lightSpaceMatrix = lightProjection * lightView`: glm::ortho(-10, 10, -10, 10, 1, 7.5)
/// times glm::lookAt(lightPos, origin, +Y).
pub fn light_space_matrix() -> Mat4 {
    let light_projection = Transformation::ortho(-10.0, 10.0, -10.0, 10.0, 1.0, 7.5);
    let to_light = LIGHT_POS.as_dvec3();
    let light_view = Transformation::light_look_at(to_light, to_light).as_mat4();
    light_projection * light_view
}

/// LearnOpenGL's `Camera`, as far as a frame needs it: its position (`viewPos`) and its
/// view matrix. The tutorial's flies with the keys and the mouse; it starts at (0, 0, 3)
/// looking down -Z.
pub struct Camera {
    pub position: Vec3,
    pub view: Mat4,
}

impl Default for Camera {
    fn default() -> Camera {
        let position = Vec3::new(0.0, 0.0, 3.0);
        let view = Mat4::look_at_rh(position, position - Vec3::Z, Vec3::Y);
        Camera { position, view }
    }
}

/// The tutorial's program: its two shaders, meshes, wood texture, depth map FBO and an
/// offscreen 800 x 600 target in place of the window. Every GL object has its engine owner.
pub struct ShadowMapping {
    gl: Gl,
    simple_depth_shader: ShaderProgram,
    shader: ShaderProgram,
    plane: Mesh,
    cube: Mesh,
    wood_texture: Texture,
    depth_map: ShadowMap,
    /// GL_CLAMP_TO_BORDER with border depth 1: outside the map is "far", so lit.
    border: Sampler,
    window: RenderTarget,
    light_space_matrix: Mat4,
    pub camera: Camera,
}

impl ShadowMapping {
    pub fn new(gl: &Gl) -> Result<ShadowMapping> {
        let program = |name: &str, vs: &str, fs: &str| {
            let source =
                |stage: &str, text: &str| ShaderSource::new(format!("{name}.{stage}"), text);
            ShaderProgram::new(gl, &source("vs", vs), &source("fs", fs), &[])
        };
        let shader = program("shadow_mapping", SCENE_VS, SCENE_FS)?;
        shader.bind();
        shader.set_i32("diffuseTexture", 0);
        shader.set_i32("shadowMap", 1);
        shader.unbind();
        let border = Sampling {
            compare: false,
            linear: false,
            wrap: Wrap::ClampToBorder,
            // The tutorial's own fragment shader: the sampler's border, as on the desktop.
            border_in_shader: false,
            interpolate_in_shader: false,
        };
        // glEnable(GL_DEPTH_TEST): the tutorial's one piece of global state.
        state::enable_depth_test(gl);
        let depth_map = Texture::depth(gl, SHADOW_SIZE, SHADOW_SIZE, DepthFormat::D24)?;
        Ok(ShadowMapping {
            gl: gl.clone(),
            simple_depth_shader: program("shadow_mapping_depth", DEPTH_VS, DEPTH_FS)?,
            shader,
            plane: Mesh::new(gl, &plane_vertices())?,
            cube: Mesh::new(gl, &MeshData::cube())?,
            wood_texture: Texture::from_image(gl, &ImageData::wood(256))?,
            depth_map: ShadowMap::from_texture(gl, depth_map, DepthFormat::D24)?,
            border: Sampler::new(gl, border)?,
            window: RenderTarget::new(gl, SCR_WIDTH, SCR_HEIGHT, Outputs::default())?,
            light_space_matrix: light_space_matrix(),
            camera: Camera::default(),
        })
    }

    /// `renderScene`: the floor and the cubes with `shader`'s `model` uniform.
    fn render_scene(&self, shader: &ShaderProgram) {
        let [floor, cubes @ ..] = models();
        shader.set_mat4("model", &floor);
        self.plane.render();
        for model in cubes {
            shader.set_mat4("model", &model);
            self.cube.render();
        }
    }

    /// One frame of the render loop: the depth pass, then the scene with its shadows.
    pub fn render_frame(&self) {
        // 1. The depth of the scene from the light, into the map.
        let no_culling = DepthState {
            cull: Cull::None,
            polygon_offset: [0.0, 0.0],
            scissor: None,
        };
        {
            let _pass = DepthPassGuard::begin(&self.gl, no_culling, &self.simple_depth_shader);
            let depth = &self.simple_depth_shader;
            depth.set_mat4("lightSpaceMatrix", &self.light_space_matrix);
            self.depth_map.bind_for_writing();
            state::clear_depth(&self.gl);
            self.render_scene(depth);
        }

        // 2. The scene as usual, reading the map.
        self.window.bind_and_clear(CLEAR);
        let shader = &self.shader;
        shader.bind();
        let aspect = SCR_WIDTH as f32 / SCR_HEIGHT as f32;
        let projection = Mat4::perspective_rh_gl(45f32.to_radians(), aspect, 0.1, 100.0);
        shader.set_mat4("projection", &projection);
        shader.set_mat4("view", &self.camera.view);
        shader.set_vec3("viewPos", self.camera.position);
        shader.set_vec3("lightPos", LIGHT_POS);
        shader.set_mat4("lightSpaceMatrix", &self.light_space_matrix);
        self.wood_texture.bind(0);
        self.depth_map.depth_map_texture().bind(1);
        let _border = self.border.bind(1);
        self.render_scene(shader);
        shader.unbind();
    }

    /// Blocks until the GPU has finished (for wall-time measurements).
    pub fn finish(&self) {
        state::finish(&self.gl);
    }

    /// The frame as RGBA8, rows top to bottom.
    pub fn read_colour(&self) -> Vec<u8> {
        self.window.read_colour()
    }

    /// The depth map, rows bottom to top (as GL stores them).
    pub fn read_depth(&self) -> Vec<f32> {
        self.depth_map.read_depth()
    }
}

/// Renders one frame headless and writes it to `out`.
fn render_to(out: &Path) -> Result<()> {
    shadowmap::output::check_output_image("OUT.png", out)?;
    let context = HeadlessContext::new()?;
    let program = ShadowMapping::new(context.gl())?;
    program.render_frame();
    engine::check_gl(context.gl(), "the frame")?;
    let image = ImageData {
        width: SCR_WIDTH,
        height: SCR_HEIGHT,
        rgba: program.read_colour(),
    };
    image.save_png(out)
}

#[allow(dead_code)] // not called where tests and benches include this file
fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = format!(
        "usage: cargo run --release --example learnopengl_3_1_3 -- OUT.png\n\
         renders LearnOpenGL's shadow_mapping 3.1.3 frame ({SCR_WIDTH}x{SCR_HEIGHT}) headless \
         and writes it as a PNG"
    );
    if let Err(code) = shadowmap::input::check_args(&args, 1..=1, &usage) {
        return code;
    }
    let out = &args[0];
    let out = PathBuf::from(out);
    match render_to(&out) {
        Ok(()) => {
            println!("wrote {} ({SCR_WIDTH}x{SCR_HEIGHT})", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
