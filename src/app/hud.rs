//! The HUD: the text the book's demo shows over the frame (the light angle), with the chapter
//! step, the first light's shadow in words (its technique and settings, from the plan) and
//! the frame time, and on request the demo's keys and the shadow cache's counters. A window title is
//! invisible full-screen and in screenshots; this is drawn into the frame itself.
//!
//! This file decides what the lines say and where they go; the glyphs and the GL drawing
//! are `engine::text`'s. The status panel sits in the top-left corner and the key panel
//! under it (in the top-right or bottom-left corner when the top-left would cover a caster
//! or a translucent item and that corner would not: [`place`]); the bottom-right corner holds the shadow-map inset ([`inset_rect`]: the light's map beside
//! the shadows it makes, LearnOpenGL's debug quad made small), which the renderer draws
//! (`Renderer::render_depth_inset`) after the scene and before the HUD.

use glam::Vec3;
use shadowmap::engine::text::{FontAtlas, TextQuad, TextRenderer};
use shadowmap::engine::{Gl, HeadlessContext, Outputs, PixelRect, RenderTarget};
use shadowmap::frame::{render_frames_with, Frame};
use shadowmap::renderer::{DepthPasses, DepthRange, MaskUses};
use shadowmap::shadows::plan::ShadowPlan;
use shadowmap::{shaders, steps, Renderer, Result, Scene, ShadowSettings, Target};

mod place;
mod words;

/// The bundled font (DejaVu Sans; its licence is in `assets/fonts`).
const FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// Pixels per em: readable at 1280 x 720 without covering the DummyGame's cube.
const FONT_PX: f32 = 15.0;
/// Space between the frame's edge and a panel, and between panels.
const MARGIN: f32 = 8.0;
/// Space between a panel's edge and its text.
const PADDING: f32 = 6.0;
/// Space between the key column and its description in the key panel.
const COLUMN_GAP: f32 = 12.0;
const TEXT_COLOUR: [f32; 4] = [1.0, 1.0, 1.0, 1.0];
const KEY_COLOUR: [f32; 4] = [1.0, 0.85, 0.35, 1.0];
/// Dark and half transparent: the text stays readable over a lit plane and the scene still
/// shows through.
const PANEL_COLOUR: [f32; 4] = [0.0, 0.0, 0.0, 0.6];

/// What the HUD reports about one frame.
pub struct HudInfo<'a> {
    pub scene: &'a Scene,
    /// Each light's shadow as the frame drew it (the renderer's plan).
    pub plan: &'a ShadowPlan,
    /// The chapter step shown, `None` for the scene's own settings.
    pub step: Option<&'a str>,
    /// The time of the frame before, if there was one.
    pub frame_ms: Option<f64>,
    /// The light whose map is shown when the settings show a depth map.
    pub depth_light: usize,
    /// The greys of the depth view or inset on screen, when it shows a 2D map.
    pub depth_range: Option<DepthRange>,
    /// The keys to offer (the demo's); `None` where there are no keys (`render`).
    pub keys: Option<&'a [(&'a str, &'a str)]>,
    /// Whether the key panel is open.
    pub show_keys: bool,
    /// The azimuth the angle keys turn the first light about (the demo keeps it, since past
    /// the overhead the light's own horizontal part points the other way); `None`: the
    /// light's own.
    pub azimuth: Option<Vec3>,
    /// The angle keys were pressed but the first light is a spot or point light.
    pub angle_keys_idle: bool,
    /// The shadow cache's counters (the stats key, P): shadow-map passes drawn, patched
    /// and reused, and frames that read the shadow mask, so far; `None`: not shown.
    pub reuse: Option<(DepthPasses, MaskUses)>,
}

/// Said once when the angle keys are pressed on a scene whose first light has no angle.
pub const ANGLE_KEYS_IDLE: &str =
    "Arrow keys: the first light is not directional; they turn nothing here";

/// The last line while the key panel is closed.
pub const KEYS_HINT: &str = "H: keys, P: shadow cache counters";

