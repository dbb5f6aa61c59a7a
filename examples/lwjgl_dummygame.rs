//! The LWJGL book's chapter "Shadows" as one file, to read beside it: the DummyGame (a
//! green cube above a blue plane, a directional light at 45 degrees) drawn the chapter's
//! way. `renderDepthMap` draws the scene from the light into the `ShadowMap`, then the
//! scene pass tests each fragment with `calcShadow`: bias 0.05 and the 3 x 3 PCF of the
//! section "Shadow Mapping improvements".
//!
//! ```sh
//! cargo run --release --example lwjgl_dummygame -- out.png
//! ```
//!
//! It renders headless (EGL, no display) into a 1280 x 720 target and writes a PNG. The GL
//! work goes through the engine's owners, named as the book's classes (`ShaderProgram`,
//! `Mesh`, `Texture`'s depth constructor, `ShadowMap`), and the matrices through its
//! `Transformation`; the shaders below are this file's own text of the chapter's.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use glam::{Mat4, Vec3, Vec4};
use shadowmap::engine::{self, state, DepthPassGuard, DepthState, Gl, HeadlessContext, Mesh};
use shadowmap::engine::{Outputs, RenderTarget, ShaderProgram, ShaderSource, ShadowMap, Texture};
use shadowmap::geometry::MeshData;
use shadowmap::image_data::ImageData;
use shadowmap::settings::{Cull, DepthFormat};
use shadowmap::transformation::Transformation;
use shadowmap::Result;

/// The window's size.
pub const WIDTH: u32 = 1280;
pub const HEIGHT: u32 = 720;
/// `ShadowMap.SHADOW_MAP_WIDTH` and `SHADOW_MAP_HEIGHT`.
pub const SHADOW_MAP_SIZE: u32 = 1024;
/// The light's angle in degrees: its direction is (0, sin a, cos a).
pub const LIGHT_ANGLE: f32 = 45.0;
/// `DirectionalLight.shadowPosMult`: how far along its direction the light's camera sits.
const SHADOW_POS_MULT: f32 = 5.0;
/// `Renderer`'s ambient light and specular power.
const AMBIENT_LIGHT: Vec3 = Vec3::splat(0.3);
const SPECULAR_POWER: f32 = 10.0;

/// `depth_vertex.vs`: the scene in the light's clip space.
const DEPTH_VS: &str = "#version 330

layout (location=0) in vec3 position;
layout (location=1) in vec2 texCoord;
layout (location=2) in vec3 vertexNormal;

uniform mat4 modelLightViewMatrix;
uniform mat4 orthoProjectionMatrix;

void main()
{
    gl_Position = orthoProjectionMatrix * modelLightViewMatrix * vec4(position, 1.0f);
}
";

/// `depth_fragment.fs`. The book writes `gl_FragDepth = gl_FragCoord.z` and says the line
/// can go: the depth buffer stores that value anyway.
const DEPTH_FS: &str = "#version 330

void main()
{
}
";

/// `scene_vertex.vs`: view-space position and normal, and the position in the light's
/// clip space (`mlightviewVertexPos`).
const SCENE_VS: &str = "#version 330

layout (location=0) in vec3 position;
layout (location=1) in vec2 texCoord;
layout (location=2) in vec3 vertexNormal;

out vec3 mvVertexNormal;
out vec3 mvVertexPos;
out vec4 mlightviewVertexPos;

uniform mat4 modelViewMatrix;
uniform mat4 projectionMatrix;
uniform mat4 modelLightViewMatrix;
uniform mat4 orthoProjectionMatrix;

void main()
{
    vec4 mvPos = modelViewMatrix * vec4(position, 1.0);
    gl_Position = projectionMatrix * mvPos;
    mvVertexNormal = normalize(modelViewMatrix * vec4(vertexNormal, 0.0)).xyz;
    mvVertexPos = mvPos.xyz;
    mlightviewVertexPos = orthoProjectionMatrix * modelLightViewMatrix * vec4(position, 1.0);
}
";

/// `scene_fragment.fs`, cut to what the DummyGame uses: untextured materials, one
/// directional light (view space) with Phong's diffuse and specular, and `calcShadow`.
const SCENE_FS: &str = "#version 330

in vec3 mvVertexNormal;
in vec3 mvVertexPos;
in vec4 mlightviewVertexPos;

out vec4 fragColor;

struct DirectionalLight
{
    vec3 colour;
    vec3 direction;
    float intensity;
};

struct Material
{
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    float reflectance;
};

uniform vec3 ambientLight;
uniform float specularPower;
uniform Material material;
uniform DirectionalLight directionalLight;
uniform sampler2D shadowMap;

