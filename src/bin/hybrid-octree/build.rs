//! `build`: build the Volume Octree and report it, as text or one JSON object.

use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::grid::Grid;
use hybrid_octree::octree::{BuildOptions, VolumeOctree, DEFAULT_LEAF_SIZE};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::io::IsTerminal;

/// Arguments of `build`.
#[derive(Args, Debug)]
pub struct BuildArgs {
    #[command(flatten)]
    input: InputArgs,
    /// Leaf brick size in cells per axis (power of two, 2..=256).
    #[arg(long, default_value_t = DEFAULT_LEAF_SIZE)]
    leaf_size: usize,
    /// Error tolerance of the reported cut, as a fraction of the data range.
    #[arg(long, default_value_t = 0.01, allow_negative_numbers = true)]
    tolerance: f64,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// The build report. Key names are a contract with the ParaView tests: keep them.
#[derive(Debug, Serialize)]
pub struct BuildReport {
    pub dims: [usize; 3],
    pub scalar_type: &'static str,
    pub components: usize,
    pub component: usize,
    /// NaN samples of the component (no data).
    pub nan_samples: usize,
    pub node_count: usize,
    pub terminal_count: usize,
    pub homogeneous_count: usize,
    pub nodes_per_level: Vec<usize>,
    pub levels: usize,
    pub leaf_size: usize,
    pub root_size: usize,
    pub octree_bytes: usize,
    pub input_bytes: usize,
    /// `100 * octree_bytes / input_bytes`.
    pub octree_percent: f64,
    pub build_ms: f64,
    pub value_min: f64,
    pub value_max: f64,
    pub tolerance: f64,
    /// Nodes of the cut at `tolerance` (see `VolumeOctree::cut`).
    pub cut_count: usize,
}

/// Volumes with at least this many points get a progress bar (on a terminal).
pub const PROGRESS_POINTS: usize = 1 << 24;

/// Builds with a progress bar on stderr when it is a terminal and the volume is large.
pub fn build_octree(grid: &Grid<'_>, options: &BuildOptions) -> Result<VolumeOctree> {
    if !(std::io::stderr().is_terminal() && grid.shape().point_count() >= PROGRESS_POINTS) {
        return VolumeOctree::build(grid, options);
    }
    let bar = indicatif::ProgressBar::new(1000);
    bar.set_style(
        indicatif::ProgressStyle::with_template("building octree {bar:40} {percent:>3}% {elapsed}")
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    let result = VolumeOctree::build_with_progress(grid, options, &mut |f| {
        bar.set_position((f * 1000.0) as u64);
        true
    });
    bar.finish_and_clear();
    result
}

/// Builds and reports.
pub fn run(args: &BuildArgs) -> Result<()> {
    if !(args.tolerance.is_finite() && args.tolerance >= 0.0) {
        return Err(Error::InvalidArgument(format!(
            "--tolerance {} must be a finite number >= 0 (a fraction of the data range, e.g. 0.01)",
            args.tolerance
        )));
    }
    let report = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let octree = build_octree(&grid, &BuildOptions { leaf_size: args.leaf_size })?;
        // Cheap next to the build (O(nodes)); a broken invariant is a bug to report.
        octree.validate().map_err(|e| Error::Internal(format!("octree failed validation: {e}")))?;
        report(&grid, &octree, args.tolerance)
    })?;
    print_report(&report, args.json, print_text)
}

/// Collects the statistics of a built octree.
pub fn report(grid: &Grid<'_>, octree: &VolumeOctree, tolerance: f64) -> Result<BuildReport> {
    let stats = octree.stats();
    let input_bytes = grid.input_bytes();
    Ok(BuildReport {
        dims: grid.dims(),
        scalar_type: grid.samples().scalar_type().name(),
        components: grid.components(),
        component: grid.component(),
        nan_samples: grid.nan_count(),
        node_count: stats.node_count,
        terminal_count: stats.terminal_count,
        homogeneous_count: stats.homogeneous_count,
        nodes_per_level: stats.nodes_per_level,
        levels: stats.levels,
        leaf_size: stats.leaf_size,
        root_size: stats.root_size,
        octree_bytes: stats.octree_bytes,
        input_bytes,
        octree_percent: 100.0 * stats.octree_bytes as f64 / input_bytes as f64,
        build_ms: stats.build_ms,
        value_min: stats.value_range.0,
        value_max: stats.value_range.1,
        tolerance,
        cut_count: octree.cut(tolerance)?.len(),
    })
}

fn print_text(r: &BuildReport) {
    let [x, y, z] = r.dims;
    println!("input:             {x} x {y} x {z} {} (component {} of {})", r.scalar_type, r.component, r.components);
    println!("value range:       {} .. {}", r.value_min, r.value_max);
    println!("NaN samples:       {} (no data: transparent, outside every isosurface)", r.nan_samples);
    println!("nodes:             {}", r.node_count);
    println!("terminal nodes:    {}", r.terminal_count);
    println!("homogeneous nodes: {}", r.homogeneous_count);
    println!("nodes per level:   {:?}", r.nodes_per_level);
    println!("levels:            {}", r.levels);
    println!("leaf size:         {} cells", r.leaf_size);
    println!("root size:         {} cells", r.root_size);
    println!("octree bytes:      {}", r.octree_bytes);
    println!("input bytes:       {}", r.input_bytes);
    println!("octree / input:    {:.2} %", r.octree_percent);
    println!("build time:        {:.1} ms", r.build_ms);
    println!("cut at {:<10}  {} nodes (E_0 <= tolerance x data range)", format!("{}:", r.tolerance), r.cut_count);
}
