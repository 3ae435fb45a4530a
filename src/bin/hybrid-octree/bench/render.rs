//! `bench render`: what each step of accuracy costs. For a sweep of texture
//! budgets and error tolerances, the octree's selection, SlabPolygons
//! (translucent surface), DrawList and CPU compositing, against uniform
//! downsampling (the whole volume in one texture at one stride, what VTK's
//! smart mapper does when a volume does not fit) at the same texture bytes; each
//! frame compared with the full-resolution reference ray caster.
//! Prints a table (or JSON rows), the RMSE ratio octree / uniform at equal
//! bytes, and with `--plot` a PNG of RMSE against time and against memory.
//! Every texture counts the scene's texel format (`--texel-format`).
//!
//! At each uniform row's bytes `B`, two rows of what VTK's smart mapper
//! uploads, resampled with `vtkImageResample` (cubic) and drawn by the
//! reference ray caster (see `super::smart`): `vtk-smart`, the factor VTK's
//! GPU mapper asks for under a memory limit of `B` (more than `B` bytes),
//! and `vtk-smart@bytes`, the factor whose uploaded bytes are at most `B`;
//! and `octree@vtk-smart`, the octree under the bytes `vtk-smart` uploads.
//!
//! With `--points`, the hybrid point/volume representation (paper 3) too:
//! each uniform stride with the points of each `--point-thresholds`
//! threshold, and, at the bytes of each finer stride, the next coarser
//! stride plus as many points as those bytes buy (method "points").

use super::smart;
use crate::extension::require_extension;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::plot::{error_plot, Point};
use crate::pool::with_threads;
use crate::scene::{frame, load, reference_image, visible, Loaded, SceneArgs};
use clap::Args;
use hybrid_octree::grid::Grid;
use hybrid_octree::points::{generate_hybrid, Footprint, PointMass, PointOptions, PointSelect, PointSet};
use hybrid_octree::render::image::Image;
use hybrid_octree::render::metrics::compare;
use hybrid_octree::select::{
    select, select_in_view, select_with_points, take_all_points, uniform, SelectOptions, Selection, ViewSelection,
};
use hybrid_octree::volume::Volume;
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
    #[arg(long, value_delimiter = ',', default_value = "0.02,0.05,0.1,0.2", allow_hyphen_values = true)]
    tolerances: Vec<f64>,
    /// Write the plot of RMSE against time and memory here (PNG).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// View-dependent selections measured beside the data-space one at each
    /// stride's bytes (rows "octree" with their `view`): screen, visibility, both.
    #[arg(long, value_delimiter = ',', default_value = "screen,visibility,both", value_parser = crate::view::view_selection)]
    view_selections: Vec<ViewSelection>,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
    /// Add rows of the hybrid representation: a uniform stride plus error points.
    #[arg(long)]
    points: bool,
    /// Point thresholds (|error| as a fraction of the data range) of the `--points` rows.
    #[arg(long, value_delimiter = ',', default_value = "0.2,0.1,0.05", allow_hyphen_values = true)]
    point_thresholds: Vec<f64>,
    /// Points only where the low resolution underestimates (the only errors an
    /// additive point corrects under an increasing opacity ramp); default: |error|, as the paper.
    #[arg(long)]
    underestimates_only: bool,
    /// The optimized representation (paper 3, section 3.2) for the `--points`
    /// rows: the low resolution overestimates the data by at most this
    /// fraction of the data range; default: plain subsampling.
    #[arg(long, allow_negative_numbers = true)]
    max_overestimate: Option<f64>,
    /// Footprint of the points: square or gaussian.
    #[arg(long, default_value = "square")]
    footprint: Footprint,
    /// Frame-time targets, ms: instead of the budget sweep, a row per
    /// target of frames whose budget (at most --budget-mb) the cost model
    /// chose to meet it (median and 90th percentile measured, predicted,
    /// RMSE, estimated error).
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
    targets_ms: Vec<f64>,
    /// With --targets-ms: the hard memory limit, megabytes.
    #[arg(long, default_value_t = 64.0, allow_negative_numbers = true)]
    budget_mb: f64,
    /// With --targets-ms: frames per target.
    #[arg(long, default_value_t = 5)]
    frames: usize,
    /// With --targets-ms: warm-up frames that calibrate the cost model (at least 2).
    #[arg(long, default_value_t = 3)]
    warmup_frames: usize,
}