vec4 calcLightColour(vec3 light_colour, float light_intensity, vec3 position,
                     vec3 to_light_dir, vec3 normal)
{
    // Diffuse light
    float diffuseFactor = max(dot(normal, to_light_dir), 0.0);
    vec4 diffuseColour = material.diffuse * vec4(light_colour, 1.0) * light_intensity
                         * diffuseFactor;
    // Specular light
    vec3 camera_direction = normalize(-position);
    vec3 from_light_dir = -to_light_dir;
    vec3 reflected_light = normalize(reflect(from_light_dir, normal));
    float specularFactor = max(dot(camera_direction, reflected_light), 0.0);
    specularFactor = pow(specularFactor, specularPower);
    vec4 specColour = material.specular * light_intensity * specularFactor
                      * material.reflectance * vec4(light_colour, 1.0);
    return diffuseColour + specColour;
}

vec4 calcDirectionalLight(DirectionalLight light, vec3 position, vec3 normal)
{
    return calcLightColour(light.colour, light.intensity, position,
                           normalize(light.direction), normal);
}

float calcShadow(vec4 position)
{
    vec3 projCoords = position.xyz;
    // From screen coordinates [-1, 1] to texture coordinates [0, 1]
    projCoords = projCoords * 0.5 + 0.5;
    float bias = 0.05;

    // The average of the 3 x 3 comparisons around the fragment, one texel apart
    float shadowFactor = 0.0;
    vec2 inc = 1.0 / textureSize(shadowMap, 0);
    for (int row = -1; row <= 1; ++row)
    {
        for (int col = -1; col <= 1; ++col)
        {
            float textDepth = texture(shadowMap, projCoords.xy + vec2(row, col) * inc).r;
            shadowFactor += projCoords.z - bias > textDepth ? 1.0 : 0.0;
        }
    }
    shadowFactor /= 9.0;

    return 1 - shadowFactor;
}

void main()
{
    vec3 normal = normalize(mvVertexNormal);
    vec4 diffuseSpecularComp = calcDirectionalLight(directionalLight, mvVertexPos, normal);
    // The ambient light is not shadowed
    float shadow = calcShadow(mlightviewVertexPos);
    fragColor = clamp(material.ambient * vec4(ambientLight, 1)
                      + diffuseSpecularComp * shadow, 0, 1);
}
";

/// A `GameItem`: its mesh, position, scale and colour (no rotation: the first frame of
/// the DummyGame, before the cube has turned).
struct GameItem {
    mesh: Mesh,
    position: Vec3,
    scale: f32,
    colour: Vec4,
}

impl GameItem {
    fn model_matrix(&self) -> Mat4 {
        Transformation::model(self.position, Vec3::ZERO, Vec3::splat(self.scale))
    }
}

/// The light's direction, towards it: (0, sin a, cos a), normalised.
fn light_direction() -> Vec3 {
    let a = LIGHT_ANGLE.to_radians();
    Vec3::new(0.0, a.sin(), a.cos()).normalize()
}

/// The chapter's light view: the camera at direction x `shadowPosMult`, turned by
/// x = acos(dir.z) and y = asin(dir.x) degrees (right while dir.x = 0, as here).
pub fn light_view_matrix() -> Mat4 {
    let d = light_direction();
    let angles = Vec3::new(d.z.acos().to_degrees(), d.x.asin().to_degrees(), 0.0);
    Transformation::light_view(d * SHADOW_POS_MULT, angles)
}

/// `OrthoCoords` (-10, 10, -10, 10, near -1, far 20) as an orthographic projection.
pub fn ortho_projection_matrix() -> Mat4 {
    Transformation::ortho(-10.0, 10.0, -10.0, 10.0, -1.0, 20.0)
}

/// The DummyGame's `Renderer`: its two shader programs, its `ShadowMap`, the scene and an
/// offscreen target in place of the window. Every GL object has its engine owner.
pub struct DummyGame {
    gl: Gl,
    depth_shader_program: ShaderProgram,
    scene_shader_program: ShaderProgram,
    shadow_map: ShadowMap,
    items: [GameItem; 2],
    window: RenderTarget,
}

impl DummyGame {
    pub fn new(gl: &Gl) -> Result<DummyGame> {
        let program = |name: &str, vs: &str, fs: &str| {
            let vertex = ShaderSource::new(format!("{name}_vertex.vs"), vs);
            let fragment = ShaderSource::new(format!("{name}_fragment.fs"), fs);
            ShaderProgram::new(gl, &vertex, &fragment, &[])
        };
        // The `ShadowMap` constructor: an FBO around `new Texture(width, height, format)`.
        let depth_map = Texture::depth(gl, SHADOW_MAP_SIZE, SHADOW_MAP_SIZE, DepthFormat::D24)?;
        // glEnable(GL_DEPTH_TEST), as the book's `Window` does.
        state::enable_depth_test(gl);
        let cube = GameItem {
            mesh: Mesh::new(gl, &MeshData::cube())?,
            position: Vec3::ZERO,
            scale: 0.5,
            colour: Vec4::new(0.0, 1.0, 0.0, 1.0),
        };
        let plane = GameItem {
            mesh: Mesh::new(gl, &MeshData::plane(1.0))?,
            position: Vec3::new(0.0, -1.0, 0.0),
            scale: 2.5,
            colour: Vec4::new(0.0, 0.0, 1.0, 1.0),
        };
        Ok(DummyGame {
            gl: gl.clone(),
            depth_shader_program: program("depth", DEPTH_VS, DEPTH_FS)?,
            scene_shader_program: program("scene", SCENE_VS, SCENE_FS)?,
            shadow_map: ShadowMap::from_texture(gl, depth_map, DepthFormat::D24)?,
            items: [cube, plane],
            window: RenderTarget::new(gl, WIDTH, HEIGHT, Outputs::default())?,
        })
    }

