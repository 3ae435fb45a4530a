//! [`read_volume`]: the one entry point, dispatching on the file extension.

use super::options::ReadOptions;
use crate::error::{Error, Result};
use crate::volume::Volume;
use std::path::Path;

/// The extensions [`read_volume`] understands, for messages.
pub const SUPPORTED: &str = ".vti, .vtk, .nii, .nii.gz, .raw, .bin";

/// `Error::Format` for `path` with `message`.
pub(crate) fn format_error(path: &Path, message: impl Into<String>) -> Error {
    Error::Format { path: path.display().to_string(), message: message.into() }
}

/// Reads the volume in `path`: raw when `options.raw` is given, otherwise by
/// extension (`.vti`, `.vtk`, `.nii`, `.nii.gz`; `.raw` and `.bin` need
/// `options.raw`). The volume is checked for consistent dims and length, not
/// yet for non-finite values (that is [`Volume::grid`]'s job).
pub fn read_volume(path: &Path, options: &ReadOptions) -> Result<Volume> {
    match std::fs::metadata(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            return Err(format_error(path, "the file does not exist; check the path"))
        }
        Err(e) => return Err(format_error(path, format!("cannot access the file: {e}"))),
        Ok(m) if m.is_dir() => return Err(format_error(path, "this is a directory; give a volume file")),
        Ok(_) => {}
    }
    if let Some(raw) = &options.raw {
        return super::raw::read_raw(path, raw);
    }
    let name = path.file_name().map(|n| n.to_string_lossy().to_ascii_lowercase()).unwrap_or_default();
    if name.ends_with(".vti") {
        super::vti::read_vti(path)
    } else if name.ends_with(".vtk") {
        super::vtk::read_vtk(path)
    } else if name.ends_with(".nii") || name.ends_with(".nii.gz") {
        super::nii::read_nifti(path)
    } else if name.ends_with(".raw") || name.ends_with(".bin") {
        Err(format_error(
            path,
            "a raw file has no header: give its layout with --dims X,Y,Z and --type T \
             (and --components, --spacing, --origin, --big-endian as needed)",
        ))
    } else {
        Err(format_error(
            path,
            format!(
                "unknown file extension: supported are {SUPPORTED}; for a headerless raw file give \
                 --dims X,Y,Z and --type T"
            ),
        ))
    }
}
