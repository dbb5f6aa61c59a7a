//! `shadowmap steps`: every chapter step rendered and measured, as PNGs and an HTML page a
//! student reads beside the chapters: each step's frame and its errors side by side, the
//! lesson beside them, and every figure explained where it stands.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::fmt::Write as _;

use shadowmap::compare::render_visibility;
use shadowmap::compare::{compute_reference, CompareOptions, Reference};
use shadowmap::engine::HeadlessContext;
use shadowmap::image_data::ImageData;
use shadowmap::output::{check_output_dir, write_into};
use shadowmap::reference::{error_image, transmittance_error_image, Metrics, SoftMetrics};
use shadowmap::settings::LightProjection;
use shadowmap::steps::Step;
use shadowmap::{steps, Error, Result, Scene, ShadowSettings};

use super::cli::StepsArgs;
use super::plot::{with_error_legend, with_legend, TRANSMITTANCE_LEGEND};

/// One step as measured: what the page shows of it.
struct Row {
    step: &'static Step,
    settings: ShadowSettings,
    image: String,
    error_file: Option<String>,
    metrics: Option<Metrics>,
    area: Option<SoftMetrics>,
    changed: String,
    /// The step it builds on, measured in this step's view (its settings on this step's
    /// scene), so the two columns of its table differ by the step's change alone.
    before: Option<Before>,
    /// How many times brighter the frame is shown than drawn (1: as drawn).
    gain: f32,
    /// A depth map's greys in words: the depths they are stretched over.
    depth_range: Option<String>,
    /// How the step is shown on this scene (its stage) and why its picture is the one
    /// before's, where it is by design: HTML paragraphs, or empty.
    view: String,
}

/// A step's predecessor measured in the step's own view.
struct Before {
    /// Its name on the page ("step 5, cull-front").
    name: String,
    metrics: Metrics,
    area: Option<SoftMetrics>,
}

/// What every step is rendered and scored with.
struct Bench<'a> {
    gl: &'a shadowmap::engine::Gl,
    /// The scene as loaded with the flags, before any step: each step is shown from here
    /// by [`steps::stage`], as `render --step` shows it.
    loaded: &'a Scene,
    /// A flag picked the lights' size: the steps keep it.
    keep_light_size: bool,
    opts: CompareOptions,
    /// One reference per kind of light projection (orthographic: parallel rays;
    /// perspective: rays to a point) and per stage (a step's own view of the scene).
    references: HashMap<(LightProjection, Option<&'static str>), Reference>,
    /// A camera flag picked the view: the stages keep it.
    keep_camera: bool,
}

