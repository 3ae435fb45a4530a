//! `convert`: any input the CLI reads becomes an OME-Zarr image (NGFF 0.5)
//! holding the Hybrid Octree: every stride's level and the Volume Octree,
//! which `render --file` then draws from disk, brick by brick.
//!
//! One pass over z writes every level and builds the octree
//! ([`write_store_streaming`]): a built-in dataset is generated plane by
//! plane as the pass asks (never whole in memory), an OME-Zarr store is
//! read plane by plane; any other file is read whole by its reader, then
//! passed through the same writer.

use crate::build::PROGRESS_POINTS;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::octree::{BuildOptions, DEFAULT_LEAF_SIZE};
use hybrid_octree::planes::{GridPlanes, PlaneSource};
use hybrid_octree::store::{write_store_streaming, WriteOptions};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Arguments of `convert`.
#[derive(Args, Debug)]
pub struct ConvertArgs {
    #[command(flatten)]
    input: InputArgs,
    /// The OME-Zarr image folder to create (.ome.zarr); it must not exist.
    #[arg(long)]
    output: PathBuf,
    /// Leaf brick size in cells (a power of two, 2..=256).
    #[arg(long, default_value_t = DEFAULT_LEAF_SIZE)]
    leaf_size: usize,
    /// Megabytes (10^6 bytes) for the writer's slab of planes and its encoding (a file's volume, read
    /// whole, and the octree's node arrays come on top).
    #[arg(long, default_value_t = 1024.0)]
    memory_mb: f64,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// What `convert` reports.
#[derive(Debug, Serialize)]
struct ConvertReport {
    output: String,
    dims: [usize; 3],
    scalar_type: String,
    levels: usize,
    /// Samples written over all levels.
    samples: u64,
    /// Planes per slab (shard depth).
    slab_planes: u64,
    /// Bytes of the store on disk.
    store_bytes: u64,
    /// Bytes of the full-resolution samples.
    volume_bytes: u64,
    /// NaN samples (no data).
    nan_count: usize,
    /// A file read whole (0 for a built-in dataset or a store, read plane by plane in the pass).
    read_ms: f64,
    /// The one pass: planes generated or copied, the octree built, every level written.
    pass_ms: f64,
}

/// Converts and reports.
pub fn run(args: &ConvertArgs) -> Result<()> {
    let lower = args.output.to_string_lossy().to_ascii_lowercase();
    if !lower.trim_end_matches('/').ends_with(".zarr") {
        return Err(Error::InvalidArgument(format!(
            "--output '{}' must name an OME-Zarr folder ending in .ome.zarr (or .zarr)",
            hybrid_octree::limits::escape_controls(&args.output.display().to_string())
        )));
    }
    if !(args.memory_mb.is_finite() && args.memory_mb > 0.0 && args.memory_mb <= 1e9) {
        return Err(Error::InvalidArgument(format!(
            "--memory-mb {} must be a positive number of megabytes",
            args.memory_mb
        )));
    }
    if args.output.exists() {
        return Err(Error::InvalidArgument(format!(
            "'{}' already exists: choose a new --output path, or remove it first (nothing is overwritten)",
            hybrid_octree::limits::escape_controls(&args.output.display().to_string())
        )));
    }
    let report = with_threads(args.input.threads, || {
        let started = Instant::now();
        if let Some(planes) = args.input.dataset_planes()? {
            return convert(args, &planes, planes.dataset.name(), 0.0);
        }
        if let Some(stack) = args.input.tiff_stack()? {
            return convert(args, &stack, &stack.name.clone(), 0.0);
        }
        match args.input.store()? {
            Some(store) => convert(args, &store, &store.name.clone(), 0.0),
            None => {
                let volume = args.input.load()?;
                let grid = args.input.grid(&volume)?;
                let read_ms = started.elapsed().as_secs_f64() * 1e3;
                convert(args, &GridPlanes(grid), &volume.name, read_ms)
            }
        }
    })?;
    print_report(&report, args.json, |r| {
        println!(
            "wrote {}: {}x{}x{} {}, {} levels ({} samples), {:.2} MB on disk for {:.2} MB of samples",
            r.output,
            r.dims[0],
            r.dims[1],
            r.dims[2],
            r.scalar_type,
            r.levels,
            r.samples,
            r.store_bytes as f64 / 1e6,
            r.volume_bytes as f64 / 1e6
        );
        println!(
            "times: read {:.0} ms, one pass (octree and levels) {:.0} ms ({:.1} MB/s of samples)",
            r.read_ms,
            r.pass_ms,
            r.volume_bytes as f64 / 1e3 / r.pass_ms.max(1e-3)
        );
    })
}

/// Writes the store of `source` in one pass and reports.
fn convert(args: &ConvertArgs, source: &dyn PlaneSource, name: &str, read_ms: f64) -> Result<ConvertReport> {
    let shape = source.shape();
    let options = WriteOptions { memory_limit: (args.memory_mb * 1e6) as usize, name: name.to_string() };
    let started = Instant::now();
    let bar = (std::io::stderr().is_terminal() && shape.point_count() >= PROGRESS_POINTS).then(|| {
        let bar = indicatif::ProgressBar::new(1000);
        bar.set_style(
            indicatif::ProgressStyle::with_template("converting {bar:40} {percent:>3}% {elapsed} (eta {eta})")
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar
    });
    let build = BuildOptions { leaf_size: args.leaf_size };
    let written = write_store_streaming(&args.output, source, &build, &options, &mut |done, total| {
        if let Some(bar) = &bar {
            bar.set_position(done * 1000 / total.max(1));
        }
    });
    if let Some(bar) = bar {
        bar.finish_and_clear();
    }
    let written = written?;
    Ok(ConvertReport {
        output: args.output.display().to_string(),
        dims: shape.dims,
        scalar_type: source.scalar_type().name().to_string(),
        levels: written.summary.levels,
        samples: written.summary.samples,
        slab_planes: written.summary.slab_planes,
        store_bytes: folder_bytes(&args.output),
        volume_bytes: (shape.point_count() * source.scalar_type().size()) as u64,
        nan_count: written.streamed.nan_count,
        read_ms,
        pass_ms: started.elapsed().as_secs_f64() * 1e3,
    })
}

/// Bytes of the files under `dir`.
fn folder_bytes(dir: &Path) -> u64 {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return 0;
    };
    entries
        .flatten()
        .map(|e| match e.file_type() {
            Ok(t) if t.is_dir() => folder_bytes(&e.path()),
            Ok(_) => e.metadata().map_or(0, |m| m.len()),
            Err(_) => 0,
        })
        .sum()
}
