//! Pictures that explain themselves: `pareto.png` (error against time for every
//! benchmarked configuration, both log axes labelled, the Pareto front's points named and
//! the tutorials' configurations circled) and the colour legend under every error image.

use plotters::prelude::*;
use shadowmap::bench::{BenchRow, Family};
use shadowmap::image_data::ImageData;
use shadowmap::scale::{Axis, Pass, PowerFit, ScaleRow};
use shadowmap::{Error, Result};

const WIDTH: u32 = 1100;
const HEIGHT: u32 = 700;
/// Errors are drawn on a log axis; zero is drawn at this floor (in percent).
const ERROR_FLOOR_PCT: f64 = 0.001;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// Makes the embedded font the plots' "sans-serif" (no system fonts are needed).
fn register_font() -> std::result::Result<(), String> {
    // Registering twice is harmless.
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "the embedded font is not readable".to_string())
}

/// The Pareto plot's axes: log scales with our own ticks.
type LogAxis = plotters::coord::combinators::WithKeyPoints<LogCoord<f64>>;
type ParetoChart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<LogAxis, LogAxis>>;

/// Why pareto.png could not be drawn.
fn pareto_err(e: &dyn std::fmt::Display) -> Error {
    Error::Invalid(format!("cannot draw pareto.png: {e}"))
}

/// A row's place on the Pareto plot: (median wall ms, error in percent), both kept above
/// zero for the log axes.
fn pareto_at(r: &BenchRow) -> (f64, f64) {
    (
        r.wall_ms.median.max(1e-6),
        (r.error() * 100.0).max(ERROR_FLOOR_PCT),
    )
}

/// The PNG bytes of the Pareto plot.
pub fn pareto_png(title: &str, rows: &[BenchRow]) -> Result<Vec<u8>> {
    let err = pareto_err;
    register_font().map_err(|e| err(&e))?;
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        // Log axes with our own ticks: plotters' own label only the powers of ten, often
        // just one or two on a frame-time axis.
        let (x_lo, x_hi) = padded_range(rows.iter().map(|r| pareto_at(r).0), 1.15);
        let (y_lo, y_hi) = padded_range(rows.iter().map(|r| pareto_at(r).1), 1.6);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(log_axis(x_lo, x_hi), log_axis(y_lo, y_hi))
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("wall time per frame, median (ms, glFinish), log scale")
            .y_desc(format!(
                "{}, log scale (0 drawn at the bottom)",
                rows.first().map_or("error", |r| r.error_name())
            ))
            .x_label_formatter(&|v| tick_label(*v))
            .y_label_formatter(&|&v| match v <= ERROR_FLOOR_PCT * 1.0001 {
                true => format!("≤{}%", tick_label(v)),
                false => format!("{}%", tick_label(v)),
            })
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        draw_families(&mut chart, rows)?;
        draw_front(&mut chart, rows)?;
        draw_tutorials(&mut chart, rows)?;
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    rgb_image(WIDTH, HEIGHT, &buf).encode_png()
}

/// One series per kind of shadow (one map, cascades, a point light's two ways of drawing
/// its cube), each in its own colour.
fn draw_families(chart: &mut ParetoChart<'_, '_>, rows: &[BenchRow]) -> Result<()> {
    for family in Family::ALL {
        let colour = match family {
            Family::OneMap => RGBColor(150, 150, 150),
            Family::Cascades => RGBColor(20, 150, 60),
            Family::Groups => RGBColor(0, 170, 200),
            Family::PointLayered => RGBColor(140, 60, 190),
            Family::PointSixPasses => RGBColor(230, 140, 20),
            Family::Volumes => RGBColor(220, 30, 30),
            Family::Soft => RGBColor(30, 110, 220),
        };
        let points: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.config.family == family)
            .map(pareto_at)
            .collect();
        if points.is_empty() {
            continue;
        }
        chart
            .draw_series(
                points
                    .into_iter()
                    .map(|p| Circle::new(p, 3, colour.filled())),
            )
            .map_err(|e| pareto_err(&e))?
            .label(family.name())
            .legend(move |(x, y)| Circle::new((x, y), 3, colour.filled()));
    }
    Ok(())
}

