//! NIfTI-1 single files (`.nii`, `.nii.gz`): one 3D volume.
//!
//! The header ([`super::nii_header`]) is read and checked first; the memory
//! for the voxels it declares is checked next; only then are the voxel data
//! read, from `vox_offset`, exactly as many bytes as declared, converted while
//! they are read (no second copy). A `.nii.gz` is decompressed as a stream
//! that stops at the declared size: what follows the data may be at most
//! [`TRAILING_SLACK`] bytes, and the gzip trailer (CRC-32 and length) is
//! verified, so a damaged or inflated file is an error, never a picture.
//!
//! Geometry: spacing `pixdim[1..=3]`, origin the qform offset when
//! `qform_code > 0`, else the sform translation when `sform_code > 0`, else 0.
//! Rotations and the RAS orientation are not applied: the volume is in voxel
//! order, as VTK image data. When `scl_slope` is set (not 0, and not the
//! identity 1, 0) the stored values are rescaled, `v = scl_slope * stored +
//! scl_inter`, into `f32` (`f64` data stay `f64`).

use super::format_error;
use super::nii_header::{parse, NiftiHeader, HEADER_BYTES};
use super::sample_sink;
use crate::base::error::Result;
use crate::base::limits::{check_memory, human_bytes};
use crate::data::grid::{GridShape, ScalarType};
use crate::data::volume::{SampleBuf, Volume};
use std::io::Read;

/// Bytes allowed after the voxel data (padding some writers add); more means
/// the header does not describe the file.
pub const TRAILING_SLACK: u64 = 64 * 1024;

/// Deflate's largest ratio of output to input, about 1032:1: a gzip file of
/// `n` bytes cannot inflate to more than `n * MAX_DEFLATE_RATIO`.
const MAX_DEFLATE_RATIO: u64 = 1032;

/// Reads the NIfTI-1 file `bytes` (gzip-compressed when `gz`) named
/// `file_name`; `label` names it in errors.
pub fn read_nifti_bytes(label: &str, file_name: &str, bytes: &[u8], gz: bool) -> Result<Volume> {
    let fail = |m: String| format_error(label, m);
    let volume = if gz {
        let mut stream = flate2::read::MultiGzDecoder::new(bytes);
        let header = read_header(&mut stream).map_err(fail)?;
        let end = header.data_end();
        let most = (bytes.len() as u64).saturating_mul(MAX_DEFLATE_RATIO);
        if end > most {
            return Err(fail(format!(
                "the header puts the voxel data at bytes {} to {end}, but {} of gzip data cannot inflate past \
                 {most} bytes; the header is corrupt",
                header.vox_offset,
                human_bytes(bytes.len() as u128)
            )));
        }
        read_volume(label, file_name, &header, &mut stream, None)?
    } else {
        let header = parse(bytes).map_err(fail)?;
        let mut rest = bytes.get(HEADER_BYTES..).unwrap_or_default();
        read_volume(label, file_name, &header, &mut rest, Some(bytes.len() as u64))?
    };
    Ok(volume)
}

/// Reads the NIfTI-1 file `file` of `len` bytes (gzip-compressed when `gz`)
/// as a stream: the values go from the file (or the inflater) into the
/// volume's buffer, the file is never held whole.
pub fn read_nifti_file(label: &str, file_name: &str, file: std::fs::File, len: u64, gz: bool) -> Result<Volume> {
    let fail = |m: String| format_error(label, m);
    let buffered = std::io::BufReader::with_capacity(1 << 16, file);
    if gz {
        let mut stream = flate2::read::MultiGzDecoder::new(buffered);
        let header = read_header(&mut stream).map_err(fail)?;
        let end = header.data_end();
        let most = len.saturating_mul(MAX_DEFLATE_RATIO);
        if end > most {
            return Err(fail(format!(
                "the header puts the voxel data at bytes {} to {end}, but {} of gzip data cannot inflate past \
                 {most} bytes; the header is corrupt",
                header.vox_offset,
                human_bytes(u128::from(len))
            )));
        }
        read_volume(label, file_name, &header, &mut stream, None)
    } else {
        let mut stream = buffered;
        let mut head = Vec::with_capacity(HEADER_BYTES);
        (&mut stream)
            .take(HEADER_BYTES as u64)
            .read_to_end(&mut head)
            .map_err(|e| fail(format!("cannot read the file: {e}")))?;
        let header = parse(&head).map_err(fail)?;
        read_volume(label, file_name, &header, &mut stream, Some(len))
    }
}

/// The header from the first bytes of `stream`.
fn read_header(stream: &mut impl Read) -> std::result::Result<NiftiHeader, String> {
    let mut head = Vec::with_capacity(HEADER_BYTES);
    stream
        .take(HEADER_BYTES as u64)
        .read_to_end(&mut head)
        .map_err(|e| format!("the gzip data do not decompress ({e}); the file is corrupt"))?;
    parse(&head)
}

