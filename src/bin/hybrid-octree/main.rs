//! `hybrid-octree`: build, describe, generate and benchmark Hybrid Octree
//! volumes from the command line.
//!
//! ```text
//! hybrid-octree info     (--dataset NAME --size N | --file PATH) [--type T] [--component C]
//! hybrid-octree build    (--dataset NAME --size N | --file PATH) [--leaf-size B] [--tolerance T] [--json]
//! hybrid-octree surface  (--dataset NAME --size N | --file PATH) --isovalue V [--mode discretized|interpolated] [--distance] [--output F.vtk] [--json]
//! hybrid-octree render   (--dataset NAME --size N | --file PATH) --output F.png [--budget-mb M] [--tolerance T] [--isovalue V] [--reference R.png] [--target-ms T] [--json]
//! hybrid-octree generate --dataset NAME --size N [--type T] --output FILE.vti
//! hybrid-octree convert  (--dataset NAME --size N | --file PATH) --output F.ome.zarr [--leaf-size B] [--memory-mb M] [--json]
//! hybrid-octree bench build [--sizes 64,128] [--types f32,u8] [--threads 1,2] [--leaf-sizes 16] [--kernels fast,general] [--repeats 3] [--json]
//! hybrid-octree bench render (--dataset NAME --size N | --file PATH) [--strides 2,4,8] [--tolerances ...] [--targets-ms 20,50,100,200] [--plot P.png] [--json]
//! hybrid-octree bench effects (--dataset NAME --size N | --file PATH) [--budget-mb M] [--frames 5] [--effects plain,shade,...] [--plot P.png] [--json]
//! hybrid-octree bench scale [--sizes 256,512,1024] [--type u8,u16] [--dataset NAME] [--budget-mb M] [--json]
//! hybrid-octree bench select (--dataset NAME --size N | --file PATH) [--budgets-mb 8,64] [--roi X,Y,Z,R] [--repeats 5] [--json]
//! hybrid-octree bench surface [--cases shepp-logan:0.5,...] [--size 256] [--modes discmc,...] [--threads 1,2] [--json]
//! ```
//!
//! Library errors print `error: <message>` on stderr and exit with status 2.

mod bench;
mod build;
mod convert;
mod crop;
mod extension;
mod field;
mod ftb;
mod generate;
mod info;
mod input;
mod output;
mod plot;
mod points;
mod pool;
mod render;
mod scattering;
mod scene;
mod shade;
mod slice;
mod surface;
mod timed;
mod transfer2d;
mod view;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "hybrid-octree", version, about = "Build, describe and benchmark Hybrid Octree volumes")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Describe the input volume (dims, type, geometry, value range) without building.
    Info(info::InfoArgs),
    /// Build the Volume Octree and report its size, shape and build time.
    Build(build::BuildArgs),
    /// Extract the Hybrid Octree's isosurface (DiscMC + face compression, or interpolated MC).
    Surface(surface::SurfaceArgs),
    /// Render one frame under a texture budget to a PNG (CPU compositor), optionally against the reference.
    Render(Box<render::RenderArgs>),
    /// Write a built-in dataset to a VTK XML image file (.vti).
    Generate(generate::GenerateArgs),
    /// Write any input as an OME-Zarr image holding the Hybrid Octree (every stride's level and the octree).
    Convert(Box<convert::ConvertArgs>),
    /// Display the binary octree of an isovalue front to back with blocking quadtrees, against back to front.
    Ftb(ftb::FtbArgs),
    /// The hybrid point/volume representation: points where the low resolution is wrong, written to a file and drawn.
    Points(Box<points::PointsArgs>),
    /// Benchmarks that print a table.
    Bench {
        #[command(subcommand)]
        bench: bench::BenchCommand,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Info(args) => info::run(&args),
        Command::Build(args) => build::run(&args),
        Command::Surface(args) => surface::run(&args),
        Command::Render(args) => render::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Convert(args) => convert::run(&args),
        Command::Ftb(args) => ftb::run(&args),
        Command::Points(args) => points::run(&args),
        Command::Bench { bench } => bench::run(&bench),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
