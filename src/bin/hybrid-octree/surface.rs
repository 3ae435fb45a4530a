//! `surface`: extract the Hybrid Octree's isosurface (DiscMC with face
//! compression, or interpolated MC) and report counts, times, watertightness
//! and, with `--distance`, how far the DiscMC surface lies from the
//! interpolated one; `--output` writes it as a legacy VTK polydata file.

use crate::build::build_octree;
use crate::extension::require_extension;
use crate::input::InputArgs;
use crate::output::print_report;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::hybrid::HybridOctree;
use hybrid_octree::octree::{BuildOptions, DEFAULT_LEAF_SIZE};
use hybrid_octree::surface::{check, distance, Surface, SurfaceMode, SurfaceOptions};
use hybrid_octree::{Error, Result};
use serde::Serialize;
use std::io::Write;
use std::path::PathBuf;

/// Arguments of `surface`.
#[derive(Args, Debug)]
pub struct SurfaceArgs {
    #[command(flatten)]
    input: InputArgs,
    /// The isovalue (inside is value >= isovalue).
    #[arg(long, allow_negative_numbers = true)]
    isovalue: f64,
    /// `discretized` (DiscMC, coplanar facets merged) or `interpolated` (classic MC).
    #[arg(long, default_value = "discretized")]
    mode: String,
    /// Keep DiscMC facets unmerged (to see what compression saves).
    #[arg(long)]
    no_compress: bool,
    /// Leaf brick size of the Volume Octree.
    #[arg(long, default_value_t = DEFAULT_LEAF_SIZE)]
    leaf_size: usize,
    /// Also measure the distance between the DiscMC and the interpolated surface (voxel units).
    #[arg(long)]
    distance: bool,
    /// Write the surface to this legacy VTK polydata file (.vtk).
    #[arg(long)]
    output: Option<PathBuf>,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
}

/// The surface report. Key names are a contract with the ParaView tests.
#[derive(Debug, Serialize)]
struct SurfaceReport {
    isovalue: f64,
    mode: SurfaceMode,
    compressed: bool,
    polygons: usize,
    faces: usize,
    triangles: usize,
    uncompressed_triangles: usize,
    vertices: usize,
    boundary_edges: usize,
    /// Edges used once along NaN (cells touching NaN have no facets).
    nan_boundary_edges: usize,
    surface_nodes: usize,
    extract_ms: f64,
    compress_ms: f64,
    build_ms: f64,
    area: f64,
    volume: f64,
    /// Edges used by more than two polygons or twice in one direction (0 = valid).
    nonmanifold_edges: usize,
    distance_mean: Option<f64>,
    distance_max: Option<f64>,
    distance_ms: Option<f64>,
}

/// Extracts and reports.
pub fn run(args: &SurfaceArgs) -> Result<()> {
    if let Some(path) = &args.output {
        require_extension(path, "--output", &[".vtk"], "legacy VTK polydata")?;
    }
    let mode = SurfaceMode::parse(&args.mode)?;
    let options = match mode {
        SurfaceMode::Discretized => {
            SurfaceOptions { compress: !args.no_compress, ..SurfaceOptions::discretized(args.isovalue) }
        }
        SurfaceMode::Interpolated => SurfaceOptions::interpolated(args.isovalue),
    };
    let report = with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let grid = args.input.grid(&volume)?;
        let octree = build_octree(&grid, &BuildOptions { leaf_size: args.leaf_size })?;
        let build_ms = octree.stats().build_ms;
        let surface = Surface::extract(&grid, &octree, &options)?;
        let hybrid = HybridOctree { volume: octree, surface: Some(surface), points: None };
        hybrid.validate().map_err(|e| Error::Internal(format!("Hybrid Octree failed validation: {e}")))?;
        let measured = if args.distance {
            let started = std::time::Instant::now();
            let d = distance::discretized_to_interpolated(&grid, &hybrid.volume, args.isovalue)?;
            Some((d, started.elapsed().as_secs_f64() * 1e3))
        } else {
            None
        };
        let Some(s) = &hybrid.surface else { unreachable!("the surface was integrated above") };
        if let Some(path) = &args.output {
            write_vtk(path, s, grid.shape())?;
        }
        let st = &s.stats;
        Ok(SurfaceReport {
            isovalue: args.isovalue,
            mode,
            compressed: options.compress && mode == SurfaceMode::Discretized,
            polygons: st.polygons,
            faces: st.faces,
            triangles: st.triangles,
            uncompressed_triangles: st.uncompressed_triangles,
            vertices: st.vertices,
            boundary_edges: st.boundary_edges,
            nan_boundary_edges: st.nan_boundary_edges,
            surface_nodes: st.surface_nodes,
            extract_ms: st.extract_ms,
            compress_ms: st.compress_ms,
            build_ms,
            area: check::area(s),
            volume: check::volume(s),
            nonmanifold_edges: check::edge_use(s).nonmanifold,
            distance_mean: measured.map(|m| m.0.mean),
            distance_max: measured.map(|m| m.0.max),
            distance_ms: measured.map(|m| m.1),
        })
    })?;
    print_report(&report, args.json, print_text)
}

