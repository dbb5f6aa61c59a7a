//! The command line: `shadowmap` (the demo window), `shadowmap render` (headless frames).

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use shadowmap::engine::WindowApi;
use shadowmap::settings::ShadowPatch;
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::steps;
use shadowmap::{Scene, ShadowSettings};

use super::quality::Quality;

#[derive(Parser, Debug)]
#[command(
    name = "shadowmap",
    version,
    about = "The classic shadow-mapping chapters, ported to Rust and OpenGL 3.3 core.",
    long_about = "The classic shadow-mapping chapters, ported to Rust and OpenGL 3.3 core.\n\n\
        With no command, opens the DummyGame demo in a window (or, with no display, renders it \
        headless to shadowmap-demo.png). `render` draws frames headless through EGL and writes \
        PNGs.\n\nScenes: a built-in name (dummy, learnopengl, slides, playground, point-shadows, \
        large, three-lights, overlap, penumbra, smoke, ramp) or a path to a .toml scene file (see docs/scene-format.md).",
    after_help = "Examples:\n  shadowmap\n  shadowmap render --scene dummy --out frame.png --shadow-out shadow.png\n  \
        shadowmap render --light-angle 90 --map-size 2048 --filter single --out overhead.png\n  \
        shadowmap compare --scene dummy --out-dir cmp --filter hw2x2 --bias-mode slope\n  \
        shadowmap render --scene large --cascades 4 --map-size 1024 --show-cascades --out csm.png\n  \
        shadowmap compare --scene three-lights --light 2 --out-dir point\n  \
        shadowmap compare --scene large --cascades 4 --snap on --motion strafe --frames 8 --out-dir moving"
)]
#[command(args_conflicts_with_subcommands = true)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Option<Command>,
    /// With no command: the demo's options (`shadowmap --scene learnopengl` is
    /// `shadowmap demo --scene learnopengl`).
    #[command(flatten)]
    pub demo: DemoArgs,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Open the interactive window (the default).
    #[command(after_help = super::keys::keys_help())]
    Demo(DemoArgs),
    /// Render frames headless (EGL, no display needed) and write PNG files.
    Render(RenderArgs),
    /// Score a frame's shadows against an exact ray-traced reference.
    Compare(CompareArgs),
    /// Sweep shadow settings: time each one and score it against the reference.
    Bench(BenchArgs),
    /// Render every chapter step with its measured errors: PNGs and index.html.
    #[command(after_help = steps::lists_help())]
    Steps(StepsArgs),
    /// Render many frames headless while the light, map size and step change; report memory.
    ///
    /// Each step is drawn in its own view, as `render --step` draws it; `--step` holds one
    /// step while the light and the map size change.
    Soak(SoakArgs),
    /// Print the scene program's GLSL exactly as it is compiled for these settings.
    Shaders(ShadersArgs),
}

