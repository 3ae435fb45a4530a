//! The XML header of a VTK XML ImageData file (`.vti`), as written by VTK's
//! `vtkXMLImageDataWriter` (ParaView's "Save Data" to `.vti`):
//!
//! ```text
//! <VTKFile type="ImageData" version="1.0" byte_order="LittleEndian"
//!          header_type="UInt64" compressor="vtkZLibDataCompressor">
//!   <ImageData WholeExtent="x0 x1 y0 y1 z0 z1" Origin="ox oy oz" Spacing="sx sy sz"
//!              Direction="1 0 0 0 1 0 0 0 1">
//!     <Piece Extent="x0 x1 y0 y1 z0 z1">
//!       <PointData Scalars="name">
//!         <DataArray type="Float32" Name="name" NumberOfComponents="1"
//!                    format="appended" offset="0"/>
//!       </PointData>
//!       <CellData>...</CellData>
//!     </Piece>
//!   </ImageData>
//!   <AppendedData encoding="raw">
//!    _<binary bytes, or base64 text when encoding="base64">
//!   </AppendedData>
//! </VTKFile>
//! ```
//!
//! * `byte_order` defaults to `LittleEndian`, `header_type` to `UInt32`
//!   (files of version 0.1 have none), `compressor` to none,
//!   `NumberOfComponents` to 1.
//! * A `DataArray` is `format="ascii"` (numbers in its text), `"binary"`
//!   (base64 in its text) or `"appended"` (at `offset` after the `_` marker of
//!   `AppendedData`; bytes for `encoding="raw"`, characters for `"base64"`).
//!   Its text is only the text directly inside it: VTK may nest
//!   `<InformationKey>` elements in a `DataArray`. The text is not copied:
//!   the header keeps where its runs are in the file (numbers and base64
//!   hold no markup to unescape).
//! * `Direction` (VTK 9) is the row-major 3x3 orientation matrix.
//!
//! Parsing stops at the `AppendedData` start tag: what follows the `_` may be
//! raw binary, which is not XML. How array bytes are laid out is described in
//! [`super::vti_data`].

use crate::base::limits::{excerpt, excerpt_bytes};
use quick_xml::events::{BytesStart, Event};
use quick_xml::Reader;

/// Byte order of binary words (header words and values).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ByteOrder {
    /// `byte_order="LittleEndian"` (the default).
    Little,
    /// `byte_order="BigEndian"`.
    Big,
}

/// The block compressor of binary data (`compressor` on `VTKFile`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Compressor {
    /// `vtkZLibDataCompressor`: each block is a zlib stream.
    ZLib,
    /// `vtkLZ4DataCompressor`: each block is a raw LZ4 block (no frame).
    Lz4,
    /// `vtkLZMADataCompressor`: each block is an `.xz` stream.
    Lzma,
}

/// How the `AppendedData` section is encoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AppendedEncoding {
    /// `encoding="raw"`: bytes, VTK's default.
    Raw,
    /// `encoding="base64"`: base64 text.
    Base64,
}

/// Where an array's values are.
#[derive(Debug, Clone, PartialEq)]
pub enum ArrayData {
    /// `format="ascii"`: the text (these runs of the file's bytes) holds
    /// whitespace-separated numbers.
    Ascii(Vec<std::ops::Range<usize>>),
    /// `format="binary"`: the text (these runs of the file's bytes) is base64
    /// of header and (compressed) bytes.
    Binary(Vec<std::ops::Range<usize>>),
    /// `format="appended"`: at this offset after the `_` of `AppendedData`.
    Appended(u64),
}

/// One `DataArray` of `PointData` or `CellData`.
#[derive(Debug, Clone, PartialEq)]
pub struct ArrayHeader {
    /// `Name` (may be empty).
    pub name: String,
    /// `type`, e.g. `Float32`.
    pub type_name: String,
    /// `NumberOfComponents`.
    pub components: usize,
    /// The values' location and format.
    pub data: ArrayData,
}

/// One `Piece` of the image.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PieceHeader {
    /// `Extent` (`x0 x1 y0 y1 z0 z1`, inclusive point indices).
    pub extent: Option<[i64; 6]>,
    /// The `Scalars` attribute of `PointData`: the active point scalars.
    pub active_scalars: Option<String>,
    /// The point data arrays, in file order.
    pub point_arrays: Vec<ArrayHeader>,
    /// The number of cell data arrays.
    pub cell_arrays: usize,
    /// `Source` attribute: the piece is in another file (parallel `.pvti`).
    pub source: Option<String>,
}