fn print_text(r: &SurfaceReport) {
    println!("isovalue:               {} ({:?}{})", r.isovalue, r.mode, if r.compressed { ", compressed" } else { "" });
    println!("polygons:               {}", r.polygons);
    println!("faces:                  {} (coplanar facets merged)", r.faces);
    println!("triangles:              {} (the faces triangulated)", r.triangles);
    println!("uncompressed triangles: {}", r.uncompressed_triangles);
    println!("vertices:               {}", r.vertices);
    println!("boundary edges:         {} (where the surface leaves the volume)", r.boundary_edges);
    println!("NaN boundary edges:     {} (where the surface meets no data)", r.nan_boundary_edges);
    println!("non-manifold edges:     {}", r.nonmanifold_edges);
    println!("surface nodes:          {}", r.surface_nodes);
    println!("area / volume:          {:.6} / {:.6} (index units)", r.area, r.volume);
    println!("octree build:           {:.1} ms", r.build_ms);
    println!("extract + compress:     {:.1} + {:.1} ms", r.extract_ms, r.compress_ms);
    if let (Some(mean), Some(max), Some(ms)) = (r.distance_mean, r.distance_max, r.distance_ms) {
        println!("DiscMC vs interpolated: mean {mean:.4}, max {max:.4} voxels ({ms:.0} ms to measure)");
    }
}

/// Writes `s` as a legacy ASCII VTK polydata file in world coordinates, with normals.
fn write_vtk(path: &PathBuf, s: &Surface, shape: &hybrid_octree::grid::GridShape) -> Result<()> {
    let fail = |e: std::io::Error| Error::Write { path: path.display().to_string(), message: e.to_string() };
    let mut f = std::io::BufWriter::new(std::fs::File::create(path).map_err(fail)?);
    let mut text = String::new();
    text.push_str("# vtk DataFile Version 3.0\nHybrid Octree isosurface\nASCII\nDATASET POLYDATA\n");
    text.push_str(&format!("POINTS {} double\n", s.points.len()));
    for p in &s.points {
        let w = shape.world(*p);
        text.push_str(&format!("{} {} {}\n", w[0], w[1], w[2]));
    }
    text.push_str(&format!("POLYGONS {} {}\n", s.polygon_count(), s.polygon_count() + s.connectivity.len()));
    for i in 0..s.polygon_count() {
        let poly = s.polygon(i);
        text.push_str(&poly.len().to_string());
        for v in poly {
            text.push_str(&format!(" {v}"));
        }
        text.push('\n');
    }
    text.push_str(&format!("POINT_DATA {}\nNORMALS Normals float\n", s.points.len()));
    for n in &s.normals {
        text.push_str(&format!("{} {} {}\n", n[0], n[1], n[2]));
    }
    f.write_all(text.as_bytes()).map_err(fail)?;
    f.flush().map_err(fail)
}
