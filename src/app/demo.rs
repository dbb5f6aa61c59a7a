//! The demo: the DummyGame in a window (winit 0.30 + glutin), with the book's controls.
//! Without a display it renders the same scene headless to `shadowmap-demo.png`.

use std::collections::HashSet;
use web_time::{Duration, Instant};

use glam::Vec3;
use shadowmap::engine::context::{self, WindowContext};
use shadowmap::output::check_output_image;
use shadowmap::settings::{ShadowTechnique, MAX_CASCADES};
use shadowmap::{steps, Error, Renderer, Result, Scene, ShadowSettings};
use winit::application::ApplicationHandler;
use winit::dpi::PhysicalSize;
use winit::event::{ElementState, MouseButton, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow};
use winit::keyboard::{KeyCode, PhysicalKey};
use winit::window::{Window, WindowId};

use super::cli::DemoArgs;
use super::hud::Hud;
use super::quality::choose_for_target;
use fallback::headless_fallback;

mod controls;
mod fallback;
mod frame;

/// The scene as loaded with the flags (what the step keys start from), the scene as
/// shown first and its settings: `--step` shows what `render --step` shows, the step's view
/// and settings.
pub(super) fn scenes(args: &DemoArgs) -> Result<(Scene, Scene, ShadowSettings)> {
    let mut loaded = args.scene.load()?;
    if args.no_animation {
        loaded.items.iter_mut().for_each(|i| i.spin = Vec3::ZERO);
        for light in &mut loaded.lights {
            if let shadowmap::scene::Light::Point(p) = light {
                p.oscillate = Vec3::ZERO;
            }
        }
    }
    let mut scene = loaded.clone();
    let settings = args.settings.resolve(&args.scene, &mut scene)?;
    Ok((loaded, scene, settings))
}

