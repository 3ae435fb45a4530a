//! `bench effects`: what each rendering effect costs. One row per effect of
//! [`list::EFFECTS`] (each alone, and common combinations): the same volume,
//! view and texture budget (default: the full budget, every leaf brick at
//! stride 1 with its gradient border), the effect's selection, DrawList and
//! CPU compositing; per row the median frame time of `--frames` frames and
//! its ratio to the plain composite frame of the same run (the frames of all
//! rows interleaved, so that the machine's load falls on every row alike),
//! the image RMSE against the full-resolution reference ray caster drawing
//! the same effect, the texture bytes (shading's gradient border shows
//! there) and the plan's passes (the planner ran the effect). Then the
//! process's peak RSS. `--plot` draws RMSE against time and memory, one
//! point per effect.

mod list;

use crate::bench::memory::peak_rss_bytes;
use crate::bench::render::budget_bytes;
use crate::extension::require_extension;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::plot::{error_plot, Point};
use crate::pool::with_threads;
use crate::scene::{dress, frame, load, reference_image, select_options, visible, Loaded, SceneArgs};
use clap::Args;
use hybrid_octree::grid::Grid;
use hybrid_octree::octree::VolumeOctree;
use hybrid_octree::plan::BlendMode;
use hybrid_octree::render::image::Image;
use hybrid_octree::render::metrics::{compare, Metrics};
use hybrid_octree::select::{select, Selection};
use hybrid_octree::{Error, Result};
use list::{chosen, Context, Effect, TRANSLUCENT};
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `bench effects`. The view options are the scene's; its
/// `--isovalue` and `--surface-opacity` (below 1) are the surface rows'
/// (default: the middle of the data range, 0.4), its `--ambient`,
/// `--diffuse`, `--specular` and `--specular-power` the shaded rows'
/// material; each row sets shading, the blend mode and the surface itself.
#[derive(Args, Debug)]
pub struct BenchEffectsArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// Texture budget in megabytes (10^6 bytes); default: the full budget
    /// (every leaf brick at stride 1, with its gradient border).
    #[arg(long, allow_negative_numbers = true)]
    budget_mb: Option<f64>,
    /// Timed frames per effect (their median), after one untimed frame.
    #[arg(long, default_value_t = 5)]
    frames: usize,
    /// The effects to measure, by name (default: all); the plain frame is always measured.
    #[arg(long, value_delimiter = ',')]
    effects: Vec<String>,
    /// Write the plot of RMSE against time and memory here (PNG).
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Print one JSON object (the rows and the peak RSS) instead of a table.
    #[arg(long)]
    json: bool,
}

/// One effect's row.
#[derive(Debug, Serialize)]
struct Row {
    effect: &'static str,
    /// The plan's passes (e.g. `["volume-shaded"]`).
    passes: Vec<String>,
    /// The plan's effects (e.g. `["shading"]`, `["cropping"]`).
    effects: Vec<String>,
    /// Median wall time of a frame (SlabPolygons, DrawList, texture upload, compositing), ms.
    frame_ms: f64,
    /// `frame_ms` over the plain frame's.
    frame_ratio: f64,
    /// Median compositing time alone, ms.
    composite_ms: f64,
    /// `composite_ms` over the plain frame's.
    composite_ratio: f64,
    /// The selection (once per effect), ms.
    select_ms: f64,
    texture_bytes: usize,
    bricks: usize,
    /// The selection's estimated error (0: the full-resolution field).
    estimated_error: f64,
    /// Image RMSE (RGB in [0, 1]) against the reference caster with the same effect.
    rmse: f64,
    psnr: f64,
    /// The reference picture's time, ms.
    reference_ms: f64,
}

/// What `bench effects` reports.
#[derive(Debug, Serialize)]
struct Report {
    input: String,
    width: usize,
    height: usize,
    /// The texture budget, bytes.
    budget_bytes: usize,
    /// True when the budget is the full one (no `--budget-mb`).
    full_budget: bool,
    frames: usize,
    threads: usize,
    rows: Vec<Row>,
    /// The process's peak resident set size, bytes (null where not measurable).
    peak_rss_bytes: Option<u64>,
}

/// One effect's scene, selection and reference picture.
struct Case<'e> {
    effect: &'e Effect,
    args: SceneArgs,
    scene: Loaded,
    selection: Selection,
    select_ms: f64,
    truth: Image,
    reference_ms: f64,
}