/// The status lines, top to bottom.
pub fn status_lines(info: &HudInfo) -> Vec<String> {
    let scene = info.scene;
    let light = match scene.light().as_directional() {
        Some(l) => {
            let azimuth = info.azimuth.unwrap_or_else(|| l.azimuth());
            match azimuth == Vec3::Z {
                // The DummyGame's light turns in the YZ plane: the book shows its angle.
                true => format!("Light angle: {:.1}", l.angle_about(azimuth)),
                false => format!(
                    "Light angle: {:.1} over azimuth {:.2}",
                    l.angle_about(azimuth),
                    azimuth
                ),
            }
        }
        None => upper_first(&scene.light().describe()),
    };
    let list = steps::of(scene);
    let (step, lesson) = match info.step {
        Some(name) => match list.iter().position(|s| s.name == name) {
            Some(i) => (
                format!("Step {} of {}: {name}", i + 1, list.len()),
                Some(lesson(list[i].look_for)),
            ),
            None => (format!("Step: {name}"), None),
        },
        None => (format!("Settings: the {} scene's own", scene.name), None),
    };
    let mut lines = vec![light];
    match scene.lights.len() {
        0 | 1 => {}
        2 => lines.push("and 1 more light".to_string()),
        n => lines.push(format!("and {} more lights", n - 1)),
    }
    lines.push(step);
    if let Some(lesson) = lesson {
        lines.extend(wrap_words(&lesson, LINE_WIDTH));
    }
    // Translucent casters: which shadows they cast (T changes it), as the demo may start
    // them otherwise than the scene's own settings.
    if shadowmap::shadows::volumetric::translucent_casters(scene)
        .next()
        .is_some()
    {
        let v = info.plan.scene_settings().volumetric;
        lines.push(format!("Translucent shadows: {} (T)", v.name()));
    }
    // The first light's shadow in words, each line wrapped to stay in the corner.
    if let Some(first) = info.plan.lights.first() {
        for line in words::shadow(first) {
            lines.extend(wrap_words(&line, LINE_WIDTH));
        }
    }
    if info.angle_keys_idle {
        lines.push(ANGLE_KEYS_IDLE.to_string());
    }
    if info.plan.scene_settings().show_depth_map {
        lines.push(format!("Showing light {}'s shadow map", info.depth_light));
    }
    if let Some(range) = info.depth_range {
        lines.extend(wrap_words(&upper_first(&range.words()), LINE_WIDTH));
    }
    lines.push(match info.frame_ms {
        Some(ms) => format!("Frame time: {ms:.2} ms"),
        None => "Frame time: -".to_string(),
    });
    if let Some((passes, mask)) = info.reuse {
        for line in words::cache(passes, mask) {
            lines.extend(wrap_words(&line, LINE_WIDTH));
        }
    }
    if info.keys.is_some() && !info.show_keys {
        lines.push(KEYS_HINT.to_string());
    }
    lines
}

/// A step's lesson for the HUD: the first sentence of what to look for.
fn lesson(look_for: &str) -> String {
    let end = look_for.find(". ").map_or(look_for.len(), |i| i + 1);
    format!("Look for: {}", &look_for[..end])
}

fn upper_first(s: &str) -> String {
    let mut chars = s.chars();
    match chars.next() {
        Some(c) => c.to_uppercase().chain(chars).collect(),
        None => String::new(),
    }
}

