//! Benchmarks that print tables: `bench build` (the Volume Octree) and
//! `bench surface` (the Surface Octree's extraction and face compression),
//! `bench render` (what accuracy costs in time and memory when rendering),
//! `bench effects` (what each rendering effect costs), `bench scale` (each
//! step's time and peak memory as the volume grows), `bench select` (the
//! selection, fresh and incremental), `bench orbit` (the view-dependent
//! selection while the camera moves).

mod build;
mod effects;
mod memory;
mod orbit;
pub mod render;
mod scale;
mod select;
mod smart;
mod surface;
mod targets;

use clap::Subcommand;
use hybrid_octree::Result;
use std::time::Instant;

/// Benchmarks.
#[derive(Subcommand, Debug)]
pub enum BenchCommand {
    /// Volume Octree build time.
    Build(build::BenchBuildArgs),
    /// Isosurface extraction and face compression: time, faces, triangles.
    Surface(surface::BenchSurfaceArgs),
    /// Rendering under a texture budget: error against time and memory, octree vs uniform downsampling.
    Render(Box<render::BenchRenderArgs>),
    /// Each rendering effect (shading, blend modes, surfaces): frame time against the plain frame, RMSE, bytes, plan.
    Effects(Box<effects::BenchEffectsArgs>),
    /// Generate, read, build, select and first frame over sizes: time, time per voxel and peak RSS of each step.
    Scale(Box<scale::BenchScaleArgs>),
    /// A camera orbit under each view selection: re-selections, selection ms, uploaded bytes per frame, RMSE.
    Orbit(Box<orbit::BenchOrbitArgs>),
    /// Texture-budget selection: fresh and incremental re-selection (budget +-10 %, region of interest moved): ms and bricks.
    Select(Box<select::BenchSelectArgs>),
}

/// Runs a benchmark.
pub fn run(command: &BenchCommand) -> Result<()> {
    match command {
        BenchCommand::Build(args) => build::run(args),
        BenchCommand::Surface(args) => surface::run(args),
        BenchCommand::Render(args) => render::run(args),
        BenchCommand::Effects(args) => effects::run(args),
        BenchCommand::Scale(args) => scale::run(args),
        BenchCommand::Select(args) => select::run(args),
        BenchCommand::Orbit(args) => orbit::run(args),
    }
}

/// The median wall time of `repeats` runs of `f` (after one untimed warm-up), ms.
fn median_ms(repeats: usize, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    f()?;
    let mut times = Vec::with_capacity(repeats);
    for _ in 0..repeats {
        let started = Instant::now();
        f()?;
        times.push(started.elapsed().as_secs_f64() * 1e3);
    }
    times.sort_by(f64::total_cmp);
    Ok(times[times.len() / 2])
}