/// Everything the reader needs from the XML part of a `.vti` file.
#[derive(Debug, Clone, PartialEq)]
pub struct VtiHeader {
    /// `type` of `VTKFile`, e.g. `ImageData`.
    pub file_type: String,
    /// Byte order of binary words.
    pub byte_order: ByteOrder,
    /// True for `header_type="UInt64"`, false for `UInt32`.
    pub header_u64: bool,
    /// The block compressor, if any.
    pub compressor: Option<Compressor>,
    /// `WholeExtent` of `ImageData`.
    pub whole_extent: Option<[i64; 6]>,
    /// `Origin`: world position of point index (0, 0, 0) (not of the extent's first point).
    pub origin: [f64; 3],
    /// `Spacing`.
    pub spacing: [f64; 3],
    /// `Direction`, row-major, if given.
    pub direction: Option<[f64; 9]>,
    /// The pieces.
    pub pieces: Vec<PieceHeader>,
    /// Encoding and file offset of the first byte after the `_` marker of `AppendedData`.
    pub appended: Option<(AppendedEncoding, usize)>,
}

/// Parses the XML header of `bytes` (a whole `.vti` file). Errors are
/// messages for [`crate::Error::Format`].
pub fn parse_header(bytes: &[u8]) -> Result<VtiHeader, String> {
    let mut reader = Reader::from_reader(bytes);
    let mut parser = HeaderParser::default();
    loop {
        let event = reader.read_event().map_err(|e| {
            format!(
                "the XML header is malformed near byte {} ({}); the file is truncated or corrupt",
                reader.buffer_position(),
                excerpt(&e.to_string())
            )
        })?;
        match event {
            Event::Start(ref e) | Event::Empty(ref e) => {
                let after_tag = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
                if parser.start(e, matches!(event, Event::Empty(_)), bytes, after_tag)? {
                    break;
                }
            }
            // The event's raw bytes end where the reader now is (a CDATA
            // section's before its closing `]]>`).
            Event::Text(t) => {
                let end = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX);
                if let Some(text) = parser.array_text() {
                    text.push(end - t.len()..end);
                }
            }
            Event::CData(t) => {
                let end = usize::try_from(reader.buffer_position()).unwrap_or(usize::MAX) - 3;
                if let Some(text) = parser.array_text() {
                    text.push(end - t.len()..end);
                }
            }
            Event::End(e) => parser.end(e.local_name().as_ref())?,
            Event::Eof => break,
            _ => {}
        }
    }
    parser.finish()
}

/// The state of [`parse_header`] between XML events.
#[derive(Default)]
struct HeaderParser {
    /// Set by the `VTKFile` element.
    header: Option<VtiHeader>,
    /// Open elements, innermost last.
    stack: Vec<Vec<u8>>,
    /// The point data array being read, with its text runs so far.
    array: Option<(ArrayHeader, Vec<std::ops::Range<usize>>)>,
}

impl HeaderParser {
    /// A start (or empty, `empty`) element `e`, whose tag ends at byte
    /// `after_tag` of `bytes`. Returns true when parsing is over: the file is
    /// not image data (the caller explains what it is instead), or the
    /// `AppendedData` section starts.
    fn start(&mut self, e: &BytesStart, empty: bool, bytes: &[u8], after_tag: usize) -> Result<bool, String> {
        if self.header.is_none() && e.local_name().as_ref() != b"VTKFile" {
            return Err(format!(
                "this is not a VTK XML file: the first element is <{}>, not <VTKFile>",
                excerpt_bytes(e.name().as_ref())
            ));
        }
        let name = e.local_name().as_ref().to_vec();
        let parent = self.stack.last().map(Vec::as_slice);
        match (name.as_slice(), parent) {
            (b"VTKFile", None) => {
                let h = vtk_file(e)?;
                let image = h.file_type == "ImageData";
                self.header = Some(h);
                if !image {
                    return Ok(true);
                }
            }
            (b"ImageData", Some(b"VTKFile")) => image_data(self.header.as_mut().expect("set by VTKFile"), e)?,
            (b"Piece", Some(b"ImageData")) => {
                let extent = attr(e, "Extent")?.map(|v| numbers(&v, "Extent")).transpose()?;
                let source = attr(e, "Source")?;
                let piece = PieceHeader { extent, source, ..PieceHeader::default() };
                self.header.as_mut().expect("set by VTKFile").pieces.push(piece);
            }
            (b"PointData", Some(b"Piece")) => {
                if let Some(p) = self.header.as_mut().and_then(|h| h.pieces.last_mut()) {
                    p.active_scalars = attr(e, "Scalars")?;
                }
            }
            (b"DataArray", Some(b"CellData")) => {
                if let Some(p) = self.header.as_mut().and_then(|h| h.pieces.last_mut()) {
                    p.cell_arrays += 1;
                }
            }
            (b"DataArray", Some(b"PointData")) => {
                let a = data_array(e)?;
                if empty {
                    push_array(&mut self.header, a, Vec::new())?;
                } else {
                    self.array = Some((a, Vec::new()));
                }
            }
            (b"AppendedData", Some(b"VTKFile")) => {
                let appended = appended_data(e, empty, bytes, after_tag)?;
                self.header.as_mut().expect("set by VTKFile").appended = Some(appended);
                return Ok(true);
            }
            _ => {}
        }
        if !empty {
            self.stack.push(name);
        }
        Ok(false)
    }

