//! `info`: describe the input without building.

use crate::input::InputArgs;
use crate::pool::with_threads;
use clap::Args;
use hybrid_octree::Result;

/// Arguments of `info`.
#[derive(Args, Debug)]
pub struct InfoArgs {
    #[command(flatten)]
    input: InputArgs,
}

/// Prints dims, type, components, spacing, origin, bytes, the value range and the NaN count.
pub fn run(args: &InfoArgs) -> Result<()> {
    with_threads(args.input.threads, || {
        let volume = args.input.load()?;
        let s = &volume.shape;
        let [x, y, z] = s.dims;
        println!("name:        {}", volume.name);
        println!("dims:        {x} x {y} x {z} ({} points)", s.point_count());
        println!("type:        {}", volume.samples.scalar_type().name());
        println!("components:  {}", volume.components);
        println!("spacing:     {:?}", s.spacing);
        println!("origin:      {:?}", s.origin);
        println!("bytes:       {}", volume.samples.len() * volume.samples.scalar_type().size());
        if volume.components > 1 && args.input.component.is_none() {
            println!("value range: (choose --component 0..{} to see it)", volume.components - 1);
            return Ok(());
        }
        let grid = args.input.grid(&volume)?;
        let (lo, hi) = value_range(&grid);
        println!("value range: {lo} .. {hi} (component {}; NaN left out)", grid.component());
        println!("NaN samples: {} (no data)", grid.nan_count());
        Ok(())
    })
}

/// (min, max) of the grid's component, in parallel over z-slices (`f64::min`
/// and `f64::max` skip NaN).
fn value_range(grid: &hybrid_octree::grid::Grid<'_>) -> (f64, f64) {
    use rayon::prelude::*;
    let [nx, ny, nz] = grid.dims();
    (0..nz)
        .into_par_iter()
        .map(|k| {
            let mut r = (f64::INFINITY, f64::NEG_INFINITY);
            for j in 0..ny {
                for i in 0..nx {
                    let v = grid.value(i, j, k);
                    r = (r.0.min(v), r.1.max(v));
                }
            }
            r
        })
        .reduce(|| (f64::INFINITY, f64::NEG_INFINITY), |a, b| (a.0.min(b.0), a.1.max(b.1)))
}