/// One row.
#[derive(Debug, Serialize)]
struct Row {
    /// "octree", "uniform", "points" (uniform stride plus error points),
    /// "octree+points" (the selection may buy points instead of refining),
    /// "vtk-smart" or "vtk-smart@bytes" (VTK's smart mapper's resampled volume),
    /// "octree@vtk-smart" (the octree under the bytes of the vtk-smart row before it).
    method: &'static str,
    /// What an octree row's selection weighed nodes by besides their errors
    /// (`--view-selection`): data, screen, visibility or both.
    view: &'static str,
    /// Eu (octree rows); null for uniform rows.
    tolerance: Option<f64>,
    /// Uniform stride (uniform and points rows; vtk-smart rows: the stride
    /// whose bytes are their budget); null for octree rows.
    stride: Option<usize>,
    /// Point threshold (points rows chosen by threshold).
    point_threshold: Option<f64>,
    /// Point budget (points rows at the bytes of a finer stride).
    point_budget: Option<usize>,
    /// The texture budget (vtk-smart rows: the GPU mapper's memory limit).
    budget_bytes: usize,
    /// Bytes of the textures as uploaded (vtk-smart rows: the resampled volume).
    texture_bytes: usize,
    /// The texel format of the textures (vtk-smart rows: VTK's, by the data type).
    texel_format: &'static str,
    /// vtk-smart rows: the magnification factor on each axis.
    magnification: Option<f64>,
    /// vtk-smart rows: the samples per axis of the resampled volume.
    resampled_dims: Option<[usize; 3]>,
    /// Points drawn with the volume.
    points: usize,
    /// Bytes of the points as stored (6 or 9 a point).
    point_bytes: usize,
    /// Texture plus point bytes.
    total_bytes: usize,
    /// Point generation (error grid and selection), ms; once per data set and threshold.
    points_ms: f64,
    bricks: usize,
    select_ms: f64,
    /// The selection's SlabPolygons (translucent surface only), ms.
    slab_polygons_ms: f64,
    /// The per-view DrawList, ms.
    drawlist_ms: f64,
    /// Texture upload (vtk-smart rows: the resampling), ms.
    upload_ms: f64,
    /// Compositing (vtk-smart rows: the reference ray caster's frame), ms.
    composite_ms: f64,
    /// Per frame: DrawList plus compositing, ms.
    ms: f64,
    rmse: f64,
    psnr: f64,
    ssim: f64,
    /// The selection's estimated error (`select::estimated_error`), as
    /// `render` and the mapper report it (vtk-smart rows: NaN, null in JSON).
    estimated_error: f64,
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
#[derive(Default)]
struct Method {
    method: &'static str,
    view: ViewSelection,
    tolerance: Option<f64>,
    stride: Option<usize>,
    point_threshold: Option<f64>,
    point_budget: Option<usize>,
}

/// The points of a row, the low-resolution volume they complete (when
/// optimized; else the grid's own T_s) and what making them took.
struct Points<'a> {
    set: &'a PointSet,
    low: Option<&'a Grid<'a>>,
    footprint: Footprint,
    ms: f64,
}

fn measure(b: &Bench<'_, '_>, m: Method, selection: Selection, select_ms: f64) -> Result<Row> {
    measure_with(b, m, selection, select_ms, None)
}

