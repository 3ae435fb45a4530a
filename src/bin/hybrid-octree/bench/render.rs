//! `bench render`: what each step of accuracy costs. For a sweep of texture
//! budgets and error tolerances, the octree's selection, SlabPolygons
//! (translucent surface), DrawList and CPU compositing, against uniform
//! downsampling (the whole volume in one texture at one stride, what VTK's
//! smart mapper does when a volume does not fit) at the same texture bytes; each
//! frame compared with the full-resolution reference ray caster.
//! Prints a table (or JSON rows), the RMSE ratio octree / uniform at equal
//! bytes, and with `--plot` a PNG of RMSE against time and against memory.

use crate::input::InputArgs;
use crate::output::print_report;
use crate::plot::{error_plot, Point};
use crate::pool::with_threads;
use crate::scene::{frame, load, reference_image, visible, Loaded, SceneArgs};
use clap::Args;
use hybrid_octree::grid::Grid;
use hybrid_octree::render::image::Image;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::select::{select, uniform, SelectOptions, Selection};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `bench render`.
#[derive(Args, Debug)]
pub struct BenchRenderArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// Strides of uniform downsampling; the octree gets each one's bytes as its budget.
    #[arg(long, value_delimiter = ',', default_value = "2,4,8")]
    strides: Vec<usize>,
    /// Error tolerances swept at the largest of those budgets.
    #[arg(long, value_delimiter = ',', default_value = "0.02,0.05,0.1,0.2")]
    tolerances: Vec<f64>,
    /// Write the plot of RMSE against time and memory here (PNG).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One row.
#[derive(Debug, Serialize)]
struct Row {
    /// "octree" or "uniform".
    method: &'static str,
    /// Eu (octree rows); null for uniform rows.
    tolerance: Option<f64>,
    /// Uniform stride (uniform rows); null for octree rows.
    stride: Option<usize>,
    budget_bytes: usize,
    texture_bytes: usize,
    bricks: usize,
    select_ms: f64,
    /// The selection's SlabPolygons (translucent surface only), ms.
    slab_polygons_ms: f64,
    /// The per-view DrawList, ms.
    drawlist_ms: f64,
    upload_ms: f64,
    composite_ms: f64,
    rmse: f64,
    psnr: f64,
    ssim: f64,
    max_error: f64,
}

/// Megabytes (10^6 bytes) to a byte budget: positive and finite, or a clear error.
pub fn budget_bytes(mb: f64) -> Result<usize> {
    if !(mb > 0.0 && mb.is_finite()) {
        return Err(Error::InvalidArgument(format!(
            "texture budget {mb} MB: give a positive number of megabytes (e.g. --budget-mb 64)"
        )));
    }
    Ok(((mb * 1e6) as usize).max(1))
}

/// The frame a row measures against: grid, scene, view and the reference picture.
struct Bench<'a, 'g> {
    grid: &'a Grid<'g>,
    scene: &'a Loaded,
    args: &'a SceneArgs,
    truth: &'a Image,
}

/// Which method made a selection, for the row.
struct Method {
    method: &'static str,
    tolerance: Option<f64>,
    stride: Option<usize>,
}

fn measure(b: &Bench<'_, '_>, m: Method, selection: Selection, select_ms: f64) -> Result<Row> {
    let Method { method, tolerance, stride } = m;
    let (grid, scene, args, truth) = (b.grid, b.scene, b.args, b.truth);
    let f = frame(grid, scene, &selection, args)?;
    let metrics = compare(&f.image, truth)?;
    Ok(Row {
        method,
        tolerance,
        stride,
        budget_bytes: selection.budget_bytes,
        texture_bytes: selection.texture_bytes,
        bricks: selection.bricks.len(),
        select_ms,
        slab_polygons_ms: f.slab_polygons_ms,
        drawlist_ms: f.drawlist_ms,
        upload_ms: f.upload_ms,
        composite_ms: f.composite_ms,
        rmse: metrics.rmse,
        psnr: metrics.psnr,
        ssim: metrics.ssim,
        max_error: selection.max_error,
    })
}

