//! Writing a volume as a VTK XML ImageData file (`.vti`) that ParaView's
//! `XMLImageDataReader` reads: one piece, the array as the active point
//! scalars, whole extent `0 nx-1 0 ny-1 0 nz-1`, origin and spacing, and the
//! values as raw appended data (ParaView's own default encoding):
//!
//! ```text
//! <VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" header_type="UInt64">
//!   <ImageData WholeExtent=".." Origin=".." Spacing="..">
//!     <Piece Extent=".."><PointData Scalars="name">
//!       <DataArray type="UInt8" Name="name" NumberOfComponents="1" format="appended" offset="0"/>
//!     </PointData><CellData></CellData></Piece>
//!   </ImageData>
//!   <AppendedData encoding="raw">
//!    _<UInt64 byte count><the values, little endian>
//!   </AppendedData>
//! </VTKFile>
//! ```
//!
//! The values are streamed ([`VtiWriter`]): a caller may hand them over in
//! pieces (the dataset generator writes slab by slab), and a whole volume is
//! written from its own memory, never copied.

use super::source::display_path;
use crate::base::error::{Error, Result};
use crate::data::grid::{GridShape, Samples, ScalarType};
use crate::data::volume::Volume;
use std::io::Write;
use std::path::Path;

/// Writes `volume` to `path`, which must end in `.vti` (any case): this
/// writer writes nothing else, and a file named for another format would be
/// misread later.
pub fn write_vti(path: &Path, volume: &Volume) -> Result<()> {
    let label = display_path(path);
    if volume.samples.len() != volume.shape.point_count() * volume.components {
        return Err(Error::Write {
            path: label,
            message: "the volume's sample count does not match its dims; nothing written".into(),
        });
    }
    let mut writer =
        VtiWriter::create(path, &volume.shape, volume.components, &volume.name, volume.samples.scalar_type())?;
    writer.write(volume.samples.as_samples())?;
    writer.finish()
}

/// A `.vti` file being written: the header first, then the values in
/// order, piece by piece, then [`VtiWriter::finish`].
pub struct VtiWriter {
    out: std::io::BufWriter<std::fs::File>,
    label: String,
    scalar_type: ScalarType,
    /// Bytes of values still to come.
    remaining: u64,
}

impl VtiWriter {
    /// Creates `path` (which must end in `.vti`) and writes the header of a
    /// volume of `shape`, `components` values of `scalar_type` a point, the
    /// array named `name` (`scalars` when empty).
    pub fn create(
        path: &Path,
        shape: &GridShape,
        components: usize,
        name: &str,
        scalar_type: ScalarType,
    ) -> Result<VtiWriter> {
        let label = display_path(path);
        let fail = |message: String| Error::Write { path: label.clone(), message };
        if !path.to_string_lossy().to_ascii_lowercase().ends_with(".vti") {
            return Err(fail("a volume is written as VTK XML image data only: name the file .vti".into()));
        }
        let count = shape.check(components).map_err(|e| fail(format!("{e}; nothing written")))?;
        let bytes = (count as u64).checked_mul(scalar_type.size() as u64).ok_or_else(|| fail("too large".into()))?;
        let file = std::fs::File::create(path)
            .map_err(|e| fail(format!("cannot create the file: {e}; check the folder exists and is writable")))?;
        let mut out = std::io::BufWriter::with_capacity(1 << 20, file);
        let name = escape(if name.is_empty() { "scalars" } else { name });
        let [nx, ny, nz] = shape.dims.map(|d| d - 1);
        let extent = format!("0 {nx} 0 {ny} 0 {nz}");
        let [ox, oy, oz] = shape.origin;
        let [sx, sy, sz] = shape.spacing;
        let header = format!(
            "<?xml version=\"1.0\"?>\n\
             <VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  \
             <ImageData WholeExtent=\"{extent}\" Origin=\"{ox:?} {oy:?} {oz:?}\" Spacing=\"{sx:?} {sy:?} {sz:?}\">\n    \
             <Piece Extent=\"{extent}\">\n      <PointData Scalars=\"{name}\">\n        \
             <DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{components}\" format=\"appended\" \
             offset=\"0\"/>\n      </PointData>\n      <CellData>\n      </CellData>\n    </Piece>\n  \
             </ImageData>\n  <AppendedData encoding=\"raw\">\n   _",
            ty = xml_type(scalar_type),
        );
        let write = |out: &mut std::io::BufWriter<std::fs::File>| -> std::io::Result<()> {
            out.write_all(header.as_bytes())?;
            out.write_all(&bytes.to_le_bytes())
        };
        write(&mut out).map_err(|e| fail(format!("cannot write the file: {e}")))?;
        Ok(VtiWriter { out, label, scalar_type, remaining: bytes })
    }

    /// Appends the next values (x fastest, components interleaved), of the
    /// writer's scalar type.
    pub fn write(&mut self, values: Samples<'_>) -> Result<()> {
        let bytes = values.as_bytes();
        if values.scalar_type() != self.scalar_type || bytes.len() as u64 > self.remaining {
            return Err(self.fail(format!(
                "{} {} values do not fit what the header declared ({} bytes of {} left)",
                values.len(),
                values.scalar_type().name(),
                self.remaining,
                self.scalar_type.name()
            )));
        }
        let written = if cfg!(target_endian = "little") {
            self.out.write_all(bytes)
        } else {
            let size = self.scalar_type.size();
            bytes.chunks(size * 65536).try_for_each(|chunk| {
                let swapped: Vec<u8> = chunk.chunks_exact(size).flat_map(|v| v.iter().rev().copied()).collect();
                self.out.write_all(&swapped)
            })
        };
        written.map_err(|e| self.fail(format!("cannot write the file: {e}")))?;
        self.remaining -= bytes.len() as u64;
        Ok(())
    }

    /// Closes the file once every value is written.
    pub fn finish(mut self) -> Result<()> {
        if self.remaining != 0 {
            return Err(
                self.fail(format!("{} bytes of values were never written; the file is incomplete", self.remaining))
            );
        }
        let end = self.out.write_all(b"\n  </AppendedData>\n</VTKFile>\n").and_then(|()| self.out.flush());
        end.map_err(|e| self.fail(format!("cannot write the file: {e}")))
    }

    fn fail(&self, message: String) -> Error {
        Error::Write { path: self.label.clone(), message }
    }
}

/// The VTK XML name of `ty`.
fn xml_type(ty: ScalarType) -> &'static str {
    match ty {
        ScalarType::U8 => "UInt8",
        ScalarType::I8 => "Int8",
        ScalarType::U16 => "UInt16",
        ScalarType::I16 => "Int16",
        ScalarType::U32 => "UInt32",
        ScalarType::I32 => "Int32",
        ScalarType::F32 => "Float32",
        ScalarType::F64 => "Float64",
    }
}

/// `s` fit for an XML attribute value.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if (c as u32) < 0x20 => out.push_str(&format!("&#{};", c as u32)),
            c => out.push(c),
        }
    }
    out
}
