//! `pareto.png`: error against time for every benchmarked configuration, with the Pareto
//! front drawn and the tutorials' configurations labelled.

use std::path::Path;

use plotters::prelude::*;
use shadowmap::bench::{BenchRow, Family};
use shadowmap::image_data::ImageData;
use shadowmap::{Error, Result};

const WIDTH: u32 = 1000;
const HEIGHT: u32 = 650;
/// Errors are drawn on a log axis; zero is drawn at this floor (in percent).
const ERROR_FLOOR_PCT: f64 = 0.001;

static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

pub fn pareto_png(path: &Path, title: &str, rows: &[BenchRow]) -> Result<()> {
    let err = |e: &dyn std::fmt::Display| Error::file(path, format!("cannot draw the plot: {e}"));
    // Registering twice is harmless; the font is embedded, so no system fonts are needed.
    plotters::style::register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| err(&"the embedded font is not readable"))?;
    let mut buf = vec![255u8; (WIDTH * HEIGHT * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (WIDTH, HEIGHT)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let y = |r: &BenchRow| (r.error() * 100.0).max(ERROR_FLOOR_PCT);
        let x_max = rows.iter().map(|r| r.wall_ms.median).fold(1.0f64, f64::max) * 1.05;
        let x_min = rows.iter().map(|r| r.wall_ms.median).fold(x_max, f64::min) * 0.9;
        let y_max = rows.iter().map(y).fold(1.0f64, f64::max) * 2.0;
        let y_min = rows.iter().map(y).fold(y_max, f64::min) * 0.5;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 22))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d((x_min..x_max).log_scale(), (y_min..y_max).log_scale())
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("wall time per frame, median (ms, glFinish), log")
            .y_desc("misclassified receiver pixels (%), log; 0 drawn at the bottom")
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        // One series per kind of shadow (one map, cascades, a point light's two ways of
        // drawing its cube), each in its own colour.
        for (family, colour) in [
            (Family::OneMap, RGBColor(150, 150, 150)),
            (Family::Cascades, RGBColor(20, 150, 60)),
            (Family::PointLayered, RGBColor(140, 60, 190)),
            (Family::PointSixPasses, RGBColor(230, 140, 20)),
        ] {
            let points: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.config.family == family)
                .map(|r| (r.wall_ms.median, y(r)))
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
                .map_err(|e| err(&e))?
                .label(family.name())
                .legend(move |(x, y)| Circle::new((x, y), 3, colour.filled()));
        }
        let mut front: Vec<&BenchRow> = rows.iter().filter(|r| r.pareto).collect();
        front.sort_by(|a, b| a.wall_ms.median.total_cmp(&b.wall_ms.median));
        // The front as a staircase: each step holds the best error reached so far.
        let mut steps = Vec::new();
        for (i, r) in front.iter().enumerate() {
            if i > 0 {
                steps.push((r.wall_ms.median, y(front[i - 1])));
            }
            steps.push((r.wall_ms.median, y(r)));
        }
        chart
            .draw_series(LineSeries::new(steps, RED.stroke_width(2)))
            .map_err(|e| err(&e))?
            .label("Pareto front")
            .legend(|(x, y)| PathElement::new(vec![(x - 8, y), (x + 8, y)], RED.stroke_width(2)));
        chart
            .draw_series(
                front
                    .iter()
                    .map(|r| Circle::new((r.wall_ms.median, y(r)), 4, RED.filled())),
            )
            .map_err(|e| err(&e))?;
        // The tutorials' configurations, circled and named.
        for r in rows.iter().filter(|r| r.config.tutorial.is_some()) {
            let p = (r.wall_ms.median, y(r));
            let name = r.config.tutorial.unwrap_or_default();
            chart
                .draw_series([EmptyElement::at(p)
                    + Circle::new((0, 0), 6, BLUE.stroke_width(2))
                    + Text::new(
                        name.to_string(),
                        (-30, -22),
                        ("sans-serif", 16).into_font().color(&BLUE),
                    )])
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .label_font(("sans-serif", 14))
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    let rgba = buf
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    ImageData {
        width: WIDTH,
        height: HEIGHT,
        rgba,
    }
    .save_png(path)
}
