//! What the caller tells the readers: the layout of a raw file.

use crate::data::grid::ScalarType;

/// Layout of a headerless raw file: `dims[0] * dims[1] * dims[2] * components`
/// values of `scalar_type`, x fastest, components interleaved.
#[derive(Debug, Clone, PartialEq)]
pub struct RawOptions {
    /// Samples per axis.
    pub dims: [usize; 3],
    /// Type of every value.
    pub scalar_type: ScalarType,
    /// Distance between samples per axis.
    pub spacing: [f64; 3],
    /// World position of sample `(0, 0, 0)`.
    pub origin: [f64; 3],
    /// Values per point.
    pub components: usize,
    /// Byte order of multi-byte values (false: little endian).
    pub big_endian: bool,
}

impl RawOptions {
    /// Single-component, little-endian, unit spacing, zero origin.
    pub fn new(dims: [usize; 3], scalar_type: ScalarType) -> RawOptions {
        RawOptions { dims, scalar_type, spacing: [1.0; 3], origin: [0.0; 3], components: 1, big_endian: false }
    }
}

/// Options of [`super::read_volume`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {
    /// Layout of a raw file; when given, the file is read as raw whatever its extension.
    pub raw: Option<RawOptions>,
}
