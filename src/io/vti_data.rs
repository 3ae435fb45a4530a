//! Decoding one `DataArray` of a `.vti` file into samples.
//!
//! Binary array layout (`format="binary"` and `format="appended"`), with every
//! header word a `header_type` integer (`UInt32` or `UInt64`) in the file's
//! `byte_order`, like the values:
//!
//! * uncompressed: `[nbytes]` then `nbytes` bytes of values;
//! * compressed (`compressor` on `VTKFile`):
//!   `[nblocks, block_size, last_block_size, csize_0 .. csize_{nblocks-1}]`
//!   then the `nblocks` compressed blocks back to back. Block `i` inflates to
//!   `block_size` bytes, except the last one, which inflates to
//!   `last_block_size` bytes when that is not 0. ZLib blocks are zlib
//!   streams, LZ4 blocks raw LZ4 blocks, LZMA blocks `.xz` streams.
//!
//! Where those bytes are:
//!
//! * `format="binary"`: base64 in the `DataArray` text;
//! * `format="appended"`, `encoding="raw"`: the bytes themselves, at `offset`
//!   bytes after the `_` marker of `AppendedData`;
//! * `format="appended"`, `encoding="base64"`: base64 at `offset` characters
//!   after the `_` marker.
//!
//! VTK base64-encodes the compression header and the blocks as two separate
//! runs, each with its own `=` padding (the uncompressed header and data as
//! one run); the decoder reads 4-character groups one after another, so a
//! padded group may end any run. Whitespace between groups is skipped.
//!
//! `format="ascii"` arrays are whitespace-separated numbers.
//!
//! Every size is checked against the data actually present before anything
//! is allocated or sliced; errors are messages for [`crate::Error::Format`].

use super::vti_xml::{AppendedEncoding, ArrayData, ArrayHeader, ByteOrder, Compressor, VtiHeader};
use crate::base::limits::{check_memory, excerpt};
use crate::data::grid::ScalarType;
use crate::data::volume::SampleBuf;
use std::io::Read;

/// Where the bytes of appended raw data are read from: the file's bytes in
/// memory, or the open file itself (positioned anywhere; `len` is its length),
/// so that a large array goes from the disk straight into its buffer.
pub enum Appended<'a> {
    /// The whole file is in `bytes` (what [`decode_array`] is given).
    InMemory,
    /// The appended raw data are read from this file of `len` bytes.
    File {
        /// The open file.
        file: &'a mut std::fs::File,
        /// Its length in bytes.
        len: u64,
    },
}

/// Decodes `array` of the file `bytes` (whose header is `header`), which must
/// hold exactly `count` values (points times components). The values are
/// decoded straight into the returned buffer: no copy of the text or of the
/// bytes is made. With [`Appended::File`], `bytes` need only hold the XML
/// header (up to the `_` of `AppendedData`) and raw appended data are read
/// from the file.
pub fn decode_array(
    bytes: &[u8],
    header: &VtiHeader,
    array: &ArrayHeader,
    count: usize,
    appended: Appended<'_>,
) -> Result<SampleBuf, String> {
    let name = &excerpt(&array.name);
    let ty = value_type(&array.type_name, name)?;
    let need = count.checked_mul(ty.size()).ok_or("the array is too large")?;
    check_memory(
        need as u128,
        &format!("the point array '{name}' ({count} {} values)", ty.name()),
        "crop or subsample the volume, or free memory",
    )
    .map_err(|e| e.to_string())?;
    let runs = |spans: &[std::ops::Range<usize>]| -> Vec<&[u8]> {
        spans.iter().filter_map(|r| bytes.get(r.clone())).collect()
    };
    let mut stream = match &array.data {
        ArrayData::Ascii(spans) => return parse_ascii(&runs(spans), ty, count, name),
        ArrayData::Binary(spans) => Stream::Base64(Base64::new(runs(spans))),
        ArrayData::Appended(offset) => {
            let (encoding, start) = header.appended.ok_or_else(|| {
                format!(
                    "the array '{}' is appended but the file has no AppendedData section; it is truncated or corrupt",
                    name
                )
            })?;
            let file_len = match &appended {
                Appended::File { len, .. } if encoding == AppendedEncoding::Raw => *len,
                _ => bytes.len() as u64,
            };
            let at = u64::try_from(start).ok().and_then(|s| offset.checked_add(s)).filter(|&at| at <= file_len);
            let at = at.ok_or_else(|| {
                format!(
                    "the array '{}' starts at appended offset {offset}, past the end of the file; it is truncated or corrupt",
                    name
                )
            })?;
            match (encoding, appended) {
                (AppendedEncoding::Raw, Appended::File { file, len }) => {
                    use std::io::Seek;
                    file.seek(std::io::SeekFrom::Start(at)).map_err(|e| format!("cannot read the file: {e}"))?;
                    Stream::File { file: std::io::BufReader::with_capacity(1 << 16, file), left: len - at }
                }
                (AppendedEncoding::Raw, Appended::InMemory) => Stream::Raw { bytes, pos: at as usize },
                (AppendedEncoding::Base64, _) => Stream::Base64(Base64::new(vec![&bytes[at as usize..]])),
            }
        }
    };
    let words = Words { u64: header.header_u64, order: header.byte_order };
    let mut out = SampleBuf::zeroed(ty, count);
    match header.compressor {
        None => {
            let nbytes = words.read(&mut stream, 1, name)?[0];
            if nbytes != need as u64 {
                return Err(size_mismatch(name, nbytes, need, count));
            }
            stream.take_into(out.as_bytes_mut(), name)?;
        }
        Some(compressor) => read_compressed(&mut stream, words, compressor, out.as_bytes_mut(), count, name)?,
    }
    out.fix_byte_order(header.byte_order == ByteOrder::Big);
    Ok(out)
}

