//! `shadowmap steps`: every chapter step rendered and measured, as PNGs and an HTML page.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::fmt::Write as _;

use shadowmap::compare::render_visibility;
use shadowmap::compare::{compute_reference, CompareOptions, Reference};
use shadowmap::engine::HeadlessContext;
use shadowmap::image_data::ImageData;
use shadowmap::output::{check_output_dir, write_into};
use shadowmap::reference::{error_image, Metrics};
use shadowmap::settings::LightProjection;
use shadowmap::{steps, Error, Result, ShadowSettings};

use super::cli::StepsArgs;
use super::plot::with_error_legend;

pub fn run(args: &StepsArgs) -> Result<()> {
    let mut scene = args.scene.load()?;
    // Shown from the scene's steps camera, unless a camera flag picks the view.
    let camera_flag = args.scene.camera_position.is_some()
        || args.scene.camera_rotation.is_some()
        || args.scene.camera_target.is_some();
    if !camera_flag {
        scene.camera = scene.steps_camera();
    }
    // With the lights' size its steps ask for, unless --light-size gives one.
    if args.scene.light_size.is_none() {
        scene.use_steps_light_size();
    }
    scene
        .items
        .iter_mut()
        .for_each(|i| i.spin = glam::Vec3::ZERO);
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
    let gl = context.gl();
    let opts = CompareOptions {
        rays: shadowmap::compare::AREA_RAYS,
        width,
        height,
        supersample: args.supersample,
        band: 1,
        light: 0,
    };
    // One reference per kind of light projection (orthographic: parallel rays; perspective:
    // rays to a point).
    let mut references: HashMap<LightProjection, Reference> = HashMap::new();
    let mut rows = Vec::new();
    // Every picture and the page, written together at the end.
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    // The first step is told against the chapter's start, each other against the one before.
    let mut previous = steps::start(&scene);
    for (i, step) in steps::of(&scene).iter().enumerate() {
        let settings = steps::settings_for(&scene, step.name)?;
        let changed = match changed_fields(&previous, &settings) {
            c if c.is_empty() => "nothing on this scene (the settings of the step before)".into(),
            c => c.join(", "),
        };
        previous = settings;
        let frame = render_visibility(gl, &scene, &settings, width, height, 0)?;
        let image = format!("{:02}-{}.png", i + 1, step.name);
        files.push((image.clone(), frame.colour.encode_png()?));
        let mut metrics: Option<Metrics> = None;
        let mut error_file = None;
        let mut area = None;
        if !settings.show_depth_map {
            let reference = match references.entry(settings.light_projection) {
                Entry::Occupied(e) => e.into_mut(),
                Entry::Vacant(e) => e.insert(compute_reference(gl, &scene, &settings, &opts)?),
            };
            let vis = frame.visibility.as_deref().unwrap_or_default();
            metrics = Some(reference.score(vis, 1));
            let grey: Vec<u8> = frame
                .colour
                .rgba
                .chunks_exact(4)
                .map(|p| ((u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10) as u8)
                .collect();
            // A light with a size: the errors against its area truth (the soft answer).
            let truth = reference
                .area
                .as_ref()
                .map_or(&reference.hard, |a| &a.pixels);
            area = reference.score_area(vis);
            let err = error_image(width as usize, height as usize, vis, truth, &grey);
            let name = format!("{:02}-{}-error.png", i + 1, step.name);
            let err = with_error_legend(ImageData {
                width,
                height,
                rgba: err.concat(),
            })?;
            files.push((name.clone(), err.encode_png()?));
            error_file = Some(name);
        }
        println!(
            "{:>2} {:<22} {}; changed: {changed}",
            i + 1,
            step.name,
            metrics
                .as_ref()
                .map(|m| format!(
                    "false shadow {:.3}%, false light {:.3}%, MAE {}",
                    m.false_shadow_rate * 100.0,
                    m.false_light_rate * 100.0,
                    m.mae.map_or("n/a".into(), |v| format!("{v:.4}"))
                ))
                .unwrap_or_else(|| "(depth map)".into())
        );
        if let Some(a) = &area {
            println!("   {}", super::compare::area_summary(a));
        }
        rows.push((step, settings, image, error_file, metrics, changed));
    }
    let mut html = String::new();
    let _ = write!(
        html,
        "<!doctype html>\n<html><head><meta charset=\"utf-8\"><title>shadowmap: the steps on {0}</title>\n\
         <style>body{{font-family:sans-serif;margin:2em;max-width:1400px}} figure{{display:inline-block;\
         vertical-align:top;width:620px;margin:0 1em 2em 0}} img{{width:300px;border:1px solid #ccc}}\
         figcaption{{font-size:14px}} td,th{{padding:2px 8px;text-align:right}} .n{{text-align:left}}</style>\n\
         </head><body>\n<h1>The chapter steps on the <code>{0}</code> scene</h1>\n\
         <p>Each step adds one change to the one before (variants, marked, do not carry over). Left: the \
         frame; right: its errors against the exact ray-traced reference (red = false shadow, blue = \
         false light). Figures are fractions of the receiver pixels (geometry facing the light); MAE \
         is against a {1}x{1} supersampled reference.{2}</p>\n",
        scene.name,
        args.supersample,
        match scene.light().size() {
            0.0 => String::new(),
            size => format!(
                " The light has a size ({size}): the error images are against its area truth \
                 ({} rays per pixel to its disc), and the terminal prints its figures.",
                shadowmap::compare::AREA_RAYS
            ),
        }
    );
    html.push_str("<table><tr><th class=n>step</th><th>false shadow</th><th>false light</th><th>outside 1-px edge band</th><th>MAE</th></tr>\n");
    for (step, _, _, _, m, _) in &rows {
        match m {
            Some(m) => {
                let _ = writeln!(
                    html,
                    "<tr><td class=n>{}</td><td>{:.3}%</td><td>{:.3}%</td><td>{:.3}%</td><td>{}</td></tr>",
                    step.name,
                    m.false_shadow_rate * 100.0,
                    m.false_light_rate * 100.0,
                    m.misclassified_outside_band_rate * 100.0,
                    m.mae.map_or("n/a".into(), |v| format!("{v:.4}"))
                );
            }
            None => {
                let _ = writeln!(
                    html,
                    "<tr><td class=n>{}</td><td colspan=4>depth map</td></tr>",
                    step.name
                );
            }
        }
    }
    html.push_str("</table>\n");
    for (i, (step, settings, image, error_file, m, changed)) in rows.iter().enumerate() {
        let figures = m
            .as_ref()
            .map(|m| {
                format!(
                    "false shadow {:.3}%, false light {:.3}%, MAE {}",
                    m.false_shadow_rate * 100.0,
                    m.false_light_rate * 100.0,
                    m.mae.map_or("n/a".into(), |v| format!("{v:.4}"))
                )
            })
            .unwrap_or_else(|| "no shadow test in this view".into());
        let err = error_file
            .as_ref()
            .map(|f| format!("<img src=\"{f}\" alt=\"errors of {}\">", step.name))
            .unwrap_or_default();
        let _ = writeln!(
            html,
            "<figure><img src=\"{image}\" alt=\"{name}\">{err}<figcaption><b>{n}. {name}</b>{variant}<br>\
             <i>Changed:</i> {change}<br><i>Settings changed:</i> {changed}<br>\
             <i>Look for:</i> {look}<br><i>Measured:</i> {figures}<br>\
             <small>{summary}</small></figcaption></figure>",
            n = i + 1,
            name = step.name,
            variant = if step.cumulative { "" } else { " (variant)" },
            change = step.change,
            look = step.look_for,
            summary = settings.summary(),
        );
    }
    html.push_str("</body></html>\n");
    let path = dir.join("index.html");
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
    println!("wrote {} and {} images", path.display(), rows.len());
    Ok(())
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