/// The quads of the whole HUD for a `size` frame (pixels from its top-left corner, y down).
pub fn layout(atlas: &FontAtlas, info: &HudInfo, size: (u32, u32)) -> Vec<TextQuad> {
    let mut quads = Vec::new();
    let line = atlas.line_height();
    let status = status_lines(info);
    let widest = |texts: &mut dyn Iterator<Item = &str>| {
        texts.map(|t| atlas.text_width(t)).fold(0.0, f32::max)
    };
    let status_width = widest(&mut status.iter().map(String::as_str));
    let keys = info.keys.filter(|_| info.show_keys);
    let key_width = keys.map_or(0.0, |k| widest(&mut k.iter().map(|(k, _)| *k)).ceil());
    let keys_width = keys.map_or(0.0, |k| {
        key_width + COLUMN_GAP + widest(&mut k.iter().map(|(_, d)| *d))
    });
    let key_lines = keys.map_or(0, <[_]>::len);
    let keys_height = match keys {
        Some(_) => MARGIN + line * key_lines as f32 + 2.0 * PADDING,
        None => 0.0,
    };
    let column = (
        status_width.max(keys_width) + 2.0 * PADDING,
        line * status.len() as f32 + 2.0 * PADDING + keys_height,
    );
    let corner = place::corner(info.scene, size, column);
    let top = corner.origin(size, column).1;
    // Each panel against the frame's left edge, or its right edge.
    let x_of = |text_width: f32| match corner.right() {
        true => (size.0 as f32 - MARGIN - text_width - 2.0 * PADDING).floor(),
        false => MARGIN,
    };
    let x = x_of(status_width);
    let bottom = panel(
        atlas,
        &mut quads,
        (x, top),
        (status_width, line * status.len() as f32),
    );
    let mut y = top + PADDING;
    for text in &status {
        atlas.push_text(&mut quads, text, x + PADDING, y, TEXT_COLOUR);
        y += line;
    }
    if let Some(keys) = keys {
        let top = bottom + MARGIN;
        let x = x_of(keys_width);
        panel(
            atlas,
            &mut quads,
            (x, top),
            (keys_width, line * keys.len() as f32),
        );
        let mut y = top + PADDING;
        for (key, does) in keys {
            atlas.push_text(&mut quads, key, x + PADDING, y, KEY_COLOUR);
            let x = x + PADDING + key_width + COLUMN_GAP;
            atlas.push_text(&mut quads, does, x, y, TEXT_COLOUR);
            y += line;
        }
    }
    quads
}

/// A panel around text of the given size whose top-left corner is `at`; returns its bottom.
fn panel(atlas: &FontAtlas, quads: &mut Vec<TextQuad>, at: (f32, f32), text: (f32, f32)) -> f32 {
    let right = (at.0 + text.0 + 2.0 * PADDING).ceil();
    let bottom = (at.1 + text.1 + 2.0 * PADDING).ceil();
    atlas.push_rect(quads, [at.0, at.1, right, bottom], PANEL_COLOUR);
    bottom
}

/// The HUD's glyphs and their GL side, made once per GL context.
pub struct Hud {
    atlas: FontAtlas,
    text: TextRenderer,
}

impl Hud {
    pub fn new(gl: &Gl) -> Result<Hud> {
        let atlas = FontAtlas::new(FONT, FONT_PX)?;
        let text = TextRenderer::new(gl, &atlas, &shaders::text_vert(), &shaders::text_frag())?;
        Ok(Hud { atlas, text })
    }

    /// Draws the HUD over the frame in the bound framebuffer.
    pub fn draw(&mut self, info: &HudInfo, width: u32, height: u32) -> Result<()> {
        let quads = layout(&self.atlas, info, (width, height));
        self.text.draw(&quads, width, height)
    }
}

/// Characters per line of a wrapped line (about 400 pixels at `FONT_PX`).
const LINE_WIDTH: usize = 48;

/// `text` split into lines of at most `width` characters at spaces, the lines after the
/// first indented (a longer word keeps its own line).
fn wrap_words(text: &str, width: usize) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if line.len() + 1 + word.len() <= width => {
                line.push(' ');
                line.push_str(word);
            }
            Some(_) => lines.push(format!("  {word}")),
            None => lines.push(word.to_string()),
        }
    }
    lines
}

/// Where the shadow-map inset goes in a `width` x `height` frame: the bottom-right corner,
/// a quarter of the frame's height on a side, [`MARGIN`] from the edges (GL's rectangle,
/// y from the bottom). `None` when the frame is too small to hold one.
pub fn inset_rect(width: u32, height: u32) -> Option<PixelRect> {
    let side = height / 4;
    let margin = MARGIN as u32;
    (side > 0 && side + 2 * margin <= width && side + 2 * margin <= height).then(|| PixelRect {
        x: width - side - margin,
        y: margin,
        width: side,
        height: side,
    })
}

/// What is drawn over a headless frame.
#[derive(Debug, Clone, Copy, Default)]
pub struct Overlays {
    /// The HUD (`render --hud`, the demo's fallback).
    pub hud: bool,
    /// The shadow-map inset (`render --inset`).
    pub inset: bool,
}

