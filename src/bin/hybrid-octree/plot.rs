//! The accuracy/cost plot of `bench render`: image error against frame time
//! and against texture memory, one series per method, as a PNG.

use hybrid_octree::{Error, Result};
use plotters::prelude::*;
use std::path::Path;

/// One measured point of a series.
#[derive(Debug, Clone, Copy)]
pub struct Point {
    /// Milliseconds (selection + SlabPolygons + DrawList + compositing).
    pub ms: f64,
    /// Texture megabytes.
    pub mb: f64,
    /// Image RMSE against the reference.
    pub rmse: f64,
}

fn err(e: impl std::fmt::Display) -> Error {
    Error::InvalidArgument(format!("cannot draw the plot: {e}"))
}

/// Writes a two-panel PNG: RMSE against ms (left) and against texture MB
/// (right), both on log axes (the cheap end, where points and small
/// budgets sit, would be a sliver on a linear one), one coloured line per
/// `(name, points)` series; the RMSE axis leaves the top third to the legend.
pub fn error_plot(path: &Path, title: &str, series: &[(&str, Vec<Point>)]) -> Result<()> {
    let root = BitMapBackend::new(path, (1200, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(err)?;
    let root = root.titled(title, ("sans-serif", 22)).map_err(err)?;
    let panels = root.split_evenly((1, 2));
    let all: Vec<Point> = series.iter().flat_map(|s| s.1.iter().copied()).collect();
    let max = |f: fn(&Point) -> f64| all.iter().map(f).fold(0.0f64, f64::max) * 1.1 + 1e-9;
    let min = |f: fn(&Point) -> f64| all.iter().map(f).filter(|v| *v > 0.0).fold(f64::INFINITY, f64::min);
    let colours = [
        RED,
        BLUE,
        GREEN,
        MAGENTA,
        CYAN,
        BLACK,
        RGBColor(230, 140, 0),
        RGBColor(120, 60, 160),
        RGBColor(140, 90, 40),
        RGBColor(0, 120, 120),
        RGBColor(150, 150, 150),
        RGBColor(200, 90, 140),
    ];
    type Axis = (fn(&Point) -> f64, &'static str);
    let axes: [Axis; 2] =
        [(|p| p.ms, "time per frame (ms)"), (|p| p.mb, "memory (MB: textures, plus points where drawn)")];
    for (panel, (x_of, x_desc)) in panels.iter().zip(axes) {
        let mut chart = ChartBuilder::on(panel)
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(65)
            .build_cartesian_2d(
                (min(x_of).min(max(x_of) / 10.0) * 0.8..max(x_of)).log_scale(),
                0.0..1.6 * max(|p| p.rmse),
            )
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_labels(6)
            .x_label_formatter(&|v| format!("{}", (v * 100.0).round() / 100.0))
            .x_desc(x_desc)
            .y_desc("RMSE against the reference")
            .draw()
            .map_err(err)?;
        for ((name, points), colour) in series.iter().zip(colours.iter().cycle()) {
            let mut line: Vec<(f64, f64)> =
                points.iter().filter(|p| x_of(p) > 0.0).map(|p| (x_of(p), p.rmse)).collect();
            line.sort_by(|a, b| a.0.total_cmp(&b.0));
            chart
                .draw_series(LineSeries::new(line.clone(), colour.stroke_width(2)))
                .map_err(err)?
                .label(*name)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2)));
            chart.draw_series(line.iter().map(|&p| Circle::new(p, 4, colour.filled()))).map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE)
            .border_style(BLACK)
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}
