//! The 348-byte NIfTI-1 header: parsed and checked on its own, so that the
//! size of the voxel data is known (and refused if too large) before any of
//! it is read or decompressed.
//!
//! Fields used (byte offsets): `sizeof_hdr` (0, 348; byte-swapped in a
//! big-endian file), `dim` (40, 8 x i16), `datatype` (70), `bitpix` (72),
//! `pixdim` (76, 8 x f32), `vox_offset` (108, f32), `scl_slope` (112),
//! `scl_inter` (116), `qform_code` (252), `sform_code` (254), `qoffset_x/y/z`
//! (268), `srow_x/y/z` (280, 296, 312, 4 x f32), `magic` (344, `n+1` for a
//! single `.nii` file).

use crate::data::grid::ScalarType;

/// Bytes in a NIfTI-1 header.
pub const HEADER_BYTES: usize = 348;
/// The first byte voxel data may start at in a single file: the header and
/// the 4-byte extension flag.
pub const MIN_VOX_OFFSET: u64 = 352;

/// What the reader takes from a NIfTI-1 header, checked.
#[derive(Debug, Clone, PartialEq)]
pub struct NiftiHeader {
    /// Samples per axis (axes beyond `dim[0]` are 1).
    pub dims: [usize; 3],
    /// The type of the stored values.
    pub stored: ScalarType,
    /// Multi-byte values are big endian.
    pub big_endian: bool,
    /// `|pixdim[1..=3]|`.
    pub spacing: [f64; 3],
    /// The qform offset, else the sform translation, else 0.
    pub origin: [f64; 3],
    /// Byte offset of the voxel data.
    pub vox_offset: u64,
    /// `(scl_slope, scl_inter)` when the values are rescaled.
    pub scaling: Option<(f64, f64)>,
}

impl NiftiHeader {
    /// Samples in the volume.
    pub fn count(&self) -> usize {
        self.dims.iter().product()
    }

    /// Bytes of stored voxel data.
    pub fn data_bytes(&self) -> u64 {
        self.count() as u64 * self.stored.size() as u64
    }

    /// The byte just past the voxel data (saturating: a `vox_offset` near
    /// `u64::MAX` is simply beyond any file).
    pub fn data_end(&self) -> u64 {
        self.vox_offset.saturating_add(self.data_bytes())
    }
}

/// Parses and checks the first [`HEADER_BYTES`] of `bytes`. Errors are
/// messages for [`crate::Error::Format`].
pub fn parse(bytes: &[u8]) -> Result<NiftiHeader, String> {
    let h: &[u8; HEADER_BYTES] = bytes.get(..HEADER_BYTES).and_then(|b| b.try_into().ok()).ok_or_else(|| {
        format!("the file holds {} bytes, fewer than the 348-byte NIfTI-1 header; it is truncated", bytes.len())
    })?;
    let big_endian = match (i32::from_le_bytes(word(h, 0)), i32::from_be_bytes(word(h, 0))) {
        (348, _) => false,
        (_, 348) => true,
        (540, _) | (_, 540) => {
            return Err("this is a NIfTI-2 file, which is not supported; save it as NIfTI-1 \
                        (e.g. nibabel's Nifti1Image)"
                .into())
        }
        (n, _) => return Err(format!("sizeof_hdr is {n}, not 348: this is not a NIfTI-1 file, or it is corrupt")),
    };
    let i16_at = |at: usize| {
        let b = [h[at], h[at + 1]];
        if big_endian {
            i16::from_be_bytes(b)
        } else {
            i16::from_le_bytes(b)
        }
    };
    let f32_at = |at: usize| {
        let b = word(h, at);
        f64::from(if big_endian { f32::from_be_bytes(b) } else { f32::from_le_bytes(b) })
    };
    match &h[344..348] {
        b"n+1\0" => {}
        b"ni1\0" => {
            return Err("this is the header of a .hdr/.img pair, whose data are in another file; \
                        convert it to a single .nii file (e.g. fslchfiletype NIFTI)"
                .into())
        }
        other => {
            return Err(format!(
                "the NIfTI magic is '{}', not 'n+1': this is not a single-file NIfTI-1 image, or it is corrupt",
                crate::base::limits::excerpt_bytes(other)
            ))
        }
    }
    let dims = dims(&std::array::from_fn(|a| i16_at(40 + 2 * a)))?;
    let (stored, bits) = data_type(i16_at(70))?;
    let bitpix = i16_at(72);
    if i32::from(bitpix) != bits {
        return Err(format!(
            "the NIfTI header says datatype {} ({} bits a value) but bitpix {bitpix}; the header is corrupt \
             (rewrite it with the right bitpix, e.g. with nibabel)",
            i16_at(70),
            bits
        ));
    }
    let vox_offset = vox_offset(f32_at(108))?;
    let spacing = [1, 2, 3].map(|a| f32_at(76 + 4 * a).abs());
    let origin = if i16_at(252) > 0 {
        [268, 272, 276].map(f32_at)
    } else if i16_at(254) > 0 {
        [292, 308, 324].map(f32_at)
    } else {
        [0.0; 3]
    };
    let (slope, inter) = (f32_at(112), f32_at(116));
    let scaling = (slope != 0.0 && slope.is_finite() && inter.is_finite() && !(slope == 1.0 && inter == 0.0))
        .then_some((slope, inter));
    Ok(NiftiHeader { dims, stored, big_endian, spacing, origin, vox_offset, scaling })
}