/// The Pareto front as a staircase (each step holds the best error reached so far), each
/// of its points named.
fn draw_front(chart: &mut ParetoChart<'_, '_>, rows: &[BenchRow]) -> Result<()> {
    let at = pareto_at;
    let mut front: Vec<&BenchRow> = rows.iter().filter(|r| r.pareto).collect();
    front.sort_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median));
    let mut steps = Vec::new();
    for (i, r) in front.iter().enumerate() {
        if i > 0 {
            steps.push((at(r).0, at(front[i - 1]).1));
        }
        steps.push(at(r));
    }
    chart
        .draw_series(LineSeries::new(steps, RED.stroke_width(2)))
        .map_err(|e| pareto_err(&e))?
        .label("Pareto front (named)")
        .legend(|(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], RED.stroke_width(2)));
    // Each front point with its configuration's name, alternating above and below so
    // neighbours do not overlap.
    for (i, r) in front.iter().enumerate() {
        let dy = if i % 2 == 0 { -16 } else { 6 };
        chart
            .draw_series([EmptyElement::at(at(r))
                + Circle::new((0, 0), 4, RED.filled())
                + Text::new(
                    short_label(r),
                    (7, dy),
                    ("sans-serif", 12).into_font().color(&RGBColor(160, 0, 0)),
                )])
            .map_err(|e| pareto_err(&e))?;
    }
    Ok(())
}

/// The tutorials' configurations, circled and named.
fn draw_tutorials(chart: &mut ParetoChart<'_, '_>, rows: &[BenchRow]) -> Result<()> {
    for r in rows.iter().filter(|r| r.config.tutorial.is_some()) {
        let name = r.config.tutorial.unwrap_or_default();
        chart
            .draw_series([EmptyElement::at(pareto_at(r))
                + Circle::new((0, 0), 6, BLUE.stroke_width(2))
                + Text::new(
                    name.to_string(),
                    (-30, -24),
                    ("sans-serif", 16).into_font().color(&BLUE),
                )])
            .map_err(|e| pareto_err(&e))?;
    }
    Ok(())
}

