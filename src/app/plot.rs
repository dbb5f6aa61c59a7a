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

/// Makes the embedded font the plots' "sans-serif" (no system fonts are needed).
pub(super) fn register_font() -> std::result::Result<(), String> {
    // Registering twice is harmless.
    static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
    shadowmap::engine::context::register_plot_font("sans-serif", FONT)
}

/// The Pareto plot's axes: log scales with our own ticks.
type LogAxis = plotters::coord::combinators::WithKeyPoints<LogCoord<f64>>;
type ParetoChart<'a, 'b> = ChartContext<'a, BitMapBackend<'b>, Cartesian2d<LogAxis, LogAxis>>;

/// Why pareto.png could not be drawn.
fn pareto_err(e: &dyn std::fmt::Display) -> Error {
    Error::Invalid(format!("cannot draw pareto.png: {e}"))
}

/// Where an overhead that is noise or below zero is drawn on the log axis (ms); such
/// points are crossed out and the legend says so ([`draw_noise`]).
const OVERHEAD_FLOOR_MS: f64 = 0.01;

/// A row's place on the Pareto plot: (shadow overhead ms, error in percent), both kept
/// above zero for the log axes (an overhead at or below zero at [`OVERHEAD_FLOOR_MS`]).
fn pareto_at(r: &BenchRow) -> (f64, f64) {
    (
        r.overhead_ms.max(OVERHEAD_FLOOR_MS),
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
        // The plot's inner size, for ticks whose labels keep apart (margins and label areas
        // off, the caption's line off the height).
        let (x_px, y_px) = (
            f64::from(WIDTH - 2 * 15 - 80),
            f64::from(HEIGHT - 2 * 15 - 50 - 30),
        );
        let x_ticks = spaced_log_ticks(x_lo, x_hi, x_px, &|a, b| {
            (label_px(&tick_label(a)) + label_px(&tick_label(b))) / 2.0 + 14.0
        });
        let y_ticks = spaced_log_ticks(y_lo, y_hi, y_px, &|_, _| 22.0);
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(50)
            .y_label_area_size(80)
            .build_cartesian_2d(
                (x_lo..x_hi).log_scale().with_key_points(x_ticks),
                (y_lo..y_hi).log_scale().with_key_points(y_ticks),
            )
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("shadow overhead per frame, median (ms: the frame minus one without shadows), log scale")
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
        draw_noise(&mut chart, rows)?;
        let mut labels = Labels::new(&chart, rows);
        draw_front(&mut chart, rows, &mut labels)?;
        draw_tutorials(&mut chart, rows, &mut labels)?;
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

/// The rows whose overhead is noise ([`BenchRow::overhead_is_noise`]), crossed out, each
/// with its spread as a bar along the overhead axis.
fn draw_noise(chart: &mut ParetoChart<'_, '_>, rows: &[BenchRow]) -> Result<()> {
    let noisy: Vec<&BenchRow> = rows.iter().filter(|r| r.overhead_is_noise()).collect();
    if noisy.is_empty() {
        return Ok(());
    }
    let colour = RGBColor(0, 0, 0);
    let range = chart.x_range();
    let (lo, hi) = (range.start, range.end);
    for r in &noisy {
        let (x, y) = pareto_at(r);
        let spread = if r.overhead_spread_ms.is_finite() {
            r.overhead_spread_ms
        } else {
            0.0
        };
        let from = (r.overhead_ms - spread).clamp(lo, hi);
        let to = (r.overhead_ms + spread).clamp(lo, hi);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(from.min(x), y), (to.max(x), y)],
                colour.stroke_width(1),
            )))
            .map_err(|e| pareto_err(&e))?;
    }
    chart
        .draw_series(
            noisy
                .iter()
                .map(|r| Cross::new(pareto_at(r), 6, colour.stroke_width(2))),
        )
        .map_err(|e| pareto_err(&e))?
        .label(format!(
            "overhead within its noise (±spread; at or below 0 drawn at {OVERHEAD_FLOOR_MS} ms)"
        ))
        .legend(move |(x, y)| Cross::new((x, y), 5, colour.stroke_width(2)));
    Ok(())
}

/// Where the Pareto plot's names go: beside their point, over no data point and no name
/// placed before (the first free of a few places around the point, else the least covered).
struct Labels {
    /// Every row's point, in pixels.
    points: Vec<(i32, i32)>,
    /// The names placed so far: left, top, right, bottom in pixels.
    placed: Vec<[i32; 4]>,
    /// The plotting area: left, top, right, bottom.
    area: [i32; 4],
}

impl Labels {
    fn new(chart: &ParetoChart<'_, '_>, rows: &[BenchRow]) -> Labels {
        let (x, y) = chart.plotting_area().get_pixel_range();
        Labels {
            points: rows
                .iter()
                .map(|r| chart.backend_coord(&pareto_at(r)))
                .collect(),
            placed: Vec::new(),
            area: [x.start, y.start, x.end, y.end],
        }
    }

