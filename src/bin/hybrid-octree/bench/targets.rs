//! `bench render --targets-ms`: accuracy for time. The cost model is
//! calibrated on warm-up frames (`crate::timed`), then for each target in
//! turn `--frames` frames are searched, drawn, measured and fed back to
//! the model's online correction; each frame is compared with the
//! full-resolution reference. A row per target: the median and 90th
//! percentile of the measured times against the target, the median
//! predicted time, the last frame's budget, bricks and errors. Then
//! Spearman's rank correlation of the estimated error against the measured
//! RMSE over the rows and over every frame, and, with `--plot`, RMSE
//! against time (measured and predicted).

use crate::field::Field;
use crate::plot::{error_plot, Point};
use crate::scene::{Loaded, SceneArgs};
use crate::timed::Timer;
use hybrid_octree::grid::Grid;
use hybrid_octree::plan::cost::{check_target_ms, rank_correlation, TERM_NAMES};
use hybrid_octree::render::image::Image;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::select::{SelectOptions, ViewImportance};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::path::Path;

/// One target's row.
#[derive(Debug, Serialize)]
pub struct TargetRow {
    /// The frame-time target, ms.
    pub target_ms: f64,
    /// Frames drawn at it.
    pub frames: usize,
    /// Median measured frame time (upload and compositing), ms.
    pub ms: f64,
    /// 90th percentile of the measured times (nearest rank), ms.
    pub p90_ms: f64,
    /// Median predicted time, ms.
    pub predicted_ms: f64,
    /// Median measured / target.
    pub ms_over_target: f64,
    /// The last frame's outcome: met, full or below-fastest.
    pub outcome: &'static str,
    /// The last frame's budget, bytes.
    pub budget_bytes: usize,
    /// Its textures' bytes.
    pub texture_bytes: usize,
    /// Its bricks.
    pub bricks: usize,
    /// Its slices' least spacing in multiples of d0.
    pub slice_factor: u32,
    /// Median search time (the candidates' selections and DrawLists), ms.
    pub select_ms: f64,
    /// The last frame's RMSE against the full-resolution reference.
    pub rmse: f64,
    /// Its PSNR, dB.
    pub psnr: f64,
    /// Its SSIM.
    pub ssim: f64,
    /// Its estimated error (`select::estimated_error`: the largest of a visible brick).
    pub estimated_error: f64,
    /// Its estimated root-mean-square error (`select::estimated_rms_error`: what the search minimises).
    pub estimated_rms_error: f64,
}