/// The PNG bytes of `scale.png`: one log-log panel per axis, each pass' median time against
/// the work, with the fitted line and its exponent in the legend.
pub fn scale_png(rows: &[ScaleRow], fits: &[PowerFit]) -> Result<Vec<u8>> {
    let err = |e: &dyn std::fmt::Display| Error::Invalid(format!("cannot draw scale.png: {e}"));
    register_font().map_err(|e| err(&e))?;
    let (width, height) = (1500u32, 900u32);
    let mut buf = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let root = root
            .titled(
                "time per pass against the work (median wall ms, log-log; exponent = fitted slope)",
                ("sans-serif", 22),
            )
            .map_err(|e| err(&e))?;
        let panels = root.split_evenly((2, 3));
        let series = [
            (Pass::Depth, RGBColor(30, 90, 200)),
            (Pass::Scene, RGBColor(200, 50, 40)),
            (Pass::Frame, RGBColor(90, 90, 90)),
        ];
        for (axis, panel) in Axis::ALL.iter().zip(panels.iter()) {
            let on: Vec<&ScaleRow> = rows.iter().filter(|r| r.point.axis == *axis).collect();
            if on.is_empty() {
                continue;
            }
            let (x_lo, x_hi) = padded_range(on.iter().map(|r| r.work), 1.2);
            let (y_lo, y_hi) = padded_range(
                on.iter()
                    .flat_map(|r| series.iter().map(move |(p, _)| p.of(r))),
                1.5,
            );
            let mut chart = ChartBuilder::on(panel)
                .margin(12)
                .x_label_area_size(40)
                .y_label_area_size(55)
                .build_cartesian_2d(log_axis(x_lo, x_hi), log_axis(y_lo, y_hi))
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_desc(axis.description())
                .y_desc("ms")
                .x_label_formatter(&|v| si_label(*v))
                .y_label_formatter(&|v| tick_label(*v))
                .label_style(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
            for (pass, colour) in series {
                let points: Vec<(f64, f64)> = on.iter().map(|r| (r.work, pass.of(r))).collect();
                let fit = fits
                    .iter()
                    .find(|f| f.axis == *axis && f.pass == pass && !f.upper);
                let label = match fit {
                    Some(f) => format!("{}: exponent {:.2}", pass.name(), f.exponent),
                    None => pass.name().to_string(),
                };
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                    .map_err(|e| err(&e))?
                    .label(label)
                    .legend(move |(x, y)| Circle::new((x, y), 3, colour.filled()));
                if let Some(f) = fit {
                    let line = (0..=40).map(|k| {
                        let x = x_lo * (x_hi / x_lo).powf(k as f64 / 40.0);
                        (x, f.coefficient * x.powf(f.exponent))
                    });
                    chart
                        .draw_series(LineSeries::new(
                            line.into_iter().filter(|(_, y)| (y_lo..=y_hi).contains(y)),
                            colour.mix(0.6).stroke_width(1),
                        ))
                        .map_err(|e| err(&e))?;
                }
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .border_style(BLACK)
                .background_style(WHITE.mix(0.8))
                .label_font(("sans-serif", 12))
                .draw()
                .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    rgb_image(width, height, &buf).encode_png()
}

/// The smallest and largest of `values` widened by `pad` times on a log scale (1 to 10 when
/// there are none).
fn padded_range(values: impl Iterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        });
    match lo <= hi {
        true => (lo / pad, hi * pad),
        false => (1.0, 10.0),
    }
}

/// A log axis from `lo` to `hi` labelled at [`log_ticks`] (both plots' axes).
fn log_axis(lo: f64, hi: f64) -> LogAxis {
    (lo..hi).log_scale().with_key_points(log_ticks(lo, hi))
}

/// Ticks for a log axis from `lo` to `hi`: 1, 2 and 5 in each decade; every digit when
/// the axis spans little more than a decade; only powers of ten when it spans many.
pub fn log_ticks(lo: f64, hi: f64) -> Vec<f64> {
    let decades = (hi / lo).log10();
    let mantissas: &[f64] = match decades {
        d if d < 1.5 => &[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
        d if d <= 5.0 => &[1.0, 2.0, 5.0],
        _ => &[1.0],
    };
    let mut ticks = Vec::new();
    let mut exp = lo.log10().floor() as i32;
    while 10f64.powi(exp) <= hi {
        for m in mantissas {
            let v = m * 10f64.powi(exp);
            if (lo..=hi).contains(&v) {
                ticks.push(v);
            }
        }
        exp += 1;
    }
    ticks
}

/// A tick value with three significant digits at most and no trailing zeros.
pub fn tick_label(v: f64) -> String {
    let decimals = (2 - v.log10().floor() as i32).max(0) as usize;
    let text = format!("{v:.decimals$}");
    match text.contains('.') {
        true => text.trim_end_matches('0').trim_end_matches('.').to_string(),
        false => text,
    }
}

/// A tick value with k or M for thousands and millions (20k, 1.5M): work axes span them.
fn si_label(v: f64) -> String {
    match v {
        v if v >= 1e6 => format!("{}M", tick_label(v / 1e6)),
        v if v >= 1e3 => format!("{}k", tick_label(v / 1e3)),
        v => tick_label(v),
    }
}

/// A front point's name: map size, filter and bias, plus what differs from the usual.
fn short_label(r: &BenchRow) -> String {
    let s = &r.config.settings;
    if r.config.family == Family::Volumes {
        return format!("volumes, {} px/frame", r.volume_pixels);
    }
    let mut name = match r.config.family {
        Family::Cascades => format!("{}x{}", s.cascades, s.map_size),
        Family::Groups => format!("{}x{} groups", s.caster_groups, s.map_size),
        _ => s.map_size.to_string(),
    };
    name.push_str(&format!(
        " {} {}",
        s.filter.name(),
        r.config.bias_preset.name()
    ));
    if s.cull.name() != "none" {
        name.push_str(&format!(" cull-{}", s.cull.name()));
    }
    if s.depth_format.name() != "24" {
        name.push_str(&format!(" d{}", s.depth_format.name()));
    }
    match r.config.family {
        Family::PointSixPasses => name.push_str(" six-passes"),
        Family::PointLayered => name.push_str(" layered"),
        _ => {}
    }
    name
}

fn rgb_image(width: u32, height: u32, rgb: &[u8]) -> ImageData {
    ImageData {
        width,
        height,
        rgba: rgb
            .chunks_exact(3)
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect(),
    }
}

/// The error image's colours and what they mean.
pub const ERROR_LEGEND: [([u8; 3], &str); 3] = [
    ([255, 0, 0], "false shadow"),
    ([0, 0, 255], "false light"),
    ([128, 128, 128], "agrees (grey: the frame)"),
];

/// The error image with a band below it naming its colours; the picture itself is left
/// untouched (row for row the same as the other images of the comparison).
pub fn with_error_legend(image: ImageData) -> Result<ImageData> {
    let err = |e: &dyn std::fmt::Display| Error::Invalid(format!("cannot draw the legend: {e}"));
    register_font().map_err(|e| err(&e))?;
    const LINE: u32 = 18;
    const SWATCH: i32 = 11;
    let font = ("sans-serif", 13).into_font();
    // Lay the entries out left to right, wrapping to a new line when the width runs out.
    let mut places = Vec::new();
    let (mut x, mut line) = (4i32, 0u32);
    for (_, text) in ERROR_LEGEND {
        let (tw, _) = font.box_size(text).map_err(|e| err(&format!("{e:?}")))?;
        let w = SWATCH + 4 + tw as i32 + 12;
        if x > 4 && x + w > image.width as i32 {
            x = 4;
            line += 1;
        }
        places.push((x, line));
        x += w;
    }
    let band = (line + 1) * LINE + 4;
    let (width, height) = (image.width, image.height + band);
    let mut buf = vec![255u8; (width * height * 3) as usize];
    for (dst, src) in buf.chunks_exact_mut(3).zip(image.rgba.chunks_exact(4)) {
        dst.copy_from_slice(&src[..3]);
    }
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        for ((colour, text), (x, line)) in ERROR_LEGEND.iter().zip(places) {
            let y = (image.height + 3 + line * LINE) as i32;
            let c = RGBColor(colour[0], colour[1], colour[2]);
            root.draw(&Rectangle::new(
                [(x, y + 2), (x + SWATCH, y + 2 + SWATCH)],
                c.filled(),
            ))
            .map_err(|e| err(&e))?;
            root.draw(&Text::new(
                text.to_string(),
                (x + SWATCH + 4, y),
                font.clone().color(&BLACK),
            ))
            .map_err(|e| err(&e))?;
        }
        root.present().map_err(|e| err(&e))?;
    }
    Ok(rgb_image(width, height, &buf))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_ticks_label_every_decade_readably() {
        let close = |got: Vec<f64>, want: &[f64]| {
            assert_eq!(got.len(), want.len(), "{got:?}");
            for (g, w) in got.iter().zip(want) {
                assert!((g / w - 1.0).abs() < 1e-9, "{got:?}");
            }
        };
        close(
            log_ticks(1.5, 300.0),
            &[2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0],
        );
        close(
            log_ticks(0.3, 7.0),
            &[
                0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0,
            ],
        );
        close(
            log_ticks(0.0005, 500.0),
            &[0.001, 0.01, 0.1, 1.0, 10.0, 100.0],
        );
        let labels: Vec<String> = [0.001, 0.05, 1.5, 20.0, 150.0]
            .iter()
            .map(|&v| tick_label(v))
            .collect();
        assert_eq!(labels, ["0.001", "0.05", "1.5", "20", "150"]);
    }

    #[test]
    fn the_legend_keeps_the_picture_and_adds_its_colours_below() {
        let image = ImageData {
            width: 300,
            height: 20,
            rgba: [7u8, 8, 9, 255].repeat(300 * 20),
        };
        let out = with_error_legend(image.clone()).unwrap();
        assert_eq!(out.width, 300);
        assert!(out.height > 20);
        assert_eq!(out.rgba[..image.rgba.len()], image.rgba[..]);
        let below = &out.rgba[image.rgba.len()..];
        let has = |c: [u8; 3]| below.chunks_exact(4).any(|p| p[..3] == c);
        assert!(has([255, 0, 0]) && has([0, 0, 255]) && has([128, 128, 128]));
        // A narrow picture wraps the legend onto more lines rather than cutting it.
        let narrow = ImageData {
            width: 64,
            height: 36,
            rgba: vec![0; 64 * 36 * 4],
        };
        assert!(with_error_legend(narrow).unwrap().height >= 36 + 3 * 18);
    }
}