/// Scene choice and the light angle, shared by every command.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// A built-in scene (dummy, learnopengl, slides, playground, point-shadows, large,
    /// three-lights, overlap, penumbra, smoke, ramp) or a .toml scene file.
    #[arg(long, default_value = "dummy", value_name = "NAME|FILE")]
    pub scene: String,
    /// The first light's angle in degrees, 0 to 180 (90 = overhead); replaces the scene's.
    ///
    /// The light turns about the horizontal axis across its azimuth: 0 is the horizon
    /// towards the azimuth, 90 overhead, 180 the opposite horizon; the azimuth stays. A light
    /// in the YZ plane (the DummyGame's) has the azimuth +Z: the direction is the book's
    /// (0, sin a, cos a). Any other directional light's azimuth is its own horizontal
    /// direction (LearnOpenGL's light at (-2, 4, -1): about 60.8 degrees towards (-2, 0, -1)),
    /// and a light given by `position` keeps its distance from the origin. Spot and point
    /// lights have no angle: the flag is refused for them.
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    pub light_angle: Option<f32>,
    /// Every light's size, replacing the scene file's `size`: a directional light's
    /// angular diameter in degrees (the sun: 0.53; under 90), a spot or point light's radius
    /// in world units (under 1000); 0 = a point (hard shadows). PCSS widens its penumbra
    /// with it, and `compare` and `bench` measure against a light of that size (rays to its
    /// disc).
    #[arg(long, value_name = "SIZE", value_parser = shadowmap::settings::parse_finite, allow_negative_numbers = true)]
    pub light_size: Option<f32>,
    /// Frame size in pixels; default: the scene's size.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,
    /// Show the scene from its named view NAME (its file's [views]; `learnopengl`: `above`,
    /// where it opens, or `code`, the tutorial code's camera at (0, 0, 3)); the camera
    /// flags move it from there.
    #[arg(long, value_name = "NAME")]
    pub view: Option<String>,
    /// Move the camera: world position X,Y,Z.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    pub camera_position: Option<[f32; 3]>,
    /// Turn the camera: PITCH,YAW,ROLL in degrees (positive pitch looks down).
    #[arg(long, value_name = "P,Y,R", value_parser = parse_triple, allow_hyphen_values = true)]
    pub camera_rotation: Option<[f32; 3]>,
    /// Aim the camera at the world point X,Y,Z (from its position, after
    /// --camera-position): the pitch and yaw that look at it, roll 0. Not with
    /// --camera-rotation.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_triple, allow_hyphen_values = true)]
    pub camera_target: Option<[f32; 3]>,
}

/// Every shadow setting; unset flags keep the scene's (or the step's) values. The flags
/// come from the settings' one description (`shadowmap::settings::ShadowPatch`).
#[derive(Args, Debug, Clone, Default)]
pub struct SettingsArgs {
    /// A chapter step: its view and its preset of settings (flags still apply on top).
    #[arg(long, value_name = "STEP", value_parser = clap::builder::PossibleValuesParser::new(steps::names()),
          long_help = format!("A chapter step: its view and its preset of settings, which \
              replaces the scene's (flags still apply on top). Every command (render, demo, \
              compare, bench, soak) draws it as `steps` does: from the scene's steps camera, \
              and from the step's own view where it has one; a camera flag or --view keeps \
              its camera, --light-size its size.\n\n{}", steps::lists_help()))]
    pub step: Option<String>,
    /// A preset chosen from the bench's measurements (docs/results.md, "Quality presets"): map
    /// size, filter, bias, culling and the light's box over the scene's (or the step's) settings; the flags
    /// given here win over it.
    #[arg(long, value_name = "LEVEL", value_enum)]
    pub quality: Option<Quality>,
    #[command(flatten)]
    pub patch: ShadowPatch,
}

#[derive(Args, Debug, Clone)]
pub struct DemoArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub motion: super::motion_args::MotionArgs,
    /// Before drawing: run the bench's quick sweep on this scene's view (timed and scored
    /// against the exact reference, about half a minute) and use the cheapest
    /// configuration whose misclassified fraction is at most E (0.01 = 1%); prints which
    /// and its measured error and time. Settings given as flags keep the search to the
    /// configurations that have them (`--technique maps`: no volumes).
    #[arg(long, value_name = "E", value_parser = parse_fraction, allow_negative_numbers = true, conflicts_with = "quality")]
    pub target_error: Option<f64>,
    /// Close the window after this many frames (for scripted runs); at least 1.
    #[arg(long, value_name = "N", value_parser = parse_frames, allow_negative_numbers = true)]
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
    /// Refuse to run without a window: with no display, fail instead of rendering headless
    /// to a PNG (for scripts and tests that mean to test the window).
    #[arg(long)]
    pub require_window: bool,
    /// Leave the HUD (light angle, step, settings, frame time) out of the frame.
    #[arg(long)]
    pub no_hud: bool,
    /// Start with the shadow-map inset shown (the I key toggles it): the map in the
    /// bottom-right corner, a quarter of the frame's height on a side. Also drawn by the
    /// no-display fallback.
    #[arg(long)]
    pub inset: bool,
    /// Show the shadow test's visibility instead of the colour frame, as `render
    /// --shadow-out` writes it: grey 255 lit .. 0 shadowed; blue where no geometry was drawn
    /// (a depth-map view shows its map). The page's `&view=visibility`.
    #[arg(long)]
    pub show_visibility: bool,
    /// Where the window's OpenGL context comes from: auto (the platform's own: GLX on X11,
    /// WGL on Windows, CGL on macOS, EGL on Wayland; else EGL), glx (X11's; the frame reaches
    /// the X server through shared memory), egl (Mesa's on Linux; on X11 with a software
    /// driver the frame goes down the socket, 1.2 to 1.35 times slower), wgl (Windows) or cgl
    /// (macOS). An API the platform lacks is refused with the list of those it has.
    #[arg(long, value_enum, default_value_t = WindowApi::Auto, value_name = "API")]
    pub gl_api: WindowApi,
}