fn word(h: &[u8; HEADER_BYTES], at: usize) -> [u8; 4] {
    [h[at], h[at + 1], h[at + 2], h[at + 3]]
}

/// `dim[1..=3]` from `dim`, refusing a bad `dim[0]`, non-positive sizes and
/// more than one volume.
fn dims(dim: &[i16; 8]) -> Result<[usize; 3], String> {
    let ndim = dim[0];
    if !(1..=7).contains(&ndim) {
        return Err(format!("invalid NIfTI dim[0] = {ndim} (must be 1 to 7); the header is corrupt"));
    }
    let ndim = ndim as usize;
    if let Some(a) = (1..=ndim).find(|&a| dim[a] < 1) {
        return Err(format!("NIfTI dim[{a}] = {} is not a positive size; the header is corrupt", dim[a]));
    }
    let extra: usize = (4..=ndim).map(|a| dim[a] as usize).product();
    if extra > 1 {
        return Err(format!(
            "the image has {ndim} dimensions with {extra} volumes; the Hybrid Octree takes one 3D volume \
             (extract one first, e.g. fslroi or nibabel)"
        ));
    }
    Ok([1, 2, 3].map(|a| if a <= ndim { dim[a] as usize } else { 1 }))
}

/// The scalar type and bits of a NIfTI `datatype` code.
fn data_type(code: i16) -> Result<(ScalarType, i32), String> {
    Ok(match code {
        2 => (ScalarType::U8, 8),
        256 => (ScalarType::I8, 8),
        4 => (ScalarType::I16, 16),
        512 => (ScalarType::U16, 16),
        8 => (ScalarType::I32, 32),
        768 => (ScalarType::U32, 32),
        16 => (ScalarType::F32, 32),
        64 => (ScalarType::F64, 64),
        other => {
            let name = match other {
                1 => "binary (1 bit)",
                32 => "complex64",
                128 => "RGB24",
                1024 => "int64",
                1280 => "uint64",
                1536 => "float128",
                1792 => "complex128",
                2048 => "complex256",
                2304 => "RGBA32",
                _ => "unknown",
            };
            return Err(format!(
                "NIfTI datatype {other} ({name}) is not supported; convert the image to an 8/16/32-bit integer \
                 or float type"
            ));
        }
    })
}

/// The start of the voxel data of a single-file `.nii`: `vox_offset` when it
/// is finite, whole and at least 352; 0, the value of an unset field (written
/// by older tools, and read as 352 by nibabel and niftilib), is 352.
fn vox_offset(value: f64) -> Result<u64, String> {
    if value == 0.0 {
        return Ok(MIN_VOX_OFFSET);
    }
    if !value.is_finite() || value.fract() != 0.0 || value < MIN_VOX_OFFSET as f64 {
        return Err(format!(
            "the NIfTI vox_offset {value} is not a whole number of bytes of at least 352 (where the voxel data \
             of a single-file .nii start) nor 0 (unset: the data start at 352); the header is corrupt"
        ));
    }
    Ok(value as u64)
}
