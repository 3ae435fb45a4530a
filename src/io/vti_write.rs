//! Writing a [`Volume`] as a VTK XML ImageData file (`.vti`) that ParaView's
//! `XMLImageDataReader` reads: one inline piece, binary (base64) data, the
//! volume's array as the active point scalars, whole extent
//! `0 nx-1 0 ny-1 0 nz-1`, origin and spacing (written as `f32`, vtkio's
//! precision).

use super::source::display_path;
use crate::base::error::{Error, Result};
use crate::data::volume::{SampleBuf, Volume};
use std::io::Write;
use std::path::Path;
use vtkio::model::{
    Attribute, Attributes, ByteOrder, DataArray, DataSet, ElementType, Extent, IOBuffer, ImageDataPiece, Piece,
    Version, Vtk,
};

/// Writes `volume` to `path`, which must end in `.vti` (any case): this
/// writer writes nothing else, and a file named for another format would be
/// misread later.
pub fn write_vti(path: &Path, volume: &Volume) -> Result<()> {
    let label = display_path(path);
    let fail = |message: String| Error::Write { path: label.clone(), message };
    if !path.to_string_lossy().to_ascii_lowercase().ends_with(".vti") {
        return Err(fail("a volume is written as VTK XML image data only: name the file .vti".into()));
    }
    volume.shape.check(volume.components).map_err(|e| fail(format!("{e}; nothing written")))?;
    if volume.samples.len() != volume.shape.point_count() * volume.components {
        return Err(fail("the volume's sample count does not match its dims; nothing written".into()));
    }
    let [nx, ny, nz] = volume.shape.dims.map(|d| d as i32 - 1);
    let extent = Extent::Ranges([0..=nx, 0..=ny, 0..=nz]);
    let array = DataArray {
        name: if volume.name.is_empty() { "scalars".into() } else { volume.name.clone() },
        elem: ElementType::Scalars { num_comp: volume.components as u32, lookup_table: None },
        data: to_io_buffer(&volume.samples),
    };
    let piece = ImageDataPiece {
        extent: extent.clone(),
        data: Attributes { point: vec![Attribute::DataArray(array)], cell: Vec::new() },
    };
    let vtk = Vtk {
        version: Version::new_xml(1, 0),
        title: String::new(),
        byte_order: ByteOrder::LittleEndian,
        file_path: None,
        data: DataSet::ImageData {
            extent,
            origin: volume.shape.origin.map(|v| v as f32),
            spacing: volume.shape.spacing.map(|v| v as f32),
            meta: None,
            pieces: vec![Piece::Inline(Box::new(piece))],
        },
    };
    let file = std::fs::File::create(path)
        .map_err(|e| fail(format!("cannot create the file: {e}; check the folder exists and is writable")))?;
    let mut out = std::io::BufWriter::new(file);
    vtk.write_xml(&mut out).map_err(|e| fail(format!("cannot write VTK XML: {e}")))?;
    out.flush().map_err(|e| fail(format!("cannot write the file: {e}")))
}

fn to_io_buffer(samples: &SampleBuf) -> IOBuffer {
    match samples {
        SampleBuf::U8(v) => IOBuffer::U8(v.clone()),
        SampleBuf::I8(v) => IOBuffer::I8(v.clone()),
        SampleBuf::U16(v) => IOBuffer::U16(v.clone()),
        SampleBuf::I16(v) => IOBuffer::I16(v.clone()),
        SampleBuf::U32(v) => IOBuffer::U32(v.clone()),
        SampleBuf::I32(v) => IOBuffer::I32(v.clone()),
        SampleBuf::F32(v) => IOBuffer::F32(v.clone()),
        SampleBuf::F64(v) => IOBuffer::F64(v.clone()),
    }
}