pub fn run(args: &DemoArgs) -> Result<()> {
    let (loaded, mut scene, settings) = scenes(args)?;
    // What needs no window or driver is checked before anything opens.
    args.settings.check_values(&scene, &settings)?;
    args.motion.start(&mut scene)?;
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
    match context::window_system() {
        Ok(()) => {}
        Err(reason) if args.require_window => {
            return Err(Error::Context(format!(
                "--require-window: no window ({reason}); nothing rendered"
            )))
        }
        Err(reason) => return headless_fallback(args, scene, &settings, &reason),
    }
    let size = args.scene.size(&scene);
    let step = args
        .settings
        .step
        .as_deref()
        .and_then(|name| steps::get(&scene, name))
        .map(|s| s.name);
    let mut demo = Demo::new(args, (loaded, scene), settings, size, step);
    // Taken once: past the overhead a light's own horizontal part points the other way.
    demo.azimuth = demo.scene.light_azimuth();
    // In the browser the page runs the demo after this returns, and shows its errors.
    let Some(demo) = context::run_app(demo)? else {
        return Ok(());
    };
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

/// Window, GL context, renderer and HUD; the GL users are declared first so they drop
/// before the context.
struct Running {
    renderer: Renderer,
    /// `--show-visibility`'s frame: drawn with the visibility output, its greys shown.
    visibility: Option<shadowmap::engine::RenderTarget>,
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
    /// The scene as loaded with the flags, before any step: each step key shows its step
    /// from here, as `--step` would ([`super::cli::SettingsArgs::resolve`]).
    loaded: Scene,
    /// Wall time of each frame after the first, frame to frame (printed at a scripted exit).
    frame_times: Vec<f64>,
    /// What a key changed, until a frame is drawn with the change: one that cannot be
    /// drawn (what WebGL2 lacks) goes back to it, said, and the demo goes on.
    undo: Option<Undo>,
}

/// The scene, settings and step before a key changed them.
struct Undo {
    scene: Scene,
    settings: ShadowSettings,
    step: Option<&'static str>,
}

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

    fn fail(&mut self, event_loop: &ActiveEventLoop, e: Error) {
        if !context::HAS_TERMINAL {
            context::report_error(&e.to_string());
        }
        self.error.get_or_insert(e);
        self.running = None;
        event_loop.exit();
    }

    fn open(&mut self, event_loop: &ActiveEventLoop) -> Result<Running> {
        let attributes = Window::default_attributes()
            .with_title("shadowmap")
            .with_inner_size(PhysicalSize::new(self.size.0.max(1), self.size.1.max(1)));
        let context = WindowContext::new(event_loop, attributes, self.args.gl_api)?;
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
            visibility: None,
            hud,
            context,
        })
    }

    /// The demo before its window opens: the scene at `size`, the step chosen by name.
    fn new(
        args: &DemoArgs,
        (loaded, scene): (Scene, Scene),
        settings: ShadowSettings,
        size: (u32, u32),
        step: Option<&'static str>,
    ) -> Demo {
        Demo {
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
            last_title: Instant::now()
                .checked_sub(Duration::from_secs(1))
                .unwrap_or_else(Instant::now),
            screenshot_requested: false,
            screenshots: 0,
            step,
            minimised: false,
            skipped: 0,
            depth_light: 0,
            azimuth: None,
            angle_keys_idle: false,
            show_inset: args.inset,
            loaded,
            frame_times: Vec::new(),
            undo: None,
        }
    }

    /// A key pressed: the demo's keys (README's table), a step's key, Esc to quit.
    fn key_pressed(&mut self, event_loop: &ActiveEventLoop, code: KeyCode, repeat: bool) {
        match code {
            KeyCode::Escape => event_loop.exit(),
            KeyCode::F12 if !repeat => self.screenshot_requested = true,
            KeyCode::KeyM if !repeat => self.next_depth_view(event_loop),
            KeyCode::KeyH if !repeat => self.show_keys = !self.show_keys,
            KeyCode::KeyP if !repeat => self.show_stats = !self.show_stats,
            KeyCode::KeyI if !repeat => self.show_inset = !self.show_inset,
            KeyCode::ArrowUp | KeyCode::ArrowDown | KeyCode::ArrowLeft | KeyCode::ArrowRight
                if self.azimuth.is_none() =>
            {
                self.angle_keys_idle()
            }
            KeyCode::KeyC if !repeat => {
                self.change_settings(event_loop, |s| s.show_cascades = !s.show_cascades)
            }
            KeyCode::KeyV if !repeat => self.change_settings(event_loop, |s| {
                s.technique = match s.technique {
                    ShadowTechnique::Maps => ShadowTechnique::Volumes,
                    ShadowTechnique::Volumes => ShadowTechnique::Maps,
                }
            }),
            KeyCode::KeyB if !repeat => {
                self.change_settings(event_loop, |s| s.show_volumes = !s.show_volumes)
            }
            KeyCode::KeyK if !repeat => {
                self.change_settings(event_loop, |s| s.cascades = s.cascades % MAX_CASCADES + 1)
            }
            KeyCode::KeyG if !repeat => self.change_settings(event_loop, |s| {
                s.caster_groups = s.caster_groups % MAX_CASCADES + 1
            }),
            KeyCode::KeyT if !repeat => {
                self.change_settings(event_loop, |s| s.volumetric = s.volumetric.next())
            }
            _ if !repeat => {
                let list = steps::of(&self.scene);
                let shift = [KeyCode::ShiftLeft, KeyCode::ShiftRight]
                    .iter()
                    .any(|k| self.keys.contains(k));
                let current = self
                    .step
                    .and_then(|n| list.iter().position(|s| s.name == n));
                if let Some(pick) = super::keys::step_key(code, shift, current, list.len()) {
                    self.select_step(event_loop, pick.map(|i| list[i].name));
                }
            }
            _ => {}
        }
    }
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
                        self.key_pressed(event_loop, code, event.repeat);
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
