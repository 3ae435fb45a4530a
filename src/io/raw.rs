//! Headerless raw files: `nx * ny * nz * components` values, x fastest.

use super::options::RawOptions;
use super::read::format_error;
use crate::error::Result;
use crate::grid::GridShape;
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
    let samples = SampleBuf::from_bytes(&bytes, raw.scalar_type, raw.big_endian);
    let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "scalars".into());
    Ok(Volume { samples, shape, components: raw.components, name })
}
