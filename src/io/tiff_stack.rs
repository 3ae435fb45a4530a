//! TIFF stacks: a folder of 2D TIFF slices (one z-plane a file, in the
//! natural order of the file names: `slice2.tif` before `slice10.tif`), or
//! one multi-page TIFF (ImageJ's and tifffile's stacks, OME-TIFF's planes),
//! or a folder of multi-page files, read as one volume, one page a z-plane.
//!
//! Pages hold one grayscale sample a pixel: 8-, 16- or 32-bit integers
//! (unsigned or signed), 32- or 64-bit floats; strips or tiles; no
//! compression, LZW, Deflate or PackBits ([`tiff`]). Every page must have the
//! first page's width, height and sample type: a page that differs is an
//! error naming its file and page. Hidden files (names starting with `.`,
//! e.g. macOS `._` companions) and files not ending in `.tif`/`.tiff` (any
//! case) are not slices.
//!
//! Geometry: spacing 1 and origin 0, except for ImageJ stacks (an
//! `ImageDescription` starting `ImageJ=`), whose `XResolution` and
//! `YResolution` are pixels per unit (spacing their inverse) and whose
//! `spacing=` is the z step. ImageJ hyperstacks with several channels or
//! time points are refused (save one channel and time point first).
//!
//! Opening reads every page's directory, not its pixels; [`TiffStack::read_planes`]
//! decodes a range of pages straight into the volume's buffer (no second
//! copy), in parallel runs of pages, after [`check_memory`] allowed it.

use super::format_error;
use super::source::display_path;
use crate::base::error::{Error, Result};
use crate::base::limits::{check_memory, human_bytes};
use crate::data::grid::{GridShape, ScalarType};
use crate::data::volume::{SampleBuf, Volume};
use rayon::prelude::*;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use tiff::decoder::{Decoder, DecodingSampleType, Limits};
use tiff::tags::Tag;
use tiff::ColorType;

/// The most pages a stack may have (a directory chain longer than this is
/// damaged or hostile, and a volume of more planes is not a TIFF stack's job).
pub const MAX_PAGES: usize = 1 << 20;

/// Pages a parallel task decodes at least (a multi-page file's directories are
/// walked from its start, so runs are long).
const RUN_PAGES: usize = 16;

/// One z-plane: page `ifd` of file `file`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Page {
    file: usize,
    ifd: usize,
}

/// A TIFF stack, opened: its pages and the volume they make.
#[derive(Debug, Clone)]
pub struct TiffStack {
    label: String,
    files: Vec<PathBuf>,
    pages: Vec<Page>,
    /// Samples per axis (x the width, y the height, z the pages).
    pub dims: [usize; 3],
    /// The pages' sample type.
    pub scalar_type: ScalarType,
    /// Spacing (ImageJ's calibration, else 1) and origin 0.
    pub shape: GridShape,
    /// The array's name: the folder's or file's stem.
    pub name: String,
}

/// What a page's directory says.
#[derive(Debug, Clone, PartialEq)]
struct PageInfo {
    width: usize,
    height: usize,
    scalar_type: ScalarType,
}

impl TiffStack {
    /// Opens the stack at `path`: a folder of TIFF files or one TIFF file.
    ///
    /// # Errors
    ///
    /// [`Error::Format`] naming the file and page for a folder without TIFF
    /// files, a file that is not TIFF, an unsupported page (colour, 1-bit,
    /// 16-bit float, 64-bit integer, several samples a pixel), a page whose
    /// size or type differs from the first, or an ImageJ hyperstack.
    pub fn open(path: &Path) -> Result<TiffStack> {
        let label = display_path(path);
        let files = if path.is_dir() { slice_files(path, &label)? } else { vec![path.to_path_buf()] };
        let mut pages = Vec::new();
        let mut first: Option<PageInfo> = None;
        let mut spacing = [1.0; 3];
        for (f, file) in files.iter().enumerate() {
            let file_label = display_path(file);
            let mut decoder = open_decoder(file, &file_label)?;
            if f == 0 {
                spacing = imagej_spacing(&mut decoder, &file_label)?;
            }
            let mut ifd = 0;
            loop {
                let info = page_info(&mut decoder, &file_label, ifd)?;
                match &first {
                    None => first = Some(info),
                    Some(expected) if *expected != info => {
                        return Err(format_error(
                            &file_label,
                            format!(
                                "page {ifd} is {}x{} {}, the stack's first page {}x{} {}: every slice must have one \
                                 size and sample type",
                                info.width,
                                info.height,
                                info.scalar_type.name(),
                                expected.width,
                                expected.height,
                                expected.scalar_type.name()
                            ),
                        ))
                    }
                    Some(_) => {}
                }
                pages.push(Page { file: f, ifd });
                if pages.len() > MAX_PAGES {
                    return Err(format_error(
                        &label,
                        format!("more than {MAX_PAGES} pages: the stack is damaged or not a volume"),
                    ));
                }
                if !decoder.more_images() {
                    break;
                }
                decoder.next_image().map_err(|e| tiff_error(&file_label, ifd + 1, &e))?;
                ifd += 1;
            }
        }
        let info = first.ok_or_else(|| format_error(&label, "the stack has no pages"))?;
        let dims = [info.width, info.height, pages.len()];
        let name = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_else(|| "tiff".into());
        let name = name.strip_suffix(".ome").unwrap_or(&name).to_string();
        Ok(TiffStack {
            label,
            files,
            pages,
            dims,
            scalar_type: info.scalar_type,
            shape: GridShape { dims, spacing, origin: [0.0; 3] },
            name,
        })
    }