/// The report: the rows and what they say together.
#[derive(Debug, Serialize)]
pub struct TargetReport {
    /// The measured time of the coarsest selection's frame (the warm-up's first), ms.
    pub fastest_ms: Option<f64>,
    /// The calibrated coefficients, by term (ms per unit).
    pub coefficients: Vec<(&'static str, f64)>,
    /// The online correction after the last frame.
    pub correction: f64,
    /// Spearman's rank correlation of estimated error and RMSE over the rows.
    pub rank_correlation: Option<f64>,
    /// The same over every frame.
    pub rank_correlation_frames: Option<f64>,
    /// Spearman's rank correlation of the estimated RMS error and RMSE over the rows.
    pub rank_correlation_rms: Option<f64>,
    /// The same over every frame.
    pub rank_correlation_rms_frames: Option<f64>,
    /// One row per target.
    pub rows: Vec<TargetRow>,
}

/// `--targets-ms`: each in range, or the error naming the value.
pub fn check_targets(targets: &[f64]) -> Result<()> {
    for &t in targets {
        check_target_ms(t).map_err(|e| Error::InvalidArgument(format!("--targets-ms: {e}")))?;
    }
    Ok(())
}

/// What one run measures against.
pub struct Bench<'a, 'g> {
    /// The volume.
    pub grid: &'a Grid<'g>,
    /// The scene.
    pub scene: &'a Loaded,
    /// Its arguments.
    pub args: &'a SceneArgs,
    /// The full-resolution reference picture.
    pub truth: &'a Image,
}

/// The rows of `targets` (module documentation): `frames` frames each
/// after `warmup` calibration frames, under `options` (their budget the
/// memory limit) and `view`.
pub fn measure(
    b: &Bench<'_, '_>,
    options: SelectOptions,
    view: Option<&ViewImportance>,
    targets: &[f64],
    (frames, warmup): (usize, usize),
) -> Result<TargetReport> {
    let mut timer = Timer::new(Field::Grid(b.grid), b.scene, b.args, options, view);
    timer.calibrate(warmup)?;
    let mut rows = Vec::new();
    let mut pairs = Vec::new();
    let mut rms_pairs = Vec::new();
    for &target in targets {
        let (mut ms, mut predicted, mut search) = (Vec::new(), Vec::new(), Vec::new());
        let mut last = None;
        for _ in 0..frames.max(1) {
            let t = timer.frame(target)?;
            let m = compare(&t.frame.image, b.truth)?;
            pairs.push((t.selection.estimated_error, m.rmse));
            rms_pairs.push((t.selection.estimated_rms_error, m.rmse));
            ms.push(t.ms);
            predicted.push(t.predicted_ms);
            search.push(t.search_ms);
            last = Some((t, m));
        }
        let Some((t, m)) = last else { continue };
        let median = quantile(&ms, 0.5);
        rows.push(TargetRow {
            target_ms: target,
            frames: ms.len(),
            ms: median,
            p90_ms: quantile(&ms, 0.9),
            predicted_ms: quantile(&predicted, 0.5),
            ms_over_target: median / target,
            outcome: t.outcome.name(),
            budget_bytes: t.budget_bytes,
            texture_bytes: t.selection.texture_bytes,
            bricks: t.selection.bricks.len(),
            slice_factor: t.slice_factor,
            select_ms: quantile(&search, 0.5),
            rmse: m.rmse,
            psnr: m.psnr,
            ssim: m.ssim,
            estimated_error: t.selection.estimated_error,
            estimated_rms_error: t.selection.estimated_rms_error,
        });
    }
    let row_pairs: Vec<(f64, f64)> = rows.iter().map(|r| (r.estimated_error, r.rmse)).collect();
    let row_rms_pairs: Vec<(f64, f64)> = rows.iter().map(|r| (r.estimated_rms_error, r.rmse)).collect();
    let c = timer.calibration.model().coefficients();
    Ok(TargetReport {
        fastest_ms: timer.fastest_ms,
        coefficients: TERM_NAMES.iter().copied().zip(c).collect(),
        correction: timer.calibration.ratio(),
        rank_correlation: rank_correlation(&row_pairs),
        rank_correlation_frames: rank_correlation(&pairs),
        rank_correlation_rms: rank_correlation(&row_rms_pairs),
        rank_correlation_rms_frames: rank_correlation(&rms_pairs),
        rows,
    })
}

/// The `q` quantile of `v` by nearest rank (`v` not empty).
fn quantile(v: &[f64], q: f64) -> f64 {
    let mut s: Vec<f64> = v.to_vec();
    s.sort_by(f64::total_cmp);
    let k = ((q * s.len() as f64).ceil() as usize).clamp(1, s.len().max(1)) - 1;
    s.get(k).copied().unwrap_or(f64::NAN)
}

/// The plot of RMSE against the measured and the predicted times.
pub fn plot(path: &Path, title: &str, report: &TargetReport) -> Result<()> {
    let series = |predicted: bool| -> Vec<Point> {
        report
            .rows
            .iter()
            .map(|r| Point {
                ms: if predicted { r.predicted_ms } else { r.ms },
                mb: r.texture_bytes as f64 / 1e6,
                rmse: r.rmse,
            })
            .collect()
    };
    error_plot(path, title, &[("frame-time targets, measured", series(false)), ("predicted", series(true))])
}

/// Prints the rows and the summary.
pub fn print_table(r: &TargetReport) {
    println!(
        "{:>9} {:>6} {:>9} {:>9} {:>9} {:>7} {:>13} {:>11} {:>11} {:>7} {:>5} {:>9} {:>8} {:>7} {:>8} {:>8}",
        "target",
        "frames",
        "ms",
        "p90 ms",
        "predicted",
        "ms/tgt",
        "outcome",
        "budget B",
        "texture B",
        "bricks",
        "slice",
        "select",
        "RMSE",
        "SSIM",
        "est err",
        "est rms"
    );
    for row in &r.rows {
        println!(
            "{:>9.1} {:>6} {:>9.1} {:>9.1} {:>9.1} {:>7.2} {:>13} {:>11} {:>11} {:>7} {:>5} {:>9.1} {:>8.5} {:>7.4} {:>8.4} {:>8.5}",
            row.target_ms,
            row.frames,
            row.ms,
            row.p90_ms,
            row.predicted_ms,
            row.ms_over_target,
            row.outcome,
            row.budget_bytes,
            row.texture_bytes,
            row.bricks,
            row.slice_factor,
            row.select_ms,
            row.rmse,
            row.ssim,
            row.estimated_error,
            row.estimated_rms_error
        );
    }
    if let Some(f) = r.fastest_ms {
        println!("fastest frame (the coarsest selection): {f:.1} ms");
    }
    let rho = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.3}"));
    println!(
        "rank correlation of estimated error and RMSE: {} over the rows, {} over every frame",
        rho(r.rank_correlation),
        rho(r.rank_correlation_frames)
    );
    println!(
        "rank correlation of estimated RMS error and RMSE: {} over the rows, {} over every frame",
        rho(r.rank_correlation_rms),
        rho(r.rank_correlation_rms_frames)
    );
    let c: Vec<String> = r.coefficients.iter().map(|(n, c)| format!("{n} {c:.3e}")).collect();
    println!("cost model (ms per unit): {}; online correction {:.3}", c.join(", "), r.correction);
}