    /// `renderDepthMap`: the scene from the light, into the shadow map.
    fn render_depth_map(&self, light_view: &Mat4) {
        let no_culling = DepthState {
            cull: Cull::None,
            polygon_offset: [0.0, 0.0],
            scissor: None,
        };
        let program = &self.depth_shader_program;
        // Binds the program; unbinds it and the FBO when the pass ends.
        let _pass = DepthPassGuard::begin(&self.gl, no_culling, program);
        self.shadow_map.bind_for_writing();
        state::clear_depth(&self.gl);
        program.set_mat4("orthoProjectionMatrix", &ortho_projection_matrix());
        for item in &self.items {
            let model_light_view = Transformation::model_view(&item.model_matrix(), light_view);
            program.set_mat4("modelLightViewMatrix", &model_light_view);
            item.mesh.render();
        }
    }

    /// `renderScene`: the camera's view, each fragment tested against the shadow map.
    fn render_scene(&self, light_view: &Mat4) {
        let p = &self.scene_shader_program;
        p.bind();
        let camera_view = Transformation::view(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO);
        let projection =
            Transformation::projection(60.0, WIDTH as f32, HEIGHT as f32, 0.01, 1000.0);
        p.set_mat4("projectionMatrix", &projection);
        p.set_mat4("orthoProjectionMatrix", &ortho_projection_matrix());
        p.set_vec3("ambientLight", AMBIENT_LIGHT);
        p.set_f32("specularPower", SPECULAR_POWER);
        // The light's direction in view space (w = 0: only the rotation applies).
        let direction = camera_view * light_direction().extend(0.0);
        p.set_vec3("directionalLight.colour", Vec3::ONE);
        p.set_vec3("directionalLight.direction", direction.truncate());
        p.set_f32("directionalLight.intensity", 1.0);
        p.set_i32("shadowMap", 1);
        self.shadow_map.depth_map_texture().bind(1);
        for item in &self.items {
            let model = item.model_matrix();
            p.set_mat4(
                "modelViewMatrix",
                &Transformation::model_view(&model, &camera_view),
            );
            p.set_mat4(
                "modelLightViewMatrix",
                &Transformation::model_view(&model, light_view),
            );
            p.set_vec4("material.ambient", item.colour);
            p.set_vec4("material.diffuse", item.colour);
            p.set_vec4("material.specular", item.colour);
            p.set_f32("material.reflectance", 1.0);
            item.mesh.render();
        }
        p.unbind();
    }

    /// The book's `Renderer.render`: the depth map first, then the scene into the window.
    pub fn render_frame(&self) {
        let light_view = light_view_matrix();
        self.render_depth_map(&light_view);
        self.window.bind_and_clear([0.0, 0.0, 0.0, 1.0]);
        self.render_scene(&light_view);
    }

    /// The frame as RGBA8, rows top to bottom.
    pub fn read_colour(&self) -> Vec<u8> {
        self.window.read_colour()
    }

    /// The depth map, rows bottom to top (as GL stores them).
    pub fn read_depth(&self) -> Vec<f32> {
        self.shadow_map.read_depth()
    }
}

/// Renders one frame headless and writes it to `out`.
fn render_to(out: &Path) -> Result<()> {
    shadowmap::output::check_output_image("OUT.png", out)?;
    let context = HeadlessContext::new()?;
    let game = DummyGame::new(context.gl())?;
    game.render_frame();
    engine::check_gl(context.gl(), "the frame")?;
    let image = ImageData {
        width: WIDTH,
        height: HEIGHT,
        rgba: game.read_colour(),
    };
    image.save_png(out)
}

#[allow(dead_code)] // not called where tests include this file
fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = format!(
        "usage: cargo run --release --example lwjgl_dummygame -- OUT.png\n\
         renders the LWJGL book's DummyGame with its shadows ({WIDTH}x{HEIGHT}) headless and \
         writes it as a PNG"
    );
    if let Err(code) = shadowmap::input::check_args(&args, 1..=1, &usage) {
        return code;
    }
    let out = &args[0];
    let out = PathBuf::from(out);
    match render_to(&out) {
        Ok(()) => {
            println!("wrote {} ({WIDTH}x{HEIGHT})", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