/// Headless frames with the overlays drawn over each (`frame::render_frames_with` and its
/// after-scene hook), for `render --hud --inset` and the demo's fallback: the inset first,
/// the HUD over it. Both are timed with their frame, and both write colour only: the other
/// outputs read as they would without them.
/// The inset shows the frame's own maps (the hook hands over the frame's renderer).
#[allow(clippy::too_many_arguments)]
pub fn render_frames_with_overlays(
    context: &HeadlessContext,
    scene: &mut Scene,
    settings: &ShadowSettings,
    step: Option<&str>,
    size: (u32, u32),
    frames: u32,
    outputs: Outputs,
    overlays: Overlays,
) -> Result<Frame> {
    let gl = context.gl();
    let mut hud = overlays.hud.then(|| Hud::new(gl)).transpose()?;
    let mut draw =
        |renderer: &mut Renderer, target: &RenderTarget, scene: &Scene, frame_ms: Option<f64>| {
            let rect = inset_rect(target.width(), target.height());
            if let (true, Some(rect)) = (overlays.inset, rect) {
                renderer.render_depth_inset(scene, Target::Offscreen(target), rect)?;
            }
            let Some(hud) = &mut hud else {
                return Ok(());
            };
            target.bind();
            // No keys here: the cache's counters go to stdout, not over the frame.
            let info = HudInfo {
                scene,
                plan: renderer.plan(),
                step,
                frame_ms,
                depth_light: 0,
                depth_range: renderer
                    .depth_view_range()
                    .filter(|_| overlays.inset || renderer.plan().scene_settings().show_depth_map),
                keys: None,
                show_keys: false,
                azimuth: None,
                angle_keys_idle: false,
                reuse: None,
            };
            hud.draw(&info, target.width(), target.height())
        };
    render_frames_with(gl, scene, settings, size, frames, outputs, 0, &mut draw)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dummy_at(angle: f32) -> Scene {
        let mut scene = Scene::load("dummy").unwrap();
        assert!(scene.set_light_angle(angle));
        scene
    }

    const KEYS: &[(&str, &str)] = &[
        ("H", "these keys"),
        ("P", "the shadow cache's counters"),
        ("ESC", "quit"),
    ];

    fn plan(scene: &Scene, settings: &ShadowSettings) -> ShadowPlan {
        ShadowPlan::resolve(&scene.lights, settings, None).unwrap()
    }

    fn info<'a>(scene: &'a Scene, plan: &'a ShadowPlan, step: Option<&'a str>) -> HudInfo<'a> {
        HudInfo {
            scene,
            plan,
            step,
            frame_ms: Some(3.25),
            depth_light: 0,
            depth_range: None,
            keys: Some(KEYS),
            show_keys: false,
            azimuth: None,
            angle_keys_idle: false,
            reuse: None,
        }
    }

    /// The lines as one text, the wrapping undone.
    fn joined(lines: &[String]) -> String {
        let words: Vec<&str> = lines.iter().map(|l| l.trim()).collect();
        words.join(" ")
    }

    #[test]
    fn the_stats_key_shows_the_caches_counters_and_says_what_they_count() {
        let scene = Scene::load("learnopengl").unwrap();
        let plan = plan(&scene, &scene.shadow);
        let mut i = info(&scene, &plan, None);
        assert!(!joined(&status_lines(&i)).contains("Shadow maps"));
        i.reuse = Some((
            DepthPasses {
                drawn: 1,
                skipped: 20,
                patched: 39,
                patched_texels: 39 * 5000,
            },
            MaskUses {
                written: 1,
                read: 58,
            },
        ));
        let lines = status_lines(&i);
        let text = joined(&lines);
        assert!(
            text.contains(
                "Shadow maps: 1 drawn whole, 39 patched (redrawn only where casters moved), 20 \
                 reused (nothing changed) Frames whose shadow tests were read from the saved \
                 mask (camera and lights still): 58"
            ),
            "{lines:?}"
        );
        // Wrapped to stay in the corner (the light's line is the light's).
        assert!(
            lines.iter().skip(1).all(|l| l.len() <= LINE_WIDTH + 2),
            "{lines:?}"
        );
    }

    #[test]
    fn the_dummy_game_at_45_degrees_shows_angle_step_shadow_in_words_and_time() {
        let scene = dummy_at(45.0);
        let settings = steps::settings_for(&scene, "pcf").unwrap();
        let plan = plan(&scene, &settings);
        let lines = status_lines(&info(&scene, &plan, Some("pcf")));
        assert_eq!(lines[0], "Light angle: 45.0");
        assert!(
            lines[1].contains("pcf") && lines[1].starts_with("Step 9 of"),
            "{lines:?}"
        );
        // The step's lesson under its name, wrapped, then the shadow in words.
        let shadow = lines.iter().position(|l| l.starts_with("Shadow:")).unwrap();
        assert_eq!(
            lines[2..shadow]
                .iter()
                .map(|l| l.trim())
                .collect::<Vec<_>>()
                .join(" "),
            "Look for: Softer, less blocky shadow edges with intermediate values."
        );
        let lines: Vec<String> = lines.iter().skip(shadow - 2).cloned().collect();
        let m = settings.map_size;
        assert_eq!(
            lines[2],
            format!(
                "Shadow: one {} x {} depth map, 24-bit depth",
                m.width, m.height
            )
        );
        assert_eq!(lines[3], "Filter: PCF, 3 x 3 depth tests averaged");
        assert!(lines[4].starts_with("Bias: "), "{lines:?}");
        assert!(
            lines.contains(&"Frame time: 3.25 ms".to_string()),
            "{lines:?}"
        );
        assert_eq!(lines.last().map(String::as_str), Some(KEYS_HINT));
        assert!(lines.iter().all(|l| l.len() <= LINE_WIDTH + 2), "{lines:?}");

        let own = plan_own(&scene);
        let own = status_lines(&info(&scene, &own, None));
        assert_eq!(own[1], "Settings: the dummy scene's own");
        assert!(own[2].starts_with("Shadow: one "), "{own:?}");
    }

    fn plan_own(scene: &Scene) -> ShadowPlan {
        plan(scene, &scene.shadow)
    }

    #[test]
    fn other_lights_are_counted_in_words_and_a_cube_map_is_described() {
        let scene = Scene::load("three-lights").unwrap();
        let own = plan_own(&scene);
        let lines = status_lines(&info(&scene, &own, None));
        // The sun has an azimuth of its own: the angle is measured from it, and shown.
        let sun = scene.light().as_directional().unwrap();
        let angle = sun.angle_deg();
        assert_eq!(
            lines[0],
            format!("Light angle: {angle:.1} over azimuth {:.2}", sun.azimuth())
        );
        assert_eq!(lines[1], "and 3 more lights");
        let mut scene = Scene::load("point-shadows").unwrap();
        let own = plan_own(&scene);
        let lines = status_lines(&info(&scene, &own, None));
        assert!(lines[0].starts_with("Point light at"), "{lines:?}");
        let m = scene.shadow.map_size;
        assert!(
            joined(&lines).contains(&format!(
                "Shadow: a cube map, 6 faces of {} x {}, 24-bit depth, drawn in one pass",
                m.width, m.height
            )),
            "{lines:?}"
        );
        assert!(!lines.iter().any(|l| l == ANGLE_KEYS_IDLE), "{lines:?}");
        // The angle keys pressed on it: said in the HUD.
        let mut hud = info(&scene, &own, None);
        hud.angle_keys_idle = true;
        assert!(status_lines(&hud).iter().any(|l| l == ANGLE_KEYS_IDLE));
        assert!(!scene.set_light_angle(30.0));
        // Shadows off, and a light that casts none: said so.
        let off = plan(
            &scene,
            &ShadowSettings {
                shadows: false,
                ..scene.shadow
            },
        );
        assert!(status_lines(&info(&scene, &off, None)).contains(&"Shadows: off".to_string()));
    }

    #[test]
    fn past_the_overhead_the_hud_keeps_the_demos_azimuth() {
        let mut scene = Scene::load("learnopengl").unwrap();
        let azimuth = scene.light_azimuth().unwrap();
        assert!(scene.set_light_angle_about(azimuth, 120.0));
        let own = plan_own(&scene);
        let mut hud = info(&scene, &own, None);
        hud.azimuth = Some(azimuth);
        assert_eq!(
            status_lines(&hud)[0],
            "Light angle: 120.0 over azimuth [-0.89, 0.00, -0.45]"
        );
        // Measured from its own horizontal part, the light would read 60 the other way.
        hud.azimuth = None;
        assert_eq!(
            status_lines(&hud)[0],
            "Light angle: 60.0 over azimuth [0.89, 0.00, 0.45]"
        );
    }

    #[test]
    fn the_inset_sits_in_the_bottom_right_corner() {
        let r = inset_rect(640, 360).unwrap();
        assert_eq!((r.x, r.y, r.width, r.height), (542, 8, 90, 90));
        let r = inset_rect(1280, 720).unwrap();
        assert_eq!((r.x, r.y, r.width, r.height), (1092, 8, 180, 180));
        assert!(inset_rect(16, 16).is_none());
        assert!(inset_rect(1, 720).is_none());
    }

    #[test]
    fn panels_stay_in_the_top_left_and_the_key_panel_lists_every_key() {
        let atlas = FontAtlas::new(FONT, FONT_PX).unwrap();
        let scene = dummy_at(45.0);
        let own = plan_own(&scene);
        let mut hud = info(&scene, &own, None);
        let closed = layout(&atlas, &hud, (640, 360));
        hud.show_keys = true;
        let open = layout(&atlas, &hud, (640, 360));
        assert!(open.len() > closed.len());
        // The key panel replaces the hint with the keys and their descriptions.
        let glyphs = |s: &str| s.chars().filter(|c| !c.is_whitespace()).count();
        let keys: usize = KEYS.iter().map(|(k, d)| glyphs(k) + glyphs(d)).sum();
        assert_eq!(open.len(), closed.len() - glyphs(KEYS_HINT) + keys + 1);
        for q in &open {
            let [x0, y0, x1, y1] = q.rect;
            assert!(
                x0 >= 0.0 && y0 >= 0.0 && x1 <= 640.0 && y1 <= 360.0,
                "{q:?}"
            );
        }
    }

    /// The status panel's rectangle over `scene` at `size`, with `step`'s lesson; and
    /// whether it covers any of the scene's casters or translucent items.
    fn status_panel(scene: &Scene, step: Option<&str>, size: (u32, u32)) -> ([f32; 4], bool) {
        let atlas = FontAtlas::new(FONT, FONT_PX).unwrap();
        let settings = step.map_or(scene.shadow, |s| steps::settings_for(scene, s).unwrap());
        let plan = plan(scene, &settings);
        let rect = layout(&atlas, &info(scene, &plan, step), size)[0].rect;
        let shapes = place::silhouettes(scene, size);
        (rect, shapes.iter().any(|(_, h)| place::overlaps(h, rect)))
    }

    #[test]
    fn panels_keep_off_the_smoke_and_the_cubes_and_stay_left_where_they_can() {
        let (rect, covers) = status_panel(&dummy_at(45.0), None, (1280, 720));
        assert_eq!((rect[0], rect[1], covers), (MARGIN, MARGIN, false));
        let smoke = Scene::load("smoke").unwrap();
        let puffs = place::silhouettes(&smoke, (1280, 720));
        let left = [MARGIN, MARGIN, 420.0, 160.0];
        assert!(puffs.iter().any(|(t, h)| *t && place::overlaps(h, left)));
        let (rect, covers) = status_panel(&smoke, None, (1280, 720));
        assert!(
            rect[0] > 640.0 && !covers,
            "the status panel at {rect:?}, over the smoke"
        );
        // LearnOpenGL's top cube stands where the top-left panel would go; the cull-front
        // step's views show a cube close up.
        for (name, step) in [
            ("learnopengl", None),
            ("learnopengl", Some("cull-front")),
            ("dummy", Some("cull-front")),
        ] {
            let mut scene = Scene::load(name).unwrap();
            if let Some(step) = step {
                steps::get(&scene, step)
                    .unwrap()
                    .set_stage(&mut scene, false)
                    .unwrap();
            }
            let size = (scene.size[0], scene.size[1]);
            let (rect, covers) = status_panel(&scene, step, size);
            assert!(
                !covers,
                "{name} {step:?}: the status panel at {rect:?} covers a cube"
            );
        }
    }
}
