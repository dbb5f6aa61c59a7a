//! The command line: `shadowmap` (the demo window), `shadowmap render` (headless frames).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use shadowmap::settings::{
    BeyondFar, BiasMode, Cull, DepthFormat, Filter, Fit, LightProjection, LightView, PointPass,
    Wrap,
};
use shadowmap::steps;
use shadowmap::{Scene, ShadowSettings};

#[derive(Parser, Debug)]
#[command(
    name = "shadowmap",
    version,
    about = "The classic shadow-mapping chapters, ported to Rust and OpenGL 3.3 core.",
    long_about = "The classic shadow-mapping chapters, ported to Rust and OpenGL 3.3 core.\n\n\
        With no command, opens the DummyGame demo in a window (or, with no display, renders it \
        headless to shadowmap-demo.png). `render` draws frames headless through EGL and writes \
        PNGs.\n\nScenes: a built-in name (dummy, learnopengl, slides, playground, point-shadows, \
        large, three-lights) or a path to a .toml scene file (see the README, \"Scene files\").",
    after_help = "Examples:\n  shadowmap\n  shadowmap render --scene dummy --out frame.png --shadow-out shadow.png\n  \
        shadowmap render --light-angle 90 --map-size 2048 --filter single --out overhead.png\n  \
        shadowmap compare --scene dummy --out-dir cmp --filter hw2x2 --bias-mode slope\n  \
        shadowmap render --scene large --cascades 4 --map-size 1024 --show-cascades --out csm.png\n  \
        shadowmap compare --scene three-lights --light 2 --out-dir point"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the interactive window (the default).
    #[command(after_help = super::demo::keys_help())]
    Demo(DemoArgs),
    /// Render frames headless (EGL, no display needed) and write PNG files.
    Render(RenderArgs),
    /// Score a frame's shadows against an exact ray-traced reference.
    Compare(CompareArgs),
    /// Sweep shadow settings: time each one and score it against the reference.
    Bench(BenchArgs),
    /// Render every chapter step with its measured errors: PNGs and index.html.
    Steps(StepsArgs),
    /// Render many frames headless while the light, map size and step change; report memory.
    Soak(SoakArgs),
}

/// Scene choice and the light angle, shared by every command.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// A built-in scene (dummy, learnopengl, slides, playground, point-shadows, large,
    /// three-lights) or a .toml scene file.
    #[arg(long, default_value = "dummy", value_name = "NAME|FILE")]
    pub scene: String,
    /// The DummyGame light angle in degrees, 0 to 180 (90 = overhead); replaces the scene's.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub light_angle: Option<f32>,
    /// Frame size in pixels; default: the scene's size.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Move the camera: world position X,Y,Z.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_negative_numbers = true)]
    pub camera_position: Option<[f32; 3]>,
    /// Turn the camera: PITCH,YAW,ROLL in degrees (positive pitch looks down).
    #[arg(long, value_name = "P,Y,R", value_parser = parse_triple, allow_negative_numbers = true)]
    pub camera_rotation: Option<[f32; 3]>,
}

