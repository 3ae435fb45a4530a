//! `generate`: write a built-in dataset to a `.vti` file.

use crate::extension::require_extension;
use crate::input::{check_size, triple};
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::datasets::generate::generate_slabs;
use hybrid_octree::datasets::Dataset;
use hybrid_octree::grid::{GridShape, ScalarType};
use hybrid_octree::io::vti_write::VtiWriter;
use hybrid_octree::{Error, Result};
use std::path::PathBuf;

/// Arguments of `generate`.
#[derive(Args, Debug)]
pub struct GenerateArgs {
    /// Built-in dataset: shepp-logan, marschner-lobb, sphere, ramp, constant, vessels, wavelet.
    #[arg(long)]
    dataset: String,
    /// Samples per axis (a cube; or --dims).
    #[arg(long, required_unless_present = "dims", conflicts_with = "dims")]
    size: Option<usize>,
    /// Samples along X,Y,Z (a box, e.g. 2048,2048,1024; or --size).
    #[arg(long, value_parser = triple::<usize>)]
    dims: Option<[usize; 3]>,
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

/// Generates the dataset and writes it, slab by slab (the volume is never
/// held whole).
pub fn run(args: &GenerateArgs) -> Result<()> {
    require_extension(&args.output, "--output", &[".vti"], "VTK XML image data")?;
    let dataset = Dataset::parse(&args.dataset)?;
    let scalar_type = ScalarType::parse(&args.scalar_type)?;
    let dims = match (args.size, args.dims) {
        (Some(size), None) => {
            check_size(size, scalar_type)?;
            [size; 3]
        }
        (None, Some(dims)) => {
            hybrid_octree::datasets::generate::check_generate(dims, scalar_type)?;
            dims
        }
        _ => return Err(Error::InvalidArgument("give the size as --size N (a cube) or --dims X,Y,Z, not both".into())),
    };
    write_dataset(&args.output, dataset, dims, scalar_type, args.threads)?;
    eprintln!(
        "wrote {} {}x{}x{} {} to {}",
        dataset.name(),
        dims[0],
        dims[1],
        dims[2],
        scalar_type.name(),
        args.output.display()
    );
    Ok(())
}

/// Writes `dims` samples of `dataset` as `scalar_type` to the `.vti` file
/// `path`, generated slab by slab on `threads` workers.
pub fn write_dataset(
    path: &std::path::Path,
    dataset: Dataset,
    dims: [usize; 3],
    scalar_type: ScalarType,
    threads: Option<usize>,
) -> Result<()> {
    let shape = GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] };
    // The file is created once the thread count is accepted: a refused run writes nothing.
    with_threads(threads, || {
        let mut writer = VtiWriter::create(path, &shape, 1, dataset.name(), scalar_type)?;
        generate_slabs(dataset, dims, scalar_type, &mut |slab| writer.write(slab.as_samples()))?;
        writer.finish()
    })
}
