//! The demo's controls: the chapter steps and settings its keys pick, and the book's fixed
//! update (the held keys turn the light and move the camera).

use web_time::{Duration, Instant};

use glam::Vec3;
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::ShadowSettings;
use winit::event_loop::ActiveEventLoop;
use winit::keyboard::KeyCode;

use super::{Demo, Undo};
use crate::app::cli::SettingsArgs;
use shadowmap::engine::context;
use shadowmap::Error;

/// Camera step per update (DummyGame's CAMERA_POS_STEP).
const CAMERA_POS_STEP: f32 = 0.05;
/// Degrees of camera rotation per pixel of mouse drag (DummyGame's MOUSE_SENSITIVITY).
const MOUSE_SENSITIVITY: f32 = 0.2;
/// Light-angle acceleration per update while a key is held (DummyGame: +-0.05).
const ANGLE_STEP: f32 = 0.05;

impl Demo {
    /// Switches to a chapter step (or back to the scene's settings with `None`): what
    /// `demo --step` with the same flags shows, the step's view and settings.
    pub(super) fn select_step(&mut self, event_loop: &ActiveEventLoop, step: Option<&'static str>) {
        let mut scene = self.loaded.clone();
        // Kept from the running scene: the frame's shape and the animation's clock.
        (scene.size, scene.time) = (self.scene.size, self.scene.time);
        let flags = SettingsArgs {
            step: step.map(str::to_string),
            ..self.args.settings.clone()
        };
        let settings = flags.resolve(&self.args.scene, &mut scene);
        let undo = self.undo_point();
        if settings.is_ok() {
            (self.scene.camera, self.scene.lights) = (scene.camera, scene.lights);
            self.scene.items = scene.items;
        }
        let result = settings.and_then(|s| {
            if let Some(r) = &mut self.running {
                r.renderer.set_settings(&s)?;
            }
            self.settings = s;
            Ok(())
        });
        match result {
            Ok(()) => {
                self.undo = Some(undo);
                self.step = step;
                self.last_title = Instant::now()
                    .checked_sub(Duration::from_secs(1))
                    .unwrap_or_else(Instant::now);
            }
            Err(e) => self.fail(event_loop, e),
        }
    }

    /// Applies a change to the settings (rebuilding what it touches), or stops on an error.
    pub(super) fn change_settings(
        &mut self,
        event_loop: &ActiveEventLoop,
        change: impl Fn(&mut ShadowSettings),
    ) {
        let mut s = self.settings;
        change(&mut s);
        // What a light cannot be drawn with (cascades with PCSS, a non-square map) is
        // said, and the key does nothing, rather than ending the demo.
        if let Err(e) = ShadowPlan::resolve(&self.scene.lights, &s, None) {
            return context::report_note(&format!("{e}; the settings stay as they were"));
        }
        let undo = self.undo_point();
        if let Some(r) = &mut self.running {
            if let Err(e) = r.renderer.set_settings(&s) {
                return self.fail(event_loop, e);
            }
        }
        self.settings = s;
        self.undo = Some(undo);
        self.last_title = Instant::now()
            .checked_sub(Duration::from_secs(1))
            .unwrap_or_else(Instant::now);
    }

    fn undo_point(&self) -> Undo {
        Undo {
            scene: self.scene.clone(),
            settings: self.settings,
            step: self.step,
        }
    }

    /// A frame after a key's change could not be drawn (a refusal: what WebGL2 lacks):
    /// back to the scene and settings before it, `e` said, and the demo goes on. The
    /// animation's clock and the frame's shape are kept.
    pub(super) fn undo_change(&mut self, event_loop: &ActiveEventLoop, undo: Undo, e: Error) {
        context::report_note(&format!("{e}; the settings stay as they were"));
        let (time, size) = (self.scene.time, self.scene.size);
        self.scene = undo.scene;
        (self.scene.time, self.scene.size) = (time, size);
        if let Some(r) = &mut self.running {
            if let Err(e) = r.renderer.set_settings(&undo.settings) {
                return self.fail(event_loop, e);
            }
            r.context.window().request_redraw();
        }
        (self.settings, self.step) = (undo.settings, undo.step);
    }

    /// M: the first casting light's shadow map instead of the scene, then the next light's,
    /// and after the last, the scene again.
    pub(super) fn next_depth_view(&mut self, event_loop: &ActiveEventLoop) {
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
    pub(super) fn angle_keys_idle(&mut self) {
        if !std::mem::replace(&mut self.angle_keys_idle, true) {
            println!(
                "note: the arrow keys turn a directional light's angle; the {} scene's first \
                 light is a {}, so they do nothing here",
                self.scene.name,
                self.scene.light().describe()
            );
        }
    }

    /// One fixed update: the book's `input` and `update`.
    pub(super) fn update(&mut self) {
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
}