fn measure_with(
    b: &Bench<'_, '_>,
    m: Method,
    selection: Selection,
    select_ms: f64,
    points: Option<Points<'_>>,
) -> Result<Row> {
    let Method { method, view, tolerance, stride, point_threshold, point_budget } = m;
    let (grid, scene, args, truth) = (b.grid, b.scene, b.args, b.truth);
    let mut selection = selection;
    if let (Some(p), "points") = (points.as_ref(), method) {
        // A uniform stride with all its points.
        take_all_points(&mut selection, &PointMass::new(p.set, scene.octree.layout().leaf_size()));
    }
    let textures_from = points.as_ref().and_then(|p| p.low).unwrap_or(grid);
    let f = frame(textures_from, scene, &selection, args, points.as_ref().map(|p| (p.set, p.footprint)))?;
    let metrics = compare(&f.image, truth)?;
    let point_count = selection.bricks.iter().map(|b| b.point_count).sum();
    let point_bytes = selection.point_bytes;
    Ok(Row {
        method,
        view: view.name(),
        tolerance,
        stride,
        point_threshold,
        point_budget,
        budget_bytes: selection.budget_bytes,
        texture_bytes: selection.texture_bytes,
        texel_format: scene.texel.format.name(),
        magnification: None,
        resampled_dims: None,
        points: point_count,
        point_bytes,
        total_bytes: selection.texture_bytes + point_bytes,
        points_ms: points.as_ref().map_or(0.0, |p| p.ms),
        ms: f.drawlist_ms + f.composite_ms,
        bricks: selection.bricks.len(),
        select_ms,
        slab_polygons_ms: f.slab_polygons_ms,
        drawlist_ms: f.drawlist_ms,
        upload_ms: f.upload_ms,
        composite_ms: f.composite_ms,
        rmse: metrics.rmse,
        psnr: metrics.psnr,
        ssim: metrics.ssim,
        estimated_error: selection.estimated_error,
    })
}

/// `options` with the bytes and the quantization error of the scene's texel format.
fn texel_options(scene: &Loaded, options: SelectOptions) -> SelectOptions {
    SelectOptions {
        bytes_per_texel: scene.texel.bytes(),
        texel_error: scene.texel.normalized_error(scene.octree.value_range()),
        ..options
    }
}

/// The `vtk-smart` and `vtk-smart@bytes` rows at a memory limit of `bytes`
/// (the bytes of uniform stride `stride`); a row whose factor leaves fewer
/// than 2 samples on an axis is left out (noted on stderr).
fn smart_rows_at(b: &Bench<'_, '_>, stride: usize, bytes: usize) -> Result<Vec<Row>> {
    let dims = b.grid.dims();
    let scalar = b.grid.samples().scalar_type();
    let texel = smart::vtk_texel(scalar).bytes();
    let vtk = smart::reduction_ratio(dims, scalar.size(), bytes);
    let equal = [smart::equal_bytes_ratio(dims, texel, bytes); 3];
    let mut rows = Vec::new();
    for (method, ratio) in [("vtk-smart", vtk), ("vtk-smart@bytes", equal)] {
        let Some(s) = smart::draw(b.grid, b.scene, b.args, ratio)? else { continue };
        let metrics = compare(&s.image, b.truth)?;
        rows.push(Row {
            method,
            view: ViewSelection::Data.name(),
            tolerance: None,
            stride: Some(stride),
            point_threshold: None,
            point_budget: None,
            budget_bytes: bytes,
            texture_bytes: s.bytes,
            texel_format: s.texel.name(),
            magnification: Some(s.ratio[0]),
            resampled_dims: Some(s.dims),
            points: 0,
            point_bytes: 0,
            total_bytes: s.bytes,
            points_ms: 0.0,
            bricks: 1,
            select_ms: 0.0,
            slab_polygons_ms: 0.0,
            drawlist_ms: 0.0,
            upload_ms: s.resample_ms,
            composite_ms: s.render_ms,
            ms: s.render_ms,
            rmse: metrics.rmse,
            psnr: metrics.psnr,
            ssim: metrics.ssim,
            estimated_error: f64::NAN,
        });
    }
    Ok(rows)
}