/// The texture bytes of every leaf brick at stride 1 with a gradient border:
/// per axis `ceil(cells / B)` leaves of `B + 3` texels (`B + 1` samples and
/// one border texel on each side), 4 bytes a texel. A coarser cut of the same
/// strides (bigger bricks, shared borders counted once) needs fewer.
fn full_budget(grid: &Grid<'_>, octree: &VolumeOctree) -> usize {
    let b = octree.layout().leaf_size();
    let texels: usize = grid.dims().iter().map(|&n| (n.max(2) - 1).div_ceil(b) * (b + 3)).product();
    4 * texels
}

/// The scene arguments of a plain composite frame: no shading, no
/// scattering, Composite, no surface, no cropping or clipping.
fn plain(args: &SceneArgs) -> SceneArgs {
    let mut plain = args.clone();
    plain.shade.shade = false;
    plain.scattering = Default::default();
    plain.blend = BlendMode::Composite;
    plain.isovalue = None;
    plain.crop = Default::default();
    plain
}

/// Refuses the scene options a row sets itself.
fn check(args: &BenchEffectsArgs) -> Result<()> {
    if let Some(path) = &args.plot {
        require_extension(path, "--plot", &[".png"], "PNG plots")?;
    }
    if !(1..=1000).contains(&args.frames) {
        return Err(Error::InvalidArgument(format!("--frames {}: give 1 to 1000 timed frames", args.frames)));
    }
    if args.scene.shade.shade || args.scene.blend != BlendMode::Composite {
        return Err(Error::InvalidArgument(
            "bench effects sets shading and the blend mode in each row: drop --shade and --blend \
             (choose rows with --effects)"
                .into(),
        ));
    }
    Ok(())
}

impl<'e> Case<'e> {
    fn new(
        grid: &Grid<'_>,
        base: &Loaded,
        plain: &SceneArgs,
        effect: &'e Effect,
        c: &Context,
        budget: usize,
    ) -> Result<Self> {
        let mut args = plain.clone();
        (effect.apply)(&mut args, c);
        let scene = dress(grid, base.octree.clone(), &args)?;
        let started = Instant::now();
        let selection =
            select(&scene.octree, &select_options(&scene, &args, budget, 0.0), visible(&scene, args.isovalue))?;
        let select_ms = started.elapsed().as_secs_f64() * 1e3;
        let started = Instant::now();
        let truth = reference_image(grid, &scene, &args)?;
        let reference_ms = started.elapsed().as_secs_f64() * 1e3;
        Ok(Case { effect, args, scene, selection, select_ms, truth, reference_ms })
    }
}

/// A first frame's RMSE against the reference, the plan's passes and effects.
type FirstFrame = (Metrics, Vec<String>, Vec<String>);

/// One untimed frame of each case ([`FirstFrame`]).
fn first_frames(grid: &Grid<'_>, cases: &[Case<'_>]) -> Result<Vec<FirstFrame>> {
    cases
        .iter()
        .map(|c| {
            let f = frame(grid, &c.scene, &c.selection, &c.args, None)?;
            Ok((compare(&f.image, &c.truth)?, f.list.plan.passes, f.list.plan.effects))
        })
        .collect()
}

/// The median frame and compositing times of each case over `frames`
/// rounds, one frame of every case a round (the order reversed every other
/// round, so that a change of the machine's load falls on all alike), ms.
fn timed_medians(grid: &Grid<'_>, cases: &[Case<'_>], frames: usize) -> Result<Vec<(f64, f64)>> {
    let mut times = vec![(Vec::new(), Vec::new()); cases.len()];
    for round in 0..frames {
        let order: Vec<usize> =
            if round % 2 == 0 { (0..cases.len()).collect() } else { (0..cases.len()).rev().collect() };
        for i in order {
            let c = &cases[i];
            let started = Instant::now();
            let f = frame(grid, &c.scene, &c.selection, &c.args, None)?;
            times[i].0.push(started.elapsed().as_secs_f64() * 1e3);
            times[i].1.push(f.composite_ms);
        }
    }
    Ok(times.into_iter().map(|(f, c)| (median(f), median(c))).collect())
}

