//! `bench build`: Volume Octree build time over sizes, types, thread counts
//! and leaf sizes, on built-in datasets (default: the Shepp-Logan phantom).
//! Prints a table (or JSON rows) and, per (dataset, type, threads, leaf size),
//! the ns/voxel ratio between the largest and the smallest size (1.0 means
//! linear scaling) and the spread max/min of ns/voxel over all sizes.
//!
//! The phantom is piecewise constant, so larger sizes have relatively more
//! constant bricks and get cheaper per voxel; `--datasets marschner-lobb`
//! (smooth everywhere, no constant brick) shows the kernel's own scaling.

use super::median_ms;
use crate::input::check_size;
use crate::output::print_report;
use crate::pool::{check_thread_list, with_threads};
use clap::Args;
use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::grid::ScalarType;
use hybrid_octree::octree::{BuildOptions, KernelPath, VolumeOctree, DEFAULT_LEAF_SIZE};
use hybrid_octree::volume::Volume;
use hybrid_octree::{Error, Result};
use serde::Serialize;

/// Arguments of `bench build`.
#[derive(Args, Debug)]
pub struct BenchBuildArgs {
    /// Cube sizes (samples per axis).
    #[arg(long, value_delimiter = ',', default_value = "64,128,256,512")]
    sizes: Vec<usize>,
    /// Built-in datasets.
    #[arg(long, value_delimiter = ',', default_value = "shepp-logan")]
    datasets: Vec<String>,
    /// Scalar types.
    #[arg(long, value_delimiter = ',', default_value = "f32,u8")]
    types: Vec<String>,
    /// Thread counts (default: all cores).
    #[arg(long, value_delimiter = ',')]
    threads: Option<Vec<usize>>,
    /// Leaf brick sizes.
    #[arg(long, value_delimiter = ',', default_values_t = [DEFAULT_LEAF_SIZE])]
    leaf_sizes: Vec<usize>,
    /// Leaf kernel paths: `fast` (the build's) and `general` (the stride-by-stride
    /// reference kernel, for a before/after in one run).
    #[arg(long, value_delimiter = ',', default_value = "fast")]
    kernels: Vec<String>,
    /// Timed builds per row (after one untimed warm-up); the median is reported.
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One row of the table.
#[derive(Debug, Serialize)]
struct Row {
    dataset: &'static str,
    size: usize,
    scalar_type: &'static str,
    threads: usize,
    leaf_size: usize,
    kernel: &'static str,
    node_count: usize,
    build_ms: f64,
    copy_ms: f64,
    build_per_copy: f64,
    mvoxels_per_s: f64,
    ns_per_voxel: f64,
    octree_bytes: usize,
    octree_percent: f64,
}

/// Runs the benchmark.
pub fn run(args: &BenchBuildArgs) -> Result<()> {
    if args.repeats == 0 {
        return Err(Error::InvalidArgument("--repeats must be at least 1".into()));
    }
    let types = args.types.iter().map(|t| ScalarType::parse(t)).collect::<Result<Vec<_>>>()?;
    let datasets = args.datasets.iter().map(|d| Dataset::parse(d)).collect::<Result<Vec<_>>>()?;
    let kernels = args.kernels.iter().map(|k| parse_kernel(k)).collect::<Result<Vec<_>>>()?;
    let threads = args.threads.clone().unwrap_or_else(|| vec![rayon::current_num_threads()]);
    check_thread_list(&threads)?;
    for &size in &args.sizes {
        if size < 2 {
            return Err(Error::InvalidArgument(format!("benchmark size {size} is too small: use at least 2")));
        }
        for &scalar_type in &types {
            check_size(size, scalar_type)?;
        }
    }
    let mut rows = Vec::new();
    if !args.json {
        println!(
            "{:>15} {:>6} {:>5} {:>7} {:>5} {:>7} {:>9} {:>10} {:>8} {:>10} {:>9} {:>8} {:>12} {:>8}",
            "dataset",
            "size",
            "type",
            "threads",
            "leaf",
            "kernel",
            "nodes",
            "build ms",
            "copy ms",
            "build/copy",
            "Mvox/s",
            "ns/vox",
            "octree B",
            "oct/in %"
        );
    }
    for &dataset in &datasets {
        for &scalar_type in &types {
            for &t in &threads {
                for &leaf_size in &args.leaf_sizes {
                    for &size in &args.sizes {
                        let volume = generate(dataset, size, scalar_type);
                        for &kernel in &kernels {
                            let row = with_threads(Some(t), || {
                                measure(dataset, &volume, size, t, leaf_size, kernel, args.repeats)
                            })?;
                            if !args.json {
                                print_row(&row);
                            }
                            rows.push(row);
                        }
                    }
                }
            }
        }
    }
    print_report(&rows, args.json, |rows| print_ratios(rows))
}

fn parse_kernel(name: &str) -> Result<KernelPath> {
    match name {
        "fast" => Ok(KernelPath::Fast),
        "general" => Ok(KernelPath::General),
        _ => Err(Error::InvalidArgument(format!("unknown kernel {name:?}: use fast or general"))),
    }
}

fn kernel_name(kernel: KernelPath) -> &'static str {
    match kernel {
        KernelPath::Fast => "fast",
        KernelPath::General => "general",
    }
}