fn size_mismatch(name: &str, found: u64, need: usize, count: usize) -> String {
    format!(
        "the array '{name}' holds {found} bytes but the extent and components need {need} ({count} values); \
         the file is truncated or corrupt"
    )
}

/// Inflates the compressed blocks of `stream` into `out` (exactly its length).
fn read_compressed(
    stream: &mut Stream,
    words: Words,
    compressor: Compressor,
    out: &mut [u8],
    count: usize,
    name: &str,
) -> Result<(), String> {
    let need = out.len();
    let head = words.read(stream, 3, name)?; // exactly three words
    let (nblocks, block_size, last_size) = (head[0], head[1], head[2]);
    let nblocks_usize = usize::try_from(nblocks).map_err(|_| format!("the array '{name}' claims {nblocks} blocks"))?;
    // nblocks * block_size, less what the partial last block lacks.
    let total = match (nblocks, last_size) {
        (0, _) => Some(0),
        (n, 0) => n.checked_mul(block_size),
        (n, last) if last <= block_size => (n - 1).checked_mul(block_size).and_then(|v| v.checked_add(last)),
        _ => None,
    };
    if total != Some(need as u64) {
        return Err(format!(
            "the compressed array '{name}' declares {nblocks} block(s) of {block_size} bytes (last {last_size}) \
             but the extent and components need {need} bytes ({count} values); the file is truncated or corrupt"
        ));
    }
    let sizes = words.read(stream, nblocks_usize, name)?;
    let mut at = 0usize;
    for (i, &csize) in sizes.iter().enumerate() {
        let size = if i + 1 == sizes.len() && last_size != 0 { last_size } else { block_size } as usize;
        let csize = usize::try_from(csize).map_err(|_| format!("block {i} of the array '{name}' is too large"))?;
        let block = stream.take(csize, name)?;
        let corrupt = |e: &dyn std::fmt::Display| {
            format!("block {i} of the array '{name}' does not decompress ({compressor:?}: {e}); the file is corrupt")
        };
        let target = &mut out[at..at + size];
        let inflated = match compressor {
            Compressor::ZLib => inflate_into(flate2::read::ZlibDecoder::new(&block[..]), target),
            Compressor::Lzma => inflate_into(xz2::read::XzDecoder::new(&block[..]), target),
            Compressor::Lz4 => {
                // LZ4 expands at most ~255:1; refuse absurd sizes before inflating.
                if size > csize.saturating_mul(255).saturating_add(64) {
                    return Err(corrupt(&format!("{csize} bytes cannot inflate to {size}")));
                }
                lz4_flex::block::decompress_into(&block, target).map_err(|e| std::io::Error::other(e.to_string()))
            }
        }
        .map_err(|e| corrupt(&e))?;
        if inflated > size {
            return Err(corrupt(&format!("it inflates to more than the {size} bytes its header declares")));
        }
        if inflated < size {
            return Err(corrupt(&format!("it inflates to {inflated} bytes, not the {size} its header declares")));
        }
        at += size;
    }
    Ok(())
}

/// Inflates `decoder` into `target`: the bytes it gave, `target.len() + 1`
/// when it has more than fit.
fn inflate_into(mut decoder: impl Read, target: &mut [u8]) -> std::io::Result<usize> {
    let mut got = 0;
    while got < target.len() {
        match decoder.read(&mut target[got..])? {
            0 => return Ok(got),
            n => got += n,
        }
    }
    let mut extra = [0u8; 1];
    Ok(got + decoder.read(&mut extra)?)
}

/// Header words: `UInt32` or `UInt64`, in the file's byte order.
#[derive(Clone, Copy)]
struct Words {
    u64: bool,
    order: ByteOrder,
}

