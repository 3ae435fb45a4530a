//! `--transfer-2d FILE`: a 2D transfer function (vtkVolumeProperty's TF_2D,
//! ParaView's *Use 2D Transfer Function*) read from a small JSON file
//! (docs/CLI.md):
//!
//! ```text
//! { "width": W, "height": H,
//!   "rgba": [r, g, b, a, ...],      4 W H numbers in [0, 1], row-major: x the value, y the gradient magnitude
//!   "scalar_range": [lo, hi],       optional; default the data's range (VTK's axis)
//!   "gradient_max": g }             optional; default VTK's (hi - lo) / (4 mean spacing)
//! ```

use hybrid_octree::grid::GridShape;
use hybrid_octree::transfer::TransferFunction2D;
use hybrid_octree::{Error, Result};
use std::path::Path;

/// The largest file read (a 4096 x 4096 table in short decimals fits).
const MAX_FILE_BYTES: u64 = 1 << 30;

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    width: usize,
    height: usize,
    rgba: Vec<f32>,
    scalar_range: Option<[f64; 2]>,
    gradient_max: Option<f64>,
}

/// The table of `path` for data of `range` on a grid of `shape` (module documentation).
pub fn load(path: &Path, range: (f64, f64), shape: &GridShape) -> Result<TransferFunction2D> {
    let bad = |message: String| Error::InvalidArgument(format!("--transfer-2d {}: {message}", path.display()));
    let size = std::fs::metadata(path).map_err(|e| bad(format!("cannot read it ({e})")))?.len();
    if size > MAX_FILE_BYTES {
        return Err(bad(format!("{size} bytes, more than the {MAX_FILE_BYTES} a table file may have")));
    }
    let text = std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it ({e})")))?;
    let file: File = serde_json::from_str(&text).map_err(|e| {
        bad(format!(
            "not a 2D transfer function ({e}): give {{\"width\": W, \"height\": H, \"rgba\": [4 W H numbers]}} (docs/CLI.md)"
        ))
    })?;
    TransferFunction2D::check_sides(file.width, file.height).map_err(|e| bad(e.to_string()))?;
    if file.rgba.len() != 4 * file.width * file.height {
        return Err(bad(format!(
            "{} rgba numbers for a {} x {} table: give 4 (r, g, b, a) per texel, {}",
            file.rgba.len(),
            file.width,
            file.height,
            4 * file.width * file.height
        )));
    }
    let rgba: Vec<[f32; 4]> = file.rgba.chunks_exact(4).map(|t| [t[0], t[1], t[2], t[3]]).collect();
    let vtk = TransferFunction2D::from_vtk(file.width, file.height, rgba, range, shape.spacing)
        .map_err(|e| bad(e.to_string()))?;
    let scalar_range = file.scalar_range.unwrap_or(vtk.scalar_range());
    let gradient_max = file.gradient_max.unwrap_or(vtk.gradient_max());
    let texels = vtk.texels().to_vec();
    TransferFunction2D::new(file.width, file.height, texels, scalar_range, gradient_max).map_err(|e| bad(e.to_string()))
}
