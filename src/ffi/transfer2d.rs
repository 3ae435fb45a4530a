//! The 2D transfer function as the host hands it over (`SelectDesc`'s
//! `transfer_2d_*`): vtkVolumeProperty's TransferFunction2D image, its
//! texels flattened, read with VTK 9.2's axes
//! ([`TransferFunction2D::from_vtk`]).

use super::SelectDesc;
use crate::error::{Error, Result};
use crate::grid::GridShape;
use crate::transfer::TransferFunction2D;

/// The 2D transfer function of `desc` for a grid of `shape` (`None` when
/// its size is `[0, 0]`), sides checked before the texels are read.
pub(crate) fn vtk_transfer_2d(desc: &SelectDesc, shape: &GridShape) -> Result<Option<TransferFunction2D>> {
    let [width, height] = desc.transfer_2d_size;
    if width == 0 && height == 0 && desc.transfer_2d_rgba.is_empty() {
        return Ok(None);
    }
    TransferFunction2D::check_sides(width, height)?;
    if desc.transfer_2d_rgba.len() != 4 * width * height {
        return Err(Error::InvalidArgument(format!(
            "2D transfer function: {} values for a {width} x {height} image: give 4 (r, g, b, a) per texel",
            desc.transfer_2d_rgba.len()
        )));
    }
    let rgba = desc.transfer_2d_rgba.chunks_exact(4).map(|t| [t[0], t[1], t[2], t[3]]).collect();
    let [lo, hi] = desc.transfer_2d_range;
    TransferFunction2D::from_vtk(width, height, rgba, (lo, hi), shape.spacing).map(Some)
}
