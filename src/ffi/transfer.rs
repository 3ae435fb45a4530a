//! Transfer functions as the host hands them over: flattened tuples.

use crate::error::{Error, Result};
use crate::grid::GridShape;
use crate::transfer::{GradientOpacity, TransferFunction};

/// The transfer function of `(value, r, g, b)` and `(value, opacity)` tuples, flattened.
pub(crate) fn transfer_function(colors: &[f64], opacities: &[f64]) -> Result<TransferFunction> {
    if !colors.len().is_multiple_of(4) || !opacities.len().is_multiple_of(2) {
        return Err(Error::InvalidArgument(format!(
            "{} colour and {} opacity values: give (value, r, g, b) and (value, opacity) tuples, flattened",
            colors.len(),
            opacities.len()
        )));
    }
    let c = colors.chunks(4).map(|v| (v[0], [v[1] as f32, v[2] as f32, v[3] as f32])).collect();
    let o = opacities.chunks(2).map(|v| (v[0], v[1] as f32)).collect();
    TransferFunction::new(c, o)
}

/// The transfer function of `(value, opacity)` pairs, flattened, with a white
/// colour (only the opacity matters); `None` when there are none.
pub(crate) fn opacity_function(points: &[f64]) -> Result<Option<TransferFunction>> {
    if points.is_empty() {
        return Ok(None);
    }
    if !points.len().is_multiple_of(2) {
        return Err(Error::InvalidArgument(format!(
            "{} opacity values: give (value, opacity) pairs, flattened",
            points.len()
        )));
    }
    let pairs: Vec<(f64, f32)> = points.chunks(2).map(|v| (v[0], v[1] as f32)).collect();
    TransferFunction::new(vec![(0.0, [1.0; 3])], pairs).map(Some)
}

/// The gradient opacity of VTK's `(magnitude, opacity)` pairs, flattened
/// (magnitudes per mean voxel spacing), for a grid of `shape` and value
/// `range` ([`GradientOpacity::from_vtk`]); `None` when there are none.
pub(crate) fn vtk_gradient_opacity(
    points: &[f64],
    shape: &GridShape,
    range: (f64, f64),
) -> Result<Option<GradientOpacity>> {
    if points.is_empty() {
        return Ok(None);
    }
    if !points.len().is_multiple_of(2) {
        return Err(Error::InvalidArgument(format!(
            "{} gradient opacity values: give (gradient magnitude, opacity) pairs, flattened",
            points.len()
        )));
    }
    let pairs: Vec<(f64, f32)> = points.chunks(2).map(|v| (v[0], v[1] as f32)).collect();
    GradientOpacity::from_vtk(pairs, shape.spacing, range).map(Some)
}