fn measure(
    dataset: Dataset,
    volume: &Volume,
    size: usize,
    threads: usize,
    leaf_size: usize,
    kernel: KernelPath,
    repeats: usize,
) -> Result<Row> {
    let grid = volume.grid(None)?;
    let options = BuildOptions { leaf_size };
    let build = || VolumeOctree::build_with_kernel(&grid, &options, kernel, &mut |_| true);
    let octree = build()?; // for the counts
    let build_ms = median_ms(repeats, || build().map(drop))?;
    // A plain copy of the samples into an allocated buffer: one read and one write of the volume.
    let bytes = grid.samples().as_bytes();
    let mut copy = vec![0u8; bytes.len()];
    let copy_ms = median_ms(repeats, || {
        copy.copy_from_slice(std::hint::black_box(bytes));
        std::hint::black_box(&copy);
        Ok(())
    })?;
    let voxels = grid.shape().point_count() as f64;
    let stats = octree.stats();
    Ok(Row {
        dataset: dataset.name(),
        size,
        scalar_type: grid.samples().scalar_type().name(),
        threads,
        leaf_size,
        kernel: kernel_name(kernel),
        node_count: stats.node_count,
        build_ms,
        copy_ms,
        build_per_copy: build_ms / copy_ms,
        mvoxels_per_s: voxels / (build_ms * 1e3),
        ns_per_voxel: build_ms * 1e6 / voxels,
        octree_bytes: stats.octree_bytes,
        octree_percent: 100.0 * stats.octree_bytes as f64 / grid.input_bytes() as f64,
    })
}

fn print_row(r: &Row) {
    println!(
        "{:>15} {:>6} {:>5} {:>7} {:>5} {:>7} {:>9} {:>10.1} {:>8.2} {:>10.1} {:>9.1} {:>8.2} {:>12} {:>8.2}",
        r.dataset,
        r.size,
        r.scalar_type,
        r.threads,
        r.leaf_size,
        r.kernel,
        r.node_count,
        r.build_ms,
        r.copy_ms,
        r.build_per_copy,
        r.mvoxels_per_s,
        r.ns_per_voxel,
        r.octree_bytes,
        r.octree_percent
    );
}

/// Per (dataset, type, threads, leaf size): ns/voxel of the largest size over
/// the smallest, and the spread (max / min ns/voxel over all sizes).
fn print_ratios(rows: &[Row]) {
    let mut groups: Vec<(&str, &str, usize, usize, &str)> = Vec::new();
    for r in rows {
        let key = (r.dataset, r.scalar_type, r.threads, r.leaf_size, r.kernel);
        if !groups.contains(&key) {
            groups.push(key);
        }
    }
    for (dataset, ty, threads, leaf, kernel) in groups {
        let group: Vec<&Row> = rows
            .iter()
            .filter(|r| {
                r.dataset == dataset
                    && r.scalar_type == ty
                    && r.threads == threads
                    && r.leaf_size == leaf
                    && r.kernel == kernel
            })
            .collect();
        let (Some(small), Some(large)) = (group.iter().min_by_key(|r| r.size), group.iter().max_by_key(|r| r.size))
        else {
            continue;
        };
        if small.size != large.size {
            let ns = group.iter().map(|r| r.ns_per_voxel);
            let spread = ns.clone().fold(0.0, f64::max) / ns.fold(f64::INFINITY, f64::min);
            println!(
                "{dataset} {ty}, {threads} thread(s), leaf {leaf}, {kernel} kernel: ns/voxel size {} / size {} = {:.2}, max/min over sizes = {:.2}",
                large.size,
                small.size,
                large.ns_per_voxel / small.ns_per_voxel,
                spread
            );
        }
    }
}