/// Every shadow setting; unset flags keep the scene's (or the step's) values.
#[derive(Args, Debug, Clone, Default)]
pub struct SettingsArgs {
    /// A chapter step: its preset of settings replaces the scene's (flags still apply on top).
    #[arg(long, value_name = "STEP", value_parser = clap::builder::PossibleValuesParser::new(steps::names()))]
    pub step: Option<String>,
    /// Shadow-map side in texels (1 to the driver's maximum texture size).
    #[arg(long, value_name = "N")]
    pub map_size: Option<u32>,
    /// Depth-map precision.
    #[arg(long, value_enum)]
    pub depth_format: Option<DepthFormat>,
    /// How the shadow map is sampled.
    #[arg(long, value_enum)]
    pub filter: Option<Filter>,
    /// How the depth comparison is offset against acne.
    #[arg(long, value_enum)]
    pub bias_mode: Option<BiasMode>,
    /// Constant bias, or the slope bias' maximum, in [0, 1] depth units.
    #[arg(long, value_name = "B")]
    pub bias: Option<f32>,
    /// The slope bias' floor.
    #[arg(long, value_name = "B")]
    pub bias_min: Option<f32>,
    /// Normal-offset bias: move the lookup this many shadow-map texels along the normal.
    #[arg(long, value_name = "TEXELS")]
    pub normal_offset: Option<f32>,
    /// glPolygonOffset in the depth pass, e.g. 1.1,4.
    #[arg(long, value_name = "FACTOR,UNITS", value_parser = parse_pair, allow_negative_numbers = true)]
    pub polygon_offset: Option<[f32; 2]>,
    /// Faces culled in the depth pass.
    #[arg(long, value_enum)]
    pub cull: Option<Cull>,
    /// Shadow-map wrap mode for lookups outside [0, 1].
    #[arg(long, value_enum)]
    pub wrap: Option<Wrap>,
    /// What fragments beyond the light's far plane get.
    #[arg(long, value_enum)]
    pub beyond_far: Option<BeyondFar>,
    /// How the light's view matrix is built.
    #[arg(long, value_enum)]
    pub light_view: Option<LightView>,
    /// A directional light's shadow projection.
    #[arg(long, value_enum)]
    pub light_projection: Option<LightProjection>,
    /// Field of view of a perspective shadow camera for a directional light (degrees).
    #[arg(long, value_name = "DEG")]
    pub perspective_fov: Option<f32>,
    /// A directional light's box: the scene file's by hand, or fitted to the scene each frame.
    #[arg(long, value_enum)]
    pub fit: Option<Fit>,
    /// With --fit scene: snap the box to whole texels (true) or let it slide (false).
    #[arg(long, value_name = "BOOL")]
    pub snap: Option<bool>,
    /// How a point light's cube faces are drawn.
    #[arg(long, value_enum)]
    pub point_pass: Option<PointPass>,
    /// Cascaded shadow maps for directional lights: 2 to 4 layers of --map-size each, one
    /// per slice of the view (1 = one map, as the chapters).
    #[arg(long, value_name = "N")]
    pub cascades: Option<u32>,
    /// Where the cascades split: 0 = uniform slices, 1 = logarithmic (the practical scheme).
    #[arg(long, value_name = "LAMBDA")]
    pub cascade_lambda: Option<f32>,
    /// The last fraction of each cascade that fades into the next (0 = a hard seam, at most 0.5).
    #[arg(long, value_name = "FRACTION")]
    pub cascade_blend: Option<f32>,
    /// Where cascaded shadows end, in view depth (0 = the camera's far plane).
    #[arg(long, value_name = "DEPTH")]
    pub shadow_distance: Option<f32>,
    /// Draw the first light's shadow map instead of the scene (a cube map as a panorama,
    /// cascades side by side).
    #[arg(long)]
    pub show_depth_map: bool,
    /// Tint each cascade's part of the frame (red, green, blue, yellow from the camera out).
    #[arg(long)]
    pub show_cascades: bool,
}

#[derive(Args, Debug, Clone)]
pub struct DemoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Close the window after this many frames (for scripted runs).
    #[arg(long, value_name = "N")]
    pub exit_after_frames: Option<u64>,
    /// With --exit-after-frames: save the last frame to this PNG.
    #[arg(long, value_name = "FILE", requires = "exit_after_frames")]
    pub screenshot: Option<PathBuf>,
    /// Freeze the scene's animation (the cube stops turning).
    #[arg(long)]
    pub no_animation: bool,
    /// For testing the window: resize it many times, minimise it and restore it while
    /// running (use with --exit-after-frames 40 or more).
    #[arg(long)]
    pub stress_window: bool,
    /// Leave the HUD (light angle, step, settings, frame time) out of the frame.
    #[arg(long)]
    pub no_hud: bool,
}

