//! Legacy VTK `.vtk` STRUCTURED_POINTS, read through vtkio. (`.vti` files go
//! through [`super::vti`], which reads every encoding VTK writes; vtkio cannot
//! read ParaView's default raw appended data.)
//!
//! The volume takes the active point scalars (the `SCALARS` attribute) or,
//! without one, the first point data array; its name and component count are
//! kept. Origin and spacing come from the file (vtkio stores them as `f32`).

use super::read::format_error;
use crate::error::Result;
use crate::grid::GridShape;
use crate::volume::{SampleBuf, Volume};
use std::path::Path;
use vtkio::model::{Attribute, DataArray, DataSet, ElementType, IOBuffer, ImageDataPiece, Piece};

/// Reads a legacy `.vtk` STRUCTURED_POINTS image.
pub fn read_vtk(path: &Path) -> Result<Volume> {
    let vtk = vtkio::Vtk::import(path).map_err(|e| {
        format_error(path, format!("not a readable VTK image file ({e}); the file may be truncated or corrupt"))
    })?;
    let DataSet::ImageData { extent, origin, spacing, pieces, .. } = vtk.data else {
        return Err(format_error(
            path,
            "the file holds no image data (vtkImageData / STRUCTURED_POINTS); \
             resample it to an image first (ParaView: Resample To Image)",
        ));
    };
    let piece = single_piece(path, pieces)?;
    // Legacy files carry the dims on the data set; XML pieces carry their own extent.
    let dims = match &piece.extent {
        vtkio::model::Extent::Ranges(_) => piece.extent.clone().into_dims(),
        vtkio::model::Extent::Dims(_) => extent.into_dims(),
    };
    let dims = dims.map(|d| d as usize);
    let array = point_scalars(path, piece.data)?;
    let components = array.elem.num_comp() as usize;
    let name = array.name.clone();
    let samples = to_samples(path, array.data)?;
    let shape = GridShape { dims, spacing: spacing.map(f64::from), origin: origin.map(f64::from) };
    let expected = shape.check(components).map_err(|e| format_error(path, e.to_string()))?;
    if samples.len() != expected {
        return Err(format_error(
            path,
            format!(
                "the point array '{name}' holds {} values but the extent {}x{}x{} with {components} component(s) \
                 needs {expected}; the file is truncated or corrupt",
                samples.len(),
                dims[0],
                dims[1],
                dims[2]
            ),
        ));
    }
    Ok(Volume { samples, shape, components, name })
}

fn single_piece(path: &Path, pieces: Vec<Piece<ImageDataPiece>>) -> Result<ImageDataPiece> {
    if pieces.len() != 1 {
        return Err(format_error(
            path,
            format!(
                "the image has {} pieces; only single-piece images are supported \
                 (save it again from ParaView as one .vti file)",
                pieces.len()
            ),
        ));
    }
    match pieces.into_iter().next() {
        Some(Piece::Inline(p)) => Ok(*p),
        _ => Err(format_error(path, "the image piece is stored in another file; open the .vti piece file itself")),
    }
}

/// The active point scalars, else the first point data array.
fn point_scalars(path: &Path, attributes: vtkio::model::Attributes) -> Result<DataArray> {
    let has_cell_data = !attributes.cell.is_empty();
    let mut arrays: Vec<DataArray> = attributes
        .point
        .into_iter()
        .filter_map(|a| match a {
            Attribute::DataArray(d) => Some(d),
            Attribute::Field { .. } => None,
        })
        .collect();
    if arrays.is_empty() {
        return Err(format_error(
            path,
            if has_cell_data {
                "the file has only cell data; the Hybrid Octree needs point scalars \
                 (ParaView: Cell Data to Point Data)"
            } else {
                "the file has no point data arrays; the Hybrid Octree needs point scalars"
            },
        ));
    }
    let active = arrays.iter().position(|a| matches!(a.elem, ElementType::Scalars { .. })).unwrap_or(0);
    Ok(arrays.swap_remove(active))
}

fn to_samples(path: &Path, data: IOBuffer) -> Result<SampleBuf> {
    Ok(match data {
        IOBuffer::U8(v) => SampleBuf::U8(v),
        IOBuffer::I8(v) => SampleBuf::I8(v),
        IOBuffer::U16(v) => SampleBuf::U16(v),
        IOBuffer::I16(v) => SampleBuf::I16(v),
        IOBuffer::U32(v) => SampleBuf::U32(v),
        IOBuffer::I32(v) => SampleBuf::I32(v),
        IOBuffer::F32(v) => SampleBuf::F32(v),
        IOBuffer::F64(v) => SampleBuf::F64(v),
        IOBuffer::Bit(_) | IOBuffer::U64(_) | IOBuffer::I64(_) => {
            return Err(format_error(
                path,
                "the point scalars are bit or 64-bit integer values, which the Hybrid Octree does not take; \
                 convert them to float, double or a 32-bit integer type",
            ))
        }
    })
}
