//! `bench scale`: what each step costs as the volume grows, in time and in
//! memory. Per size and scalar type, a built-in dataset is written to a
//! `.vti` file (generated slab by slab), read back, its Volume Octree built,
//! bricks selected under the texture budget, and the first frame drawn
//! (DrawList, texture upload, CPU composite). Each step reports its wall
//! time, its time per voxel and the process's peak resident memory while it
//! ran (Linux: `VmHWM` after resetting it through `/proc/self/clear_refs`),
//! also as a multiple of the volume's bytes.

use super::memory::peak_rss_bytes;
use crate::generate::write_dataset;
use crate::input::check_size;
use crate::output::print_report;
use crate::pool::with_threads;
use crate::scene::{dress, frame, select_options, visible, SceneArgs};
use clap::Args;
use hybrid_octree::datasets::Dataset;
use hybrid_octree::grid::ScalarType;
use hybrid_octree::io::{read_volume, ReadOptions};
use hybrid_octree::octree::{BuildOptions, VolumeOctree};
use hybrid_octree::select::select;
use hybrid_octree::Result;
use serde::Serialize;
use std::path::PathBuf;
use std::time::Instant;

/// Arguments of `bench scale`.
#[derive(Args, Debug)]
pub struct BenchScaleArgs {
    /// Cube sizes (samples per axis).
    #[arg(long, value_delimiter = ',', default_value = "256,512,1024")]
    sizes: Vec<usize>,
    /// Scalar types: u8, u16 (any type the generator writes).
    #[arg(long = "type", value_delimiter = ',', default_value = "u8")]
    types: Vec<String>,
    /// Built-in dataset written and read back.
    #[arg(long, default_value = "shepp-logan")]
    dataset: String,
    /// Texture budget in megabytes (10^6 bytes).
    #[arg(long, default_value_t = 64.0, allow_negative_numbers = true)]
    budget_mb: f64,
    /// Folder for the `.vti` files (default: the system's temp folder); each is removed after its row.
    #[arg(long)]
    dir: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
    /// The view.
    #[command(flatten)]
    scene: SceneArgs,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One step of one size.
#[derive(Debug, Serialize)]
struct Row {
    size: usize,
    scalar_type: &'static str,
    step: &'static str,
    ms: f64,
    ns_per_voxel: f64,
    /// Peak resident memory of the process while the step ran, bytes (None off Linux).
    peak_rss_bytes: Option<u64>,
    /// `peak_rss_bytes` over the volume's bytes.
    peak_rss_ratio: Option<f64>,
    volume_bytes: u64,
}

/// Runs the benchmark.
pub fn run(args: &BenchScaleArgs) -> Result<()> {
    let dataset = Dataset::parse(&args.dataset)?;
    let types = args.types.iter().map(|t| ScalarType::parse(t)).collect::<Result<Vec<_>>>()?;
    for &size in &args.sizes {
        for &ty in &types {
            check_size(size, ty)?;
        }
    }
    let budget_bytes = super::render::budget_bytes(args.budget_mb)?;
    let dir = args.dir.clone().unwrap_or_else(std::env::temp_dir);
    let mut rows = Vec::new();
    for &size in &args.sizes {
        for &ty in &types {
            let path = dir.join(format!("hybrid-octree-scale-{}-{size}-{}.vti", std::process::id(), ty.name()));
            let result = one_size(args, dataset, size, ty, budget_bytes, &path, &mut rows);
            let _ = std::fs::remove_file(&path);
            result?;
        }
    }
    print_report(&rows, args.json, print_table)
}

/// The steps of one size and type, appended to `rows`.
fn one_size(
    args: &BenchScaleArgs,
    dataset: Dataset,
    size: usize,
    ty: ScalarType,
    budget_bytes: usize,
    path: &std::path::Path,
    rows: &mut Vec<Row>,
) -> Result<()> {
    let voxels = (size * size * size) as f64;
    let volume_bytes = (size * size * size * ty.size()) as u64;
    let mut row = |step: &'static str, ms: f64, peak: Option<u64>| {
        rows.push(Row {
            size,
            scalar_type: ty.name(),
            step,
            ms,
            ns_per_voxel: ms * 1e6 / voxels,
            peak_rss_bytes: peak,
            peak_rss_ratio: peak.map(|p| p as f64 / volume_bytes as f64),
            volume_bytes,
        })
    };
    let (_, ms, peak) = measured(|| write_dataset(path, dataset, [size; 3], ty, args.threads))?;
    row("generate", ms, peak);
    with_threads(args.threads, || {
        let (volume, ms, peak) = measured(|| {
            let volume = read_volume(path, &ReadOptions::default())?;
            volume.grid(None)?; // the checked grid: its NaN count and infinities scanned
            Ok(volume)
        })?;
        row("read", ms, peak);
        let grid = volume.grid(None)?;
        let (octree, ms, peak) =
            measured(|| VolumeOctree::build(&grid, &BuildOptions { leaf_size: args.scene.leaf_size }))?;
        row("build", ms, peak);
        let scene = dress(&grid, octree, &args.scene)?;
        let options = select_options(&scene, &args.scene, budget_bytes, 0.0);
        let (selection, ms, peak) = measured(|| select(&scene.octree, &options, visible(&scene, args.scene.isovalue)))?;
        row("select", ms, peak);
        let (_, ms, peak) = measured(|| frame(&grid, &scene, &selection, &args.scene, None))?;
        row("first frame", ms, peak);
        Ok(())
    })
}

/// Runs `f`, returning its result, wall time in ms and the process's peak
/// resident memory while it ran.
fn measured<R>(f: impl FnOnce() -> Result<R>) -> Result<(R, f64, Option<u64>)> {
    reset_peak_rss();
    let started = Instant::now();
    let r = f()?;
    let ms = started.elapsed().as_secs_f64() * 1e3;
    Ok((r, ms, peak_rss_bytes()))
}

/// Resets the kernel's peak resident memory (`VmHWM`) to the current
/// resident memory (Linux: `5` to `/proc/self/clear_refs`); a no-op elsewhere.
fn reset_peak_rss() {
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

fn print_table(rows: &Vec<Row>) {
    println!(
        "{:>6} {:>5} {:<12} {:>10} {:>9} {:>12} {:>8}",
        "size", "type", "step", "ms", "ns/voxel", "peak RSS MB", "x volume"
    );
    for r in rows {
        let (mb, ratio) = match (r.peak_rss_bytes, r.peak_rss_ratio) {
            (Some(b), Some(x)) => (format!("{:.1}", b as f64 / 1e6), format!("{x:.2}")),
            _ => ("-".into(), "-".into()),
        };
        println!(
            "{:>6} {:>5} {:<12} {:>10.1} {:>9.2} {:>12} {:>8}",
            r.size, r.scalar_type, r.step, r.ms, r.ns_per_voxel, mb, ratio
        );
    }
}