impl Default for DemoArgs {
    fn default() -> Self {
        DemoArgs {
            scene: SceneArgs {
                scene: "dummy".into(),
                light_angle: None,
                size: None,
                camera_position: None,
                camera_rotation: None,
            },
            settings: SettingsArgs::default(),
            exit_after_frames: None,
            screenshot: None,
            no_animation: false,
            stress_window: false,
            no_hud: false,
        }
    }
}

#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// The rendered image.
    #[arg(long, value_name = "FILE.png", default_value = "shadowmap.png")]
    pub out: PathBuf,
    /// Frames to render (the scene animates between them); the last one is written.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Also write the shadow test's visibility: grey 255 lit .. 0 shadowed, alpha 0 off geometry.
    #[arg(long, value_name = "FILE.png")]
    pub shadow_out: Option<PathBuf>,
    /// Also write the shadow map as a grey image (black = near the light).
    #[arg(long, value_name = "FILE.png")]
    pub depth_out: Option<PathBuf>,
    /// Draw the demo's HUD (light, step, settings, frame time) over the image.
    #[arg(long)]
    pub hud: bool,
}

#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Folder for visibility.png, reference.png, error.png, positions.npy, normals.npy and
    /// metrics.json (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Sub-pixel rays per side for the supersampled reference that judges filtered edges
    /// (N x N per pixel; 1 = off).
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    #[arg(long, value_name = "K", default_value_t = 1)]
    pub band: usize,
    /// Which light to measure, numbered from 0 in the scene file's order (a scene with
    /// several lights is measured one light at a time).
    #[arg(long, value_name = "N", default_value_t = 0)]
    pub light: usize,
}

#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Settings the sweep does not vary (wrap, beyond-far, light view) come from here.
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Folder for bench.csv, bench.md and pareto.png (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// A representative subset (27 configurations plus the tutorials') instead of the full sweep.
    #[arg(long)]
    pub quick: bool,
    /// Timed frames per block; each configuration gets two blocks (one per pass over the
    /// sweep) and the quieter block's median and p95 are reported.
    #[arg(long, value_name = "N", default_value_t = 100, value_parser = clap::value_parser!(u32).range(1..))]
    pub frames: u32,
    /// Untimed frames before them.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub warmup: u32,
    /// Sub-pixel rays per side for the MAE reference (1 = no MAE).
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    #[arg(long, value_name = "K", default_value_t = 1)]
    pub band: usize,
    /// Print the cheapest configuration whose misclassified fraction is at most E (0.01 = 1%).
    #[arg(long, value_name = "E")]
    pub target_error: Option<f64>,
}

#[derive(Args, Debug, Clone)]
pub struct StepsArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Folder for the images and index.html (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Sub-pixel rays per side for the MAE reference.
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=8))]
    pub supersample: u32,
}

#[derive(Args, Debug, Clone)]
pub struct SoakArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Frames to render.
    #[arg(long, value_name = "N", default_value_t = 20_000, value_parser = clap::value_parser!(u64).range(1..))]
    pub frames: u64,
}

/// Parses `WxH`, e.g. `1280x720`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let err = || format!("'{s}': expected WIDTHxHEIGHT with both at least 1, like 1280x720");
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(err)?;
    let w: u32 = w.trim().parse().map_err(|_| err())?;
    let h: u32 = h.trim().parse().map_err(|_| err())?;
    if w == 0 || h == 0 {
        return Err(err());
    }
    Ok((w, h))
}

/// Parses `A,B,C` into three finite numbers.
pub fn parse_triple(s: &str) -> Result<[f32; 3], String> {
    let err = || format!("'{s}': expected three numbers separated by commas, like 0,10,14");
    let v: Vec<f32> = s
        .split(',')
        .map(|p| p.trim().parse::<f32>().map_err(|_| err()))
        .collect::<Result<_, _>>()?;
    match v[..] {
        [a, b, c] if v.iter().all(|x| x.is_finite()) => Ok([a, b, c]),
        _ => Err(err()),
    }
}

