//! The demo: the DummyGame in a window (winit 0.30 + glutin), with the book's controls.
//! Without a display it renders the same scene headless to `shadowmap-demo.png`.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use glam::Vec3;
use shadowmap::engine::window_context::WindowContext;
use shadowmap::engine::{HeadlessContext, Outputs};
use shadowmap::frame::render_frames;
use shadowmap::image_data::ImageData;
use shadowmap::output::check_output_image;
use shadowmap::settings::{ShadowTechnique, MAX_CASCADES};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::{steps, Error, Renderer, Result, Scene, ShadowSettings, Target};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::cli::DemoArgs;
use super::hud::{inset_rect, render_frames_with_overlays, Hud, HudInfo, Overlays};
use super::quality::choose_for_target;

/// The book's fixed update rate.
const UPDATES_PER_SECOND: f64 = 30.0;
/// Camera step per update (DummyGame's CAMERA_POS_STEP).
const CAMERA_POS_STEP: f32 = 0.05;
/// Degrees of camera rotation per pixel of mouse drag (DummyGame's MOUSE_SENSITIVITY).
const MOUSE_SENSITIVITY: f32 = 0.2;
/// Light-angle acceleration per update while a key is held (DummyGame: +-0.05).
const ANGLE_STEP: f32 = 0.05;

/// Where the no-display fallback writes its picture.
const FALLBACK_IMAGE: &str = "shadowmap-demo.png";

pub fn run(args: &DemoArgs) -> Result<()> {
    let mut scene = args.scene.load()?;
    let settings = args.settings.apply(&mut scene)?;
    // What needs no window or driver is checked before anything opens.
    args.settings.check_values(&scene, &settings)?;
    if let Some(path) = &args.screenshot {
        check_output_image("--screenshot", path)?;
    }
    if let Some(target) = args.target_error {
        // Chosen headless before the window opens; then the demo runs as if the chosen
        // configuration had been given as flags (a step key and back keeps it).
        let size = args.scene.size(&scene);
        let chosen = choose_for_target(&scene, &settings, size, target, &args.settings.patch)?;
        let mut args = args.clone();
        args.settings.patch = chosen.or(&args.settings.patch);
        args.target_error = None;
        return run(&args);
    }
    if let Some(line) = args.settings.quality_summary()? {
        println!("{line}");
    }
    if args.no_animation {
        scene.items.iter_mut().for_each(|i| i.spin = Vec3::ZERO);
        for light in &mut scene.lights {
            if let shadowmap::scene::Light::Point(p) = light {
                p.oscillate = Vec3::ZERO;
            }
        }
    }
    let event_loop = match EventLoop::new() {
        Ok(l) => l,
        // winit's own error names its source file and line: the fallback says what it means.
        Err(_) => return headless_fallback(args, scene, &settings),
    };
    let size = args.scene.size(&scene);
    let step = args
        .settings
        .step
        .as_deref()
        .and_then(|name| steps::get(&scene, name))
        .map(|s| s.name);
    let mut demo = Demo {
        args: args.clone(),
        scene,
        settings,
        size,
        running: None,
        error: None,
        keys: HashSet::new(),
        dragging: false,
        cursor: None,
        mouse_delta: (0.0, 0.0),
        angle_inc: 0.0,
        frames: 0,
        last_frame: Instant::now(),
        update_debt: 0.0,
        frame_ms: 0.0,
        shown_ms: None,
        show_keys: false,
        show_stats: false,
        last_title: Instant::now() - Duration::from_secs(1),
        screenshot_requested: false,
        screenshots: 0,
        step,
        minimised: false,
        skipped: 0,
        depth_light: 0,
        azimuth: None,
        angle_keys_idle: false,
        show_inset: args.inset,
        camera_before_steps: None,
        sizes_before_steps: None,
        before_stage: None,
        frame_times: Vec::new(),
    };
    // Taken once: past the overhead a light's own horizontal part points the other way.
    demo.azimuth = demo.scene.light_azimuth();
    event_loop
        .run_app(&mut demo)
        .map_err(|e| Error::Context(format!("window event loop: {e}")))?;
    if args.stress_window {
        println!(
            "stress: {} frames drawn, {} redraws skipped while minimised",
            demo.frames, demo.skipped
        );
    }
    match demo.error {
        Some(e) => Err(e),
        None => Ok(()),
    }
}

