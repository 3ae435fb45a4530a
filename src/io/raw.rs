//! Headerless raw files: `nx * ny * nz * components` values, x fastest.

use super::format_error;
use super::options::RawOptions;
use crate::base::error::Result;
use crate::base::limits::{check_memory, human_bytes};
use crate::data::grid::GridShape;
use crate::data::volume::{SampleBuf, Volume};

/// The bytes the layout `raw` needs, after checking the dims.
fn expected_bytes(label: &str, raw: &RawOptions) -> Result<usize> {
    let shape = GridShape { dims: raw.dims, spacing: raw.spacing, origin: raw.origin };
    let values = shape.check(raw.components).map_err(|e| format_error(label, e.to_string()))?;
    values
        .checked_mul(raw.scalar_type.size())
        .ok_or_else(|| format_error(label, "the layout's byte count overflows; check --dims, --type and --components"))
}

/// Checks that a raw file of `actual` bytes holds exactly the layout `raw`,
/// and that the volume fits in memory, before anything is read.
pub fn check_raw_size(label: &str, raw: &RawOptions, actual: u64) -> Result<()> {
    let expected = expected_bytes(label, raw)?;
    if actual != expected as u64 {
        let [x, y, z] = raw.dims;
        return Err(format_error(
            label,
            format!(
                "the raw file has {actual} bytes but {x}x{y}x{z} points x {} component(s) x {} bytes ({}) \
                 need {expected} bytes; check --dims, --type and --components",
                raw.components,
                raw.scalar_type.size(),
                raw.scalar_type.name()
            ),
        ));
    }
    let [x, y, z] = raw.dims;
    check_memory(
        expected as u128,
        &format!(
            "the {x}x{y}x{z} {} raw volume of '{label}' ({} on disk)",
            raw.scalar_type.name(),
            human_bytes(expected as u128)
        ),
        "crop or subsample the volume, or free memory",
    )
}

/// The raw volume in `bytes` (a file named `file_name`, `label` in errors)
/// with the layout `raw`: exactly `nx * ny * nz * components * size_of(type)`
/// bytes.
pub fn read_raw_bytes(label: &str, file_name: &str, bytes: &[u8], raw: &RawOptions) -> Result<Volume> {
    check_raw_size(label, raw, bytes.len() as u64)?;
    Ok(volume_of(SampleBuf::from_bytes(bytes, raw.scalar_type, raw.big_endian), file_name, raw))
}

/// The raw volume in the open `file` (checked by [`check_raw_size`]), read
/// straight into the volume's buffer.
pub fn read_raw_file(label: &str, file_name: &str, file: &mut std::fs::File, raw: &RawOptions) -> Result<Volume> {
    use std::io::Read;
    let count = expected_bytes(label, raw)? / raw.scalar_type.size();
    let mut samples = SampleBuf::zeroed(raw.scalar_type, count);
    file.read_exact(samples.as_bytes_mut())
        .map_err(|e| format_error(label, format!("cannot read the file: {e}; it may have shrunk while it was read")))?;
    samples.fix_byte_order(raw.big_endian);
    Ok(volume_of(samples, file_name, raw))
}

fn volume_of(samples: SampleBuf, file_name: &str, raw: &RawOptions) -> Volume {
    let shape = GridShape { dims: raw.dims, spacing: raw.spacing, origin: raw.origin };
    let stem = file_name.rsplit_once('.').map_or(file_name, |(stem, _)| stem);
    let name = if stem.is_empty() { "scalars".to_string() } else { stem.to_string() };
    Volume { samples, shape, components: raw.components, name }
}
