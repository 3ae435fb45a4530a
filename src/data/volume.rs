//! An owned volume: what the built-in datasets generate and the file readers
//! load. A [`Volume`] lends itself out as a borrowed [`Grid`].

use crate::base::error::Result;
use crate::data::grid::{Grid, GridShape, Samples, ScalarType};
use rayon::prelude::*;

/// Owned samples of one of the supported scalar types.
#[derive(Debug, Clone, PartialEq)]
#[allow(missing_docs)] // variants and fields are named by what they hold
pub enum SampleBuf {
    U8(Vec<u8>),
    I8(Vec<i8>),
    U16(Vec<u16>),
    I16(Vec<i16>),
    U32(Vec<u32>),
    I32(Vec<i32>),
    F32(Vec<f32>),
    F64(Vec<f64>),
}

impl SampleBuf {
    /// Borrows the buffer.
    pub fn as_samples(&self) -> Samples<'_> {
        match self {
            SampleBuf::U8(v) => Samples::U8(v),
            SampleBuf::I8(v) => Samples::I8(v),
            SampleBuf::U16(v) => Samples::U16(v),
            SampleBuf::I16(v) => Samples::I16(v),
            SampleBuf::U32(v) => Samples::U32(v),
            SampleBuf::I32(v) => Samples::I32(v),
            SampleBuf::F32(v) => Samples::F32(v),
            SampleBuf::F64(v) => Samples::F64(v),
        }
    }
    /// The scalar type.
    pub fn scalar_type(&self) -> ScalarType {
        self.as_samples().scalar_type()
    }
    /// Number of values.
    pub fn len(&self) -> usize {
        self.as_samples().len()
    }
    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// A zeroed buffer of `n` values of `ty` (the allocator hands out zero
    /// pages lazily, so nothing is touched before it is written).
    pub fn zeroed(ty: ScalarType, n: usize) -> SampleBuf {
        match ty {
            ScalarType::U8 => SampleBuf::U8(vec![0; n]),
            ScalarType::I8 => SampleBuf::I8(vec![0; n]),
            ScalarType::U16 => SampleBuf::U16(vec![0; n]),
            ScalarType::I16 => SampleBuf::I16(vec![0; n]),
            ScalarType::U32 => SampleBuf::U32(vec![0; n]),
            ScalarType::I32 => SampleBuf::I32(vec![0; n]),
            ScalarType::F32 => SampleBuf::F32(vec![0.0; n]),
            ScalarType::F64 => SampleBuf::F64(vec![0.0; n]),
        }
    }

    /// The values' bytes in native byte order: a view, not a copy.
    pub fn as_bytes(&self) -> &[u8] {
        self.as_samples().as_bytes()
    }

    /// The values' bytes in native byte order, writable: readers decode a
    /// file's bytes straight into the final buffer. Every bit pattern is a
    /// value of these plain number types, so any bytes are valid.
    pub fn as_bytes_mut(&mut self) -> &mut [u8] {
        fn view<T>(v: &mut [T]) -> &mut [u8] {
            // SAFETY: `T` is a plain number type (no padding, every bit pattern
            // valid); the byte slice covers exactly the values and borrows them
            // mutably for its lifetime.
            unsafe { std::slice::from_raw_parts_mut(v.as_mut_ptr().cast::<u8>(), std::mem::size_of_val(v)) }
        }
        match self {
            SampleBuf::U8(v) => view(v),
            SampleBuf::I8(v) => view(v),
            SampleBuf::U16(v) => view(v),
            SampleBuf::I16(v) => view(v),
            SampleBuf::U32(v) => view(v),
            SampleBuf::I32(v) => view(v),
            SampleBuf::F32(v) => view(v),
            SampleBuf::F64(v) => view(v),
        }
    }

    /// Converts values held in `file_big_endian` byte order (read into
    /// [`SampleBuf::as_bytes_mut`]) to native order, in place.
    pub fn fix_byte_order(&mut self, file_big_endian: bool) {
        if file_big_endian == cfg!(target_endian = "big") {
            return;
        }
        let size = self.scalar_type().size();
        if size > 1 {
            self.as_bytes_mut()
                .par_chunks_mut(size * 4096)
                .for_each(|c| c.chunks_exact_mut(size).for_each(<[u8]>::reverse));
        }
    }

    /// Decodes `bytes` (whole values; a trailing partial value is ignored) as
    /// values of `scalar_type` in little- or big-endian byte order.
    pub fn from_bytes(bytes: &[u8], scalar_type: ScalarType, big_endian: bool) -> SampleBuf {
        let n = bytes.len() / scalar_type.size();
        let mut out = SampleBuf::zeroed(scalar_type, n);
        let whole = out.as_bytes().len();
        out.as_bytes_mut().copy_from_slice(&bytes[..whole]);
        out.fix_byte_order(big_endian);
        out
    }

    /// Converts `f64` values to `scalar_type`, rounding and saturating for
    /// integer types (used by the dataset generators' `--type`).
    pub fn from_f64(values: &[f64], scalar_type: ScalarType) -> SampleBuf {
        fn conv<T>(values: &[f64], f: impl Fn(f64) -> T) -> Vec<T> {
            values.iter().map(|&v| f(v)).collect()
        }
        // `as` from f64 to an integer saturates and maps NaN to 0 (Rust semantics).
        match scalar_type {
            ScalarType::U8 => SampleBuf::U8(conv(values, |v| v.round() as u8)),
            ScalarType::I8 => SampleBuf::I8(conv(values, |v| v.round() as i8)),
            ScalarType::U16 => SampleBuf::U16(conv(values, |v| v.round() as u16)),
            ScalarType::I16 => SampleBuf::I16(conv(values, |v| v.round() as i16)),
            ScalarType::U32 => SampleBuf::U32(conv(values, |v| v.round() as u32)),
            ScalarType::I32 => SampleBuf::I32(conv(values, |v| v.round() as i32)),
            ScalarType::F32 => SampleBuf::F32(conv(values, |v| v as f32)),
            ScalarType::F64 => SampleBuf::F64(values.to_vec()),
        }
    }
}