/// Why there is no window, from the environment winit read (its own error names a source
/// file of winit's, not the cause).
fn no_display_reason() -> String {
    let var = |name| std::env::var(name).ok().filter(|v| !v.is_empty());
    match (var("DISPLAY"), var("WAYLAND_DISPLAY")) {
        (None, None) => "DISPLAY and WAYLAND_DISPLAY are not set".to_string(),
        (Some(d), _) => format!("the X server at DISPLAY={d} refused the connection"),
        (None, Some(w)) => format!("the Wayland compositor at WAYLAND_DISPLAY={w} refused"),
    }
}

/// The one line the no-display fallback prints: why, what was written, how to get a window.
pub fn fallback_message(
    reason: &str,
    scene: &str,
    frames: u32,
    path: &Path,
    replaced: bool,
) -> String {
    format!(
        "No display for a window ({reason}): rendered {frames} frame{} of the {scene} scene \
         headless to {}{} instead. For a window, run under X11: `apt-get install xvfb`, \
         `Xvfb :99 &`, then `DISPLAY=:99 shadowmap`.",
        if frames == 1 { "" } else { "s" },
        path.display(),
        if replaced {
            " (replacing the file there)"
        } else {
            ""
        },
    )
}

/// No display: render what the window would have shown headless, the same way with or
/// without `--exit-after-frames` (N frames, the scene animating between them, else one),
/// to `--screenshot` if given, else [`FALLBACK_IMAGE`]; the path is checked before any
/// rendering.
fn headless_fallback(args: &DemoArgs, mut scene: Scene, settings: &ShadowSettings) -> Result<()> {
    let path = args
        .screenshot
        .clone()
        .unwrap_or_else(|| PathBuf::from(FALLBACK_IMAGE));
    check_output_image(
        match args.screenshot {
            Some(_) => "--screenshot",
            None => "the no-display fallback",
        },
        &path,
    )?;
    let frames = match args.exit_after_frames {
        None => 1,
        Some(n) => u32::try_from(n.max(1)).map_err(|_| {
            Error::Invalid(format!(
                "--exit-after-frames {n}: without a display the frames are rendered headless; \
                 expected at most {}",
                u32::MAX
            ))
        })?,
    };
    let (w, h) = args.scene.size(&scene);
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, settings)?;
    args.scene.check_size(context.gl(), &scene)?;
    let overlays = Overlays {
        hud: !args.no_hud,
        inset: args.inset,
    };
    let frame = match overlays.hud || overlays.inset {
        true => render_frames_with_overlays(
            &context,
            &mut scene,
            settings,
            args.settings.step.as_deref(),
            (w, h),
            frames,
            Outputs::default(),
            overlays,
        )?,
        false => render_frames(
            context.gl(),
            &mut scene,
            settings,
            w,
            h,
            frames,
            Outputs::default(),
        )?,
    };
    let replaced = std::fs::metadata(&path).is_ok_and(|m| m.is_file());
    frame.colour.save_png(&path)?;
    let shown = std::fs::canonicalize(&path).unwrap_or_else(|_| path.clone());
    println!(
        "{}",
        fallback_message(&no_display_reason(), &scene.name, frames, &shown, replaced)
    );
    Ok(())
}

/// Window, GL context, renderer and HUD; the GL users are declared first so they drop
/// before the context.
struct Running {
    renderer: Renderer,
    /// `None` with `--no-hud`.
    hud: Option<Hud>,
    context: WindowContext,
}