pub fn run(args: &StepsArgs) -> Result<()> {
    let mut loaded = args.scene.load()?;
    loaded
        .items
        .iter_mut()
        .for_each(|i| i.spin = glam::Vec3::ZERO);
    // The scene as the steps show it (the steps camera, unless a camera flag picks the
    // view; the steps' light size, unless --light-size gives one), for the page's words.
    let camera_flag = args.scene.camera_given();
    let keep_light_size = args.scene.light_size.is_some();
    let mut scene = loaded.clone();
    steps::show(&mut scene, "", camera_flag, keep_light_size)?;
    let (width, height) = args.scene.size(&scene);
    let dir = &args.out_dir;
    // Checked before any GL work; the folder is made when the first picture is ready.
    check_output_dir("--out-dir", dir)?;
    if !scene.light().casts_shadows() {
        return Err(Error::Invalid(format!(
            "{}: the first light does not cast shadows (casts_shadows = false): the steps \
             measure the first light; expected a scene whose first light casts",
            scene.source.display()
        )));
    }
    let context = HeadlessContext::new()?;
    let mut bench = Bench {
        gl: context.gl(),
        loaded: &loaded,
        keep_light_size,
        opts: CompareOptions {
            rays: shadowmap::compare::AREA_RAYS,
            width,
            height,
            supersample: args.supersample,
            band: 1,
            light: 0,
        },
        references: HashMap::new(),
        keep_camera: camera_flag,
    };
    let mut rows = Vec::new();
    // Every picture and the page, written together at the end.
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    // Each step is told against the last step that carries over (variants do not), the
    // first against the chapter's start.
    let start = match scene.steps.list {
        shadowmap::scene::StepList::Volumetric => "the scene's own settings",
        shadowmap::scene::StepList::Chapters | shadowmap::scene::StepList::Playground => {
            "the chapter's start"
        }
    };
    let mut base = (steps::start(&scene), start.to_string());
    for (i, step) in steps::of(&scene).iter().enumerate() {
        let row = bench.measure(i + 1, step, &base, &mut files)?;
        if step.cumulative {
            base = (row.settings, format!("step {}, {}", i + 1, step.name));
        }
        rows.push(row);
    }
    let html = page(&scene, args.supersample, &rows);
    files.push(("index.html".into(), html.into_bytes()));
    let batch: Vec<(&str, &str, &[u8])> = files
        .iter()
        .map(|(name, bytes)| {
            let what = match name.ends_with(".png") {
                true => "the image",
                false => "the page",
            };
            (name.as_str(), what, bytes.as_slice())
        })
        .collect();
    write_into(dir, &batch)?;
    let names: Vec<&str> = files.iter().map(|(name, _)| name.as_str()).collect();
    println!("wrote {}: {}", dir.display(), names.join(", "));
    Ok(())
}

impl Bench<'_> {
    /// Renders step number `n`, scores it (unless it shows a depth map), adds its pictures
    /// to `files` and prints its line; `base` is the settings it builds on, and their name.
    fn measure(
        &mut self,
        n: usize,
        step: &'static Step,
        base: &(ShadowSettings, String),
        files: &mut Vec<(String, Vec<u8>)>,
    ) -> Result<Row> {
        let (gl, opts) = (self.gl, &self.opts);
        let (width, height) = (opts.width, opts.height);
        // The step as `render --step` shows it: its view of the scene and its settings.
        let mut scene = self.loaded.clone();
        let settings = steps::stage(
            &mut scene,
            step.name,
            self.keep_camera,
            self.keep_light_size,
        )?;
        let scene = &scene;
        let changed = match changed_fields(&base.0, &settings) {
            c if c.is_empty() => format!("nothing on this scene against {}", base.1),
            c => format!("{} (against {})", c.join(", "), base.1),
        };
        let stage = step.stage(scene);
        let mut view = view_notes(step, scene);
        let frame = render_visibility(gl, scene, &settings, width, height, 0)?;
        // A dim scene (LearnOpenGL's light colour is 0.3) is shown brighter to be read; a
        // depth map is shown as drawn.
        let (colour, gain) = match settings.show_depth_map {
            true => (frame.colour.clone(), 1.0),
            false => brightened(&frame.colour),
        };
        let image = format!("{n:02}-{}.png", step.name);
        files.push((image.clone(), colour.encode_png()?));
        let (mut metrics, mut error_file, mut area) = (None, None, None);
        let (mut transmittance, mut before) = (None, None);
        if !settings.show_depth_map {
            let key = (settings.light_projection, stage.map(|s| s.note));
            let reference = match self.references.entry(key) {
                Entry::Occupied(e) => e.into_mut(),
                Entry::Vacant(e) => e.insert(compute_reference(gl, scene, &settings, opts)?),
            };
            let vis = frame.visibility.as_deref().unwrap_or_default();
            metrics = Some(reference.score(vis, 1));
            area = reference.score_area(vis);
            transmittance = reference.score_transmittance(vis);
            let err = error_picture(reference, vis, &colour)?;
            let name = format!("{n:02}-{}-error.png", step.name);
            files.push((name.clone(), err.encode_png()?));
            error_file = Some(name);
            if let Some(note) = outside_note(gl, scene, step, &settings, reference, opts)? {
                let _ = write!(view, "<p><b>Outside the light's box:</b> {note}</p>");
            }
            // What it builds on, in this view and against the same reference.
            if base.0.light_projection == settings.light_projection {
                before = Some(measure_before(gl, scene, base, reference, opts)?);
            }
        }
        let figures = match (&metrics, frame.depth_view_range) {
            (Some(m), _) => line_figures(m),
            (None, Some(range)) => format!("(depth map; {})", range.words()),
            (None, None) => "(depth map)".into(),
        };
        println!("{n:>2} {:<22} {figures}; changed: {changed}", step.name);
        if let Some(b) = &before {
            println!("   {} in this view: {}", b.name, line_figures(&b.metrics));
        }
        if let Some(a) = &area {
            println!("   {}", super::compare::area_summary(a));
        }
        if let Some(t) = transmittance {
            println!("   {}", transmittance_line(&t));
        }
        Ok(Row {
            step,
            settings,
            image,
            error_file,
            metrics,
            area,
            changed,
            before,
            gain,
            depth_range: frame.depth_view_range.map(|r| r.words()),
            view,
        })
    }
}

