//! Reading volumes from files into a [`crate::volume::Volume`], and writing
//! them as VTK XML image data.
//!
//! | extension          | format                                   | module   |
//! |--------------------|------------------------------------------|----------|
//! | `.vti`             | VTK XML ImageData (one piece; appended raw or base64, binary, ascii; ZLib, LZ4, LZMA) | [`vti`] |
//! | `.vtk`             | legacy VTK STRUCTURED_POINTS             | [`vtk`]  |
//! | `.nii`, `.nii.gz`  | NIfTI-1 (3D, one volume)                 | [`nii`]  |
//! | `.raw`, `.bin`, or any file with [`RawOptions`] | headerless samples | [`raw`] |
//!
//! Every failure is an [`crate::Error::Format`] naming the file and what to do.

pub mod nii;
pub mod options;
pub mod raw;
pub mod read;
pub mod vti;
pub mod vti_data;
pub mod vti_write;
pub mod vti_xml;
pub mod vtk;

pub use options::{RawOptions, ReadOptions};
pub use read::read_volume;
pub use vti_write::write_vti;