/// An owned scalar volume with its geometry.
#[derive(Debug, Clone, PartialEq)]
pub struct Volume {
    /// Samples, x fastest, `components` values per point.
    pub samples: SampleBuf,
    /// Dimensions, spacing, origin.
    pub shape: GridShape,
    /// Values per point.
    pub components: usize,
    /// Name of the array (file readers keep the file's name).
    pub name: String,
}

impl Volume {
    /// A single-component volume with unit spacing and zero origin.
    pub fn new(samples: SampleBuf, dims: [usize; 3], name: impl Into<String>) -> Volume {
        Volume {
            samples,
            shape: GridShape { dims, spacing: [1.0; 3], origin: [0.0; 3] },
            components: 1,
            name: name.into(),
        }
    }

    /// Borrows the volume as a checked grid of component `component`
    /// (`None` for single-component volumes).
    pub fn grid(&self, component: Option<usize>) -> Result<Grid<'_>> {
        Grid::new(self.samples.as_samples(), self.shape, self.components, component)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_order_is_honoured() {
        let bytes = [0x01, 0x02, 0x03, 0x04];
        assert_eq!(SampleBuf::from_bytes(&bytes, ScalarType::U16, false), SampleBuf::U16(vec![0x0201, 0x0403]));
        assert_eq!(SampleBuf::from_bytes(&bytes, ScalarType::U16, true), SampleBuf::U16(vec![0x0102, 0x0304]));
        assert_eq!(SampleBuf::from_bytes(&1.5f32.to_be_bytes(), ScalarType::F32, true), SampleBuf::F32(vec![1.5]));
        assert_eq!(SampleBuf::from_bytes(&[0xff], ScalarType::I8, false), SampleBuf::I8(vec![-1]));
    }
}