/// How a step is shown on `scene` and why its picture is the one before's, where it is by
/// design: HTML paragraphs, or empty.
fn view_notes(step: &Step, scene: &Scene) -> String {
    let mut view = String::new();
    if let Some(note) = step.stage(scene).map(|s| s.note) {
        let _ = write!(view, "<p><b>Shown here:</b> {}</p>", escape(note));
    }
    if let Some(why) = step.same_picture_on(scene) {
        let _ = write!(view, "<p><b>The same picture:</b> {}</p>", escape(why));
    }
    view
}

/// The settings a step builds on (`base`: them and their name), drawn on the step's scene
/// and scored against its reference.
fn measure_before(
    gl: &shadowmap::engine::Gl,
    scene: &Scene,
    base: &(ShadowSettings, String),
    reference: &Reference,
    opts: &CompareOptions,
) -> Result<Before> {
    let was = render_visibility(gl, scene, &base.0, opts.width, opts.height, 0)?;
    let vis = was.visibility.as_deref().unwrap_or_default();
    Ok(Before {
        name: base.1.clone(),
        metrics: reference.score(vis, 1),
        area: reference.score_area(vis),
    })
}

/// Where a step still wraps the map with REPEAT or CLAMP_TO_EDGE, or shadows what lies
/// beyond the far plane (the chapter's start), and that puts false shadow on floor outside
/// the light's box: how much, measured as the false shadow that LearnOpenGL's fix (a border
/// of depth 1, z > 1 lit) takes away in the same view, and which steps explain it. `None`
/// where it is under 0.5% of the receivers, or the step is one of those that explain it.
fn outside_note(
    gl: &shadowmap::engine::Gl,
    scene: &Scene,
    step: &Step,
    settings: &ShadowSettings,
    reference: &Reference,
    opts: &CompareOptions,
) -> Result<Option<String>> {
    use shadowmap::settings::{BeyondFar, Wrap};
    let list = steps::of(scene);
    let explained: Vec<usize> = (list.iter().enumerate())
        .filter(|(_, s)| s.name.starts_with("over-sampling"))
        .map(|(i, _)| i + 1)
        .collect();
    let fixed_already =
        settings.wrap == Wrap::ClampToBorder && settings.beyond_far == BeyondFar::Lit;
    let (Some(first), Some(last)) = (explained.first(), explained.last()) else {
        return Ok(None);
    };
    if fixed_already
        || step.name.starts_with("over-sampling")
        || settings.light_projection != LightProjection::Ortho
    {
        return Ok(None);
    }
    let fixed = ShadowSettings {
        wrap: Wrap::ClampToBorder,
        beyond_far: BeyondFar::Lit,
        ..*settings
    };
    let (w, h) = (opts.width, opts.height);
    let frame = render_visibility(gl, scene, &fixed, w, h, 0)?;
    let vis = frame.visibility.as_deref().unwrap_or_default();
    let with_fix = reference.score(vis, 1);
    let here = reference.score(
        render_visibility(gl, scene, settings, w, h, 0)?
            .visibility
            .as_deref()
            .unwrap_or_default(),
        1,
    );
    let outside = percent(
        here.false_shadow.saturating_sub(with_fix.false_shadow),
        here.receivers,
    );
    if outside < 0.5 {
        return Ok(None);
    }
    Ok(Some(format!(
        "{outside:.1}% of the receivers are red only because this step still wraps the map \
         with {} and counts what lies beyond the light's far plane as {} (the chapter's \
         start): floor outside the light's box. Steps {first} to {last} (over-sampling) \
         explain and fix it; with their fix in this same view the false shadow is {:.3}%, \
         the part this step's lesson is about.",
        settings.wrap.name(),
        settings.beyond_far.name(),
        with_fix.false_shadow_rate * 100.0
    )))
}