/// Runs the benchmark.
pub fn run(args: &BenchRenderArgs) -> Result<()> {
    if let Some(path) = &args.plot {
        require_extension(path, "--plot", &[".png"], "PNG plots")?;
    }
    if !args.targets_ms.is_empty() {
        return run_targets(args);
    }
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
        let mut smart_rows = Vec::new();
        // Once per scene (transfer function), not per view: not in the rows' select times.
        let medium = crate::view::medium(&grid, &scene, &args.scene)?;
        let mut largest = 0;
        for &stride in &args.strides {
            let started = Instant::now();
            let u = uniform(&scene.octree, stride, scene.texel.bytes())?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            let bytes = u.texture_bytes;
            largest = largest.max(bytes);
            rows.push(measure(
                &bench,
                Method { method: "uniform", stride: Some(stride), ..Method::default() },
                u,
                select_ms,
            )?);
            let options = texel_options(
                &scene,
                SelectOptions {
                    roi: args.scene.roi,
                    pooled: scene.blend.mode.is_extremum(),
                    region: scene.select_region,
                    ..SelectOptions::new(bytes, 0.0)
                },
            );
            let started = Instant::now();
            let s = select(&scene.octree, &options, visible(&scene, args.scene.isovalue))?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            rows.push(measure(
                &bench,
                Method { method: "octree", tolerance: Some(0.0), ..Method::default() },
                s,
                select_ms,
            )?);
            for &view in args.view_selections.iter().filter(|&&v| v != ViewSelection::Data) {
                let started = Instant::now();
                let weights = crate::view::importance(&grid, &args.scene, &scene.camera, view, medium.as_ref())?;
                let s = select_in_view(&scene.octree, &options, visible(&scene, args.scene.isovalue), None, &weights)?;
                let select_ms = started.elapsed().as_secs_f64() * 1e3;
                let m = Method { method: "octree", view, tolerance: Some(0.0), ..Method::default() };
                rows.push(measure(&bench, m, s, select_ms)?);
            }
            for r in smart_rows_at(&bench, stride, bytes)? {
                if r.method == "vtk-smart" {
                    // The octree at the bytes VTK uploads.
                    let options = texel_options(&scene, SelectOptions { budget_bytes: r.texture_bytes, ..options });
                    let started = Instant::now();
                    let s = select(&scene.octree, &options, visible(&scene, args.scene.isovalue))?;
                    let select_ms = started.elapsed().as_secs_f64() * 1e3;
                    let m = Method {
                        method: "octree@vtk-smart",
                        tolerance: Some(0.0),
                        stride: Some(stride),
                        ..Method::default()
                    };
                    smart_rows.push(r);
                    smart_rows.push(measure(&bench, m, s, select_ms)?);
                } else {
                    smart_rows.push(r);
                }
            }
        }
        rows.append(&mut smart_rows);
        for &tolerance in &args.tolerances {
            let options = texel_options(
                &scene,
                SelectOptions {
                    roi: args.scene.roi,
                    pooled: scene.blend.mode.is_extremum(),
                    region: scene.select_region,
                    ..SelectOptions::new(largest, tolerance)
                },
            );
            let started = Instant::now();
            let s = select(&scene.octree, &options, visible(&scene, args.scene.isovalue))?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            rows.push(measure(
                &bench,
                Method { method: "octree", tolerance: Some(tolerance), ..Method::default() },
                s,
                select_ms,
            )?);
        }
        if args.points {
            rows.extend(point_rows(&bench, args)?);
        }
        Ok(rows)
    })?;
    if let Some(path) = &args.plot {
        let series = |keep: &dyn Fn(&Row) -> bool| -> Vec<Point> {
            rows.iter()
                .filter(|r| keep(r))
                .map(|r| Point {
                    ms: r.select_ms + r.slab_polygons_ms + r.drawlist_ms + r.composite_ms,
                    mb: r.total_bytes as f64 / 1e6,
                    rmse: r.rmse,
                })
                .collect()
        };
        let title = format!("{}: image RMSE against the full-resolution reference", args.input.describe());
        let mut lines: Vec<(String, Vec<Point>)> = vec![
            ("octree (budget / tolerance sweep)".into(), series(&|r| r.method == "octree" && r.view == "data")),
            ("uniform downsampling".into(), series(&|r| r.method == "uniform")),
        ];
        for view in args.view_selections.iter().filter(|&&v| v != ViewSelection::Data) {
            let keep = |r: &Row| r.method == "octree" && r.view == view.name();
            lines.push((format!("octree, {} selection", view.name()), series(&keep)));
        }
        let mut point_strides: Vec<usize> = rows
            .iter()
            .filter(|r| r.method == "points" && r.point_threshold.is_some())
            .filter_map(|r| r.stride)
            .collect();
        point_strides.dedup();
        let low = match args.max_overestimate {
            Some(b) => format!(", optimized low resolution (overestimates <= {b})"),
            None => String::new(),
        };
        for s in point_strides {
            lines.push((
                format!("stride {s} + points (threshold sweep{low})"),
                series(&|r| r.method == "points" && r.stride == Some(s) && r.point_threshold.is_some()),
            ));
        }
        for f in [2, 4] {
            let keep = |r: &Row| r.method == "octree+points" && r.stride == Some(f);
            if rows.iter().any(keep) {
                lines.push((format!("octree + factor-{f} points (selection buys them)"), series(&keep)));
            }
        }
        if rows.iter().any(|r| r.point_budget.is_some()) {
            lines.push((
                format!("coarser stride + points at a finer stride's bytes{low}"),
                series(&|r| r.method == "points" && r.point_budget.is_some()),
            ));
        }
        let named: Vec<(&str, Vec<Point>)> = lines.iter().map(|(n, p)| (n.as_str(), p.clone())).collect();
        error_plot(path, &title, &named)?;
    }
    print_report(&rows, args.json, |rows| print_table(rows))
}

