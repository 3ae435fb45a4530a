//! Headerless raw files: `nx * ny * nz * components` values, x fastest.

use super::options::RawOptions;
use super::read::format_error;
use crate::error::Result;
use crate::grid::{GridShape, ScalarType};
use crate::volume::{SampleBuf, Volume};
use std::path::Path;

/// Reads `path` with the layout `raw`. The file must hold exactly
/// `nx * ny * nz * components * size_of(type)` bytes.
pub fn read_raw(path: &Path, raw: &RawOptions) -> Result<Volume> {
    let shape = GridShape { dims: raw.dims, spacing: raw.spacing, origin: raw.origin };
    let values = shape.check(raw.components).map_err(|e| format_error(path, e.to_string()))?;
    let size = raw.scalar_type.size();
    let expected = values * size;
    let actual = std::fs::metadata(path).map_err(|e| format_error(path, e.to_string()))?.len();
    if actual != expected as u64 {
        let [x, y, z] = raw.dims;
        return Err(format_error(
            path,
            format!(
                "the raw file has {actual} bytes but {x}x{y}x{z} points x {} component(s) x {size} bytes ({}) \
                 need {expected} bytes; check --dims, --type and --components",
                raw.components,
                raw.scalar_type.name()
            ),
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| format_error(path, format!("cannot read the file: {e}")))?;
    let samples = decode(&bytes, raw.scalar_type, raw.big_endian);
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scalars".into());
    Ok(Volume { samples, shape, components: raw.components, name })
}

/// Decodes `bytes` (a multiple of the type size) as values of `scalar_type`.
pub fn decode(bytes: &[u8], scalar_type: ScalarType, big_endian: bool) -> SampleBuf {
    macro_rules! conv {
        ($t:ty, $variant:ident) => {{
            const N: usize = std::mem::size_of::<$t>();
            SampleBuf::$variant(
                bytes
                    .chunks_exact(N)
                    .map(|c| {
                        let mut a = [0u8; N];
                        a.copy_from_slice(c);
                        if big_endian {
                            <$t>::from_be_bytes(a)
                        } else {
                            <$t>::from_le_bytes(a)
                        }
                    })
                    .collect(),
            )
        }};
    }
    match scalar_type {
        ScalarType::U8 => SampleBuf::U8(bytes.to_vec()),
        ScalarType::I8 => SampleBuf::I8(bytes.iter().map(|&b| b as i8).collect()),
        ScalarType::U16 => conv!(u16, U16),
        ScalarType::I16 => conv!(i16, I16),
        ScalarType::U32 => conv!(u32, U32),
        ScalarType::I32 => conv!(i32, I32),
        ScalarType::F32 => conv!(f32, F32),
        ScalarType::F64 => conv!(f64, F64),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_order_is_honoured() {
        let bytes = [0x01, 0x02, 0x03, 0x04];
        assert_eq!(decode(&bytes, ScalarType::U16, false), SampleBuf::U16(vec![0x0201, 0x0403]));
        assert_eq!(decode(&bytes, ScalarType::U16, true), SampleBuf::U16(vec![0x0102, 0x0304]));
        assert_eq!(decode(&1.5f32.to_be_bytes(), ScalarType::F32, true), SampleBuf::F32(vec![1.5]));
        assert_eq!(decode(&[0xff], ScalarType::I8, false), SampleBuf::I8(vec![-1]));
    }
}