/// The brightest receivers' level a frame is brought up to on the page.
const SHOWN_LEVEL: f32 = 230.0;

/// `frame` brightened so that its brightest pixels (the 99th percentile of the largest
/// channel) reach [`SHOWN_LEVEL`], by at most 4 times, and the gain; a frame already
/// that bright is returned as it is.
fn brightened(frame: &ImageData) -> (ImageData, f32) {
    let mut levels: Vec<u8> = (frame.rgba.chunks_exact(4))
        .map(|p| p[0].max(p[1]).max(p[2]))
        .collect();
    levels.sort_unstable();
    let top = levels.get(levels.len() * 99 / 100).copied().unwrap_or(255);
    let gain = (SHOWN_LEVEL / f32::from(top.max(1))).min(4.0);
    if gain < 1.2 {
        return (frame.clone(), 1.0);
    }
    let rgba = (frame.rgba.chunks_exact(4))
        .flat_map(|p| {
            let up = |c: u8| (f32::from(c) * gain).round().min(255.0) as u8;
            [up(p[0]), up(p[1]), up(p[2]), p[3]]
        })
        .collect();
    let shown = ImageData {
        width: frame.width,
        height: frame.height,
        rgba,
    };
    (shown, gain)
}

/// A step's errors, drawn over the frame in grey: against the transmittance truth where the
/// scene has translucent casters (its lesson is their grey shadows), else against the area
/// light's truth for a light with a size (the soft answer), else the hard truth.
fn error_picture(
    reference: &Reference,
    vis: &[Option<f32>],
    frame: &ImageData,
) -> Result<ImageData> {
    let (width, height) = (frame.width, frame.height);
    let grey: Vec<u8> = (frame.rgba.chunks_exact(4))
        .map(|p| ((u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10) as u8)
        .collect();
    let picture = |rgba: Vec<[u8; 4]>| ImageData {
        width,
        height,
        rgba: rgba.concat(),
    };
    if let Some(truth) = &reference.transmittance {
        let err = transmittance_error_image(vis, truth, &grey);
        return with_legend(picture(err), &TRANSMITTANCE_LEGEND);
    }
    let truth = (reference.area.as_ref()).map_or(&reference.hard, |a| &a.pixels);
    let err = error_image(width as usize, height as usize, vis, truth, &grey);
    with_error_legend(picture(err))
}

/// A step's error against the transmittance truth, for a scene with translucent casters.
fn transmittance_line(t: &shadowmap::reference::TransmittanceMetrics) -> String {
    format!(
        "transmittance: MAE {:.4} (within the translucent shadow {:.4}, outside it {:.4})",
        t.mae, t.mae_in_shadow, t.mae_outside
    )
}

/// The terminal's figures of a step.
fn line_figures(m: &Metrics) -> String {
    format!(
        "false shadow {:.3}%, false light {:.3}%, MAE {}",
        m.false_shadow_rate * 100.0,
        m.false_light_rate * 100.0,
        mae(m)
    )
}

fn mae(m: &Metrics) -> String {
    m.mae.map_or("n/a".into(), |v| format!("{v:.4}"))
}

/// `count` as a percentage of `of` (0 when `of` is).
fn percent(count: usize, of: usize) -> f64 {
    match of {
        0 => 0.0,
        _ => count as f64 * 100.0 / of as f64,
    }
}

/// Text for HTML: `&`, `<`, `>` and `"` escaped.
fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em auto;max-width:1700px;padding:0 1em;\
line-height:1.4;color:#222} h2{margin:0 0 .4em;border-bottom:1px solid #ccc} code{background:#f3f3f3;\
padding:0 .2em} .step{margin:0 0 2.5em} .row{display:grid;grid-template-columns:minmax(0,1fr) \
minmax(0,1fr) minmax(18em,.8fr);gap:1em;align-items:start} figure{margin:0} figure img{width:100%;\
border:1px solid #bbb;display:block} figcaption{font-size:13px;color:#555} .lesson p{margin:0 0 .6em}\
 table{border-collapse:collapse;font-size:14px} td,th{padding:2px 8px;text-align:right;\
border-bottom:1px solid #eee} .n{text-align:left} .none{color:#777;font-style:italic;padding:1em;\
border:1px dashed #bbb} dl.key dt{font-weight:bold;margin-top:.4em} dl.key dd{margin-left:1.5em}";

/// The whole page: how to read it, the overview table, then one section per step.
fn page(scene: &Scene, supersample: u32, rows: &[Row]) -> String {
    let mut html = String::new();
    let _ = write!(
        html,
        "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <title>shadowmap: the steps on {name}</title>\n<style>{STYLE}</style></head><body>\n\
         <h1>The steps on the <code>{name}</code> scene</h1>\n",
        name = escape(&scene.name)
    );
    html.push_str(&how_to_read(scene, supersample));
    html.push_str(&overview(rows));
    for (i, row) in rows.iter().enumerate() {
        html.push_str(&section(i + 1, row));
    }
    html.push_str("</body></html>\n");
    html
}

/// What the pictures and every figure on the page count.
fn how_to_read(scene: &Scene, supersample: u32) -> String {
    let area = match scene.light().size() {
        0.0 => String::new(),
        size => format!(
            "<p>The light has a size ({size}): the error images are against its area truth \
             ({} rays per pixel to its disc), and each step also lists the figures against it.</p>\n",
            shadowmap::compare::AREA_RAYS
        ),
    };
    let translucent = shadowmap::shadows::volumetric::translucent_casters(scene).count() > 0;
    let area = match translucent {
        false => area,
        true => format!(
            "{area}<p>The scene has translucent casters: the error images are against the \
             transmittance truth (the product of 1 - opacity over every crossing), red where \
             the frame is too dark, blue where too bright, full colour at 0.5 off; each step \
             also prints its transmittance error.</p>\n"
        ),
    };
    let chapters = scene.steps.list == shadowmap::scene::StepList::Chapters;
    let area = match chapters && !steps::STAGED_SCENES.contains(&scene.name.as_str()) {
        true => format!("{area}<p>{}</p>\n", escape(steps::UNSTAGED_WHY)),
        false => area,
    };
    format!(
        "<p>Each step adds one change to the one before it (a <i>variant</i> shows a choice \
         and does not carry over); each is drawn as <code>shadowmap render --step NAME</code> \
         draws it, some from a view of their own, and its table sets beside its figures those \
         of the step it builds on drawn in the same view, so the two differ by the step's \
         change alone. Left: the frame as the step draws it. Middle: the same frame \
         with its errors marked against an exact ray-traced reference: <b style=\"color:#d00\">red</b> \
         is false shadow (drawn dark where the light reaches), <b style=\"color:#00d\">blue</b> \
         false light (drawn lit where the light is blocked), grey agrees. Right: what changed, \
         what to look for, and what was measured.</p>\n{area}\
         <dl class=\"key\"><dt>receivers</dt><dd>the pixels that are scored: geometry that \
         faces the light, as the reference sees it. Every percentage below is a share of them, \
         so the figures add up.</dd>\
         <dt>false shadow, false light</dt><dd>receivers the shadow test got wrong, each way \
         (a pixel is wrong when its visibility is more than 0.5 off the reference's).</dd>\
         <dt>misclassified</dt><dd>false shadow + false light.</dd>\
         <dt>at edges / away from edges</dt><dd>the misclassified receivers split by where \
         they lie: within 1 pixel of a true shadow edge, where a map of any finite resolution \
         differs, or away from every edge, where the error is the technique's (acne, peter \
         panning, the far plane). Both are shares of all receivers: at edges + away = \
         misclassified.</dd>\
         <dt>MAE</dt><dd>the mean absolute difference between the drawn visibility and a \
         {supersample}&times;{supersample} supersampled reference, over the receivers: it \
         also counts how soft an edge is, which the pixel counts do not.</dd></dl>\n"
    )
}

/// The misclassified receivers away from every edge, as a share of all receivers (the
/// metrics' own rate is a share of the receivers away from edges, which can exceed the
/// total's rate when the edges are mostly right).
fn away_from_edges(m: &Metrics) -> f64 {
    percent(m.misclassified_outside_band, m.receivers)
}

/// The misclassified receivers within a pixel of a true shadow edge, as a share of all
/// receivers.
fn at_edges(m: &Metrics) -> f64 {
    percent(m.misclassified - m.misclassified_outside_band, m.receivers)
}

/// A row of the area light's table: its label and how its value is shown.
type AreaLine = (&'static str, fn(&SoftMetrics) -> String);

/// A row of a step's table: its label, its percentage and what it counts.
type FigureLine = (&'static str, fn(&Metrics) -> f64, &'static str);

/// The figures against the area light's truth (a light with a size), beside the step
/// before's.
fn area_figures(a: &SoftMetrics, was: Option<(&str, &SoftMetrics)>) -> String {
    let lines: [AreaLine; 4] = [
        ("MAE <small>(mean visibility error)</small>", |a| {
            format!("{:.4}", a.mae)
        }),
        (
            "light bleeding <small>(lit above 0.5 where the truth is in full shadow)</small>",
            |a| format!("{:.3}%", a.light_bleed_rate * 100.0),
        ),
        (
            "penumbra width, px <small>(10% to 90%, across the truth's edges)</small>",
            |a| format!("{:.2}", a.penumbra_width_px),
        ),
        (
            "its error, px <small>(mean |drawn - truth| per edge)</small>",
            |a| format!("{:.2}", a.penumbra_width_error_px),
        ),
    ];
    let mut html = format!(
        "<table><tr><th class=n>against the area light ({} rays a pixel; the truth's \
         penumbra: {:.2} px over {} edges)</th><th>here</th>{}</tr>\n",
        a.rays,
        a.penumbra_width_truth_px,
        a.penumbra_edges,
        was.map_or(String::new(), |(name, _)| format!("<th>{name}</th>"))
    );
    for (label, value) in lines {
        let _ = writeln!(
            html,
            "<tr><td class=n>{label}</td><td>{}</td>{}</tr>",
            value(a),
            was.map_or(String::new(), |(_, p)| format!("<td>{}</td>", value(p)))
        );
    }
    html.push_str("</table>\n");
    html
}

/// One table with every step's figures, to follow them down the chapter.
fn overview(rows: &[Row]) -> String {
    let mut html = format!(
        "<h2>All steps</h2>\n<table><tr><th class=n>step</th><th>false shadow</th>\
         <th>false light</th><th>misclassified</th><th>of which away from edges</th>\
         <th>MAE</th>{}</tr>\n",
        match rows.iter().any(|r| r.area.is_some()) {
            true => "<th>MAE against the area light</th><th>penumbra width px (truth)</th>",
            false => "",
        }
    );
    for (i, row) in rows.iter().enumerate() {
        let name = format!(
            "<a href=\"#{0}\">{1}. {0}</a>{2}",
            row.step.name,
            i + 1,
            if row.step.cumulative {
                ""
            } else {
                " (variant)"
            }
        );
        let _ = match &row.metrics {
            Some(m) => writeln!(
                html,
                "<tr><td class=n>{name}</td><td>{:.3}%</td><td>{:.3}%</td><td>{:.3}%</td>\
                 <td>{:.3}%</td><td>{}</td>{}</tr>",
                m.false_shadow_rate * 100.0,
                m.false_light_rate * 100.0,
                m.misclassified_rate * 100.0,
                away_from_edges(m),
                mae(m),
                row.area.as_ref().map_or(String::new(), |a| format!(
                    "<td>{:.4}</td><td>{:.2} ({:.2})</td>",
                    a.mae, a.penumbra_width_px, a.penumbra_width_truth_px
                ))
            ),
            None => writeln!(
                html,
                "<tr><td class=n>{name}</td><td colspan=7 class=n>a depth map: no shadow test \
                 to score</td></tr>"
            ),
        };
    }
    html.push_str("</table>\n");
    html
}

/// One step: its frame and its errors side by side, the lesson beside them.
fn section(n: usize, row: &Row) -> String {
    let name = row.step.name;
    let errors = match &row.error_file {
        Some(f) => format!(
            "<figure><a href=\"{f}\"><img src=\"{f}\" alt=\"errors of {name}\"></a>\
             <figcaption>Its errors: red false shadow, blue false light.</figcaption></figure>"
        ),
        None => "<p class=\"none\">No errors image: this step shows the shadow map itself, \
                 not a frame with a shadow test.</p>"
            .into(),
    };
    let figures = match &row.metrics {
        Some(m) => figures(m, row.before.as_ref(), row.area.as_ref()),
        None => String::new(),
    };
    let frame = match (row.gain, &row.depth_range) {
        (_, Some(range)) => format!("The shadow map: {}.", escape(range)),
        (1.0, None) => "The frame.".to_string(),
        (g, None) => format!("The frame, shown {g:.1} times as bright as drawn, to be read."),
    };
    format!(
        "<section class=\"step\" id=\"{name}\"><h2>{n}. {name}{variant}</h2>\n<div class=\"row\">\
         <figure><a href=\"{image}\"><img src=\"{image}\" alt=\"{name}\"></a>\
         <figcaption>{frame}</figcaption></figure>\n{errors}\n<div class=\"lesson\">\
         <p><b>What changed:</b> {change}</p><p><b>Look for:</b> {look}</p>{view}\
         <p><b>Settings changed:</b> {changed}</p>{figures}\
         <p><small>All settings: {summary}</small></p></div></div></section>\n",
        variant = if row.step.cumulative {
            ""
        } else {
            " (a variant)"
        },
        image = row.image,
        change = escape(row.step.change),
        look = escape(row.step.look_for),
        changed = escape(&row.changed),
        view = row.view,
        summary = escape(&row.settings.summary()),
    )
}

/// A step's figures with what each counts, and the step before's for comparison.
fn figures(m: &Metrics, before: Option<&Before>, area: Option<&SoftMetrics>) -> String {
    let label = before.map(|b| format!("{}, in this view", b.name));
    let was = before.map(|b| (label.as_deref().unwrap_or_default(), &b.metrics));
    let lines: [FigureLine; 5] = [
        (
            "false shadow",
            |m| m.false_shadow_rate * 100.0,
            "dark where the light reaches",
        ),
        (
            "false light",
            |m| m.false_light_rate * 100.0,
            "lit where the light is blocked",
        ),
        (
            "misclassified",
            |m| m.misclassified_rate * 100.0,
            "the two together",
        ),
        ("at edges", at_edges, "within 1 px of a true shadow edge"),
        (
            "away from edges",
            away_from_edges,
            "the technique's own error",
        ),
    ];
    let mut html = format!(
        "<table><tr><th class=n>against the exact hard reference{}, of {} receivers</th>\
         <th>here</th>{}</tr>\n",
        if area.is_some() {
            " (rays to the light's centre)"
        } else {
            ""
        },
        m.receivers,
        was.map_or(String::new(), |(name, _)| format!("<th>{name}</th>"))
    );
    for (label, value, says) in lines {
        let _ = writeln!(
            html,
            "<tr><td class=n>{label} <small>({says})</small></td><td>{:.3}%</td>{}</tr>",
            value(m),
            was.map_or(String::new(), |(_, p)| format!("<td>{:.3}%</td>", value(p)))
        );
    }
    let _ = writeln!(
        html,
        "<tr><td class=n>MAE <small>(mean visibility error)</small></td><td>{}</td>{}</tr></table>",
        mae(m),
        was.map_or(String::new(), |(_, p)| format!("<td>{}</td>", mae(p)))
    );
    if let Some(a) = area {
        html.push_str(&area_figures(
            a,
            before.and_then(|b| Some((label.as_deref()?, b.area.as_ref()?))),
        ));
    }
    html
}

/// The settings that differ between two steps, as "name old -> new": both serialised
/// with serde_json and compared key by key, so every field counts, new ones included.
pub fn changed_fields(before: &ShadowSettings, after: &ShadowSettings) -> Vec<String> {
    let (Ok(serde_json::Value::Object(a)), Ok(serde_json::Value::Object(b))) =
        (serde_json::to_value(before), serde_json::to_value(after))
    else {
        return Vec::new();
    };
    // Settings are f32: shown in their own shortest form (0.05, not 0.05000000074505806).
    let show = |v: &serde_json::Value| match v {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Number(n) if n.is_f64() => n
            .as_f64()
            .map_or_else(|| n.to_string(), |f| format!("{:?}", f as f32)),
        other => other.to_string(),
    };
    b.iter()
        .filter(|(key, value)| a.get(*key) != Some(*value))
        .map(|(key, value)| {
            let old = a.get(key).map(show).unwrap_or_default();
            format!("{} {old} -> {}", key.replace('_', " "), show(value))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn changed_fields_name_each_difference() {
        let scene = shadowmap::Scene::load("learnopengl").unwrap();
        let cull = steps::settings_for(&scene, "cull-front").unwrap();
        let repeat = steps::settings_for(&scene, "over-sampling-repeat").unwrap();
        let book = steps::settings_for(&scene, "over-sampling-book").unwrap();
        let fixed = steps::settings_for(&scene, "over-sampling").unwrap();
        // LearnOpenGL already wraps with REPEAT before its over-sampling steps.
        assert_eq!(changed_fields(&cull, &repeat), Vec::<String>::new());
        let bias = steps::settings_for(&scene, "bias").unwrap();
        let slope = steps::settings_for(&scene, "slope-bias").unwrap();
        assert_eq!(
            changed_fields(&bias, &slope),
            vec!["bias 0.005 -> 0.05", "bias mode constant -> slope"]
        );
        assert_eq!(
            changed_fields(&repeat, &book),
            vec!["wrap repeat -> clamp-to-edge"]
        );
        assert_eq!(
            changed_fields(&book, &fixed),
            vec![
                "beyond far shadowed -> lit",
                "wrap clamp-to-edge -> clamp-to-border"
            ]
        );
    }
}