#[derive(Args, Debug, Clone)]
pub struct RenderArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub motion: super::motion_args::MotionArgs,
    /// Before drawing: run the bench's quick sweep on this scene's view (timed and scored
    /// against the exact reference, about half a minute) and use the cheapest
    /// configuration whose misclassified fraction is at most E (0.01 = 1%); prints which
    /// and its measured error and time. Settings given as flags keep the search to the
    /// configurations that have them (`--technique maps`: no volumes).
    #[arg(long, value_name = "E", value_parser = parse_fraction, allow_negative_numbers = true, conflicts_with = "quality")]
    pub target_error: Option<f64>,
    /// The rendered image.
    #[arg(long, value_name = "FILE.png", default_value = "shadowmap.png")]
    pub out: PathBuf,
    /// Frames to render (the scene animates between them); the last one is written.
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = parse_frames_u32, allow_negative_numbers = true)]
    pub frames: u32,
    /// Also write the shadow test's visibility: grey 255 lit .. 0 shadowed, alpha 0 off geometry.
    #[arg(long, value_name = "FILE.png")]
    pub shadow_out: Option<PathBuf>,
    /// Also write the shadow map as a grey image (black = near the light, white = its far
    /// plane; a perspective map is linearised to eye distance, as the depth view shows it).
    #[arg(long, value_name = "FILE.png")]
    pub depth_out: Option<PathBuf>,
    /// Draw the demo's HUD (light, step, settings, frame time) over the image.
    #[arg(long)]
    pub hud: bool,
    /// Draw the shadow-map inset over the image, as the demo's I key does: the first
    /// casting light's map in the bottom-right corner, a quarter of the frame's height on a
    /// side (under the HUD when both are given). The other outputs are the same with it as
    /// without.
    #[arg(long)]
    pub inset: bool,
}

/// `shaders`: the scene shader's vertex and fragment source as the renderer hands them to
/// the driver: every `#include` resolved (with the `#line` directives that keep each
/// file's own line numbers in errors), the `#define`s after `#version`, and the generated
/// `addLights` that calls each light's test with its own settings as arguments. It is the
/// program of a plain frame (no --shadow-out outputs, no cached shadow mask).
#[derive(Args, Debug, Clone)]
#[command(after_help = "Examples:\n  shadowmap shaders --scene dummy\n  \
    shadowmap shaders --scene playground --filter pcss --light 0")]
pub struct ShadersArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Print only light I's part instead (numbered from 0): its sampler, the defines and
    /// library files its test needs (each file whole), and its lines in `addLights`: the
    /// call of its test with its settings, and its light times that test.
    #[arg(long, value_name = "I")]
    pub light: Option<usize>,
    /// The GLSL dialect to print: desktop (`#version 330 core`, what every desktop driver
    /// gets) or es (`#version 300 es` with its precision statements, what the browser's
    /// WebGL2 gets). The same files and the same program either way.
    #[arg(long, value_enum, default_value_t = ShaderDialect::Desktop, value_name = "DIALECT")]
    pub dialect: ShaderDialect,
}

