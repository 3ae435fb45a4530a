//! `points`: the hybrid point/volume representation of a volume (paper 3):
//! generate the points completing its stride-`f` low resolution, write them
//! to a point file, and with `--render` draw the low resolution alone, with
//! its points and at full resolution, with the difference pictures and how
//! far each is from the full-resolution reference.

use crate::extension::require_extension;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use crate::scene::{frame, load, reference_image, SceneArgs};
use clap::Args;
use hybrid_octree::points::{
    generate_hybrid, read_points, write_points, Footprint, PointMass, PointOptions, PointSelect,
};
use hybrid_octree::render::metrics::{compare, difference};
use hybrid_octree::select::{take_all_points, uniform};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `points`.
#[derive(Args, Debug)]
pub struct PointsArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// Low-resolution factor: the volume is sampled every 2, 4 or 8 samples.
    #[arg(long, default_value_t = 4)]
    factor: usize,
    /// A point wherever |error| exceeds this fraction of the data range.
    #[arg(long, conflicts_with = "budget", allow_negative_numbers = true)]
    threshold: Option<f64>,
    /// Or: the points of the largest errors, this many.
    #[arg(long)]
    budget: Option<usize>,
    /// Only where the low resolution underestimates (the errors an additive point corrects).
    #[arg(long)]
    underestimates_only: bool,
    /// The optimized representation: the low resolution may overestimate by at most this fraction of the data range.
    #[arg(long, allow_negative_numbers = true)]
    max_overestimate: Option<f64>,
    /// Write the points here (the HOPOINTS file: 6 bytes a point up to 256^3).
    #[arg(long)]
    output: PathBuf,
    /// Also draw: PREFIX-lowres.png, PREFIX-hybrid.png, PREFIX-reference.png and the differences
    /// PREFIX-lowres-diff.png, PREFIX-hybrid-diff.png (4 x |picture - reference|); with
    /// --max-overestimate also plain subsampling alone, PREFIX-subsampled.png and -subsampled-diff.png.
    #[arg(long)]
    render: Option<String>,
    /// Footprint of the drawn points: square or gaussian.
    #[arg(long, default_value = "square")]
    footprint: Footprint,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// What `points` reports.
#[derive(Debug, Serialize)]
struct PointsReport {
    output: String,
    factor: usize,
    points: usize,
    point_bytes: usize,
    file_bytes: u64,
    texture_bytes: usize,
    total_bytes: usize,
    generate_ms: f64,
    /// Of the points, how many have e > 0 (the low resolution underestimates).
    underestimates: usize,
    max_overestimate: Option<f64>,
    /// The low resolution the points complete, alone (optimized when `max_overestimate` is set).
    lowres_rmse: Option<f64>,
    lowres_ssim: Option<f64>,
    /// With `--max-overestimate`: plain subsampling alone, the volume the optimized one replaces.
    subsampled_rmse: Option<f64>,
    subsampled_ssim: Option<f64>,
    hybrid_rmse: Option<f64>,
    hybrid_ssim: Option<f64>,
    hybrid_composite_ms: Option<f64>,
    lowres_composite_ms: Option<f64>,
    passes: Option<Vec<String>>,
}

