//! The Slice blend mode across the bridge: the plane of
//! [`super::SelectDesc::slice_plane`] (blend mode 6), checked, and as
//! [`super::DrawListOutput::slice_plane`] and
//! [`super::BrickGeometryDesc::slice_plane`] carry it.

use super::SelectDesc;
use crate::error::{Error, Result};
use crate::plan::{BlendMode, SlicePlane};

/// VTK's `vtkVolumeMapper::SLICE_BLEND`.
const SLICE_BLEND: i32 = 6;

/// The plane of `desc` under blend mode 6 (origin, normal; data
/// coordinates), checked; `None` under the other modes.
///
/// # Errors
///
/// [`Error::InvalidArgument`] for a plane that is not finite or has a zero normal.
pub(crate) fn slice_plane(desc: &SelectDesc) -> Result<Option<SlicePlane>> {
    if desc.blend_mode != SLICE_BLEND {
        return Ok(None);
    }
    let p = desc.slice_plane;
    SlicePlane::new([p[0], p[1], p[2]], [p[3], p[4], p[5]]).map(Some).map_err(|e| {
        Error::InvalidArgument(format!(
            "the Slice blend mode's {e} (vtkVolumeProperty::SetSliceFunction takes a vtkPlane; ParaView: Slice \
             Function)"
        ))
    })
}

/// The 6 values (origin, normal) of a list's plane under the Slice mode,
/// none under the others.
pub(crate) fn plane_values(mode: BlendMode, plane: Option<&SlicePlane>) -> Vec<f64> {
    match (mode, plane) {
        (BlendMode::Slice, Some(p)) => p.origin.into_iter().chain(p.normal).collect(),
        _ => Vec::new(),
    }
}

/// The plane of a [`super::BrickGeometryDesc::slice_plane`]: `None` when
/// empty (not Slice), else its 6 values checked.
pub(crate) fn geometry_plane(values: &[f64]) -> Result<Option<SlicePlane>> {
    match values {
        [] => Ok(None),
        [ox, oy, oz, nx, ny, nz] => SlicePlane::new([*ox, *oy, *oz], [*nx, *ny, *nz]).map(Some),
        _ => Err(Error::InvalidArgument(format!(
            "{} slice plane values: give none (not the Slice blend mode) or 6 (origin x, y, z, normal x, y, z)",
            values.len()
        ))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ffi::test_support::select_desc as options;

    #[test]
    fn the_plane_is_read_under_slice_only_and_checked() {
        let desc = SelectDesc { blend_mode: 6, slice_plane: [1.0, 2.0, 3.0, 0.0, 0.0, 2.0], ..options(30_000) };
        let p = slice_plane(&desc).unwrap().unwrap();
        assert_eq!((p.origin, p.normal), ([1.0, 2.0, 3.0], [0.0, 0.0, 2.0]));
        assert_eq!(slice_plane(&SelectDesc { blend_mode: 0, ..desc }).unwrap(), None);
        let e = slice_plane(&SelectDesc { blend_mode: 6, slice_plane: [0.0; 6], ..options(30_000) })
            .unwrap_err()
            .to_string();
        assert!(e.contains("non-zero") && e.contains("SetSliceFunction"), "{e}");
        let nan = [0.0, f64::NAN, 0.0, 0.0, 0.0, 1.0];
        assert!(slice_plane(&SelectDesc { blend_mode: 6, slice_plane: nan, ..options(30_000) }).is_err());
        assert_eq!(geometry_plane(&[]).unwrap(), None);
        assert!(geometry_plane(&[0.0; 5]).unwrap_err().to_string().contains("5 slice plane values"));
        assert!(geometry_plane(&[0.0; 6]).is_err());
        assert_eq!(plane_values(BlendMode::Slice, Some(&p)), vec![1.0, 2.0, 3.0, 0.0, 0.0, 2.0]);
        assert!(plane_values(BlendMode::Composite, Some(&p)).is_empty());
    }
}