/// `shaders --dialect`.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShaderDialect {
    Desktop,
    Es,
}

impl From<ShaderDialect> for shadowmap::engine::Dialect {
    fn from(d: ShaderDialect) -> shadowmap::engine::Dialect {
        match d {
            ShaderDialect::Desktop => shadowmap::engine::Dialect::Desktop,
            ShaderDialect::Es => shadowmap::engine::Dialect::Es,
        }
    }
}

#[derive(Args, Debug, Clone)]
pub struct CompareArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub motion: super::motion_args::MotionArgs,
    /// Folder for visibility.png, reference.png, error.png, (for a light with a size)
    /// reference-area.png and error-area.png, and metrics.json (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Also write the reference's G-buffer as NumPy arrays: positions.npy (world
    /// positions) and normals.npy, float32 HEIGHT x WIDTH x 3 (22 MB at 1280x720).
    #[arg(long)]
    pub arrays: bool,
    /// Sub-pixel rays per side for the supersampled reference that judges filtered edges
    /// (N x N per pixel; 1 = off).
    #[arg(long, value_name = "N", default_value_t = 4, value_parser = clap::value_parser!(u32).range(1..=8), allow_negative_numbers = true)]
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        allow_negative_numbers = true
    )]
    pub band: usize,
    /// Which light to measure, numbered from 0 in the scene file's order (a scene with
    /// several lights is measured one light at a time).
    #[arg(
        long,
        value_name = "N",
        default_value_t = 0,
        allow_negative_numbers = true
    )]
    pub light: usize,
    /// Rays per pixel to a light with a size (--light-size, or the scene's `size`): the
    /// soft-shadow truth, stratified over the light's disc.
    #[arg(long, value_name = "N", default_value_t = shadowmap::compare::AREA_RAYS, value_parser = clap::value_parser!(u32).range(1..=4096), allow_negative_numbers = true)]
    pub rays: u32,
    /// What the frame is scored against: `cpu`, the exact ray cast; or `volumes`, the
    /// stencil shadow volumes' answer (the GPU's exact hard shadows), whose own agreement
    /// with the ray cast is printed beside.
    #[arg(long, value_name = "cpu|volumes", default_value = "cpu")]
    pub truth: Truth,
    /// With --motion: frames of the path, each traced and scored (writes metrics.json,
    /// motion-error.png and motion-flicker.png instead of one frame's images).
    #[arg(long, value_name = "N", default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..), allow_negative_numbers = true)]
    pub frames: u32,
}

/// The reference `compare` scores against.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum Truth {
    /// The exact CPU ray cast.
    Cpu,
    /// Stencil shadow volumes, checked against the ray cast.
    Volumes,
}