    /// The pages `z` as one buffer of z-planes, x fastest.
    ///
    /// # Errors
    ///
    /// [`Error::InvalidArgument`] for a range outside the stack or more
    /// memory than the process may use; [`Error::Format`] for a page that
    /// cannot be decoded or changed since opening.
    pub fn read_planes(&self, z: std::ops::Range<usize>) -> Result<SampleBuf> {
        if z.start > z.end || z.end > self.dims[2] {
            return Err(Error::InvalidArgument(format!(
                "planes {z:?} are not inside the {} pages of '{}'",
                self.dims[2], self.label
            )));
        }
        let plane = self.dims[0] * self.dims[1];
        let bytes = (plane as u128) * (z.len() as u128) * self.scalar_type.size() as u128;
        check_memory(bytes, &format!("{} pages of '{}'", z.len(), self.label), "read a smaller stack")?;
        let mut out = SampleBuf::zeroed(self.scalar_type, plane * z.len());
        let plane_bytes = plane * self.scalar_type.size();
        let mut tasks = Vec::new();
        let mut rest = out.as_bytes_mut();
        let mut at = z.start;
        while at < z.end {
            let first = self.pages[at];
            let mut end = at + 1;
            while end < z.end && end - at < RUN_PAGES && self.pages[end].file == first.file {
                end += 1;
            }
            let (head, tail) = std::mem::take(&mut rest).split_at_mut((end - at) * plane_bytes);
            tasks.push((first, head));
            rest = tail;
            at = end;
        }
        let expected = PageInfo { width: self.dims[0], height: self.dims[1], scalar_type: self.scalar_type };
        tasks.into_par_iter().try_for_each(|(first, buf)| {
            let file = &self.files[first.file];
            let file_label = display_path(file);
            let mut decoder = open_decoder(file, &file_label)?;
            decode_run(&mut decoder, &file_label, first.ifd, &expected, buf)
        })?;
        Ok(out)
    }

    /// The whole stack as a volume.
    ///
    /// # Errors
    ///
    /// As [`Self::read_planes`].
    pub fn read_volume(&self) -> Result<Volume> {
        let samples = self.read_planes(0..self.dims[2])?;
        Ok(Volume { samples, shape: self.shape, components: 1, name: self.name.clone() })
    }
}

/// A stack is read plane by plane by the streaming octree build and writer.
impl crate::data::planes::PlaneSource for TiffStack {
    fn shape(&self) -> GridShape {
        self.shape
    }
    fn scalar_type(&self) -> ScalarType {
        self.scalar_type
    }
    fn read_planes(&self, z: std::ops::Range<usize>) -> Result<SampleBuf> {
        TiffStack::read_planes(self, z)
    }
}

