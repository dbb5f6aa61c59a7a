//! `shadowmap compare`: one frame scored against the exact reference, with pictures.

use std::path::Path;

use shadowmap::compare::{compare, CompareOptions};
use shadowmap::engine::HeadlessContext;
use shadowmap::image_data::ImageData;
use shadowmap::reference::{error_image, write_npy_f32_hw3, Metrics, RefPixel};
use shadowmap::{Error, Result};

use super::cli::CompareArgs;

pub fn run(args: &CompareArgs) -> Result<()> {
    let scene = args.scene.load()?;
    let settings = args.settings.apply(&scene)?;
    let (width, height) = args.scene.size(&scene);
    let dir = &args.out_dir;
    std::fs::create_dir_all(dir)
        .map_err(|e| Error::file(dir, format!("cannot create the output folder: {e}")))?;
    let context = HeadlessContext::new()?;
    args.settings.check(context.gl(), &scene, &settings)?;
    let opts = CompareOptions {
        width,
        height,
        supersample: args.supersample,
        band: args.band,
        light: args.light,
    };
    let c = compare(context.gl(), &scene, &settings, &opts)?;
    let vis = c.frame.visibility.as_deref().unwrap_or_default();

    if let Some(image) = c.frame.visibility_image() {
        image.save_png(&dir.join("visibility.png"))?;
    }
    reference_image(width, height, &c.reference.hard).save_png(&dir.join("reference.png"))?;
    let grey: Vec<u8> = c
        .frame
        .colour
        .rgba
        .chunks_exact(4)
        .map(|p| ((u32::from(p[0]) * 3 + u32::from(p[1]) * 6 + u32::from(p[2])) / 10) as u8)
        .collect();
    let error = error_image(
        width as usize,
        height as usize,
        vis,
        &c.reference.hard,
        &grey,
    );
    ImageData {
        width,
        height,
        rgba: error.concat(),
    }
    .save_png(&dir.join("error.png"))?;
    let g = &c.reference.gbuffer;
    let world: Vec<[f32; 3]> = (0..g.positions.len())
        .map(|i| c.reference.world_position(i).as_vec3().to_array())
        .collect();
    for (name, data) in [("positions.npy", &world), ("normals.npy", &g.normals)] {
        let path = dir.join(name);
        write_npy_f32_hw3(&path, g.width, g.height, data)
            .map_err(|e| Error::file(&path, format!("cannot write: {e}")))?;
    }
    let json = serde_json::json!({
        "scene": scene.name,
        "size": [width, height],
        "light": args.light,
        "light_description": scene.lights.get(args.light).map(|l| l.describe()),
        "settings": settings,
        "supersample": args.supersample,
        "band": args.band,
        "reference_triangles": c.reference.triangles,
        "reference_ms": c.reference.trace_ms,
        "metrics": c.metrics,
    });
    write_text(&dir.join("metrics.json"), &format!("{json:#}\n"))?;
    println!(
        "{}",
        summary(&scene.name, &settings.summary(), &c.metrics, args.band)
    );
    Ok(())
}

/// The one-line summary printed by `compare`.
pub fn summary(scene: &str, settings: &str, m: &Metrics, band: usize) -> String {
    let pct = |x: f64| format!("{:.3}%", x * 100.0);
    format!(
        "{scene} [{settings}]: misclassified {} (false shadow {}, false light {}) of {} receivers; \
         outside a {band}-px edge band {}; MAE vs supersampled {}",
        pct(m.misclassified_rate),
        pct(m.false_shadow_rate),
        pct(m.false_light_rate),
        m.receivers,
        pct(m.misclassified_outside_band_rate),
        m.mae.map_or("n/a".to_string(), |v| format!("{v:.4}")),
    )
}

/// The hard reference as the same kind of image as `--shadow-out`.
fn reference_image(width: u32, height: u32, hard: &[RefPixel]) -> ImageData {
    let rgba = hard
        .iter()
        .flat_map(|p| match p.covered {
            true => {
                let g = (p.visibility * 255.0).round() as u8;
                [g, g, g, 255]
            }
            false => [0, 0, 0, 0],
        })
        .collect();
    ImageData {
        width,
        height,
        rgba,
    }
}

fn write_text(path: &Path, text: &str) -> Result<()> {
    std::fs::write(path, text).map_err(|e| Error::file(path, format!("cannot write: {e}")))
}