/// The volume from `stream`, positioned just after the header; `file_len`
/// is the whole file's length when known (uncompressed files).
fn read_volume(
    label: &str,
    file_name: &str,
    header: &NiftiHeader,
    stream: &mut impl Read,
    file_len: Option<u64>,
) -> Result<Volume> {
    let fail = |m: String| format_error(label, m);
    let shape = GridShape { dims: header.dims, spacing: header.spacing, origin: header.origin };
    shape.check(1).map_err(|e| fail(e.to_string()))?;
    let data_end = header.data_end();
    if let Some(len) = file_len {
        if data_end > len {
            return Err(fail(format!(
                "the header puts the voxel data at bytes {} to {data_end}, but the file has {len} bytes; \
                 it is truncated or corrupt (or its vox_offset is wrong)",
                header.vox_offset
            )));
        }
    }
    let target = target_type(header);
    let [x, y, z] = header.dims;
    check_memory(
        header.count() as u128 * target.size() as u128,
        &format!("the {x}x{y}x{z} {} volume of '{label}'", target.name()),
        "crop or subsample the volume, or free memory",
    )?;
    let short = |what: &str, e: std::io::Error| {
        fail(format!("the file ends before the end of the {what} ({e}); it is truncated or corrupt"))
    };
    let skip = header.vox_offset - HEADER_BYTES as u64;
    let skipped = std::io::copy(&mut stream.take(skip), &mut std::io::sink()).map_err(|e| short("extension", e))?;
    if skipped != skip {
        return Err(fail(format!(
            "the file ends at byte {}, before the voxel data at vox_offset {}; it is truncated or its vox_offset \
             is wrong",
            HEADER_BYTES as u64 + skipped,
            header.vox_offset
        )));
    }
    let samples = read_samples(stream, header, target).map_err(|e| short("voxel data", e))?;
    let trailing = std::io::copy(&mut stream.take(TRAILING_SLACK + 1), &mut std::io::sink())
        .map_err(|e| fail(format!("the gzip data after the voxels do not decompress ({e}); the file is corrupt")))?;
    if trailing > TRAILING_SLACK {
        return Err(fail(format!(
            "more than {} follow the {} of voxel data the header declares; the header does not describe \
             the file (wrong dims or datatype)",
            human_bytes(u128::from(TRAILING_SLACK)),
            human_bytes(u128::from(header.data_bytes()))
        )));
    }
    Ok(Volume { samples, shape, components: 1, name: stem(file_name).to_string() })
}

/// `file_name` without `.nii` or `.nii.gz` (any case).
fn stem(file_name: &str) -> &str {
    let lower = file_name.to_ascii_lowercase();
    let cut = [".nii.gz", ".nii"].iter().find(|ext| lower.ends_with(*ext)).map_or(0, |ext| ext.len());
    &file_name[..file_name.len() - cut]
}

/// The type of the volume: the stored type, or `f32` (`f64` for `f64` data)
/// when the values are rescaled.
fn target_type(header: &NiftiHeader) -> ScalarType {
    match (header.scaling, header.stored) {
        (None, stored) => stored,
        (Some(_), ScalarType::F64) => ScalarType::F64,
        (Some(_), _) => ScalarType::F32,
    }
}

/// Reads the `header.count()` stored values from `stream` in chunks, converted
/// (and rescaled) into `target` as they arrive.
fn read_samples(stream: &mut impl Read, header: &NiftiHeader, target: ScalarType) -> std::io::Result<SampleBuf> {
    const CHUNK_VALUES: usize = 1 << 16;
    if header.scaling.is_none() {
        let mut out = SampleBuf::zeroed(target, header.count());
        stream.read_exact(out.as_bytes_mut())?;
        out.fix_byte_order(header.big_endian);
        return Ok(out);
    }
    let size = header.stored.size();
    let mut out = sample_sink::with_capacity(target, header.count());
    let mut chunk = vec![0u8; CHUNK_VALUES * size];
    let mut left = header.count();
    while left > 0 {
        let n = left.min(CHUNK_VALUES);
        let bytes = &mut chunk[..n * size];
        stream.read_exact(bytes)?;
        let values = SampleBuf::from_bytes(bytes, header.stored, header.big_endian);
        match header.scaling {
            None => sample_sink::append(&mut out, values),
            Some((slope, inter)) => sample_sink::append_scaled(&mut out, &values, slope, inter),
        }
        left -= n;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::stem;

    #[test]
    fn the_name_drops_the_extension_in_any_case() {
        assert_eq!(stem("head.nii.gz"), "head");
        assert_eq!(stem("HEAD.NII.GZ"), "HEAD");
        assert_eq!(stem("a.b.Nii"), "a.b");
    }
}