/// Reads the multi-page TIFF `bytes` (a file named `label`, in memory) as
/// a volume, as [`TiffStack`] reads a file: the pages are checked first,
/// then decoded into the volume's buffer.
///
/// # Errors
///
/// As [`TiffStack::open`] and [`TiffStack::read_planes`].
pub fn read_tiff_bytes(label: &str, bytes: &[u8]) -> Result<Volume> {
    let open = || {
        let mut reader = std::io::Cursor::new(bytes);
        first_directory_fits(&mut reader, bytes.len() as u64).map_err(|m| format_error(label, m))?;
        Decoder::new(reader)
            .map(|d| d.with_limits(limits_for(bytes.len() as u64)))
            .map_err(|e| format_error(label, format!("not a TIFF file ({e}): give .tif/.tiff slices")))
    };
    let mut decoder = open()?;
    let spacing = imagej_spacing(&mut decoder, label)?;
    let info = page_info(&mut decoder, label, 0)?;
    let mut pages = 1usize;
    while decoder.more_images() {
        decoder.next_image().map_err(|e| tiff_error(label, pages, &e))?;
        let page = page_info(&mut decoder, label, pages)?;
        if page != info {
            return Err(format_error(label, format!("page {pages} differs from page 0 in size or sample type")));
        }
        pages += 1;
        if pages > MAX_PAGES {
            return Err(format_error(
                label,
                format!("more than {MAX_PAGES} pages: the stack is damaged or not a volume"),
            ));
        }
    }
    let dims = [info.width, info.height, pages];
    let count = (dims[0] * dims[1]) as u128 * pages as u128;
    check_memory(
        count * info.scalar_type.size() as u128,
        &format!("the {pages} pages of '{label}'"),
        "read a smaller stack",
    )?;
    let mut samples = SampleBuf::zeroed(info.scalar_type, dims[0] * dims[1] * pages);
    decode_run(&mut open()?, label, 0, &info, samples.as_bytes_mut())?;
    Ok(Volume { samples, shape: GridShape { dims, spacing, origin: [0.0; 3] }, components: 1, name: "tiff".into() })
}

/// Decodes pages `first ..` of `decoder`'s file, one a plane of `buf`, each
/// checked to be `expected` first.
fn decode_run<R: Read + Seek>(
    decoder: &mut Decoder<R>,
    label: &str,
    first: usize,
    expected: &PageInfo,
    buf: &mut [u8],
) -> Result<()> {
    let plane_bytes = expected.width * expected.height * expected.scalar_type.size();
    decoder.seek_to_image(first).map_err(|e| tiff_error(label, first, &e))?;
    for (k, plane) in buf.chunks_mut(plane_bytes).enumerate() {
        let ifd = first + k;
        if k > 0 {
            decoder.next_image().map_err(|e| tiff_error(label, ifd, &e))?;
        }
        if page_info(decoder, label, ifd)? != *expected {
            return Err(format_error(label, format!("page {ifd} changed since the stack was opened")));
        }
        decoder.read_image_bytes(plane).map_err(|e| tiff_error(label, ifd, &e))?;
    }
    Ok(())
}

/// True for a file name a stack's slice may have (`.tif`, `.tiff`, any case; not hidden).
pub fn is_slice_name(name: &str) -> bool {
    let lower = name.to_ascii_lowercase();
    !name.starts_with('.') && (lower.ends_with(".tif") || lower.ends_with(".tiff"))
}

/// The TIFF files of folder `dir` in natural order.
fn slice_files(dir: &Path, label: &str) -> Result<Vec<PathBuf>> {
    let entries = std::fs::read_dir(dir).map_err(|e| format_error(label, format!("cannot list the folder: {e}")))?;
    let mut files = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| format_error(label, format!("cannot list the folder: {e}")))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if is_slice_name(&name) && entry.path().is_file() {
            files.push((natural_key(&name), entry.path()));
        }
        if files.len() > MAX_PAGES {
            return Err(format_error(label, format!("more than {MAX_PAGES} TIFF files: not a stack of slices")));
        }
    }
    if files.is_empty() {
        return Err(format_error(
            label,
            "the folder holds no .tif/.tiff slices (nor OME-Zarr metadata): give a folder of TIFF slices, a TIFF \
             file, or an OME-Zarr image",
        ));
    }
    files.sort();
    Ok(files.into_iter().map(|(_, p)| p).collect())
}

/// A key that sorts names naturally: runs of digits by their value, the
/// rest by its text (`img2` before `img10`; ties by the whole name).
fn natural_key(name: &str) -> (Vec<(String, u128, usize)>, String) {
    let mut parts = Vec::new();
    let mut text = String::new();
    let mut chars = name.chars().peekable();
    while let Some(&c) = chars.peek() {
        if c.is_ascii_digit() {
            let mut digits = String::new();
            while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                digits.push(d);
                chars.next();
            }
            let value = digits.trim_start_matches('0').parse::<u128>().unwrap_or(u128::MAX);
            parts.push((std::mem::take(&mut text), value, digits.len()));
        } else {
            text.push(c);
            chars.next();
        }
    }
    parts.push((text, 0, 0));
    (parts, name.to_string())
}

