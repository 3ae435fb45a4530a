//! Reading VTK XML ImageData (`.vti`) in every encoding VTK's
//! `vtkXMLImageDataWriter` produces: appended raw (ParaView's default),
//! appended base64, inline binary (base64) and ascii; `UInt32` or `UInt64`
//! headers; little or big endian; uncompressed or compressed with ZLib, LZ4
//! or LZMA. The XML header is parsed by [`super::vti_xml`], the array by
//! [`super::vti_data`].
//!
//! The volume takes the active point scalars (the `Scalars` attribute of
//! `PointData`) or, without one, the first point data array, with its name and
//! component count. Geometry:
//!
//! * dims are the piece's `Extent` (else `WholeExtent`) plus one;
//! * the origin is the world position of the extent's first point,
//!   `Origin + extent_min * Spacing` (VTK's `Origin` is that of index 0,
//!   which need not be in the extent: ParaView's Wavelet spans -10..10);
//! * a `Direction` other than the identity is refused: the Hybrid Octree is
//!   axis-aligned, and ignoring it would misplace the data.

use super::format_error;
use super::vti_data::decode_array;
use super::vti_xml::{parse_header, VtiHeader};
use crate::base::error::Result;
use crate::base::limits::excerpt;
use crate::data::grid::GridShape;
use crate::data::volume::Volume;

/// Reads the `.vti` file `bytes` (`label` names it in errors).
pub fn read_vti_bytes(label: &str, bytes: &[u8]) -> Result<Volume> {
    let header = parse_header(bytes).map_err(|m| format_error(label, m))?;
    volume_from(bytes, &header).map_err(|m| format_error(label, m))
}

fn volume_from(bytes: &[u8], header: &VtiHeader) -> std::result::Result<Volume, String> {
    match header.file_type.as_str() {
        "ImageData" => {}
        "PImageData" => {
            return Err("this is a parallel image index (.pvti); open one of its piece files, or save the \
                        data again as a single .vti"
                .into())
        }
        other => {
            return Err(format!(
                "the file holds VTK XML '{}', not image data (ImageData); resample it to an image first \
                 (ParaView: Resample To Image)",
                excerpt(other)
            ))
        }
    }
    if let Some(d) = header.direction {
        const IDENTITY: [f64; 9] = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
        if d.iter().zip(IDENTITY).any(|(a, b)| (a - b).abs() > 1e-9) {
            return Err(format!(
                "the image has a rotated or flipped Direction {d:?}; the Hybrid Octree takes axis-aligned images \
                 only: resample it (ParaView: Resample To Image) and save it again"
            ));
        }
    }
    let piece = match header.pieces.as_slice() {
        [] => return Err("the image has no <Piece>; the file is truncated or corrupt".into()),
        [piece] => piece,
        pieces => {
            return Err(format!(
                "the image has {} pieces; only single-piece images are supported \
                 (save it again from ParaView as one .vti file)",
                pieces.len()
            ))
        }
    };
    if let Some(source) = &piece.source {
        return Err(format!(
            "the image piece is stored in another file ('{}'); open that .vti piece file itself",
            excerpt(source)
        ));
    }
    let extent = piece
        .extent
        .or(header.whole_extent)
        .ok_or("the image has neither a piece Extent nor a WholeExtent; the file is corrupt")?;
    let mut dims = [0usize; 3];
    let mut origin = header.origin;
    for a in 0..3 {
        let (lo, hi) = (extent[2 * a], extent[2 * a + 1]);
        dims[a] = hi
            .checked_sub(lo)
            .and_then(|d| usize::try_from(d).ok())
            .and_then(|d| d.checked_add(1))
            .ok_or_else(|| format!("the extent {extent:?} is empty or inverted; the file is corrupt"))?;
        origin[a] += lo as f64 * header.spacing[a];
    }

    let arrays = &piece.point_arrays;
    if arrays.is_empty() {
        return Err(if piece.cell_arrays > 0 {
            "the file has only cell data; the Hybrid Octree needs point scalars (ParaView: Cell Data to Point Data)"
        } else {
            "the file has no point data arrays; the Hybrid Octree needs point scalars"
        }
        .into());
    }
    let active = piece.active_scalars.as_ref().and_then(|s| arrays.iter().position(|a| &a.name == s)).unwrap_or(0);
    let array = &arrays[active];
    let shape = GridShape { dims, spacing: header.spacing, origin };
    let count = shape.check(array.components).map_err(|e| e.to_string())?;
    let samples = decode_array(bytes, header, array, count)?;
    Ok(Volume { samples, shape, components: array.components, name: array.name.clone() })
}
