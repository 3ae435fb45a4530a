//! [`read_volume`] and [`read_volume_bytes`]: the entry points, dispatching on
//! the file extension (case-insensitive). The path-based reader checks the
//! file (a regular file, memory for its bytes) and then hands its bytes to the
//! same code as the in-memory one, so both behave alike.

use super::format_error;
use super::options::ReadOptions;
use super::source::{display_path, open_regular_file, read_regular_file, regular_file_len};
use crate::base::error::Result;
use crate::base::limits::escape_controls;
use crate::data::volume::Volume;
use std::path::Path;

/// The extensions [`read_volume`] understands, for messages.
pub const SUPPORTED: &str = ".vti, .vtk, .nii, .nii.gz, .tif, .tiff (or a folder of TIFF slices), .raw, .bin";

/// The file formats, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// `.vti`
    Vti,
    /// `.vtk`
    LegacyVtk,
    /// `.nii`
    Nifti,
    /// `.nii.gz`
    NiftiGz,
    /// `.tif`, `.tiff`: a multi-page TIFF stack.
    Tiff,
    /// `.raw`, `.bin`: needs a layout.
    Raw,
}

impl FileKind {
    /// The kind of `file_name` by its extension, any case; `None` when unknown.
    pub fn of(file_name: &str) -> Option<FileKind> {
        let name = file_name.to_ascii_lowercase();
        [
            (".vti", FileKind::Vti),
            (".vtk", FileKind::LegacyVtk),
            (".nii.gz", FileKind::NiftiGz),
            (".nii", FileKind::Nifti),
            (".tiff", FileKind::Tiff),
            (".tif", FileKind::Tiff),
            (".raw", FileKind::Raw),
            (".bin", FileKind::Raw),
        ]
        .into_iter()
        .find(|(ext, _)| name.ends_with(ext))
        .map(|(_, kind)| kind)
    }
}

/// Reads the volume in `path`: raw when `options.raw` is given, otherwise by
/// extension (`.vti`, `.vtk`, `.nii`, `.nii.gz`, `.tif`, `.tiff`; `.raw` and
/// `.bin` need `options.raw`), or a folder of TIFF slices
/// ([`super::tiff_stack`]). Only regular files are read, never past their size.
/// Raw, `.vti` (appended raw data) and NIfTI values go from the file
/// straight into the volume's buffer; a legacy `.vtk` file is read whole
/// first. The
/// volume is checked for consistent dims and length, not yet for non-finite
/// values (that is [`Volume::grid`]'s job).
pub fn read_volume(path: &Path, options: &ReadOptions) -> Result<Volume> {
    let label = display_path(path);
    if path.is_dir() && options.raw.is_none() {
        return super::tiff_stack::TiffStack::open(path)?.read_volume();
    }
    let len = regular_file_len(path, &label)?;
    let file_name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
    if let Some(raw) = &options.raw {
        super::raw::check_raw_size(&label, raw, len)?;
        let mut file = open_regular_file(path, &label)?;
        return super::raw::read_raw_file(&label, &file_name, &mut file, raw);
    }
    match kind(&label, &file_name, options)? {
        FileKind::Vti => super::vti::read_vti_file(&label, &mut open_regular_file(path, &label)?, len),
        FileKind::Tiff => super::tiff_stack::TiffStack::open(path)?.read_volume(),
        FileKind::Nifti | FileKind::NiftiGz => {
            let gz = kind(&label, &file_name, options)? == FileKind::NiftiGz;
            super::nii::read_nifti_file(&label, &file_name, open_regular_file(path, &label)?, len, gz)
        }
        _ => {
            let bytes = read_regular_file(path, &label, len)?;
            read_labelled(&label, &file_name, &bytes, options)
        }
    }
}

/// Reads a volume from `bytes`, the contents of a file named `file_name`
/// (whose extension chooses the format, as in [`read_volume`]).
pub fn read_volume_bytes(file_name: &str, bytes: &[u8], options: &ReadOptions) -> Result<Volume> {
    read_labelled(&escape_controls(file_name), file_name, bytes, options)
}

fn read_labelled(label: &str, file_name: &str, bytes: &[u8], options: &ReadOptions) -> Result<Volume> {
    if let Some(raw) = &options.raw {
        return super::raw::read_raw_bytes(label, file_name, bytes, raw);
    }
    match kind(label, file_name, options)? {
        FileKind::Vti => super::vti::read_vti_bytes(label, bytes),
        FileKind::LegacyVtk => super::vtk::read_vtk_bytes(label, bytes),
        FileKind::Nifti => super::nii::read_nifti_bytes(label, file_name, bytes, false),
        FileKind::NiftiGz => super::nii::read_nifti_bytes(label, file_name, bytes, true),
        FileKind::Tiff => super::tiff_stack::read_tiff_bytes(label, bytes),
        FileKind::Raw => unreachable!("kind() refuses raw files without a layout"),
    }
}

/// The format of `file_name`, or the error for an unknown extension or a raw
/// file without its layout.
fn kind(label: &str, file_name: &str, options: &ReadOptions) -> Result<FileKind> {
    match FileKind::of(file_name) {
        Some(FileKind::Raw) if options.raw.is_none() => Err(format_error(
            label,
            "a raw file has no header: give its layout with --dims X,Y,Z and --type T \
             (and --components, --spacing, --origin, --big-endian as needed)",
        )),
        Some(kind) => Ok(kind),
        None => Err(format_error(
            label,
            format!(
                "unknown file extension: supported are {SUPPORTED} (any case); for a headerless raw file give \
                 --dims X,Y,Z and --type T"
            ),
        )),
    }
}
