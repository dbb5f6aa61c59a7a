//! The scene side of the book: `Camera`, `GameItem`, `DirectionalLight` and `Scene`, plus the
//! TOML scene files they load from.

pub mod camera;
pub mod file;
pub mod game_item;
pub mod light;
pub mod motion;
pub mod refusals;

use glam::{Vec3, Vec4};
use serde::{Deserialize, Serialize};

pub use camera::Camera;
pub use game_item::{GameItem, Material};
pub use light::{DirectionalLight, Light, OrthoCoords, PointLight, Shading, SpotLight};

use crate::error::{Error, Result};
use crate::geometry::MeshData;
use crate::image_data::ImageData;
use crate::settings::ShadowSettings;

/// Lights per scene. Each casting light takes one texture unit besides the material's (GL
/// 3.3 guarantees 16 per stage) and one block of per-pixel work; four keeps the shader's
/// cost within a few of the book's one light.
pub const MAX_LIGHTS: usize = 4;

/// The built-in scenes, each also a file under `assets/scenes/`.
pub const BUILTIN_SCENES: &[(&str, &str)] = &[
    ("dummy", include_str!("../../assets/scenes/dummy.toml")),
    (
        "learnopengl",
        include_str!("../../assets/scenes/learnopengl.toml"),
    ),
    ("slides", include_str!("../../assets/scenes/slides.toml")),
    (
        "playground",
        include_str!("../../assets/scenes/playground.toml"),
    ),
    (
        "point-shadows",
        include_str!("../../assets/scenes/point-shadows.toml"),
    ),
    ("large", include_str!("../../assets/scenes/large.toml")),
    (
        "three-lights",
        include_str!("../../assets/scenes/three-lights.toml"),
    ),
    ("overlap", include_str!("../../assets/scenes/overlap.toml")),
    (
        "penumbra",
        include_str!("../../assets/scenes/penumbra.toml"),
    ),
    ("smoke", include_str!("../../assets/scenes/smoke.toml")),
    ("ramp", include_str!("../../assets/scenes/ramp.toml")),
];

/// The lighting equation of the scene pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum ShadingModel {
    /// The book's Phong: reflect the light about the normal, compare with the view.
    #[default]
    Phong,
    /// LearnOpenGL's Blinn-Phong: the half vector between light and view.
    BlinnPhong,
}

/// Everything drawn in a frame, on the CPU side. The renderer uploads `meshes` and `textures`
/// once; items refer to them by index so one mesh can be drawn for many items.
#[derive(Debug, Clone)]
pub struct Scene {
    pub name: String,
    /// The file the scene came from (`<built-in NAME>` for built-in scenes), for messages.
    pub source: std::path::PathBuf,
    pub camera: Camera,
    /// One to [`MAX_LIGHTS`] lights; the first is "the" light of the
    /// chapters (the one the DummyGame's keys turn and `compare` measures by default).
    pub lights: Vec<Light>,
    pub ambient: Vec3,
    pub specular_power: f32,
    pub shading: ShadingModel,
    pub clear_colour: Vec4,
    /// The frame size: the scene file's (the window's initial size, `render`'s default),
    /// updated to whatever is being drawn (a fitted light box uses its aspect).
    pub size: [u32; 2],
    pub items: Vec<GameItem>,
    pub meshes: Vec<MeshData>,
    pub textures: Vec<ImageData>,
    /// The scene's own shadow settings (the chapter's configuration); flags override them.
    pub shadow: ShadowSettings,
    /// What the chapter steps take from the scene's tutorial.
    pub steps: StepContext,
    /// The camera a fitted light box follows, when it should not be the viewing camera
    /// (to watch or measure the fit from elsewhere).
    pub fit_camera: Option<Camera>,
    /// Named cameras (`[views]`): `--view NAME` shows one, and a tutorial's own camera
    /// keeps its name where the scene opens on another.
    pub views: Vec<(String, Camera)>,
    /// The view the commands open on (`view`), where the file names one; `camera` stays
    /// the file's `[camera]` until [`Scene::open_view`] picks it.
    pub opening_view: Option<String>,
    /// Seconds of animation so far (30 updates a second).
    pub time: f32,
    /// The scene file's `[motion] keyframes` (`--motion keyframes`).
    pub motion_keyframes: Vec<motion::Keyframe>,
    /// A scripted path: each update moves the camera and light to its next frame.
    pub motion: Option<motion::MotionPath>,
}

/// The tutorial-specific numbers the chapter steps use ([`crate::steps`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepContext {
    /// The tutorial's constant bias (the book 0.05, LearnOpenGL 0.005).
    pub bias: f32,
    /// The wrap mode its chapter starts with.
    pub start_wrap: crate::settings::Wrap,
    /// The camera its steps are shown from (`[steps] camera`), where the tutorial's own
    /// does not show what they change; `None`: the scene's camera.
    pub camera: Option<Camera>,
    /// Which tutorial's steps it has (`[steps] list`): see `crate::steps::of`.
    pub list: StepList,
    /// The lights' size while its steps are shown (`[steps] light_size`), where the
    /// tutorial's light is a point but a step (PCSS) needs a size; `None`: the lights' own.
    pub light_size: Option<f32>,
}

