//! Reading volumes from files into a [`crate::data::volume::Volume`], and writing
//! them as VTK XML image data.
//!
//! | extension          | format                                   | module   |
//! |--------------------|------------------------------------------|----------|
//! | `.vti`             | VTK XML ImageData (one piece; appended raw or base64, binary, ascii; ZLib, LZ4, LZMA) | [`vti`] |
//! | `.vtk`             | legacy VTK STRUCTURED_POINTS (ASCII, BINARY) | [`vtk`]  |
//! | `.nii`, `.nii.gz`  | NIfTI-1 (3D, one volume)                 | [`nii`]  |
//! | `.tif`, `.tiff`, a folder of them | TIFF stacks: 2D slices or multi-page, grayscale | [`tiff_stack`] |
//! | `.raw`, `.bin`, or any file with [`RawOptions`] | headerless samples | [`raw`] |
//!
//! Extensions are matched in any case. Every failure is an
//! [`crate::Error::Format`] naming the file and what to do, or an
//! [`crate::Error::InvalidArgument`] when the volume would need more memory
//! than the process may use ([`crate::base::limits::check_memory`], checked from
//! the header before anything is allocated). Only regular files are read
//! ([`source`]); [`read_volume_bytes`] reads the same formats from memory.

mod error;
pub mod nii;
pub mod nii_header;
pub mod options;
pub mod raw;
pub mod read;
pub mod sample_sink;
pub mod source;
pub mod tiff_stack;
pub mod vti;
pub mod vti_data;
pub mod vti_write;
pub mod vti_xml;
pub mod vtk;
pub mod vtk_attributes;
pub mod vtk_tokens;

pub(crate) use error::format_error;
pub use options::{RawOptions, ReadOptions};
pub use read::{read_volume, read_volume_bytes, FileKind};
pub use vti_write::write_vti;