/// A decoder over `file`, limits set so that no directory value or
/// decoding buffer beyond a page's size is allocated from the file's word.
fn open_decoder(file: &Path, label: &str) -> Result<Decoder<BufReader<std::fs::File>>> {
    let len = super::source::regular_file_len(file, label)?;
    let mut reader = BufReader::new(super::source::open_regular_file(file, label)?);
    first_directory_fits(&mut reader, len).map_err(|m| format_error(label, m))?;
    Decoder::new(reader)
        .map(|d| d.with_limits(limits_for(len)))
        .map_err(|e| format_error(label, format!("not a TIFF file ({e}): give .tif/.tiff slices")))
}

/// The decoder's limits for a file of `len` bytes: no directory value (strip
/// offsets, a description) or compressed chunk is longer than the file, and
/// none of the decoder's buffers is larger than the process may use.
fn limits_for(len: u64) -> Limits {
    let memory = crate::base::limits::available_memory().map_or(usize::MAX, |m| m.min(usize::MAX as u128) as usize);
    let len = usize::try_from(len).unwrap_or(usize::MAX);
    let mut limits = Limits::default();
    limits.ifd_value_size = limits.ifd_value_size.max(len.min(16 << 20)).min(memory);
    limits.intermediate_buffer_size = limits.intermediate_buffer_size.min(len).min(memory);
    limits.decoding_buffer_size = limits.decoding_buffer_size.min(memory);
    limits
}

/// Checks the first directory's values against the file's length `len`
/// before the decoder reads it (the decoder reads the first directory
/// before its limits can be set, sizing buffers from the counts the file
/// declares): every value fits in the file. Leaves `reader` at its start.
fn first_directory_fits<R: Read + Seek>(reader: &mut R, len: u64) -> std::result::Result<(), String> {
    let mut header = [0u8; 16];
    let got = read_up_to(reader, &mut header)?;
    let big_endian = match &header[..2] {
        b"II" => false,
        b"MM" => true,
        _ => return Err("not a TIFF file (no II or MM byte order mark): give .tif/.tiff slices".into()),
    };
    let word = |b: &[u8]| -> u64 {
        let v = b.iter().fold(0u64, |acc, &x| (acc << 8) | u64::from(x));
        if big_endian {
            v
        } else {
            b.iter().rev().fold(0u64, |acc, &x| (acc << 8) | u64::from(x))
        }
    };
    let (bigtiff, first) = match (got >= 8, word(&header[2..4])) {
        (true, 42) => (false, word(&header[4..8])),
        (_, 43) if got >= 16 => (true, word(&header[8..16])),
        _ => return Err("not a TIFF file (the header is damaged): give .tif/.tiff slices".into()),
    };
    let (count_bytes, entry_bytes, inline) = if bigtiff { (8u64, 20u64, 8u64) } else { (2, 12, 4) };
    reader.seek(SeekFrom::Start(first)).map_err(|e| e.to_string())?;
    let mut count = [0u8; 8];
    if read_up_to(reader, &mut count[..count_bytes as usize])? < count_bytes as usize {
        return Err(format!("the first directory (at byte {first}) lies past the end of the file ({len} bytes)"));
    }
    let entries = word(&count[..count_bytes as usize]);
    if u128::from(entries) * u128::from(entry_bytes) > u128::from(len) {
        return Err(format!("the first directory declares {entries} entries, more than the file's {len} bytes hold"));
    }
    let mut entry = [0u8; 20];
    for _ in 0..entries {
        let e = &mut entry[..entry_bytes as usize];
        if read_up_to(reader, e)? < e.len() {
            return Err(format!("the first directory is cut short by the end of the file ({len} bytes)"));
        }
        let (tag, kind) = (word(&e[0..2]), word(&e[2..4]));
        let n = if bigtiff { word(&e[4..12]) } else { word(&e[4..8]) };
        let size: u128 = match kind {
            1 | 2 | 6 | 7 => 1,
            3 | 8 => 2,
            4 | 9 | 11 | 13 => 4,
            5 | 10 | 12 | 16 | 17 | 18 => 8,
            _ => 0,
        };
        let bytes = u128::from(n) * size;
        if bytes > u128::from(inline) && bytes > u128::from(len) {
            return Err(format!(
                "tag {tag} declares {bytes} bytes of values, more than the file's {len}: the file is damaged"
            ));
        }
    }
    reader.seek(SeekFrom::Start(0)).map_err(|e| e.to_string())?;
    Ok(())
}

