//! `bench select`: the texture-budget selection's time and bricks over
//! budgets: a fresh `select`, then a reusable `Selector` re-selecting after
//! a budget change of +-10 % and after a move of the region of interest,
//! each checked equal to a fresh `select` with the same options (the run
//! fails with an error otherwise).

use super::median_ms;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use crate::scene::{load, select_options, visible, SceneArgs};
use clap::Args;
use hybrid_octree::select::{select, Roi, SelectOptions, Selection, Selector};
use hybrid_octree::{Error, Result};
use serde::Serialize;

/// Arguments of `bench select`.
#[derive(Args, Debug)]
pub struct BenchSelectArgs {
    #[command(flatten)]
    input: InputArgs,
    #[command(flatten)]
    scene: SceneArgs,
    /// Texture budgets in megabytes (10^6 bytes).
    #[arg(long, value_delimiter = ',', default_value = "8,64")]
    budgets_mb: Vec<f64>,
    /// Timed runs per row (the median is reported, after one untimed run).
    #[arg(long, default_value_t = 5)]
    repeats: usize,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One row: one budget, one operation.
#[derive(Debug, Serialize)]
struct Row {
    /// "select" (fresh), "selector first" (a new `Selector`'s first
    /// selection), "reselect budget +10%", "reselect budget -10%" (the
    /// `Selector` after a selection under the row's budget), "select roi"
    /// (fresh, with the region of interest), "reselect roi moved" (the
    /// `Selector` after a selection with the region before the move).
    operation: &'static str,
    budget_bytes: usize,
    bricks: usize,
    texture_bytes: usize,
    /// Median wall time, ms.
    ms: f64,
}

/// Runs the benchmark.
pub fn run(args: &BenchSelectArgs) -> Result<()> {
    let volume = args.input.load()?;
    let grid = volume.grid(args.input.component)?;
    let scene = load(&grid, &args.scene)?;
    let mut rows = Vec::new();
    let shows = visible(&scene, args.scene.isovalue);
    let dims = scene.octree.layout().dims;
    // The region of interest and where it moves: `--roi`, or a sphere of an
    // eighth of the grid at its centre; moved by half its radius along x.
    let roi = args.scene.roi.unwrap_or_else(|| Roi {
        center: dims.map(|d| (d - 1) as f64 / 2.0),
        radius: dims.iter().copied().max().unwrap_or(2) as f64 / 8.0,
    });
    let moved = Roi { center: [roi.center[0] + roi.radius / 2.0, roi.center[1], roi.center[2]], ..roi };
    with_threads(args.input.threads, || {
        for &mb in &args.budgets_mb {
            let budget = super::render::budget_bytes(mb)?;
            let options = select_options(&scene, &args.scene, budget, 0.0);
            let mut row = |operation: &'static str, ms: f64, selection: &Selection, options: &SelectOptions| {
                let fresh = select(&scene.octree, options, &shows)?;
                if *selection != fresh {
                    return Err(Error::InvalidArgument(format!(
                        "{operation} under {} bytes: the Selector's {} bricks differ from a fresh selection's {}",
                        options.budget_bytes,
                        selection.bricks.len(),
                        fresh.bricks.len()
                    )));
                }
                rows.push(Row {
                    operation,
                    budget_bytes: options.budget_bytes,
                    bricks: selection.bricks.len(),
                    texture_bytes: selection.texture_bytes,
                    ms,
                });
                Ok(())
            };
            let fresh = select(&scene.octree, &options, &shows)?;
            let ms = median_ms(args.repeats, || select(&scene.octree, &options, &shows).map(drop))?;
            row("select", ms, &fresh, &options)?;
            let (first, ms) = timed_selector(args.repeats, &options, &scene.octree, &shows, None)?;
            row("selector first", ms, &first, &options)?;
            for (operation, factor) in [("reselect budget +10%", 1.1), ("reselect budget -10%", 0.9)] {
                let changed = SelectOptions { budget_bytes: (budget as f64 * factor) as usize, ..options };
                let (s, ms) = timed_selector(args.repeats, &changed, &scene.octree, &shows, Some(&options))?;
                row(operation, ms, &s, &changed)?;
            }
            let before = SelectOptions { roi: Some(roi), ..options };
            let after = SelectOptions { roi: Some(moved), ..options };
            let fresh = select(&scene.octree, &after, &shows)?;
            let ms = median_ms(args.repeats, || select(&scene.octree, &after, &shows).map(drop))?;
            row("select roi", ms, &fresh, &after)?;
            let (s, ms) = timed_selector(args.repeats, &after, &scene.octree, &shows, Some(&before))?;
            row("reselect roi moved", ms, &s, &after)?;
        }
        Ok(())
    })?;
    print_report(&rows, args.json, print_table)
}

/// The median time of a selection under `options` by a `Selector` that
/// first selected under `prepared` (untimed; none: a new `Selector`), and
/// that selection.
fn timed_selector(
    repeats: usize,
    options: &SelectOptions,
    octree: &hybrid_octree::octree::VolumeOctree,
    shows: &dyn Fn(f64, f64) -> bool,
    prepared: Option<&SelectOptions>,
) -> Result<(Selection, f64)> {
    let mut times = Vec::with_capacity(repeats);
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let mut selector = Selector::default();
        if let Some(prepared) = prepared {
            selector.select(octree, prepared, shows)?;
        }
        let started = std::time::Instant::now();
        last = Some(selector.select(octree, options, shows)?);
        times.push(started.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    let last = last.ok_or_else(|| Error::InvalidArgument("give at least one repeat".into()))?;
    Ok((last, times[times.len() / 2]))
}

fn print_table(rows: &Vec<Row>) {
    println!("{:<22} {:>10} {:>8} {:>12} {:>10}", "operation", "budget MB", "bricks", "texture MB", "ms");
    for r in rows {
        println!(
            "{:<22} {:>10.2} {:>8} {:>12.2} {:>10.2}",
            r.operation,
            r.budget_bytes as f64 / 1e6,
            r.bricks,
            r.texture_bytes as f64 / 1e6,
            r.ms
        );
    }
}