#[derive(Args, Debug, Clone)]
pub struct BenchArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Settings the sweep does not vary (wrap, beyond-far, light view) come from here.
    #[command(flatten)]
    pub settings: SettingsArgs,
    #[command(flatten)]
    pub motion: super::motion_args::MotionArgs,
    /// Folder for bench.csv, bench.md and pareto.png (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    #[arg(long, help = quick_help())]
    pub quick: bool,
    /// Instead of the settings sweep: how each pass' time grows with the work. A generated
    /// scene (64 spheres of rising detail over a floor, one axis moved at a time from 1e4
    /// triangles, 640x360, a 1024^2 map, one light, one cascade): caster triangles 1e3 to
    /// 1e6, frames 320x180 to 3840x2160, maps 256^2 to 8192^2, 1 to 4 lights, 1 to 4
    /// cascades. Writes scale.csv, scale-fit.csv (the fitted exponents: least squares on
    /// log-log) and scale.png. Each point is timed twice (the second pass over the points in
    /// reverse order; the quieter block counts), each time with frames enough for about
    /// 3 s (3 to 100: a 1e6-triangle frame takes about half a second on llvmpipe), so the
    /// full sweep takes about 3 to 5 minutes there; with --quick, two points an axis at
    /// 320x180 and 2 to 5 frames each (seconds). The scene, settings and --frames flags
    /// are not used.
    #[arg(long)]
    pub scale: bool,
    /// Timed frames per block [default: 100, 40 with --quick]; each configuration gets two
    /// blocks (one per pass over the sweep) and the quieter block's median and p95 are
    /// reported.
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u32).range(1..), allow_negative_numbers = true)]
    pub frames: Option<u32>,
    /// Untimed frames before them [default: 10, 4 with --quick].
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub warmup: Option<u32>,
    /// Sub-pixel rays per side for the MAE reference (1 = no MAE).
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=8), allow_negative_numbers = true)]
    pub supersample: u32,
    /// Pixels around the reference's shadow edges left out of the "outside band" figures.
    #[arg(
        long,
        value_name = "K",
        default_value_t = 1,
        allow_negative_numbers = true
    )]
    pub band: usize,
    /// Print the cheapest configuration whose misclassified fraction is at most E (0.01 = 1%).
    #[arg(long, value_name = "E", value_parser = parse_fraction, allow_negative_numbers = true)]
    pub target_error: Option<f64>,
    /// Rays per pixel to a light with a size (the soft-shadow truth).
    #[arg(long, value_name = "N", default_value_t = shadowmap::compare::AREA_RAYS, value_parser = clap::value_parser!(u32).range(1..=4096), allow_negative_numbers = true)]
    pub rays: u32,
    /// With --motion: frames of the path each configuration is scored over for the
    /// flicker columns, its energy and its false-flicker share (each frame's reference
    /// traced once).
    #[arg(long, value_name = "N", default_value_t = 8, value_parser = clap::value_parser!(u32).range(2..), allow_negative_numbers = true)]
    pub motion_frames: u32,
}

#[derive(Args, Debug, Clone)]
pub struct StepsArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    /// Folder for the images and index.html (created if missing).
    #[arg(long, value_name = "DIR")]
    pub out_dir: PathBuf,
    /// Sub-pixel rays per side for the MAE reference.
    #[arg(long, value_name = "N", default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=8), allow_negative_numbers = true)]
    pub supersample: u32,
}

#[derive(Args, Debug, Clone)]
pub struct SoakArgs {
    #[command(flatten)]
    pub scene: SceneArgs,
    #[command(flatten)]
    pub settings: SettingsArgs,
    /// Frames to render.
    #[arg(long, value_name = "N", default_value_t = 20_000, value_parser = parse_frames, allow_negative_numbers = true)]
    pub frames: u64,
}

/// The help of `bench --quick`, its counts taken from the sweep itself.
pub fn quick_help() -> String {
    // llvmpipe's largest texture; a driver's own limit changes the full count by one or so.
    let counts = shadowmap::bench::configuration_counts(16384);
    let list = |pick: fn(&(&str, usize, usize)) -> usize| {
        counts
            .iter()
            .map(|c| format!("{} for a {} light", pick(c), c.0))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "A representative subset instead of the full sweep: {} (the full sweep: {}; both \
         with the tutorials' two, the full one with a driver's 16384^2 map)",
        list(|c| c.1),
        list(|c| c.2)
    )
}