/// The lists of steps a scene can have (`[steps] list`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StepList {
    /// The chapters' (LWJGL "Shadows", LearnOpenGL "Shadow Mapping", the slides).
    #[default]
    Chapters,
    /// The shadow-playground's demo pages, then PCSS.
    Playground,
    /// How translucent items cast: not at all, then as opaque.
    Volumetric,
}

impl StepList {
    pub fn name(self) -> &'static str {
        match self {
            StepList::Chapters => "chapters",
            StepList::Playground => "playground",
            StepList::Volumetric => "volumetric",
        }
    }
}

impl Scene {
    /// A built-in scene by name, or a TOML file when `name` ends in `.toml`.
    pub fn load(name: &str) -> Result<Scene> {
        if name.ends_with(".toml") {
            return file::load_file(std::path::Path::new(name));
        }
        match BUILTIN_SCENES.iter().find(|(n, _)| *n == name) {
            Some((n, text)) => {
                file::parse(text, std::path::Path::new(&format!("<built-in {n}>")), None)
            }
            None => {
                let names = Self::builtin_names();
                let guess = crate::settings::suggest::did_you_mean(name, names.iter().copied())
                    .map_or(String::new(), |g| format!(" (did you mean '{g}'?)"));
                Err(Error::Invalid(format!(
                    "unknown scene '{name}'{guess}: expected one of {} or a path to a .toml \
                     scene file",
                    names.join(", ")
                )))
            }
        }
    }

    pub fn builtin_names() -> Vec<&'static str> {
        BUILTIN_SCENES.iter().map(|(n, _)| *n).collect()
    }

    /// One fixed update (the book's `update`, 30 per second): items spin, a point light
    /// with `oscillate` moves.
    pub fn update(&mut self) {
        for item in &mut self.items {
            item.update();
        }
        self.time += 1.0 / 30.0;
        if let Some(mut path) = self.motion.take() {
            path.frame += 1;
            path.pose(self, path.frame);
            self.motion = Some(path);
        }
        for light in &mut self.lights {
            if let Light::Point(p) = light {
                p.position = p.centre + p.oscillate * (0.5 * self.time).sin();
            }
        }
    }

    /// Sets the first light's angle in degrees, clamped to [0, 180] as the book does, about
    /// the light's own azimuth ([`DirectionalLight::azimuth`]: +Z for the DummyGame, whose
    /// direction becomes (0, sin a, cos a)). Only a directional light has an angle; returns
    /// false for other lights.
    pub fn set_light_angle(&mut self, angle_deg: f32) -> bool {
        match self.light_azimuth() {
            Some(azimuth) => self.set_light_angle_about(azimuth, angle_deg),
            None => false,
        }
    }

    /// The first light's azimuth, if it is directional. Past the overhead a light's own
    /// horizontal part points the other way, so whatever turns a light step by step (the
    /// demo's keys) takes the azimuth once and turns about it with
    /// [`Scene::set_light_angle_about`].
    pub fn light_azimuth(&self) -> Option<Vec3> {
        self.lights
            .first()
            .and_then(Light::as_directional)
            .map(DirectionalLight::azimuth)
    }

    /// [`Scene::set_light_angle`] about a given azimuth (a horizontal unit vector).
    pub fn set_light_angle_about(&mut self, azimuth: Vec3, angle_deg: f32) -> bool {
        match self.lights.first_mut().and_then(Light::as_directional_mut) {
            Some(l) => {
                l.set_angle_about(azimuth, angle_deg.clamp(0.0, 180.0));
                true
            }
            None => false,
        }
    }

    /// The first light: the chapters' one light.
    pub fn light(&self) -> &Light {
        &self.lights[0]
    }

    /// The first light, to change it.
    pub fn light_mut(&mut self) -> &mut Light {
        &mut self.lights[0]
    }

    /// The lights as the steps show them: each given `[steps] light_size`, if the scene
    /// has one.
    pub fn use_steps_light_size(&mut self) {
        if let Some(size) = self.steps.light_size {
            self.lights.iter_mut().for_each(|l| l.set_size(size));
        }
    }

    /// The named view `name`'s camera, if the scene has it.
    pub fn view(&self, name: &str) -> Option<Camera> {
        self.views.iter().find(|(n, _)| n == name).map(|(_, c)| *c)
    }

    /// Puts the camera at view `name`, or at the view the scene opens on (`None`; the
    /// file's `[camera]` if it names none), as the commands show the scene.
    pub fn open_view(&mut self, name: Option<&str>) -> Result<()> {
        let Some(name) = name.or(self.opening_view.as_deref()) else {
            return Ok(());
        };
        let names: Vec<&str> = self.views.iter().map(|(n, _)| n.as_str()).collect();
        self.camera = self.view(name).ok_or_else(|| {
            Error::Invalid(match names.is_empty() {
                true => format!(
                    "--view {name}: the {} scene has no named views (its file has no [views])",
                    self.name
                ),
                false => format!(
                    "--view {name}: the {} scene's views are {}",
                    self.name,
                    names.join(", ")
                ),
            })
        })?;
        Ok(())
    }

    /// The camera the chapter steps are shown from: `[steps] camera`, else the scene's.
    pub fn steps_camera(&self) -> Camera {
        self.steps.camera.unwrap_or(self.camera)
    }

    /// The camera that shadow fitting follows: `fit_camera` when set, else the viewer.
    pub fn fitting_camera(&self) -> &Camera {
        self.fit_camera.as_ref().unwrap_or(&self.camera)
    }
}