/// Reads into `buf` until it is full or the input ends; the bytes read.
fn read_up_to<R: Read>(reader: &mut R, buf: &mut [u8]) -> std::result::Result<usize, String> {
    let mut got = 0;
    while got < buf.len() {
        match reader.read(&mut buf[got..]) {
            Ok(0) => break,
            Ok(n) => got += n,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => return Err(e.to_string()),
        }
    }
    Ok(got)
}

/// The current page's size and sample type, or why it cannot be a slice.
fn page_info<R: Read + Seek>(decoder: &mut Decoder<R>, label: &str, ifd: usize) -> Result<PageInfo> {
    let (width, height) = decoder.dimensions().map_err(|e| tiff_error(label, ifd, &e))?;
    let colour = decoder.colortype().map_err(|e| tiff_error(label, ifd, &e))?;
    let grey = matches!(colour, ColorType::Gray(_)) || matches!(colour, ColorType::Multiband { num_samples: 1, .. });
    if !grey {
        return Err(format_error(
            label,
            format!("page {ifd} is {colour:?}: only grayscale slices (one sample a pixel) make a volume; convert it"),
        ));
    }
    let layout = decoder.image_buffer_layout().map_err(|e| tiff_error(label, ifd, &e))?;
    let scalar_type = match layout.sample_type {
        Some(DecodingSampleType::U8) => ScalarType::U8,
        Some(DecodingSampleType::I8) => ScalarType::I8,
        Some(DecodingSampleType::U16) => ScalarType::U16,
        Some(DecodingSampleType::I16) => ScalarType::I16,
        Some(DecodingSampleType::U32) => ScalarType::U32,
        Some(DecodingSampleType::I32) => ScalarType::I32,
        Some(DecodingSampleType::F32) => ScalarType::F32,
        Some(DecodingSampleType::F64) => ScalarType::F64,
        other => {
            return Err(format_error(
                label,
                format!(
                    "page {ifd} holds {} samples: save the slices as 8/16/32-bit integers or 32/64-bit floats",
                    other.map_or_else(|| format!("{colour:?}"), |t| format!("{t:?}"))
                ),
            ))
        }
    };
    let (width, height) = (width as usize, height as usize);
    if width == 0 || height == 0 || layout.planes != 1 || layout.len != width * height * scalar_type.size() {
        return Err(format_error(
            label,
            format!(
                "page {ifd} ({width}x{height}, {} bytes decoded) is not one plane of samples",
                human_bytes(layout.len as u128)
            ),
        ));
    }
    Ok(PageInfo { width, height, scalar_type })
}

/// ImageJ's calibration of the first page (spacing x, y, z), 1 elsewhere;
/// an error for an ImageJ hyperstack (channels or frames).
fn imagej_spacing<R: Read + Seek>(decoder: &mut Decoder<R>, label: &str) -> Result<[f64; 3]> {
    let description = match decoder.find_tag(Tag::ImageDescription) {
        Ok(Some(value)) => value.into_string().unwrap_or_default(),
        _ => String::new(),
    };
    if !description.starts_with("ImageJ=") {
        return Ok([1.0; 3]);
    }
    let field = |key: &str| {
        description.lines().find_map(|l| l.strip_prefix(key).and_then(|v| v.strip_prefix('=')).map(str::trim))
    };
    for key in ["channels", "frames"] {
        if let Some(n) = field(key).and_then(|v| v.parse::<u64>().ok()).filter(|&n| n > 1) {
            return Err(format_error(
                label,
                format!(
                    "an ImageJ hyperstack with {n} {key}: save one channel and time point as a stack \
                     (Image > Duplicate) and read that"
                ),
            ));
        }
    }
    let mut inverse = |tag: Tag| -> Option<f64> {
        // A rational `pixels / unit`: the spacing is `unit / pixels`.
        let v = decoder.find_tag(tag).ok()??.into_u32_vec().ok()?;
        let (&[pixels, unit] | &[pixels, unit, ..]) = v.as_slice() else { return None };
        (pixels > 0 && unit > 0).then(|| f64::from(unit) / f64::from(pixels))
    };
    let x = inverse(Tag::XResolution).unwrap_or(1.0);
    let y = inverse(Tag::YResolution).unwrap_or(x);
    let z = field("spacing").and_then(|v| v.parse::<f64>().ok()).filter(|s| s.is_finite() && *s > 0.0).unwrap_or(1.0);
    Ok([x, y, z])
}

/// A decoding failure of page `ifd` of the file `label`.
fn tiff_error(label: &str, ifd: usize, e: &tiff::TiffError) -> Error {
    format_error(label, format!("page {ifd} cannot be read: {e}"))
}

#[cfg(test)]
#[path = "tiff_stack_tests.rs"]
mod tests;
