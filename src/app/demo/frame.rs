//! One frame of the demo's window: the fixed updates it owes, the scene, inset and HUD
//! drawn, screenshots, and the frame time in the title.

use std::path::PathBuf;
use web_time::{Duration, Instant};

use shadowmap::engine::{Outputs, RenderTarget};
use shadowmap::frame::visibility_rgba;
use shadowmap::image_data::ImageData;
use shadowmap::{Result, Scene, Target};
use winit::dpi::PhysicalSize;
use winit::event_loop::ActiveEventLoop;

use super::super::hud::{inset_rect, HudInfo};
use super::{Demo, Running};

/// The book's fixed update rate.
const UPDATES_PER_SECOND: f64 = 30.0;

impl Demo {
    pub(super) fn redraw(&mut self, event_loop: &ActiveEventLoop) {
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
            return match self.undo.take() {
                Some(undo) => self.undo_change(event_loop, undo, e),
                None => self.fail(event_loop, e),
            };
        }
        self.undo = None;
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
    /// On a `--motion` path one update a drawn frame instead, so the Nth frame drawn is
    /// the path's frame N - 1, as `render --frames N` draws it, however fast it came.
    fn catch_up(&mut self, dt: f64) {
        if let Some(path) = &self.scene.motion {
            if u64::from(path.frame) < self.frames {
                self.update();
            }
            return;
        }
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
        // A depth-map view has no shadow test to show: the map is shown as it is.
        match self.args.show_visibility && !self.settings.show_depth_map {
            false => running.renderer.render(&self.scene, target)?,
            true => running.show_visibility(&self.scene, w, h)?,
        }
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
                keys: Some(super::super::keys::KEYS),
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
    let secs = web_time::SystemTime::now()
        .duration_since(web_time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    PathBuf::from(format!("shadowmap-screenshot-{secs}-{n}.png"))
}

/// Off the geometry in the visibility view: a blue that no grey of the test can be.
pub(super) const VISIBILITY_OFF: [u8; 4] = [40, 70, 140, 255];

impl Running {
    /// `--show-visibility`: the frame drawn offscreen with the visibility output, its greys
    /// (`render --shadow-out`'s) shown in the window. The target is made again only when
    /// the window's size changes.
    fn show_visibility(&mut self, scene: &Scene, w: u32, h: u32) -> Result<()> {
        let gl = self.context.gl();
        let fits = |t: &RenderTarget| t.width() == w && t.height() == h;
        if !self.visibility.as_ref().is_some_and(fits) {
            let outputs = Outputs {
                visibility: true,
                gbuffer: false,
            };
            self.visibility = Some(RenderTarget::new(gl, w, h, outputs)?);
        }
        let Some(target) = &self.visibility else {
            return Ok(());
        };
        self.renderer.render(scene, Target::Offscreen(target))?;
        target.write_colour(&visibility_rgba(&target.read_visibility()?, VISIBILITY_OFF))?;
        target.blit_colour_to_window();
        Ok(())
    }
}
