//! `motion-flicker.png`: a path's false flicker and the truth's own change, frame by frame.

use plotters::prelude::*;
use shadowmap::image_data::ImageData;
use shadowmap::motion::MotionScore;
use shadowmap::{Error, Result};

/// The plot of `score`'s frames: percent of matched receivers against the frame.
pub fn flicker_png(score: &MotionScore) -> Result<Vec<u8>> {
    let err =
        |e: &dyn std::fmt::Display| Error::Invalid(format!("cannot draw motion-flicker.png: {e}"));
    super::plot::register_font().map_err(|e| err(&e))?;
    let (width, height) = (900u32, 420u32);
    let series = |g: fn(&shadowmap::motion::FrameFlicker) -> Option<f64>| -> Vec<(f64, f64)> {
        (score.frames.iter())
            .filter_map(|f| Some((f64::from(f.frame), g(f)? * 100.0)))
            .collect()
    };
    let lines = [
        (
            "false flicker",
            series(|f| f.false_flicker),
            RGBColor(200, 50, 40),
        ),
        (
            "the truth's own change",
            series(|f| f.truth_change),
            RGBColor(30, 90, 200),
        ),
        (
            "misclassified",
            series(|f| Some(f.misclassified)),
            RGBColor(120, 120, 120),
        ),
    ];
    let top = (lines.iter().flat_map(|l| l.1.iter().map(|p| p.1)))
        .fold(0.0f64, f64::max)
        .max(0.01)
        * 1.15;
    let last = score.frames.len().saturating_sub(1).max(1) as f64;
    let mut buf = vec![255u8; (width * height * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| err(&e))?;
        let title = format!(
            "{}: flicker energy {:.4}; false flicker {:.3}% a frame (truth {:.3}%)",
            score.path,
            score.energy,
            score.false_flicker * 100.0,
            score.truth_change * 100.0
        );
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(0.0..last, 0.0..top)
            .map_err(|e| err(&e))?;
        chart
            .configure_mesh()
            .x_desc("frame")
            .y_desc("% of receivers")
            .label_style(("sans-serif", 12))
            .draw()
            .map_err(|e| err(&e))?;
        for (name, points, colour) in lines {
            chart
                .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                .map_err(|e| err(&e))?
                .label(name)
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 16, y)], colour));
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(|e| err(&e))?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .label_font(("sans-serif", 13))
            .draw()
            .map_err(|e| err(&e))?;
        root.present().map_err(|e| err(&e))?;
    }
    let rgba = buf
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    ImageData {
        width,
        height,
        rgba,
    }
    .encode_png()
}
