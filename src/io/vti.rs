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
use super::vti_data::{decode_array, Appended};
use super::vti_xml::{parse_header, AppendedEncoding, VtiHeader};
use crate::base::error::Result;
use crate::base::limits::{check_memory, excerpt, human_bytes};
use crate::data::grid::GridShape;
use crate::data::volume::Volume;

/// Reads the `.vti` file `bytes` (`label` names it in errors).
pub fn read_vti_bytes(label: &str, bytes: &[u8]) -> Result<Volume> {
    let header = parse_header(bytes).map_err(|m| format_error(label, m))?;
    volume_from(bytes, &header, Appended::InMemory).map_err(|m| format_error(label, m))
}

/// Reads the `.vti` file `file` of `len` bytes: only the XML header (up to
/// the `_` of `AppendedData`, or the whole file when it has none or its
/// appended data are base64 text) is read into memory; raw appended values
/// go from the file straight into the volume's buffer.
pub fn read_vti_file(label: &str, file: &mut std::fs::File, len: u64) -> Result<Volume> {
    let fail = |m: String| format_error(label, m);
    let mut head = read_header_bytes(file, len).map_err(|e| fail(format!("cannot read the file: {e}")))?;
    let header = parse_header(&head).map_err(fail)?;
    if matches!(header.appended, Some((AppendedEncoding::Base64, _))) {
        // Base64 text is decoded from memory: the rest of the file too.
        check_memory(
            u128::from(len),
            &format!("reading '{label}' ({})", human_bytes(u128::from(len))),
            "free memory or raise HYBRID_OCTREE_MAX_MEMORY",
        )?;
        let rest = len.saturating_sub(head.len() as u64);
        std::io::Seek::seek(file, std::io::SeekFrom::Start(head.len() as u64))
            .map_err(|e| fail(format!("cannot read the file: {e}")))?;
        std::io::Read::read_to_end(&mut std::io::Read::take(&mut *file, rest), &mut head)
            .map_err(|e| fail(format!("cannot read the file: {e}")))?;
    }
    volume_from(&head, &header, Appended::File { file, len }).map_err(fail)
}

/// The file's first bytes, up to and including the `_` marker after the
/// `<AppendedData ...>` tag, or all of them when there is none (inline
/// arrays are in the XML). Read in growing chunks.
fn read_header_bytes(file: &mut std::fs::File, len: u64) -> std::io::Result<Vec<u8>> {
    use std::io::Read;
    const TAG: &[u8] = b"<AppendedData";
    let mut head = Vec::new();
    let mut chunk = 1usize << 16;
    loop {
        let before = head.len();
        let want = (len - before as u64).min(chunk as u64);
        file.by_ref().take(want).read_to_end(&mut head)?;
        let from = before.saturating_sub(TAG.len());
        if let Some(tag) = head[from..].windows(TAG.len()).position(|w| w == TAG).map(|p| p + from) {
            if let Some(marker) = head[tag..].iter().position(|&b| b == b'_') {
                head.truncate(tag + marker + 1);
                return Ok(head);
            }
        }
        if head.len() == before || head.len() as u64 >= len {
            return Ok(head);
        }
        chunk = chunk.saturating_mul(2);
    }
}

fn volume_from(bytes: &[u8], header: &VtiHeader, appended: Appended<'_>) -> std::result::Result<Volume, String> {
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
    let samples = decode_array(bytes, header, array, count, appended)?;
    Ok(Volume { samples, shape, components: array.components, name: array.name.clone() })
}