/// `--targets-ms`: the rows of [`super::targets`] under the scene's selection options.
fn run_targets(args: &BenchRenderArgs) -> Result<()> {
    super::targets::check_targets(&args.targets_ms)?;
    let budget = budget_bytes(args.budget_mb)?;
    let report = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let scene = load(&grid, &args.scene)?;
        let truth = reference_image(&grid, &scene, &args.scene)?;
        let mode = args.scene.view.view_selection;
        let medium = match mode {
            ViewSelection::Visibility | ViewSelection::Both => crate::view::medium(&grid, &scene, &args.scene)?,
            _ => None,
        };
        let view = crate::view::importance(&grid, &args.scene, &scene.camera, mode, medium.as_ref())?;
        let options = crate::scene::select_options(&scene, &args.scene, budget, 0.0);
        let bench = super::targets::Bench { grid: &grid, scene: &scene, args: &args.scene, truth: &truth };
        super::targets::measure(&bench, options, Some(&view), &args.targets_ms, (args.frames, args.warmup_frames))
    })?;
    if let Some(path) = &args.plot {
        let title = format!("{}: image RMSE at frame-time targets", args.input.describe());
        super::targets::plot(path, &title, &report)?;
    }
    print_report(&report, args.json, super::targets::print_table)
}

/// The `--points` rows (see the module documentation).
fn point_rows(bench: &Bench<'_, '_>, args: &BenchRenderArgs) -> Result<Vec<Row>> {
    let mut rows = Vec::new();
    let generate_timed = |factor: usize, select: PointSelect| -> Result<(PointSet, Option<Volume>, f64)> {
        let options = PointOptions {
            factor,
            select,
            underestimates_only: args.underestimates_only,
            max_overestimate: args.max_overestimate,
        };
        let started = Instant::now();
        let (set, low) = generate_hybrid(bench.grid, &options)?;
        Ok((set, low, started.elapsed().as_secs_f64() * 1e3))
    };
    let mut strides: Vec<usize> = args.strides.iter().copied().filter(|s| [2, 4, 8].contains(s)).collect();
    strides.sort_unstable();
    strides.dedup();
    let mut bytes = Vec::new();
    for &stride in &strides {
        let u = uniform(&bench.scene.octree, stride, bench.scene.texel.bytes())?;
        bytes.push(u.texture_bytes);
        for &threshold in &args.point_thresholds {
            let (set, low, ms) = generate_timed(stride, PointSelect::Threshold(threshold))?;
            let low = low.as_ref().map(|v| v.grid(None)).transpose()?;
            let m = Method {
                method: "points",
                stride: Some(stride),
                point_threshold: Some(threshold),
                ..Method::default()
            };
            let p = Points { set: &set, low: low.as_ref(), footprint: args.footprint, ms };
            rows.push(measure_with(bench, m, u.clone(), 0.0, Some(p))?);
        }
    }
    // The octree selection at each uniform stride's bytes, where bricks of
    // stride f (2 or 4) may take their points instead of refining (method
    // "octree+points", `stride` = f). The points on offer: e > 0.05 of the
    // data range (those that can correct the picture).
    for factor in [2, 4] {
        let started = Instant::now();
        let offer =
            PointOptions { underestimates_only: true, ..PointOptions::new(factor, PointSelect::Threshold(0.05)) };
        let set = hybrid_octree::points::generate(bench.grid, &offer)?;
        let ms = started.elapsed().as_secs_f64() * 1e3;
        let mass = PointMass::voxel_means(bench.grid, &set, bench.scene.octree.layout().leaf_size());
        for &budget in &bytes {
            let options = texel_options(
                bench.scene,
                SelectOptions {
                    roi: bench.args.roi,
                    pooled: bench.scene.blend.mode.is_extremum(),
                    region: bench.scene.select_region,
                    ..SelectOptions::new(budget, 0.0)
                },
            );
            let started = Instant::now();
            let s =
                select_with_points(&bench.scene.octree, &options, visible(bench.scene, bench.args.isovalue), &mass)?;
            let select_ms = started.elapsed().as_secs_f64() * 1e3;
            let m = Method {
                method: "octree+points",
                tolerance: Some(0.0),
                stride: Some(factor),
                point_threshold: Some(0.05),
                ..Method::default()
            };
            let p = Points { set: &set, low: None, footprint: args.footprint, ms };
            rows.push(measure_with(bench, m, s, select_ms, Some(p))?);
        }
    }
    // At the bytes of stride `fine`: the next coarser stride and the points the difference buys.
    for k in 1..strides.len() {
        let (fine, coarse) = (bytes[k - 1], strides[k]);
        let u = uniform(&bench.scene.octree, coarse, bench.scene.texel.bytes())?;
        let per_point = if bench.grid.dims().iter().all(|&n| n <= 256) { 6 } else { 9 };
        let budget = fine.saturating_sub(u.texture_bytes) / per_point;
        let (set, low, ms) = generate_timed(coarse, PointSelect::Budget(budget))?;
        let low = low.as_ref().map(|v| v.grid(None)).transpose()?;
        let m = Method { method: "points", stride: Some(coarse), point_budget: Some(budget), ..Method::default() };
        let p = Points { set: &set, low: low.as_ref(), footprint: args.footprint, ms };
        rows.push(measure_with(bench, m, u, 0.0, Some(p))?);
    }
    Ok(rows)
}

