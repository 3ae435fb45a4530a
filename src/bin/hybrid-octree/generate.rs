//! `generate`: write a built-in dataset to a `.vti` file.

use crate::extension::require_extension;
use crate::input::check_size;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::datasets::{generate, Dataset};
use hybrid_octree::grid::ScalarType;
use hybrid_octree::io::write_vti;
use hybrid_octree::Result;
use std::path::PathBuf;

/// Arguments of `generate`.
#[derive(Args, Debug)]
pub struct GenerateArgs {
    /// Built-in dataset: shepp-logan, marschner-lobb, sphere, ramp, constant, vessels.
    #[arg(long)]
    dataset: String,
    /// Samples per axis.
    #[arg(long)]
    size: usize,
    /// Scalar type (u8, i8, u16, i16, u32, i32, f32, f64).
    #[arg(long = "type", default_value = "f32")]
    scalar_type: String,
    /// Output file (.vti).
    #[arg(long)]
    output: PathBuf,
    /// Worker threads (default: all cores).
    #[arg(long)]
    threads: Option<usize>,
}

/// Generates the dataset and writes it.
pub fn run(args: &GenerateArgs) -> Result<()> {
    require_extension(&args.output, "--output", &[".vti"], "VTK XML image data")?;
    let dataset = Dataset::parse(&args.dataset)?;
    let scalar_type = ScalarType::parse(&args.scalar_type)?;
    check_size(args.size, scalar_type)?;
    let volume = with_threads(args.threads, || Ok(generate(dataset, args.size, scalar_type)))?;
    write_vti(&args.output, &volume)?;
    eprintln!("wrote {} {}^3 {} to {}", dataset.name(), args.size, scalar_type.name(), args.output.display());
    Ok(())
}