/// Generates, writes, reads back, and optionally draws.
pub fn run(args: &PointsArgs) -> Result<()> {
    require_extension(&args.output, "--output", &[".hop"], "HOPOINTS point files")?;
    let select = match (args.threshold, args.budget) {
        (Some(t), None) => PointSelect::Threshold(t),
        (None, Some(k)) => PointSelect::Budget(k),
        _ => {
            return Err(Error::InvalidArgument(
                "give --threshold (fraction of the data range) or --budget (number of points)".into(),
            ))
        }
    };
    let options = PointOptions {
        factor: args.factor,
        select,
        underestimates_only: args.underestimates_only,
        max_overestimate: args.max_overestimate,
    };
    let report = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let started = Instant::now();
        let (set, low) = generate_hybrid(&grid, &options)?;
        let generate_ms = started.elapsed().as_secs_f64() * 1e3;
        write_points(&set, &args.output)?;
        if read_points(&args.output)? != set {
            return Err(Error::Internal(format!(
                "{} did not read back as written: please report it",
                args.output.display()
            )));
        }
        let file_bytes = std::fs::metadata(&args.output).map(|m| m.len()).unwrap_or(0);
        let mut report = PointsReport {
            output: args.output.display().to_string(),
            factor: args.factor,
            points: set.points.len(),
            point_bytes: set.bytes(),
            file_bytes,
            texture_bytes: 0,
            total_bytes: set.bytes(),
            generate_ms,
            underestimates: set.points.iter().filter(|p| p.error > 0).count(),
            max_overestimate: set.max_overestimate.is_finite().then_some(set.max_overestimate),
            lowres_rmse: None,
            lowres_ssim: None,
            subsampled_rmse: None,
            subsampled_ssim: None,
            hybrid_rmse: None,
            hybrid_ssim: None,
            hybrid_composite_ms: None,
            lowres_composite_ms: None,
            passes: None,
        };
        let scene = load(&grid, &args.scene)?;
        let mut selection = uniform(&scene.octree, args.factor, 4)?;
        take_all_points(&mut selection, &PointMass::new(&set, scene.octree.layout().leaf_size()));
        report.texture_bytes = selection.texture_bytes;
        report.total_bytes += selection.texture_bytes;
        if let Some(prefix) = &args.render {
            let low_grid = low.as_ref().map(|v| v.grid(None)).transpose()?;
            let textures_from = low_grid.as_ref().unwrap_or(&grid);
            let truth = reference_image(&grid, &scene, &args.scene)?;
            let alone = frame(textures_from, &scene, &selection, &args.scene, None)?;
            let hybrid = frame(textures_from, &scene, &selection, &args.scene, Some((&set, args.footprint)))?;
            for (name, image) in [("lowres", &alone.image), ("hybrid", &hybrid.image), ("reference", &truth)] {
                image.to_png(format!("{prefix}-{name}.png"))?;
            }
            difference(&alone.image, &truth, 4.0)?.to_png(format!("{prefix}-lowres-diff.png"))?;
            difference(&hybrid.image, &truth, 4.0)?.to_png(format!("{prefix}-hybrid-diff.png"))?;
            let (a, h) = (compare(&alone.image, &truth)?, compare(&hybrid.image, &truth)?);
            report.lowres_rmse = Some(a.rmse);
            report.lowres_ssim = Some(a.ssim);
            report.hybrid_rmse = Some(h.rmse);
            report.hybrid_ssim = Some(h.ssim);
            report.lowres_composite_ms = Some(alone.drawlist_ms + alone.composite_ms);
            report.hybrid_composite_ms = Some(hybrid.drawlist_ms + hybrid.composite_ms);
            report.passes = Some(hybrid.list.plan.passes.clone());
            if low_grid.is_some() {
                // Optimized: plain subsampling alone too, the low resolution a user would otherwise have.
                let plain = frame(&grid, &scene, &selection, &args.scene, None)?;
                plain.image.to_png(format!("{prefix}-subsampled.png"))?;
                difference(&plain.image, &truth, 4.0)?.to_png(format!("{prefix}-subsampled-diff.png"))?;
                let m = compare(&plain.image, &truth)?;
                report.subsampled_rmse = Some(m.rmse);
                report.subsampled_ssim = Some(m.ssim);
            }
        }
        Ok(report)
    })?;
    print_report(&report, args.json, print_text)
}

fn print_text(r: &PointsReport) {
    println!(
        "wrote {}: {} points ({} underestimates) at factor {}, {} bytes of points ({} in the file), made in {:.0} ms",
        r.output, r.points, r.underestimates, r.factor, r.point_bytes, r.file_bytes, r.generate_ms
    );
    println!(
        "bytes:           low resolution {:.2} MB + points {:.2} MB = {:.2} MB",
        r.texture_bytes as f64 / 1e6,
        r.point_bytes as f64 / 1e6,
        r.total_bytes as f64 / 1e6
    );
    if let (Some(a), Some(h)) = (r.lowres_rmse, r.hybrid_rmse) {
        println!(
            "vs reference:    low resolution RMSE {a:.4} SSIM {:.4} ({:.0} ms); with points RMSE {h:.4} SSIM {:.4} ({:.0} ms); plan {}",
            r.lowres_ssim.unwrap_or(0.0),
            r.lowres_composite_ms.unwrap_or(0.0),
            r.hybrid_ssim.unwrap_or(0.0),
            r.hybrid_composite_ms.unwrap_or(0.0),
            r.passes.as_ref().map(|p| p.join(" -> ")).unwrap_or_default()
        );
    }
    if let (Some(rmse), Some(ssim)) = (r.subsampled_rmse, r.subsampled_ssim) {
        println!("                 plain subsampling alone (the optimized low resolution replaces it) RMSE {rmse:.4} SSIM {ssim:.4}");
    }
}