struct Demo {
    args: DemoArgs,
    scene: Scene,
    settings: ShadowSettings,
    size: (u32, u32),
    running: Option<Running>,
    error: Option<Error>,
    keys: HashSet<KeyCode>,
    dragging: bool,
    cursor: Option<(f64, f64)>,
    mouse_delta: (f64, f64),
    angle_inc: f32,
    frames: u64,
    last_frame: Instant,
    update_debt: f64,
    frame_ms: f64,
    /// The frame time the HUD shows, refreshed with the title so it can be read.
    shown_ms: Option<f64>,
    /// Whether the HUD's key panel is open (H).
    show_keys: bool,
    /// Whether the HUD shows the shadow cache's counters (P).
    show_stats: bool,
    last_title: Instant,
    screenshot_requested: bool,
    screenshots: u32,
    /// The chapter step shown (`None` = the scene's own settings).
    step: Option<&'static str>,
    minimised: bool,
    /// Redraws skipped while minimised.
    skipped: u64,
    /// The light whose map M shows.
    depth_light: usize,
    /// The azimuth the angle keys turn the first light about; `None`: not directional.
    azimuth: Option<Vec3>,
    /// The angle keys were pressed on a light they cannot turn (said once).
    angle_keys_idle: bool,
    /// Whether the shadow-map inset is drawn (I).
    show_inset: bool,
    /// The camera to go back to when the steps (shown from the scene's steps camera) end.
    camera_before_steps: Option<shadowmap::scene::Camera>,
    /// The lights' sizes to go back to when the steps (shown with the scene's
    /// `[steps] light_size`) end.
    sizes_before_steps: Option<Vec<f32>>,
    /// The camera, lights and items as they were before the shown step's own view of the
    /// scene (its stage), to go back to when another step is picked.
    before_stage: Option<StageUndo>,
    /// Wall time of each frame after the first, frame to frame (printed at a scripted exit).
    frame_times: Vec<f64>,
}

/// What a step's stage changes, as it was before: the camera, the lights, the items.
type StageUndo = (
    shadowmap::scene::Camera,
    Vec<shadowmap::scene::Light>,
    Vec<shadowmap::scene::GameItem>,
);

/// Number keys pick the chapter steps in order; Backspace goes back to the scene's settings.
const STEP_KEYS: [KeyCode; 12] = [
    KeyCode::Digit1,
    KeyCode::Digit2,
    KeyCode::Digit3,
    KeyCode::Digit4,
    KeyCode::Digit5,
    KeyCode::Digit6,
    KeyCode::Digit7,
    KeyCode::Digit8,
    KeyCode::Digit9,
    KeyCode::Digit0,
    KeyCode::Minus,
    KeyCode::Equal,
];

impl Demo {
    /// A new framebuffer size; 0 x 0 means minimised, and then nothing is drawn.
    fn on_resized(&mut self, width: u32, height: u32) {
        self.minimised = width == 0 || height == 0;
        if !self.minimised {
            // The frame's shape, which a fitted light box follows.
            self.scene.size = [width, height];
        }
        if let Some(r) = &self.running {
            if !self.minimised {
                r.context.resize(width, height);
            }
            r.context.window().request_redraw();
        }
    }

    /// `--stress-window`: a storm of resizes, then a minimise to 0 x 0 and a restore (the
    /// 0 x 0 event is also delivered by hand, as a window manager would, since a bare X
    /// server may not send one).
    fn stress_step(&mut self) {
        let Some(r) = &self.running else { return };
        let window = r.context.window();
        let sizes = [
            (320, 200),
            (1024, 700),
            (17, 9),
            (800, 600),
            (1, 1),
            (640, 480),
        ];
        match self.frames {
            1..=18 => {
                let (w, h) = sizes[self.frames as usize % sizes.len()];
                let _ = window.request_inner_size(PhysicalSize::new(w, h));
            }
            19 => {
                let _ = window.request_inner_size(PhysicalSize::new(self.size.0, self.size.1));
            }
            22 => {
                window.set_minimized(true);
                self.on_resized(0, 0);
            }
            _ => {}
        }
    }