/// Runs the benchmark.
pub fn run(args: &BenchRenderArgs) -> Result<()> {
    if args.strides.is_empty() {
        return Err(Error::InvalidArgument("--strides needs at least one stride".into()));
    }
    let rows = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let scene = load(&grid, &args.scene)?;
        let truth = reference_image(&grid, &scene, &args.scene)?;
        let bench = Bench { grid: &grid, scene: &scene, args: &args.scene, truth: &truth };
        let mut rows = Vec::new();
        let mut largest = 0;
        for &stride in &args.strides {
            let started = Instant::now();
            let u = uniform(&scene.octree, stride, 4)?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            let bytes = u.texture_bytes;
            largest = largest.max(bytes);
            rows.push(measure(
                &bench,
                Method { method: "uniform", tolerance: None, stride: Some(stride) },
                u,
                select_ms,
            )?);
            let options = SelectOptions { roi: args.scene.roi, ..SelectOptions::new(bytes, 0.0) };
            let started = Instant::now();
            let s = select(&scene.octree, &options, visible(&scene, args.scene.isovalue))?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            rows.push(measure(&bench, Method { method: "octree", tolerance: Some(0.0), stride: None }, s, select_ms)?);
        }
        for &tolerance in &args.tolerances {
            let options = SelectOptions { roi: args.scene.roi, ..SelectOptions::new(largest, tolerance) };
            let started = Instant::now();
            let s = select(&scene.octree, &options, visible(&scene, args.scene.isovalue))?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            rows.push(measure(
                &bench,
                Method { method: "octree", tolerance: Some(tolerance), stride: None },
                s,
                select_ms,
            )?);
        }
        Ok(rows)
    })?;
    if let Some(path) = &args.plot {
        let series = |method: &str| -> Vec<Point> {
            rows.iter()
                .filter(|r| r.method == method)
                .map(|r| Point {
                    ms: r.select_ms + r.slab_polygons_ms + r.drawlist_ms + r.composite_ms,
                    mb: r.texture_bytes as f64 / 1e6,
                    rmse: r.rmse,
                })
                .collect()
        };
        let title = format!("{}: image RMSE against the full-resolution reference", args.input.describe());
        error_plot(
            path,
            &title,
            &[("octree (budget / tolerance sweep)", series("octree")), ("uniform downsampling", series("uniform"))],
        )?;
    }
    print_report(&rows, args.json, |rows| print_table(rows))
}

fn print_table(rows: &[Row]) {
    println!(
        "{:>8} {:>9} {:>6} {:>11} {:>11} {:>7} {:>9} {:>9} {:>9} {:>10} {:>8} {:>8} {:>7} {:>8}",
        "method",
        "tolerance",
        "stride",
        "budget B",
        "texture B",
        "bricks",
        "select",
        "slabpoly",
        "drawlist",
        "composite",
        "RMSE",
        "PSNR",
        "SSIM",
        "max err"
    );
    for r in rows {
        println!(
            "{:>8} {:>9} {:>6} {:>11} {:>11} {:>7} {:>9.2} {:>9.2} {:>9.2} {:>10.1} {:>8.5} {:>8.2} {:>7.4} {:>8.4}",
            r.method,
            r.tolerance.map_or("-".into(), |t| format!("{t}")),
            r.stride.map_or("-".into(), |s| s.to_string()),
            r.budget_bytes,
            r.texture_bytes,
            r.bricks,
            r.select_ms,
            r.slab_polygons_ms,
            r.drawlist_ms,
            r.composite_ms,
            r.rmse,
            r.psnr,
            r.ssim,
            r.max_error
        );
    }
    // At equal bytes: each uniform row is followed by the octree row with its bytes as the budget.
    for pair in rows.windows(2) {
        if let [u, o] = pair {
            if u.method == "uniform" && o.method == "octree" && o.tolerance == Some(0.0) {
                println!(
                    "at {:.2} MB: octree RMSE / uniform (stride {}) RMSE = {:.3}",
                    u.texture_bytes as f64 / 1e6,
                    u.stride.unwrap_or(0),
                    o.rmse / u.rmse.max(1e-12)
                );
            }
        }
    }
}