    /// The text of the point data array being read, when directly inside its
    /// `DataArray` (VTK may nest `<InformationKey>` elements in it).
    fn array_text(&mut self) -> Option<&mut Vec<std::ops::Range<usize>>> {
        let inside = self.stack.last().map(Vec::as_slice) == Some(b"DataArray");
        self.array.as_mut().filter(|_| inside).map(|(_, text)| text)
    }

    /// The end of element `name`: a point data array is complete.
    fn end(&mut self, name: &[u8]) -> Result<(), String> {
        self.stack.pop();
        if name == b"DataArray" && self.stack.last().map(Vec::as_slice) == Some(b"PointData") {
            if let Some((a, text)) = self.array.take() {
                push_array(&mut self.header, a, text)?;
            }
        }
        Ok(())
    }

    /// The header, once the XML ended or the appended data started.
    fn finish(self) -> Result<VtiHeader, String> {
        let header = self.header.ok_or("this is not a VTK XML file: it has no <VTKFile> element")?;
        if !self.stack.is_empty() && header.appended.is_none() {
            return Err(format!(
                "the XML ends inside <{}>; the file is truncated or corrupt",
                excerpt_bytes(self.stack.last().map(Vec::as_slice).unwrap_or_default())
            ));
        }
        Ok(header)
    }
}

/// The geometry attributes of the `ImageData` element: `WholeExtent`,
/// `Origin` (default 0), `Spacing` (default 1), `Direction`.
fn image_data(h: &mut VtiHeader, e: &BytesStart) -> Result<(), String> {
    h.whole_extent = attr(e, "WholeExtent")?.map(|v| numbers(&v, "WholeExtent")).transpose()?;
    h.origin = attr(e, "Origin")?.map(|v| numbers(&v, "Origin")).transpose()?.unwrap_or([0.0; 3]);
    h.spacing = attr(e, "Spacing")?.map(|v| numbers(&v, "Spacing")).transpose()?.unwrap_or([1.0; 3]);
    h.direction = attr(e, "Direction")?.map(|v| numbers(&v, "Direction")).transpose()?;
    Ok(())
}

/// The encoding of the `AppendedData` element `e` (its tag ends at byte
/// `after_tag` of `bytes`) and the offset of its data: after optional
/// whitespace and the `_` marker.
fn appended_data(
    e: &BytesStart,
    empty: bool,
    bytes: &[u8],
    after_tag: usize,
) -> Result<(AppendedEncoding, usize), String> {
    let encoding = match attr(e, "encoding")?.as_deref() {
        Some("raw") | None => AppendedEncoding::Raw,
        Some("base64") => AppendedEncoding::Base64,
        Some(other) => {
            return Err(format!("unknown AppendedData encoding '{}' (VTK writes 'raw' or 'base64')", excerpt(other)))
        }
    };
    let rest = bytes.get(after_tag..).unwrap_or_default();
    let marker = rest.iter().position(|b| !b.is_ascii_whitespace());
    if empty || marker.map(|m| rest[m]) != Some(b'_') {
        return Err("the AppendedData section lacks its '_' marker before the data; \
                    the file is truncated or corrupt"
            .into());
    }
    Ok((encoding, after_tag + marker.unwrap_or(0) + 1))
}