    /// The offset from the point `at` (pixels) of the top-left corner of a name `size`
    /// pixels large, and the name recorded as placed there.
    fn place(&mut self, at: (i32, i32), (w, h): (i32, i32)) -> (i32, i32) {
        let offsets = [
            (8, -h - 4),
            (8, 4),
            (-w - 8, -h - 4),
            (-w - 8, 4),
            (-w / 2, -h - 8),
            (-w / 2, 8),
            (8, -h - 18),
            (8, 18),
            (-w - 8, -h - 18),
            (-w - 8, 18),
            (-w / 2, -h - 24),
            (-w / 2, 24),
        ];
        let cost = |(dx, dy): (i32, i32)| {
            let b = [at.0 + dx, at.1 + dy, at.0 + dx + w, at.1 + dy + h];
            let covered = self
                .points
                .iter()
                .filter(|p| {
                    (b[0] - 5..=b[2] + 5).contains(&p.0) && (b[1] - 5..=b[3] + 5).contains(&p.1)
                })
                .count();
            let crossed = self.placed.iter().filter(|o| overlap(&b, o)).count();
            let a = self.area;
            let outside = b[0] < a[0] || b[1] < a[1] || b[2] > a[2] || b[3] > a[3];
            covered + 4 * crossed + 8 * usize::from(outside)
        };
        // The first place of the least cost (min_by_key keeps the first of equals).
        let best = offsets
            .into_iter()
            .min_by_key(|o| cost(*o))
            .unwrap_or((8, 4));
        self.placed.push([
            at.0 + best.0,
            at.1 + best.1,
            at.0 + best.0 + w,
            at.1 + best.1 + h,
        ]);
        best
    }
}

/// Whether two boxes (left, top, right, bottom) overlap.
fn overlap(a: &[i32; 4], b: &[i32; 4]) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}

/// The Pareto front as a staircase (each step holds the best error reached so far), each
/// of its points named.
fn draw_front(
    chart: &mut ParetoChart<'_, '_>,
    rows: &[BenchRow],
    labels: &mut Labels,
) -> Result<()> {
    let at = pareto_at;
    let mut front: Vec<&BenchRow> = rows.iter().filter(|r| r.pareto).collect();
    front.sort_by(|a, b| a.overhead_ms.total_cmp(&b.overhead_ms));
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
    // Each front point with its configuration's name, where it covers no point.
    for r in &front {
        let name = short_label(r);
        let font = ("sans-serif", 12).into_font().color(&RGBColor(160, 0, 0));
        let offset = labels.place(chart.backend_coord(&at(r)), text_size(chart, &name, &font)?);
        chart
            .draw_series([EmptyElement::at(at(r))
                + Circle::new((0, 0), 4, RED.filled())
                + Text::new(name, offset, font)])
            .map_err(|e| pareto_err(&e))?;
    }
    Ok(())
}

/// A name's size in pixels as the plot draws it.
fn text_size(chart: &ParetoChart<'_, '_>, text: &str, font: &TextStyle<'_>) -> Result<(i32, i32)> {
    let (w, h) = chart
        .plotting_area()
        .estimate_text_size(text, font)
        .map_err(|e| pareto_err(&e))?;
    Ok((w as i32, h as i32))
}