    /// Switches to a chapter step (or back to the scene's settings with `None`).
    fn select_step(&mut self, event_loop: &ActiveEventLoop, step: Option<&'static str>) {
        if let Some((camera, lights, items)) = self.before_stage.take() {
            (self.scene.camera, self.scene.lights, self.scene.items) = (camera, lights, items);
        }
        // Steps are shown from the scene's steps camera (where its own does not show what
        // they change); back to the scene's camera with its own settings.
        if self.scene.steps.camera.is_some() {
            match (step, self.camera_before_steps) {
                (Some(_), None) => {
                    self.camera_before_steps = Some(self.scene.camera);
                    self.scene.camera = self.scene.steps_camera();
                }
                (None, Some(camera)) => {
                    self.scene.camera = camera;
                    self.camera_before_steps = None;
                }
                _ => {}
            }
        }
        // And with the lights' size its steps ask for (`[steps] light_size`), if any.
        if self.scene.steps.light_size.is_some() {
            match (step, self.sizes_before_steps.take()) {
                (Some(_), None) => {
                    let sizes = self.scene.lights.iter().map(|l| l.size()).collect();
                    self.sizes_before_steps = Some(sizes);
                    self.scene.use_steps_light_size();
                }
                (None, Some(sizes)) => {
                    for (l, size) in self.scene.lights.iter_mut().zip(sizes) {
                        l.set_size(size);
                    }
                }
                (_, kept) => self.sizes_before_steps = kept,
            }
        }
        // The step's own view of the scene, where it has one (undone by the next pick).
        if let Some(staged) = step.and_then(|name| steps::get(&self.scene, name)) {
            if staged.stage(&self.scene).is_some() {
                let s = &self.scene;
                self.before_stage = Some((s.camera, s.lights.clone(), s.items.clone()));
                if let Err(e) = staged.set_stage(&mut self.scene, false) {
                    return self.fail(event_loop, e);
                }
            }
        }
        let settings = match step {
            Some(name) => steps::settings_for(&self.scene, name),
            None => self.args.settings.apply(&mut self.scene),
        };
        let result = settings.and_then(|s| {
            if let Some(r) = &mut self.running {
                r.renderer.set_settings(&s)?;
            }
            self.settings = s;
            Ok(())
        });
        match result {
            Ok(()) => {
                self.step = step;
                self.last_title = Instant::now() - Duration::from_secs(1);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    /// Applies a change to the settings (rebuilding what it touches), or stops on an error.
    fn change_settings(
        &mut self,
        event_loop: &ActiveEventLoop,
        change: impl Fn(&mut ShadowSettings),
    ) {
        let mut s = self.settings;
        change(&mut s);
        // What a light cannot be drawn with (cascades with PCSS, a non-square map) is
        // said, and the key does nothing, rather than ending the demo.
        if let Err(e) = ShadowPlan::resolve(&self.scene.lights, &s, None) {
            eprintln!("note: {e}; the settings stay as they were");
            return;
        }
        if let Some(r) = &mut self.running {
            if let Err(e) = r.renderer.set_settings(&s) {
                return self.fail(event_loop, e);
            }
        }
        self.settings = s;
        self.last_title = Instant::now() - Duration::from_secs(1);
    }

    /// M: the first casting light's shadow map instead of the scene, then the next light's,
    /// and after the last, the scene again.
    fn next_depth_view(&mut self, event_loop: &ActiveEventLoop) {
        let casting: Vec<usize> = (0..self.scene.lights.len())
            .filter(|&i| self.scene.lights[i].casts_shadows())
            .collect();
        let next = match self.settings.show_depth_map {
            false => casting.first().copied(),
            true => casting.iter().copied().find(|&i| i > self.depth_light),
        };
        if let Some(i) = next {
            self.depth_light = i;
            if let Some(r) = &mut self.running {
                r.renderer.set_depth_view_light(i);
            }
        }
        self.change_settings(event_loop, |s| s.show_depth_map = next.is_some());
    }

    /// The angle keys on a spot or point light: said once, on the terminal and in the HUD.
    fn angle_keys_idle(&mut self) {
        if !std::mem::replace(&mut self.angle_keys_idle, true) {
            println!(
                "note: the arrow keys turn a directional light's angle; the {} scene's first \
                 light is a {}, so they do nothing here",
                self.scene.name,
                self.scene.light().describe()
            );
        }
    }

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        self.error.get_or_insert(e);
        self.running = None;
        event_loop.exit();
    }

    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<Running> {
        let attributes = Window::default_attributes()
            .with_title("shadowmap")
            .with_inner_size(PhysicalSize::new(self.size.0.max(1), self.size.1.max(1)));
        let context = WindowContext::new(event_loop, attributes, self.args.gl_api.into())?;
        self.args
            .settings
            .check(context.gl(), &self.scene, &self.settings)?;
        let mut renderer = Renderer::new(context.gl(), &self.scene, &self.settings)?;
        // A window made again (after a suspend) keeps showing the light M had picked.
        renderer.set_depth_view_light(self.depth_light);
        let hud = match self.args.no_hud {
            true => None,
            false => Some(Hud::new(context.gl())?),
        };
        Ok(Running {
            renderer,
            hud,
            context,
        })
    }

    /// One fixed update: the book's `input` and `update`.
    fn update(&mut self) {
        let held = |k| self.keys.contains(&k);
        // The book's code: LEFT/RIGHT accelerate the angle; the text says UP/DOWN.
        if held(KeyCode::ArrowLeft) || held(KeyCode::ArrowDown) {
            self.angle_inc -= ANGLE_STEP;
        } else if held(KeyCode::ArrowRight) || held(KeyCode::ArrowUp) {
            self.angle_inc += ANGLE_STEP;
        } else {
            self.angle_inc = 0.0;
        }
        // The book's `lightAngle += angleInc`, clamped to 0..180, about the light's azimuth.
        if let (true, Some(azimuth), Some(light)) = (
            self.angle_inc != 0.0,
            self.azimuth,
            self.scene.light().as_directional(),
        ) {
            let angle = light.angle_about(azimuth) + self.angle_inc;
            self.scene.set_light_angle_about(azimuth, angle);
        }
        let mut step = Vec3::ZERO;
        let axis = |neg, pos| f32::from(u8::from(held(pos))) - f32::from(u8::from(held(neg)));
        step.z = axis(KeyCode::KeyW, KeyCode::KeyS);
        step.x = axis(KeyCode::KeyA, KeyCode::KeyD);
        step.y = axis(KeyCode::KeyZ, KeyCode::KeyX);
        self.scene.camera.move_position(step * CAMERA_POS_STEP);
        let (dx, dy) = std::mem::take(&mut self.mouse_delta);
        self.scene.camera.move_rotation(Vec3::new(
            dy as f32 * MOUSE_SENSITIVITY,
            dx as f32 * MOUSE_SENSITIVITY,
            0.0,
        ));
        self.scene.update();
    }

    fn redraw(&mut self, event_loop: &ActiveEventLoop) {
        let now = Instant::now();
        let dt = now.duration_since(self.last_frame).as_secs_f64();
        self.last_frame = now;
        self.catch_up(dt);
        let Some((w, h)) = self.running.as_ref().map(|r| r.context.framebuffer_size()) else {
            return;
        };
        if self.minimised || w == 0 || h == 0 {
            return self.skip_minimised();
        }
        if let Err(e) = self.draw(w, h) {
            return self.fail(event_loop, e);
        }
        self.frames += 1;
        let last = self
            .args
            .exit_after_frames
            .is_some_and(|n| self.frames >= n);
        if let Err(e) = self.save_screenshot(last, w, h) {
            return self.fail(event_loop, e);
        }
        let Some(running) = &mut self.running else {
            return;
        };
        if let Err(e) = running.context.swap_buffers() {
            return self.fail(event_loop, e);
        }
        self.count_frame_time(dt);
        if self.args.stress_window {
            // Let the storm's sizes arrive between frames.
            std::thread::sleep(Duration::from_millis(5));
        }
        if now.duration_since(self.last_title) > Duration::from_millis(250) {
            self.last_title = now;
            self.show_title(w, h);
        }
        if last {
            self.print_frame_times();
            event_loop.exit();
        } else if self.args.stress_window {
            self.stress_step();
        }
    }

    /// Fixed updates at the book's rate, however fast frames come (at most 5 per frame).
    fn catch_up(&mut self, dt: f64) {
        self.update_debt = (self.update_debt + dt * UPDATES_PER_SECOND).min(5.0);
        while self.update_debt >= 1.0 {
            self.update_debt -= 1.0;
            self.update();
        }
    }

    /// Minimised: nothing to draw into, and nothing is drawn.
    fn skip_minimised(&mut self) {
        self.skipped += 1;
        if self.args.stress_window && self.skipped >= 5 {
            if let Some(r) = &self.running {
                r.context.window().set_minimized(false);
                let size = PhysicalSize::new(self.size.0, self.size.1);
                let _ = r.context.window().request_inner_size(size);
            }
            self.on_resized(self.size.0, self.size.1);
        }
    }

    /// The scene, then the shadow-map inset, then the HUD.
    fn draw(&mut self, w: u32, h: u32) -> Result<()> {
        let Some(running) = &mut self.running else {
            return Ok(());
        };
        let target = Target::Window {
            width: w,
            height: h,
        };
        running.renderer.render(&self.scene, target)?;
        // The shadow-map inset, between the scene and the HUD (not over the map itself).
        if let (true, false, Some(rect)) = (
            self.show_inset,
            self.settings.show_depth_map,
            inset_rect(w, h),
        ) {
            running
                .renderer
                .render_depth_inset(&self.scene, target, rect)?;
        }
        if let Some(hud) = &mut running.hud {
            running.context.bind_default_framebuffer();
            let info = HudInfo {
                scene: &self.scene,
                plan: running.renderer.plan(),
                step: self.step,
                frame_ms: self.shown_ms,
                depth_light: self.depth_light,
                depth_range: running
                    .renderer
                    .depth_view_range()
                    .filter(|_| self.show_inset || self.settings.show_depth_map),
                keys: Some(super::keys::KEYS),
                show_keys: self.show_keys,
                azimuth: self.azimuth,
                angle_keys_idle: self.angle_keys_idle,
                reuse: self.show_stats.then(|| {
                    (
                        running.renderer.depth_passes(),
                        running.renderer.mask_uses(),
                    )
                }),
            };
            hud.draw(&info, w, h)?;
        }
        Ok(())
    }

    /// The scripted run's last frame, or a frame a screenshot was asked for, as a PNG.
    /// Only the scripted run's failed write is an error: that screenshot is what it was for.
    fn save_screenshot(&mut self, last: bool, w: u32, h: u32) -> Result<()> {
        let shot = if last {
            self.args.screenshot.clone()
        } else if std::mem::take(&mut self.screenshot_requested) {
            self.screenshots += 1;
            Some(screenshot_path(self.screenshots))
        } else {
            None
        };
        let (Some(path), Some(running)) = (shot, &self.running) else {
            return Ok(());
        };
        let image = ImageData {
            width: w,
            height: h,
            rgba: running.context.read_back_buffer(),
        };
        match image.save_png(&path) {
            Ok(()) => println!("screenshot: {}", path.display()),
            Err(e) if last => return Err(e),
            Err(e) => eprintln!("error: {e}"),
        }
        Ok(())
    }

    /// Keeps the frame time (the first frame's dt runs from the window's opening, not from
    /// a frame) and its running average for the title.
    fn count_frame_time(&mut self, dt: f64) {
        if self.frames > 1 {
            self.frame_times.push(dt * 1000.0);
        }
        self.frame_ms = match (self.frames, self.frame_ms == 0.0) {
            (0 | 1, _) => self.frame_ms,
            (_, true) => dt * 1000.0,
            (_, false) => 0.9 * self.frame_ms + 0.1 * dt * 1000.0,
        };
    }

    /// The window title: scene, step, light, techniques in use and the frame time.
    fn show_title(&mut self, w: u32, h: u32) {
        self.shown_ms = (self.frame_ms > 0.0).then_some(self.frame_ms);
        let Some(running) = &self.running else {
            return;
        };
        running.context.window().set_title(&format!(
            "shadowmap: {} | step {} | {}{} | {} | {:.2} ms ({}x{})",
            self.scene.name,
            self.step.unwrap_or("(scene)"),
            self.scene.light().describe(),
            match (self.settings.show_depth_map, self.scene.lights.len()) {
                (true, _) => format!(" | depth map of light {}", self.depth_light),
                (false, 1) => String::new(),
                (false, n) => format!(" (+{} more)", n - 1),
            },
            running.renderer.plan().in_use().summary(),
            self.frame_ms,
            w,
            h
        ));
    }

    /// The scripted run's frame times, printed as it ends.
    fn print_frame_times(&self) {
        let Some(running) = &self.running else {
            return;
        };
        if let Some((median, p95)) = shadowmap::frame::median_p95(&self.frame_times) {
            println!(
                "frame time over {} frames after the first: median {median:.2} ms, p95 \
                 {p95:.2} ms (wall, frame to frame, swap included; window through {})",
                self.frame_times.len(),
                running.context.api()
            );
        }
    }
}

fn screenshot_path(n: u32) -> PathBuf {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    PathBuf::from(format!("shadowmap-screenshot-{secs}-{n}.png"))
}

impl ApplicationHandler for Demo {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.running.is_some() || self.error.is_some() {
            return;
        }
        match self.open(event_loop) {
            Ok(r) => {
                self.last_frame = Instant::now();
                self.running = Some(r);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _id: WindowId, event: WindowEvent) {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            WindowEvent::Resized(size) => self.on_resized(size.width, size.height),
            WindowEvent::KeyboardInput { event, .. } => {
                let PhysicalKey::Code(code) = event.physical_key else {
                    return;
                };
                match event.state {
                    ElementState::Pressed => {
                        match code {
                            KeyCode::Escape => event_loop.exit(),
                            KeyCode::F12 if !event.repeat => self.screenshot_requested = true,
                            KeyCode::Backspace if !event.repeat => {
                                self.select_step(event_loop, None)
                            }
                            KeyCode::KeyM if !event.repeat => self.next_depth_view(event_loop),
                            KeyCode::KeyH if !event.repeat => self.show_keys = !self.show_keys,
                            KeyCode::KeyP if !event.repeat => self.show_stats = !self.show_stats,
                            KeyCode::KeyI if !event.repeat => self.show_inset = !self.show_inset,
                            KeyCode::ArrowUp
                            | KeyCode::ArrowDown
                            | KeyCode::ArrowLeft
                            | KeyCode::ArrowRight
                                if self.azimuth.is_none() =>
                            {
                                self.angle_keys_idle()
                            }
                            KeyCode::KeyC if !event.repeat => self
                                .change_settings(event_loop, |s| {
                                    s.show_cascades = !s.show_cascades
                                }),
                            KeyCode::KeyV if !event.repeat => {
                                self.change_settings(event_loop, |s| {
                                    s.technique = match s.technique {
                                        ShadowTechnique::Maps => ShadowTechnique::Volumes,
                                        ShadowTechnique::Volumes => ShadowTechnique::Maps,
                                    }
                                })
                            }
                            KeyCode::KeyB if !event.repeat => self
                                .change_settings(event_loop, |s| s.show_volumes = !s.show_volumes),
                            KeyCode::KeyK if !event.repeat => self
                                .change_settings(event_loop, |s| {
                                    s.cascades = s.cascades % MAX_CASCADES + 1
                                }),
                            KeyCode::KeyG if !event.repeat => self
                                .change_settings(event_loop, |s| {
                                    s.caster_groups = s.caster_groups % MAX_CASCADES + 1
                                }),
                            KeyCode::KeyT if !event.repeat => self
                                .change_settings(event_loop, |s| {
                                    s.volumetric = s.volumetric.next()
                                }),
                            _ if !event.repeat => {
                                if let Some(i) = STEP_KEYS.iter().position(|k| *k == code) {
                                    let name = steps::of(&self.scene).get(i).map(|s| s.name);
                                    self.select_step(event_loop, name);
                                }
                            }
                            _ => {}
                        }
                        self.keys.insert(code);
                    }
                    ElementState::Released => {
                        self.keys.remove(&code);
                    }
                }
            }
            WindowEvent::MouseInput {
                state,
                button: MouseButton::Right,
                ..
            } => self.dragging = state == ElementState::Pressed,
            WindowEvent::CursorMoved { position, .. } => {
                if let (true, Some((x, y))) = (self.dragging, self.cursor) {
                    self.mouse_delta.0 += position.x - x;
                    self.mouse_delta.1 += position.y - y;
                }
                self.cursor = Some((position.x, position.y));
            }
            WindowEvent::CursorLeft { .. } => self.cursor = None,
            WindowEvent::RedrawRequested => self.redraw(event_loop),
            _ => {}
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        let Some(r) = &self.running else { return };
        let (w, h) = r.context.framebuffer_size();
        if w == 0 || h == 0 {
            // Minimised: sleep until the window changes instead of spinning.
            event_loop.set_control_flow(ControlFlow::Wait);
        } else {
            event_loop.set_control_flow(ControlFlow::Poll);
            r.context.window().request_redraw();
        }
    }
}