fn vtk_file(e: &BytesStart) -> Result<VtiHeader, String> {
    let byte_order = match attr(e, "byte_order")?.as_deref() {
        Some("LittleEndian") | None => ByteOrder::Little,
        Some("BigEndian") => ByteOrder::Big,
        Some(other) => {
            return Err(format!("unknown byte_order '{}' (expected LittleEndian or BigEndian)", excerpt(other)))
        }
    };
    let header_u64 = match attr(e, "header_type")?.as_deref() {
        Some("UInt32") | None => false,
        Some("UInt64") => true,
        Some(other) => return Err(format!("unknown header_type '{}' (expected UInt32 or UInt64)", excerpt(other))),
    };
    let compressor = match attr(e, "compressor")?.as_deref() {
        None | Some("") => None,
        Some("vtkZLibDataCompressor") => Some(Compressor::ZLib),
        Some("vtkLZ4DataCompressor") => Some(Compressor::Lz4),
        Some("vtkLZMADataCompressor") => Some(Compressor::Lzma),
        Some(other) => {
            return Err(format!(
                "the data are compressed with '{}', which is not supported (supported: \
                 vtkZLibDataCompressor, vtkLZ4DataCompressor, vtkLZMADataCompressor); \
                 save the file again uncompressed or with ZLib",
                excerpt(other)
            ))
        }
    };
    Ok(VtiHeader {
        file_type: attr(e, "type")?.unwrap_or_default(),
        byte_order,
        header_u64,
        compressor,
        whole_extent: None,
        origin: [0.0; 3],
        spacing: [1.0; 3],
        direction: None,
        pieces: Vec::new(),
        appended: None,
    })
}

fn data_array(e: &BytesStart) -> Result<ArrayHeader, String> {
    let full_name = attr(e, "Name")?.unwrap_or_default();
    let name = excerpt(&full_name);
    let type_name = attr(e, "type")?.ok_or_else(|| format!("the DataArray '{name}' has no type attribute"))?;
    let components = match attr(e, "NumberOfComponents")? {
        None => 1,
        Some(v) => v
            .trim()
            .parse::<usize>()
            .ok()
            .filter(|&c| c > 0)
            .ok_or_else(|| format!("the DataArray '{name}' has a bad NumberOfComponents '{}'", excerpt(&v)))?,
    };
    let data = match attr(e, "format")?.as_deref() {
        Some("ascii") => ArrayData::Ascii(Vec::new()),
        Some("binary") => ArrayData::Binary(Vec::new()),
        Some("appended") => {
            let offset = attr(e, "offset")?.ok_or_else(|| format!("the appended DataArray '{name}' has no offset"))?;
            ArrayData::Appended(
                offset
                    .trim()
                    .parse()
                    .map_err(|_| format!("the DataArray '{name}' has a bad offset '{}'", excerpt(&offset)))?,
            )
        }
        other => {
            return Err(format!(
                "the DataArray '{name}' has format {:?}; expected 'ascii', 'binary' or 'appended'",
                other.map(excerpt)
            ))
        }
    };
    Ok(ArrayHeader { name: full_name, type_name, components, data })
}

/// Stores a point array with its text runs (for `ascii` and `binary` arrays).
fn push_array(
    header: &mut Option<VtiHeader>,
    mut array: ArrayHeader,
    text: Vec<std::ops::Range<usize>>,
) -> Result<(), String> {
    match &mut array.data {
        ArrayData::Ascii(t) | ArrayData::Binary(t) => *t = text,
        ArrayData::Appended(_) => {}
    }
    let piece = header.as_mut().and_then(|h| h.pieces.last_mut()).ok_or("a DataArray lies outside any Piece")?;
    piece.point_arrays.push(array);
    Ok(())
}

/// The unescaped value of attribute `key`, if present.
fn attr(e: &BytesStart, key: &str) -> Result<Option<String>, String> {
    for a in e.attributes() {
        let a = a.map_err(|err| {
            format!("a malformed attribute in <{}> ({})", excerpt_bytes(e.name().as_ref()), excerpt(&err.to_string()))
        })?;
        if a.key.as_ref() == key.as_bytes() {
            let v = a
                .unescape_value()
                .map_err(|err| format!("a malformed value of attribute {key} ({})", excerpt(&err.to_string())))?;
            return Ok(Some(v.into_owned()));
        }
    }
    Ok(None)
}

/// Exactly `N` whitespace-separated numbers.
fn numbers<T: std::str::FromStr, const N: usize>(text: &str, what: &str) -> Result<[T; N], String> {
    let bad = || format!("the attribute {what}=\"{}\" must hold {N} numbers", excerpt(text));
    let values: Vec<T> =
        text.split_ascii_whitespace().map(|s| s.parse().map_err(|_| bad())).collect::<Result<_, _>>()?;
    values.try_into().map_err(|_| bad())
}