impl Words {
    fn read(self, stream: &mut Stream, n: usize, name: &str) -> Result<Vec<u64>, String> {
        let size = if self.u64 { 8 } else { 4 };
        let bytes = stream.take(n.checked_mul(size).ok_or("too many header words")?, name)?;
        Ok(bytes
            .chunks_exact(size)
            .map(|c| match (self.u64, self.order) {
                (true, ByteOrder::Little) => u64::from_le_bytes(c.try_into().expect("8 bytes")),
                (true, ByteOrder::Big) => u64::from_be_bytes(c.try_into().expect("8 bytes")),
                (false, ByteOrder::Little) => u32::from_le_bytes(c.try_into().expect("4 bytes")).into(),
                (false, ByteOrder::Big) => u32::from_be_bytes(c.try_into().expect("4 bytes")).into(),
            })
            .collect())
    }
}

/// A cursor over binary data: raw bytes in memory or in the file, or base64 text.
enum Stream<'a> {
    Raw {
        bytes: &'a [u8],
        pos: usize,
    },
    /// `left`: bytes of the file after the read position.
    File {
        file: std::io::BufReader<&'a mut std::fs::File>,
        left: u64,
    },
    Base64(Base64<'a>),
}

impl Stream<'_> {
    /// Bytes left, at most (base64: the characters left decode to at most this).
    fn most(&self) -> u64 {
        match self {
            Stream::Raw { bytes, pos } => bytes.len().saturating_sub(*pos) as u64,
            Stream::File { left, .. } => *left,
            Stream::Base64(b) => b.most() as u64,
        }
    }

    /// The next `n` bytes (header words, a compressed block), or an error if fewer are left.
    fn take(&mut self, n: usize, name: &str) -> Result<Vec<u8>, String> {
        if n as u64 > self.most() {
            return Err(short(name, n, self.most()));
        }
        let mut out = vec![0u8; n];
        self.take_into(&mut out, name)?;
        Ok(out)
    }

    /// Fills `out` with the next bytes, or an error if fewer are left.
    fn take_into(&mut self, out: &mut [u8], name: &str) -> Result<(), String> {
        let n = out.len();
        let most = self.most();
        if n as u64 > most {
            return Err(short(name, n, most));
        }
        match self {
            Stream::Raw { bytes, pos } => {
                out.copy_from_slice(&bytes[*pos..*pos + n]);
                *pos += n;
            }
            Stream::File { file, left } => {
                file.read_exact(out).map_err(|e| format!("the data of the array '{name}' cannot be read: {e}"))?;
                *left -= n as u64;
            }
            Stream::Base64(b) => b.decode_into(out).map_err(|e| match e {
                None => short(name, n, most),
                Some(e) => format!("the array '{name}': {e}"),
            })?,
        }
        Ok(())
    }
}

fn short(name: &str, n: usize, have: u64) -> String {
    format!(
        "the data of the array '{name}' end early: {n} bytes needed, at most {have} left; \
         the file is truncated or corrupt"
    )
}

/// Base64 text in runs (the text of a `DataArray` between nested elements,
/// or the `AppendedData` section up to its end tag), decoded group by group.
struct Base64<'a> {
    runs: Vec<&'a [u8]>,
    /// The run being read and the position in it.
    run: usize,
    pos: usize,
    /// Decoded bytes of the last group not yet taken.
    pending: Vec<u8>,
}