/// The tutorials' configurations, circled and named where the name covers no point.
fn draw_tutorials(
    chart: &mut ParetoChart<'_, '_>,
    rows: &[BenchRow],
    labels: &mut Labels,
) -> Result<()> {
    for r in rows.iter().filter(|r| r.config.tutorial.is_some()) {
        let name = r.config.tutorial.unwrap_or_default().to_string();
        let font = ("sans-serif", 16).into_font().color(&BLUE);
        let at = pareto_at(r);
        let offset = labels.place(chart.backend_coord(&at), text_size(chart, &name, &font)?);
        chart
            .draw_series([EmptyElement::at(at)
                + Circle::new((0, 0), 6, BLUE.stroke_width(2))
                + Text::new(name, offset, font)])
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
    ticks_with(lo, hi, mantissas, 1)
}

/// Ticks for a log axis from `lo` to `hi` drawn `px` pixels long: the densest of
/// [`log_ticks`]' choices (every digit, then 1, 2 and 5, then 1 and 3, then powers of ten,
/// then every second or third power) whose neighbours are at least `gap(a, b)` pixels apart,
/// so their labels never run together.
pub fn spaced_log_ticks(lo: f64, hi: f64, px: f64, gap: &dyn Fn(f64, f64) -> f64) -> Vec<f64> {
    let per_decade = px / (hi / lo).log10().max(1e-9);
    let fits = |ticks: &[f64]| {
        ticks
            .windows(2)
            .all(|w| (w[1] / w[0]).log10() * per_decade >= gap(w[0], w[1]))
    };
    let choices: [&[f64]; 4] = [
        &[1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0],
        &[1.0, 2.0, 5.0],
        &[1.0, 3.0],
        &[1.0],
    ];
    for mantissas in choices {
        let ticks = ticks_with(lo, hi, mantissas, 1);
        if fits(&ticks) {
            return ticks;
        }
    }
    (2..)
        .map(|every| ticks_with(lo, hi, &[1.0], every))
        .find(|t| fits(t))
        .unwrap_or_default()
}

/// `mantissas` times every `every`-th power of ten, from `lo` to `hi`.
fn ticks_with(lo: f64, hi: f64, mantissas: &[f64], every: i32) -> Vec<f64> {
    let mut ticks = Vec::new();
    let mut exp = lo.log10().floor() as i32;
    while 10f64.powi(exp) <= hi {
        if exp.rem_euclid(every) == 0 {
            for m in mantissas {
                let v = m * 10f64.powi(exp);
                if (lo..=hi).contains(&v) {
                    ticks.push(v);
                }
            }
        }
        exp += 1;
    }
    ticks
}

/// A tick label's width in pixels at the plots' 14-pixel font (DejaVu Sans: digits and
/// most signs 0.64 em, the point and the comma 0.32 em).
fn label_px(text: &str) -> f64 {
    text.chars()
        .map(|c| match c {
            '.' | ',' => 4.5,
            _ => 9.0,
        })
        .sum()
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
        Family::OneMap | Family::Soft | Family::Volumes => s.map_size.to_string(),
        Family::PointLayered | Family::PointSixPasses => s.map_size.to_string(),
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
        Family::OneMap | Family::Soft | Family::Volumes => {}
        Family::Cascades | Family::Groups => {}
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

/// The colours of an error image against the transmittance truth
/// (`transmittance_error_image`).
pub const TRANSMITTANCE_LEGEND: [([u8; 3], &str); 3] = [
    ([255, 0, 0], "too dark (full red: 0.5 off)"),
    ([0, 0, 255], "too bright"),
    ([128, 128, 128], "agrees (grey: the frame)"),
];

/// The error image with a band below it naming its colours; the picture itself is left
/// untouched (row for row the same as the other images of the comparison).
pub fn with_error_legend(image: ImageData) -> Result<ImageData> {
    with_legend(image, &ERROR_LEGEND)
}

/// `image` with a band below it naming `legend`'s colours.
pub fn with_legend(image: ImageData, legend: &[([u8; 3], &str)]) -> Result<ImageData> {
    let err = |e: &dyn std::fmt::Display| Error::Invalid(format!("cannot draw the legend: {e}"));
    register_font().map_err(|e| err(&e))?;
    const LINE: u32 = 18;
    const SWATCH: i32 = 11;
    let font = ("sans-serif", 13).into_font();
    // Lay the entries out left to right, wrapping to a new line when the width runs out.
    let mut places = Vec::new();
    let (mut x, mut line) = (4i32, 0u32);
    for (_, text) in legend {
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
        for ((colour, text), (x, line)) in legend.iter().zip(places) {
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

    /// An axis of 990 pixels over 1.46 decades: every digit would put "90" and "100" 31
    /// pixels apart, less than the labels need; 1, 2 and 5 keep them apart.
    #[test]
    fn crowded_log_ticks_thin_out_until_their_labels_fit() {
        let gap =
            |a: f64, b: f64| (label_px(&tick_label(a)) + label_px(&tick_label(b))) / 2.0 + 14.0;
        assert_eq!(log_ticks(8.0, 230.0).len(), 15);
        let ticks = spaced_log_ticks(8.0, 230.0, 990.0, &gap);
        assert_eq!(ticks, [10.0, 20.0, 50.0, 100.0, 200.0]);
        // A wide axis keeps every digit; a short one over many decades every third power.
        assert_eq!(
            spaced_log_ticks(60.0, 120.0, 990.0, &gap),
            [60.0, 70.0, 80.0, 90.0, 100.0]
        );
        let sparse = spaced_log_ticks(1e-3, 1e6, 200.0, &gap);
        assert_eq!(sparse, [1e-3, 1.0, 1e3, 1e6]);
    }

    /// A name goes where it covers no point and no name placed before.
    #[test]
    fn names_are_placed_off_the_points() {
        let mut labels = Labels {
            // A row of points through the name's first choices, right and left of (500, 300).
            points: (0..40).map(|i| (400 + 5 * i, 300)).collect(),
            placed: Vec::new(),
            area: [0, 0, 1000, 600],
        };
        let (w, h) = (60, 16);
        let clear = |l: &Labels, (dx, dy): (i32, i32)| {
            let b = [500 + dx, 300 + dy, 500 + dx + w, 300 + dy + h];
            l.points.iter().all(|p| {
                !((b[0] - 5..=b[2] + 5).contains(&p.0) && (b[1] - 5..=b[3] + 5).contains(&p.1))
            })
        };
        let first = labels.place((500, 300), (w, h));
        assert!(clear(&labels, first), "{first:?}");
        let second = labels.place((500, 300), (w, h));
        assert!(clear(&labels, second), "{second:?}");
        let (a, b) = (labels.placed[0], labels.placed[1]);
        assert!(!overlap(&a, &b), "{a:?} {b:?}");
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
