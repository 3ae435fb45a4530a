//! `bench surface`: isosurface extraction of the Hybrid Octree, per dataset
//! and isovalue, in every mode: DiscMC with face compression, DiscMC facets
//! unmerged, and interpolated Marching Cubes (the same-process baseline).
//! Prints the median times, the faces and triangles, and the ratios to the
//! interpolated row of the same case (what merging costs and saves).

use super::median_ms;
use crate::build::build_octree;
use crate::input::check_dataset_size;
use crate::output::print_report;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::grid::ScalarType;
use hybrid_octree::octree::{BuildOptions, DEFAULT_LEAF_SIZE};
use hybrid_octree::surface::{Surface, SurfaceOptions};
use hybrid_octree::{Error, Result};
use serde::Serialize;

/// Arguments of `bench surface`.
#[derive(Args, Debug)]
pub struct BenchSurfaceArgs {
    /// Cases as DATASET:ISOVALUE (values of the f32 datasets are in [0, 1]).
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "shepp-logan:0.5,shepp-logan:0.25,marschner-lobb:0.5,marschner-lobb:0.3"
    )]
    cases: Vec<String>,
    /// Modes to run: interpolated (the baseline of the ratios), discmc-unmerged, discmc.
    #[arg(long, value_delimiter = ',', default_values_t = MODES.map(String::from))]
    modes: Vec<String>,
    /// Samples per axis.
    #[arg(long, default_value_t = 256)]
    size: usize,
    /// Thread counts (default: all cores).
    #[arg(long, value_delimiter = ',')]
    threads: Option<Vec<usize>>,
    /// Leaf brick size of the Volume Octree.
    #[arg(long, default_value_t = DEFAULT_LEAF_SIZE)]
    leaf_size: usize,
    /// Timed extractions per row (after one untimed warm-up); the median is reported.
    #[arg(long, default_value_t = 5)]
    repeats: usize,
    /// Print the rows as a JSON array instead of a table.
    #[arg(long)]
    json: bool,
}

/// One row of the table.
#[derive(Debug, Serialize)]
struct Row {
    dataset: &'static str,
    isovalue: f64,
    mode: &'static str,
    threads: usize,
    /// Median wall time of `Surface::extract`, ms.
    total_ms: f64,
    /// Median marching time, ms.
    extract_ms: f64,
    /// Median compression + naming + assembly time, ms.
    compress_ms: f64,
    faces: usize,
    triangles: usize,
    vertices: usize,
    uncompressed_triangles: usize,
    /// `total_ms` over the interpolated row's (the first mode run, if interpolated is not).
    time_vs_interpolated: f64,
    /// `triangles` over the marched triangles.
    triangles_vs_uncompressed: f64,
}

const MODES: [&str; 3] = ["interpolated", "discmc-unmerged", "discmc"];

fn options(mode: &str, isovalue: f64) -> SurfaceOptions {
    match mode {
        "interpolated" => SurfaceOptions::interpolated(isovalue),
        "discmc-unmerged" => SurfaceOptions { compress: false, ..SurfaceOptions::discretized(isovalue) },
        _ => SurfaceOptions::discretized(isovalue),
    }
}

fn parse_case(case: &str) -> Result<(Dataset, f64)> {
    let bad = || Error::InvalidArgument(format!("case '{case}' is not DATASET:ISOVALUE (e.g. shepp-logan:0.5)"));
    let (name, iso) = case.split_once(':').ok_or_else(bad)?;
    let iso: f64 = iso.trim().parse().map_err(|_| bad())?;
    Ok((Dataset::parse(name.trim())?, iso))
}

/// Runs the benchmark.
pub fn run(args: &BenchSurfaceArgs) -> Result<()> {
    if args.repeats == 0 {
        return Err(Error::InvalidArgument("--repeats must be at least 1".into()));
    }
    let cases = args.cases.iter().map(|c| parse_case(c)).collect::<Result<Vec<_>>>()?;
    let threads = args.threads.clone().unwrap_or_else(|| vec![rayon::current_num_threads()]);
    if let Some(bad) = args.modes.iter().find(|m| !MODES.contains(&m.as_str())) {
        return Err(Error::InvalidArgument(format!("unknown mode '{bad}': use {}", MODES.join(", "))));
    }
    if !args.json {
        println!(
            "{:>15} {:>6} {:>16} {:>3} {:>9} {:>8} {:>9} {:>8} {:>9} {:>9} {:>7} {:>7}",
            "dataset",
            "iso",
            "mode",
            "thr",
            "total ms",
            "extract",
            "compress",
            "faces",
            "triangles",
            "vertices",
            "t/interp",
            "tri/unc"
        );
    }
    let mut rows = Vec::new();
    for (dataset, isovalue) in cases {
        check_dataset_size(dataset, args.size, ScalarType::F32)?;
        let volume = generate(dataset, args.size, ScalarType::F32);
        let grid = volume.grid(None)?;
        for &t in &threads {
            let case_rows = with_threads(Some(t), || {
                let octree = build_octree(&grid, &BuildOptions { leaf_size: args.leaf_size })?;
                let mut out: Vec<Row> = Vec::new();
                for mode in MODES.into_iter().filter(|m| args.modes.iter().any(|a| a == m)) {
                    let options = options(mode, isovalue);
                    let mut stats = Vec::new();
                    let total_ms = median_ms(args.repeats, || {
                        stats.push(Surface::extract(&grid, &octree, &options)?.stats);
                        Ok(())
                    })?;
                    let median = |f: fn(&hybrid_octree::surface::SurfaceStats) -> f64| {
                        let mut v: Vec<f64> = stats[1..].iter().map(f).collect();
                        v.sort_by(f64::total_cmp);
                        v[v.len() / 2]
                    };
                    let last = &stats[stats.len() - 1];
                    let baseline = out.first().map_or(total_ms, |r| r.total_ms);
                    out.push(Row {
                        dataset: dataset.name(),
                        isovalue,
                        mode,
                        threads: t,
                        total_ms,
                        extract_ms: median(|s| s.extract_ms),
                        compress_ms: median(|s| s.compress_ms),
                        faces: last.faces,
                        triangles: last.triangles,
                        vertices: last.vertices,
                        uncompressed_triangles: last.uncompressed_triangles,
                        time_vs_interpolated: total_ms / baseline,
                        triangles_vs_uncompressed: last.triangles as f64 / last.uncompressed_triangles.max(1) as f64,
                    });
                }
                Ok(out)
            })?;
            for r in case_rows {
                if !args.json {
                    print_row(&r);
                }
                rows.push(r);
            }
        }
    }
    print_report(&rows, args.json, |_| {})
}

fn print_row(r: &Row) {
    println!(
        "{:>15} {:>6} {:>16} {:>3} {:>9.1} {:>8.1} {:>9.1} {:>8} {:>9} {:>9} {:>7.2} {:>7.3}",
        r.dataset,
        r.isovalue,
        r.mode,
        r.threads,
        r.total_ms,
        r.extract_ms,
        r.compress_ms,
        r.faces,
        r.triangles,
        r.vertices,
        r.time_vs_interpolated,
        r.triangles_vs_uncompressed
    );
}