/// clap's refusal of a value, its "a similar value exists" tip chosen by the edit
/// distance every other message uses (clap's own measure offers `pcss` for `pfc`, not
/// `pcf`). Any other error passes as clap made it.
pub fn nearer_suggestion(mut e: clap::Error) -> clap::Error {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if e.kind() != ErrorKind::InvalidValue {
        return e;
    }
    let guess = match (
        e.get(ContextKind::InvalidValue),
        e.get(ContextKind::ValidValue),
    ) {
        (Some(ContextValue::String(given)), Some(ContextValue::Strings(valid))) => {
            shadowmap::settings::suggest::did_you_mean(given, valid.iter().map(String::as_str))
                .map(String::from)
        }
        _ => None,
    };
    if let Some(guess) = guess {
        e.insert(ContextKind::SuggestedValue, ContextValue::String(guess));
    }
    e
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

/// Parses a count of frames: a whole number, at least 1 (0 frames would do nothing and
/// say nothing).
pub fn parse_frames(s: &str) -> Result<u64, String> {
    match s.trim().parse::<u64>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "'{s}': expected a whole number of frames from 1 to {}",
            u64::MAX
        )),
    }
}

/// [`parse_frames`] for a count that must fit 32 bits.
pub fn parse_frames_u32(s: &str) -> Result<u32, String> {
    parse_frames(s)
        .ok()
        .and_then(|n| u32::try_from(n).ok())
        .ok_or_else(|| {
            format!(
                "'{s}': expected a whole number of frames from 1 to {}",
                u32::MAX
            )
        })
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

/// Parses a fraction from 0 to 1, e.g. `0.01` for 1%.
pub fn parse_fraction(s: &str) -> Result<f64, String> {
    match s.trim().parse::<f64>() {
        Ok(v) if (0.0..=1.0).contains(&v) => Ok(v),
        _ => Err(format!(
            "'{s}': expected a fraction from 0 to 1 (0.01 = 1% of receiver pixels)"
        )),
    }
}

impl SceneArgs {
    /// Whether a camera flag picks the view (a step's view then keeps its camera).
    pub fn camera_given(&self) -> bool {
        self.view.is_some()
            || self.camera_position.is_some()
            || self.camera_rotation.is_some()
            || self.camera_target.is_some()
    }

    /// The scene loaded with these flags, then `settings`' step and flags
    /// ([`SettingsArgs::resolve`]).
    pub fn load_with(&self, settings: &SettingsArgs) -> shadowmap::Result<(Scene, ShadowSettings)> {
        let mut scene = self.load()?;
        let s = settings.resolve(self, &mut scene)?;
        Ok((scene, s))
    }

    /// Loads the scene and applies the light angle.
    pub fn load(&self) -> shadowmap::Result<Scene> {
        if self.camera_rotation.is_some() && self.camera_target.is_some() {
            return Err(shadowmap::Error::Invalid(
                "--camera-rotation and --camera-target are both given: the camera takes one \
                 (angles, or a point to look at)"
                    .into(),
            ));
        }
        let mut scene = Scene::load(&self.scene)?;
        scene.open_view(self.view.as_deref())?;
        if let Some(p) = self.camera_position {
            scene.camera.position = p.into();
        }
        if let Some(r) = self.camera_rotation {
            scene.camera.rotation = r.into();
        }
        if let Some(t) = self.camera_target {
            let at = shadowmap::scene::Camera::look_at(scene.camera.position, t.into())
                .ok_or_else(|| {
                    shadowmap::Error::Invalid(format!(
                        "--camera-target {},{},{}: the camera's own position ({}); it must \
                         look somewhere else",
                        t[0], t[1], t[2], scene.camera.position
                    ))
                })?;
            scene.camera.rotation = at.rotation;
        }
        if let Some(a) = self.light_angle {
            // Outside 0..180 the light would be clamped without a word: refuse instead.
            if let Some(problem) = shadowmap::scene::DirectionalLight::angle_problem(a) {
                return Err(shadowmap::Error::Invalid(format!(
                    "--light-angle {problem}"
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
        if let Some(size) = self.light_size {
            for light in &mut scene.lights {
                if let Some(problem) = light.size_problem(size) {
                    return Err(shadowmap::Error::Invalid(format!(
                        "--light-size {problem}; the {} scene has a {} light",
                        scene.name,
                        light.kind_name()
                    )));
                }
                light.set_size(size);
            }
        }
        Ok(scene)
    }

    pub fn size(&self, scene: &Scene) -> (u32, u32) {
        self.size.unwrap_or((scene.size[0], scene.size[1]))
    }

    /// Checks the frame size against the driver, naming where it came from: `--size`, or
    /// the scene file's `size`.
    pub fn check_size(&self, gl: &shadowmap::engine::Gl, scene: &Scene) -> shadowmap::Result<()> {
        let limits = shadowmap::engine::gl_limits(gl);
        let max = limits
            .max_renderbuffer_size
            .min(limits.max_viewport[0])
            .min(limits.max_viewport[1]);
        let (w, h) = self.size(scene);
        if (1..=max).contains(&w) && (1..=max).contains(&h) {
            return Ok(());
        }
        let expected = format!("expected each side from 1 to {max} (the driver's maximum)");
        Err(match self.size {
            Some(_) => shadowmap::Error::Invalid(format!("--size {w}x{h}: {expected}")),
            None => {
                shadowmap::Error::in_field(&scene.source, "size", format!("[{w}, {h}]: {expected}"))
            }
        })
    }
}

impl SettingsArgs {
    /// Checks the settings against the driver, naming where a bad value came from: the
    /// flag, or the scene file. Gives each light's shadow as it will be drawn.
    pub fn check(
        &self,
        gl: &shadowmap::engine::Gl,
        scene: &Scene,
        settings: &ShadowSettings,
    ) -> shadowmap::Result<ShadowPlan> {
        let max = shadowmap::engine::gl_limits(gl).max_texture_size;
        settings
            .validate(max)
            .and_then(|()| ShadowPlan::resolve(&scene.lights, settings, Some(max)))
            .and_then(|plan| super::map_memory::check(gl, &plan, max).map(|()| plan))
            .map_err(|e| self.name_source(scene, e))
    }

    /// Checks every setting that needs no driver (biases, ranges, cascades): run before any
    /// GL work or file, so a bad flag costs nothing.
    pub fn check_values(
        &self,
        scene: &Scene,
        settings: &ShadowSettings,
    ) -> shadowmap::Result<ShadowPlan> {
        settings
            .validate_values()
            .and_then(|()| ShadowPlan::resolve(&scene.lights, settings, None))
            .map_err(|e| self.name_source(scene, e))
    }

    /// The flags given here whose legal values do nothing in this scene, as one warning
    /// each: "--cascades 4: ...". Unset flags are left alone (the defaults and the scene
    /// file's own values are not the user's doing here).
    pub fn warnings(&self, scene: &Scene, settings: &ShadowSettings) -> Vec<String> {
        let given = self.patch.given();
        ShadowPlan::decide(&scene.lights, settings)
            .idle_in(scene)
            .into_iter()
            .filter(|idle| given.contains(&idle.setting))
            .map(|idle| {
                let value = setting_value(settings, idle.setting);
                format!("--{} {value}: {}", idle.setting.replace('_', "-"), idle.why)
            })
            .collect()
    }

    /// Says where a bad setting came from: its flags, or the scene file.
    fn name_source(&self, scene: &Scene, e: shadowmap::Error) -> shadowmap::Error {
        // Messages read "shadow.NAME = VALUE: ..."; each NAME says which flag it would be
        // (a pair that must be ordered names both settings).
        let text = e.to_string();
        let mut flags: Vec<String> = Vec::new();
        for name in mentioned_settings(&text) {
            let flag = format!("--{}", name.replace('_', "-"));
            if self.flag_given(name) && !flags.contains(&flag) {
                flags.push(flag);
            }
        }
        match flags.split_last() {
            None => shadowmap::Error::file(&scene.source, text),
            Some((last, [])) => shadowmap::Error::Invalid(format!("{last}: {text}")),
            Some((last, rest)) => {
                shadowmap::Error::Invalid(format!("{} and {last}: {text}", rest.join(", ")))
            }
        }
    }

    /// The flags over the `--quality` preset, if one is given.
    pub fn effective_patch(&self) -> shadowmap::Result<ShadowPatch> {
        match self.quality {
            Some(q) => Ok(self.patch.or(&q.patch()?)),
            None => Ok(self.patch),
        }
    }

    /// The `--quality` preset's line for a summary: its name and what it set, without the
    /// fields a flag replaced.
    pub fn quality_summary(&self) -> shadowmap::Result<Option<String>> {
        let Some(q) = self.quality else {
            return Ok(None);
        };
        let preset = q.patch()?;
        let mut set = ShadowSettings::default();
        preset.apply_to(&mut set);
        let given = self.patch.given();
        let used: Vec<String> = preset
            .given()
            .into_iter()
            .filter(|name| !given.contains(name))
            .map(|name| format!("{} {}", name, setting_value(&set, name)))
            .collect();
        let replaced: Vec<String> = preset
            .given()
            .into_iter()
            .filter(|name| given.contains(name))
            .map(|name| format!("--{}", name.replace('_', "-")))
            .collect();
        let mut line = format!("quality {}: {}", q.name(), used.join(", "));
        if !replaced.is_empty() {
            line.push_str(&format!(" (flags win: {})", replaced.join(", ")));
        }
        Ok(Some(line))
    }

    /// Whether the setting `name` (as the scene file spells it) was given as a flag.
    fn flag_given(&self, name: &str) -> bool {
        self.patch.given().contains(&name)
    }

    /// What a command draws with `--step`: the step's view of `scene` and its preset
    /// ([`steps::stage`]), then the flags ([`SettingsArgs::apply`]). Every command that
    /// takes `--step` (and the demo's step keys) comes through here, so a step means one
    /// picture everywhere; a camera flag keeps its camera, `--light-size` its size.
    pub fn resolve(
        &self,
        scene_args: &SceneArgs,
        scene: &mut Scene,
    ) -> shadowmap::Result<ShadowSettings> {
        if let Some(step) = &self.step {
            let light_size = scene_args.light_size.is_some();
            steps::stage(scene, step, scene_args.camera_given(), light_size)?;
        }
        self.apply(scene)
    }

    /// The scene's settings, then the step's preset, then the flags. The flags also win
    /// over the lights' own `shadow` tables: the fields they give are taken out of those.
    pub fn apply(&self, scene: &mut Scene) -> shadowmap::Result<ShadowSettings> {
        let patch = self.effective_patch()?;
        for light in &mut scene.lights {
            let own = light.shadow_patch().without(&patch);
            *light.shadow_patch_mut() = own;
        }
        let mut s = match &self.step {
            Some(step) => steps::settings_for(scene, step)?,
            None => scene.shadow,
        };
        patch.apply_to(&mut s);
        // Once per run, every command (values that are refused get their error instead).
        if s.validate_values().is_ok() {
            for w in self.warnings(scene, &s) {
                eprintln!("warning: {w}");
            }
        }
        Ok(s)
    }
}

/// The settings a message names as "shadow.NAME", in its order.
fn mentioned_settings(text: &str) -> impl Iterator<Item = &str> {
    text.match_indices("shadow.").map(move |(i, found)| {
        let rest = &text[i + found.len()..];
        let end = rest
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
            .unwrap_or(rest.len());
        &rest[..end]
    })
}

/// A setting's value as its flag takes it (`4`, `six-passes`, `true`).
fn setting_value(settings: &ShadowSettings, name: &str) -> String {
    match serde_json::to_value(settings) {
        Ok(serde_json::Value::Object(map)) => match map.get(name) {
            Some(serde_json::Value::String(s)) => s.clone(),
            // As f32 prints it: 60, not 60.0.
            Some(serde_json::Value::Number(n)) => match n.as_f64() {
                Some(v) => format!("{}", v as f32),
                None => n.to_string(),
            },
            Some(v) => v.to_string(),
            None => String::new(),
        },
        _ => String::new(),
    }
}