/// The median of `values` (not empty).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// Runs the benchmark.
pub fn run(args: &BenchEffectsArgs) -> Result<()> {
    check(args)?;
    let effects = chosen(&args.effects).map_err(Error::InvalidArgument)?;
    let budget = args.budget_mb.map(budget_bytes).transpose()?;
    let report = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let plain_args = plain(&args.scene);
        let base = load(&grid, &plain_args)?;
        let (lo, hi) = base.octree.value_range();
        let context = Context {
            isovalue: args.scene.isovalue.unwrap_or(0.5 * (lo + hi)),
            translucent_opacity: if args.scene.surface_opacity < 1.0 {
                args.scene.surface_opacity
            } else {
                TRANSLUCENT
            },
            bounds: {
                let shape = grid.shape();
                (shape.world([0.0; 3]), shape.world(shape.dims.map(|d| (d - 1) as f64)))
            },
            value_range: (lo, hi),
            spacing: grid.shape().spacing.iter().sum::<f64>() / 3.0,
        };
        let budget_bytes = budget.unwrap_or_else(|| full_budget(&grid, &base.octree));
        let cases = effects
            .iter()
            .map(|e| Case::new(&grid, &base, &plain_args, e, &context, budget_bytes))
            .collect::<Result<Vec<_>>>()?;
        let first = first_frames(&grid, &cases)?;
        let medians = timed_medians(&grid, &cases, args.frames)?;
        let (plain_frame, plain_composite) = medians[0];
        let rows = cases
            .iter()
            .zip(first)
            .zip(&medians)
            .map(|((c, (metrics, passes, effects)), &(frame_ms, composite_ms))| Row {
                effect: c.effect.name,
                passes,
                effects,
                frame_ms,
                frame_ratio: frame_ms / plain_frame,
                composite_ms,
                composite_ratio: composite_ms / plain_composite,
                select_ms: c.select_ms,
                texture_bytes: c.selection.texture_bytes,
                bricks: c.selection.bricks.len(),
                estimated_error: c.selection.estimated_error,
                rmse: metrics.rmse,
                psnr: metrics.psnr,
                reference_ms: c.reference_ms,
            })
            .collect();
        Ok(Report {
            input: args.input.describe(),
            width: args.scene.width,
            height: args.scene.height,
            budget_bytes,
            full_budget: budget.is_none(),
            frames: args.frames,
            threads: rayon::current_num_threads(),
            rows,
            peak_rss_bytes: None,
        })
    })?;
    let report = Report { peak_rss_bytes: peak_rss_bytes(), ..report };
    if let Some(path) = &args.plot {
        let series: Vec<(&str, Vec<Point>)> = report
            .rows
            .iter()
            .map(|r| (r.effect, vec![Point { ms: r.frame_ms, mb: r.texture_bytes as f64 / 1e6, rmse: r.rmse }]))
            .collect();
        let budget = if report.full_budget {
            "full budget".into()
        } else {
            format!("{:.2} MB", report.budget_bytes as f64 / 1e6)
        };
        let title = format!("{}, {budget}: each effect's RMSE against the reference", report.input);
        error_plot(path, &title, &series)?;
    }
    print_report(&report, args.json, print_table)
}

fn print_table(r: &Report) {
    let budget = if r.full_budget { "the full budget".into() } else { "a budget".to_string() };
    println!(
        "{}, {}x{}, {budget} of {:.2} MB, median of {} frames on {} threads (CPU compositor)",
        r.input,
        r.width,
        r.height,
        r.budget_bytes as f64 / 1e6,
        r.frames,
        r.threads
    );
    println!(
        "{:<22} {:>9} {:>7} {:>10} {:>7} {:>9} {:>11} {:>7} {:>8} {:>8} {:>8}  passes",
        "effect",
        "frame ms",
        "x plain",
        "compos ms",
        "x plain",
        "select",
        "texture B",
        "bricks",
        "est err",
        "RMSE",
        "PSNR"
    );
    for row in &r.rows {
        println!(
            "{:<22} {:>9.1} {:>7.2} {:>10.1} {:>7.2} {:>9.1} {:>11} {:>7} {:>8.4} {:>8.5} {:>8.2}  {}",
            row.effect,
            row.frame_ms,
            row.frame_ratio,
            row.composite_ms,
            row.composite_ratio,
            row.select_ms,
            row.texture_bytes,
            row.bricks,
            row.estimated_error,
            row.rmse,
            row.psnr,
            row.passes.join(" -> ") + &row.effects.iter().map(|e| format!(" +{e}")).collect::<String>()
        );
    }
    match r.peak_rss_bytes {
        Some(b) => println!("peak RSS {:.1} MB", b as f64 / 1e6),
        None => println!("peak RSS: not measurable here (no /proc/self/status)"),
    }
}
