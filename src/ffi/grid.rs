//! The borrowed image: the bridge's [`GridDesc`] over the host's bytes as a
//! checked [`Grid`], and the one conversion of the bridge's scalar type.

use super::{GridDesc, ScalarType};
use crate::error::{Error, Result};
use crate::grid::{Grid, GridShape, Samples, ScalarType as GridScalarType};

/// The grid's scalar type of the bridge's (the one C++ maps VTK type codes to).
pub(crate) fn scalar_type(t: ScalarType) -> Result<GridScalarType> {
    Ok(match t {
        ScalarType::U8 => GridScalarType::U8,
        ScalarType::I8 => GridScalarType::I8,
        ScalarType::U16 => GridScalarType::U16,
        ScalarType::I16 => GridScalarType::I16,
        ScalarType::U32 => GridScalarType::U32,
        ScalarType::I32 => GridScalarType::I32,
        ScalarType::F32 => GridScalarType::F32,
        ScalarType::F64 => GridScalarType::F64,
        _ => return Err(Error::InvalidArgument("unknown scalar type code from C++".into())),
    })
}

/// The bridge's scalar type of the grid's (what C++ maps back to a VTK type code).
pub(crate) fn bridge_scalar_type(t: GridScalarType) -> ScalarType {
    match t {
        GridScalarType::U8 => ScalarType::U8,
        GridScalarType::I8 => ScalarType::I8,
        GridScalarType::U16 => ScalarType::U16,
        GridScalarType::I16 => ScalarType::I16,
        GridScalarType::U32 => ScalarType::U32,
        GridScalarType::I32 => ScalarType::I32,
        GridScalarType::F32 => ScalarType::F32,
        GridScalarType::F64 => ScalarType::F64,
    }
}

/// The samples and shape of `desc` over the borrowed bytes.
fn parts<'a>(bytes: &'a [u8], desc: &GridDesc) -> Result<(Samples<'a>, GridShape, Option<usize>)> {
    let samples = Samples::from_bytes(bytes, scalar_type(desc.scalar_type)?)?;
    let shape = GridShape { dims: desc.dims, spacing: desc.spacing, origin: desc.origin };
    Ok((samples, shape, usize::try_from(desc.component).ok()))
}

/// The checked grid over the borrowed bytes.
pub(crate) fn grid_of<'a>(bytes: &'a [u8], desc: &GridDesc) -> Result<Grid<'a>> {
    let (samples, shape, component) = parts(bytes, desc)?;
    Grid::new(samples, shape, desc.components, component)
}

/// As [`grid_of`] without the non-finite scan (see [`Grid::unscanned`]).
pub(crate) fn grid_unscanned<'a>(bytes: &'a [u8], desc: &GridDesc) -> Result<Grid<'a>> {
    let (samples, shape, component) = parts(bytes, desc)?;
    Grid::unscanned(samples, shape, desc.components, component)
}

/// `grid` is the image of `shape`, the one the octree (and its selections
/// and points) was made from: same dims, spacing and origin.
pub(crate) fn same_image(shape: &GridShape, grid: &Grid<'_>) -> Result<()> {
    if grid.shape() == shape {
        Ok(())
    } else {
        Err(Error::InvalidArgument(
            "the image changed since the octree was built (dims, spacing or origin); rebuild it".into(),
        ))
    }
}