fn print_table(rows: &[Row]) {
    println!(
        "{:>15} {:>10} {:>9} {:>6} {:>9} {:>11} {:>11} {:>7} {:>9} {:>10} {:>7} {:>9} {:>9} {:>9} {:>10} {:>8} {:>8} {:>7} {:>8}",
        "method",
        "view",
        "tolerance",
        "stride",
        "points t",
        "budget B",
        "texture B",
        "texel",
        "points",
        "total B",
        "bricks",
        "select",
        "slabpoly",
        "drawlist",
        "composite",
        "RMSE",
        "PSNR",
        "SSIM",
        "est err"
    );
    for r in rows {
        println!(
            "{:>15} {:>10} {:>9} {:>6} {:>9} {:>11} {:>11} {:>7} {:>9} {:>10} {:>7} {:>9.2} {:>9.2} {:>9.2} {:>10.1} {:>8.5} {:>8.2} {:>7.4} {:>8.4}",
            r.method,
            r.view,
            r.tolerance.map_or("-".into(), |t| format!("{t}")),
            r.stride.map_or("-".into(), |s| s.to_string()),
            match (r.point_threshold, r.point_budget) {
                (Some(t), _) => format!("{t}"),
                (_, Some(_)) => "budget".into(),
                _ => "-".into(),
            },
            r.budget_bytes,
            r.texture_bytes,
            r.texel_format,
            r.points,
            r.total_bytes,
            r.bricks,
            r.select_ms,
            r.slab_polygons_ms,
            r.drawlist_ms,
            r.composite_ms,
            r.rmse,
            r.psnr,
            r.ssim,
            r.estimated_error
        );
    }
    // At equal bytes: each uniform row is followed by the octree rows (one per view selection) with its bytes as the budget.
    for (i, u) in rows.iter().enumerate().filter(|(_, r)| r.method == "uniform") {
        let octree = rows[i + 1..].iter().take_while(|o| o.method == "octree" && o.tolerance == Some(0.0));
        let ratios: Vec<String> = octree.map(|o| format!("{} {:.3}", o.view, o.rmse / u.rmse.max(1e-12))).collect();
        if !ratios.is_empty() {
            println!(
                "at {:.2} MB: octree RMSE / uniform (stride {}) RMSE = {}",
                u.texture_bytes as f64 / 1e6,
                u.stride.unwrap_or(0),
                ratios.join(", ")
            );
        }
    }
    // VTK's smart mapper at each uniform stride's bytes: the (data-space) octree's RMSE over its RMSE.
    for o in rows.iter().filter(|r| r.method == "octree" && r.view == "data" && r.tolerance == Some(0.0)) {
        let vtk = |m: &str| rows.iter().find(|r| r.method == m && r.budget_bytes == o.budget_bytes);
        if let Some(v) = vtk("vtk-smart") {
            print!(
                "at {:.2} MB: octree RMSE / vtk-smart RMSE = {:.3} (VTK uploads {:.2} MB, factor {:.4})",
                o.budget_bytes as f64 / 1e6,
                o.rmse / v.rmse.max(1e-12),
                v.texture_bytes as f64 / 1e6,
                v.magnification.unwrap_or(1.0)
            );
            if let Some(e) = vtk("vtk-smart@bytes") {
                print!(
                    "; / vtk-smart@bytes RMSE = {:.3} ({:.2} MB, factor {:.4})",
                    o.rmse / e.rmse.max(1e-12),
                    e.texture_bytes as f64 / 1e6,
                    e.magnification.unwrap_or(1.0)
                );
            }
            println!();
        }
    }
    for pair in rows.windows(2) {
        if let [v, o] = pair {
            if v.method == "vtk-smart" && o.method == "octree@vtk-smart" {
                println!(
                    "at {:.2} MB (what VTK uploads under a {:.2} MB limit): octree RMSE / vtk-smart RMSE = {:.3}",
                    v.texture_bytes as f64 / 1e6,
                    v.budget_bytes as f64 / 1e6,
                    o.rmse / v.rmse.max(1e-12)
                );
            }
        }
    }
    // Octree + points rows: against the octree alone and uniform downsampling at the same budget.
    for r in rows.iter().filter(|r| r.method == "octree+points") {
        let same = |m: &str| {
            rows.iter().find(|o| o.method == m && o.budget_bytes == r.budget_bytes && o.tolerance == Some(0.0))
        };
        if let (Some(o), Some(u)) =
            (same("octree"), rows.iter().find(|u| u.method == "uniform" && u.texture_bytes == r.budget_bytes))
        {
            println!(
                "at {:.2} MB: octree + factor-{} points ({} points, {:.2} MB of them) RMSE {:.5}: / octree {:.3}, / uniform {:.3}",
                r.budget_bytes as f64 / 1e6,
                r.stride.unwrap_or(0),
                r.points,
                r.point_bytes as f64 / 1e6,
                r.rmse,
                r.rmse / o.rmse.max(1e-12),
                r.rmse / u.rmse.max(1e-12)
            );
        }
    }
    // Points rows: against the same stride alone, and (budget rows) against the finer stride of equal bytes.
    let uniform_at = |stride: usize| rows.iter().find(|r| r.method == "uniform" && r.stride == Some(stride));
    for r in rows.iter().filter(|r| r.method == "points") {
        let Some(stride) = r.stride else { continue };
        if let Some(u) = uniform_at(stride) {
            println!(
                "stride {stride} + {} points ({}): RMSE {:.5} vs {:.5} alone ({:+.1} %), {:.2} MB vs {:.2} MB",
                r.points,
                r.point_threshold.map_or("budget".into(), |t| format!("threshold {t}")),
                r.rmse,
                u.rmse,
                100.0 * (r.rmse / u.rmse.max(1e-12) - 1.0),
                r.total_bytes as f64 / 1e6,
                u.texture_bytes as f64 / 1e6
            );
        }
        if r.point_budget.is_some() {
            if let Some(fine) = rows.iter().find(|u| u.method == "uniform" && u.stride == Some(stride / 2)) {
                println!(
                    "at {:.2} MB: stride {stride} + {} points RMSE / stride {} alone RMSE = {:.3}",
                    fine.texture_bytes as f64 / 1e6,
                    r.points,
                    stride / 2,
                    r.rmse / fine.rmse.max(1e-12)
                );
            }
        }
    }
}