/// Parses `A,B` into two numbers, e.g. `1.1,4`.
pub fn parse_pair(s: &str) -> Result<[f32; 2], String> {
    let err = || format!("'{s}': expected two numbers separated by a comma, like 1.1,4");
    let (a, b) = s.split_once(',').ok_or_else(err)?;
    let a: f32 = a.trim().parse().map_err(|_| err())?;
    let b: f32 = b.trim().parse().map_err(|_| err())?;
    Ok([a, b])
}

impl SceneArgs {
    /// Loads the scene and applies the light angle.
    pub fn load(&self) -> shadowmap::Result<Scene> {
        let mut scene = Scene::load(&self.scene)?;
        if let Some(p) = self.camera_position {
            scene.camera.position = p.into();
        }
        if let Some(r) = self.camera_rotation {
            scene.camera.rotation = r.into();
        }
        if let Some(a) = self.light_angle {
            if !a.is_finite() {
                return Err(shadowmap::Error::Invalid(format!(
                    "--light-angle {a}: expected degrees from 0 to 180"
                )));
            }
            if !scene.set_light_angle(a) {
                return Err(shadowmap::Error::Invalid(format!(
                    "--light-angle: the {} scene's light is not directional; the angle turns \
                     only a directional light",
                    scene.name
                )));
            }
        }
        Ok(scene)
    }

    pub fn size(&self, scene: &Scene) -> (u32, u32) {
        self.size.unwrap_or((scene.size[0], scene.size[1]))
    }
}

impl SettingsArgs {
    /// Checks the settings against the driver, naming where a bad value came from: the
    /// flag, or the scene file.
    pub fn check(
        &self,
        gl: &shadowmap::engine::Gl,
        scene: &Scene,
        settings: &ShadowSettings,
    ) -> shadowmap::Result<()> {
        let max = shadowmap::engine::gl_limits(gl).max_texture_size;
        settings.validate(max).map_err(|e| {
            // Messages read "shadow.NAME = VALUE: ..."; NAME says which flag it would be.
            let text = e.to_string();
            let name = text
                .strip_prefix("shadow.")
                .and_then(|t| t.split(' ').next())
                .unwrap_or_default();
            match self.flag_given(name) {
                true => shadowmap::Error::Invalid(format!("--{}: {text}", name.replace('_', "-"))),
                false => shadowmap::Error::file(&scene.source, text),
            }
        })
    }

    /// Whether the setting `name` (as the scene file spells it) was given as a flag.
    fn flag_given(&self, name: &str) -> bool {
        match name {
            "map_size" => self.map_size.is_some(),
            "bias" => self.bias.is_some(),
            "bias_min" => self.bias_min.is_some(),
            "normal_offset" => self.normal_offset.is_some(),
            "perspective_fov" => self.perspective_fov.is_some(),
            "polygon_offset" => self.polygon_offset.is_some(),
            "cascades" => self.cascades.is_some(),
            "cascade_lambda" => self.cascade_lambda.is_some(),
            "cascade_blend" => self.cascade_blend.is_some(),
            "shadow_distance" => self.shadow_distance.is_some(),
            _ => false,
        }
    }

    /// The scene's settings with the given flags applied.
    /// The scene's settings, then the step's preset, then the flags.
    pub fn apply(&self, scene: &Scene) -> shadowmap::Result<ShadowSettings> {
        let mut s = match &self.step {
            Some(step) => steps::settings_for(scene, step)?,
            None => scene.shadow,
        };
        macro_rules! set {
            ($($f:ident),*) => { $( if let Some(v) = self.$f { s.$f = v; } )* };
        }
        set!(
            map_size,
            depth_format,
            filter,
            bias_mode,
            bias,
            bias_min,
            normal_offset,
            polygon_offset,
            cull,
            wrap,
            beyond_far,
            light_view,
            light_projection,
            perspective_fov,
            fit,
            snap,
            point_pass,
            cascades,
            cascade_lambda,
            cascade_blend,
            shadow_distance
        );
        s.show_depth_map |= self.show_depth_map;
        s.show_cascades |= self.show_cascades;
        Ok(s)
    }
}
