//! Scores a shadow-playground demo page's picture against this program's visibility for the
//! same step (`scripts/playground-originals.sh` makes both):
//!
//! ```sh
//! cargo run --release --example playground_score -- ORIGINAL.png PORT-VISIBILITY.png [DIFF.png]
//! ```
//!
//! ORIGINAL is the demo's canvas: red = 0.5 + 0.5 visibility and green 0 on geometry, the
//! (0.8, 0.9, 0.8) clear elsewhere. PORT-VISIBILITY is `render --shadow-out`: grey
//! visibility, alpha 0 off geometry. Only pixels that are geometry in both are scored; the
//! demo's canvas is antialiased, so its pixels blended with the clear colour (green above 0)
//! are left out.
//! Prints the shadow masks' IoU (visibility below [`SHADOW`]), the penumbra band's mean absolute
//! difference of visibility (pixels where either picture is in (0.02, 0.98), or next to its
//! own picture's mask edge) and the band's size in pixels. DIFF, when given, shows where
//! they differ: red where only the original is shadowed, blue where only this program is,
//! grey the difference of visibility elsewhere.

use std::process::ExitCode;

/// A pixel is in the shadow mask below this visibility: less than half lit by more than
/// either picture's 8-bit rounding (a PCF edge pixel at exactly one half reads 0.498 from the
/// demo's red, 0.502 from the grey here).
const SHADOW: f32 = 0.49;

/// One picture's visibility per pixel, `None` off geometry.
type Visibility = Vec<Option<f32>>;

fn load(path: &str) -> Result<(u32, u32, image::RgbaImage), String> {
    let img = image::open(path)
        .map_err(|e| format!("{path}: {e}"))?
        .to_rgba8();
    Ok((img.width(), img.height(), img))
}

fn original(img: &image::RgbaImage) -> Visibility {
    img.pixels()
        .map(|p| (p[1] <= 2).then(|| ((p[0] as f32 / 255.0 - 0.5) * 2.0).clamp(0.0, 1.0)))
        .collect()
}

fn port(img: &image::RgbaImage) -> Visibility {
    img.pixels()
        .map(|p| (p[3] == 255).then(|| p[0] as f32 / 255.0))
        .collect()
}

/// Whether pixel `i` of a `w` x `h` picture has an 8-connected neighbour on the other side
/// of the shadow mask.
fn at_edge(v: &Visibility, w: usize, h: usize, i: usize) -> bool {
    let Some(me) = v[i] else { return false };
    let (x, y) = ((i % w) as i64, (i / w) as i64);
    (-1..=1).any(|dy: i64| {
        (-1..=1).any(|dx: i64| {
            let (nx, ny) = (x + dx, y + dy);
            nx >= 0
                && ny >= 0
                && (nx as usize) < w
                && (ny as usize) < h
                && v[ny as usize * w + nx as usize].is_some_and(|n| (n < SHADOW) != (me < SHADOW))
        })
    })
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: cargo run --release --example playground_score -- ORIGINAL.png \
                 PORT-VISIBILITY.png [DIFF.png]\nscores a shadow-playground picture against \
                 this program's visibility for the same step (IoU of the shadow masks, the \
                 penumbra band's difference)";
    if let Err(code) = shadowmap::input::check_args(&args, 2..=3, usage) {
        return code;
    }
    let (a, b) = (&args[0], &args[1]);
    let (pa, pb) = match (load(a), load(b)) {
        (Ok(pa), Ok(pb)) => (pa, pb),
        (Err(e), _) | (_, Err(e)) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if (pa.0, pa.1) != (pb.0, pb.1) {
        eprintln!("error: {}x{} against {}x{}", pa.0, pa.1, pb.0, pb.1);
        return ExitCode::from(2);
    }
    let (w, h) = (pa.0 as usize, pa.1 as usize);
    let (o, p) = (original(&pa.2), port(&pb.2));
    let (mut both, mut either, mut band, mut sum) = (0u64, 0u64, 0u64, 0f64);
    let mut diff = image::RgbaImage::new(pa.0, pa.1);
    for i in 0..w * h {
        let (Some(vo), Some(vp)) = (o[i], p[i]) else {
            continue;
        };
        let (so, sp) = (vo < SHADOW, vp < SHADOW);
        let g = ((vo - vp).abs() * 255.0) as u8;
        let colour = match (so, sp) {
            (true, false) => [255, 0, 0, 255],
            (false, true) => [0, 0, 255, 255],
            _ => [g, g, g, 255],
        };
        diff.put_pixel((i % w) as u32, (i / w) as u32, image::Rgba(colour));
        both += (so && sp) as u64;
        either += (so || sp) as u64;
        let soft = |v: f32| v > 0.02 && v < 0.98;
        if soft(vo) || soft(vp) || at_edge(&o, w, h, i) || at_edge(&p, w, h, i) {
            band += 1;
            sum += (vo - vp).abs() as f64;
        }
    }
    let iou = if either == 0 {
        1.0
    } else {
        both as f64 / either as f64
    };
    let mean = if band == 0 { 0.0 } else { sum / band as f64 };
    if let Some(path) = args.get(2) {
        if let Err(e) = diff.save(path) {
            eprintln!("error: {path}: {e}");
            return ExitCode::from(2);
        }
    }
    println!("{iou:8.4} {mean:8.4} {band:8}");
    ExitCode::SUCCESS
}