impl<'a> Base64<'a> {
    fn new(runs: Vec<&'a [u8]>) -> Base64<'a> {
        Base64 { runs, run: 0, pos: 0, pending: Vec::new() }
    }

    /// At most the bytes the text left decodes to.
    fn most(&self) -> usize {
        let chars: usize = self.runs.iter().skip(self.run).map(|r| r.len()).sum::<usize>()
            - self.pos.min(self.runs.get(self.run).map_or(0, |r| r.len()));
        chars / 4 * 3 + self.pending.len()
    }

    /// The next non-whitespace character; `None` at the end of the text or
    /// at a `<` (the end of the base64 run in AppendedData).
    fn next_char(&mut self) -> Option<u8> {
        while let Some(run) = self.runs.get(self.run) {
            match run.get(self.pos) {
                Some(c) if c.is_ascii_whitespace() => self.pos += 1,
                Some(b'<') => return None,
                Some(&c) => {
                    self.pos += 1;
                    return Some(c);
                }
                None => {
                    self.run += 1;
                    self.pos = 0;
                }
            }
        }
        None
    }

    /// The position for messages: the character count read so far.
    fn position(&self) -> usize {
        self.runs.iter().take(self.run).map(|r| r.len()).sum::<usize>() + self.pos
    }

    /// Fills `out`; `Err(None)` when the text ends first, `Err(Some(message))` when it is not base64.
    fn decode_into(&mut self, out: &mut [u8]) -> Result<(), Option<String>> {
        let k = out.len().min(self.pending.len());
        out[..k].copy_from_slice(&self.pending[..k]);
        self.pending.drain(..k);
        let mut at = k;
        while at < out.len() {
            let (group, len) = self.next_group()?.ok_or(None)?;
            let take = len.min(out.len() - at);
            out[at..at + take].copy_from_slice(&group[..take]);
            self.pending.extend_from_slice(&group[take..len]);
            at += take;
        }
        Ok(())
    }

    /// Decodes the next 4-character group into 1 to 3 bytes; `None` at the end of the text.
    fn next_group(&mut self) -> Result<Option<([u8; 3], usize)>, String> {
        let mut chars = [0u8; 4];
        let mut got = 0;
        while got < 4 {
            match self.next_char() {
                Some(c) => {
                    chars[got] = c;
                    got += 1;
                }
                None => break,
            }
        }
        if got == 0 {
            return Ok(None);
        }
        let pos = self.position();
        if got < 4 {
            return Err(format!("the base64 data end in an incomplete group near byte {pos}; the file is truncated"));
        }
        let value = |c: u8| -> Result<u32, String> {
            Ok(match c {
                b'A'..=b'Z' => c - b'A',
                b'a'..=b'z' => c - b'a' + 26,
                b'0'..=b'9' => c - b'0' + 52,
                b'+' => 62,
                b'/' => 63,
                _ => {
                    return Err(format!(
                        "bad base64 character {:?} near byte {pos}; the file is corrupt",
                        char::from(c)
                    ))
                }
            } as u32)
        };
        let len = match chars {
            [_, _, b'=', b'='] => 1,
            [_, _, _, b'='] => 2,
            _ => 3,
        };
        let mut bits = 0u32;
        for (i, &c) in chars.iter().enumerate() {
            bits = bits << 6 | if i > len { 0 } else { value(c)? };
        }
        let b = bits.to_be_bytes();
        Ok(Some(([b[1], b[2], b[3]], len)))
    }
}

/// The value types of the Hybrid Octree, by their VTK XML names.
/// The scalar type of a VTK XML `type` name.
fn value_type(type_name: &str, name: &str) -> Result<ScalarType, String> {
    Ok(match type_name {
        "Int8" | "Char" => ScalarType::I8,
        "UInt8" | "UChar" => ScalarType::U8,
        "Int16" => ScalarType::I16,
        "UInt16" => ScalarType::U16,
        "Int32" => ScalarType::I32,
        "UInt32" => ScalarType::U32,
        "Float32" => ScalarType::F32,
        "Float64" => ScalarType::F64,
        "Int64" | "UInt64" => {
            return Err(format!(
                "the point array '{name}' holds {type_name} values, which the Hybrid Octree does not take; \
                 convert them to float, double or a 32-bit integer type (ParaView: Calculator with result type)"
            ))
        }
        other => return Err(format!("the point array '{name}' has the unsupported type '{}'", excerpt(other))),
    })
}

/// `count` whitespace-separated numbers of type `ty`, in the text `runs`.
fn parse_ascii(runs: &[&[u8]], ty: ScalarType, count: usize, name: &str) -> Result<SampleBuf, String> {
    fn parse<T: std::str::FromStr>(runs: &[&[u8]], count: usize, name: &str) -> Result<Vec<T>, String> {
        let text = runs
            .iter()
            .map(|r| std::str::from_utf8(r))
            .collect::<Result<Vec<&str>, _>>()
            .map_err(|_| format!("the ascii array '{name}' holds bytes that are not text; the file is corrupt"))?;
        let mut words = text.iter().flat_map(|t| t.split_ascii_whitespace());
        let mut values = Vec::with_capacity(count);
        for s in words.by_ref().take(count) {
            let value = s.parse().map_err(|_| {
                format!("the ascii array '{name}' holds '{}', which is not a number of its type", excerpt(s))
            })?;
            values.push(value);
        }
        let more = words.count();
        if values.len() != count || more > 0 {
            return Err(format!(
                "the ascii array '{name}' holds {} values but the extent and components need {count}; \
                 the file is truncated or corrupt",
                values.len() + more
            ));
        }
        Ok(values)
    }
    Ok(match ty {
        ScalarType::I8 => SampleBuf::I8(parse(runs, count, name)?),
        ScalarType::U8 => SampleBuf::U8(parse(runs, count, name)?),
        ScalarType::I16 => SampleBuf::I16(parse(runs, count, name)?),
        ScalarType::U16 => SampleBuf::U16(parse(runs, count, name)?),
        ScalarType::I32 => SampleBuf::I32(parse(runs, count, name)?),
        ScalarType::U32 => SampleBuf::U32(parse(runs, count, name)?),
        ScalarType::F32 => SampleBuf::F32(parse(runs, count, name)?),
        ScalarType::F64 => SampleBuf::F64(parse(runs, count, name)?),
    })
}
