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

/// Decodes `array` of the file `bytes` (whose header is `header`), which must
/// hold exactly `count` values (points times components).
pub fn decode_array(bytes: &[u8], header: &VtiHeader, array: &ArrayHeader, count: usize) -> Result<SampleBuf, String> {
    let name = &excerpt(&array.name);
    let ty = value_type(&array.type_name, name)?;
    let need = count.checked_mul(ty.size()).ok_or("the array is too large")?;
    check_memory(
        need as u128,
        &format!("the point array '{name}' ({count} {} values)", ty.name()),
        "crop or subsample the volume, or free memory",
    )
    .map_err(|e| e.to_string())?;
    let mut stream = match &array.data {
        ArrayData::Ascii(text) => return parse_ascii(text, ty, count, name),
        ArrayData::Binary(text) => Stream::Base64 { text: text.as_bytes(), pos: 0, pending: Vec::new() },
        ArrayData::Appended(offset) => {
            let (encoding, start) = header.appended.ok_or_else(|| {
                format!(
                    "the array '{}' is appended but the file has no AppendedData section; it is truncated or corrupt",
                    name
                )
            })?;
            let at = usize::try_from(*offset).ok().and_then(|o| o.checked_add(start)).filter(|&at| at <= bytes.len());
            let at = at.ok_or_else(|| {
                format!(
                    "the array '{}' starts at appended offset {offset}, past the end of the file; it is truncated or corrupt",
                    name
                )
            })?;
            match encoding {
                AppendedEncoding::Raw => Stream::Raw { bytes, pos: at },
                AppendedEncoding::Base64 => Stream::Base64 { text: bytes, pos: at, pending: Vec::new() },
            }
        }
    };
    let words = Words { u64: header.header_u64, order: header.byte_order };
    let data = match header.compressor {
        None => {
            let nbytes = words.read(&mut stream, 1, name)?[0];
            if nbytes != need as u64 {
                return Err(size_mismatch(name, nbytes, need, count));
            }
            stream.take(need, name)?
        }
        Some(compressor) => read_compressed(&mut stream, words, compressor, need, count, name)?,
    };
    Ok(SampleBuf::from_bytes(&data, ty, header.byte_order == ByteOrder::Big))
}

fn size_mismatch(name: &str, found: u64, need: usize, count: usize) -> String {
    format!(
        "the array '{name}' holds {found} bytes but the extent and components need {need} ({count} values); \
         the file is truncated or corrupt"
    )
}

fn read_compressed(
    stream: &mut Stream,
    words: Words,
    compressor: Compressor,
    need: usize,
    count: usize,
    name: &str,
) -> Result<Vec<u8>, String> {
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
    let mut out = Vec::with_capacity(need);
    for (i, &csize) in sizes.iter().enumerate() {
        let size = if i + 1 == sizes.len() && last_size != 0 { last_size } else { block_size } as usize;
        let csize = usize::try_from(csize).map_err(|_| format!("block {i} of the array '{name}' is too large"))?;
        let block = stream.take(csize, name)?;
        let before = out.len();
        let corrupt = |e: &dyn std::fmt::Display| {
            format!("block {i} of the array '{name}' does not decompress ({compressor:?}: {e}); the file is corrupt")
        };
        match compressor {
            Compressor::ZLib => flate2::read::ZlibDecoder::new(&block[..])
                .take(size as u64 + 1)
                .read_to_end(&mut out)
                .map(drop)
                .map_err(|e| corrupt(&e))?,
            Compressor::Lzma => xz2::read::XzDecoder::new(&block[..])
                .take(size as u64 + 1)
                .read_to_end(&mut out)
                .map(drop)
                .map_err(|e| corrupt(&e))?,
            Compressor::Lz4 => {
                // LZ4 expands at most ~255:1; refuse absurd sizes before allocating.
                if size > csize.saturating_mul(255).saturating_add(64) {
                    return Err(corrupt(&format!("{csize} bytes cannot inflate to {size}")));
                }
                out.resize(before + size, 0);
                let n = lz4_flex::block::decompress_into(&block, &mut out[before..]).map_err(|e| corrupt(&e))?;
                out.truncate(before + n);
            }
        }
        let inflated = out.len() - before;
        if inflated > size {
            return Err(corrupt(&format!("it inflates to more than the {size} bytes its header declares")));
        }
        if inflated < size {
            return Err(corrupt(&format!("it inflates to {inflated} bytes, not the {size} its header declares")));
        }
    }
    Ok(out)
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

/// A cursor over binary data: raw bytes or base64 text.
enum Stream<'a> {
    Raw {
        bytes: &'a [u8],
        pos: usize,
    },
    /// `pending`: decoded bytes of the last group not yet taken.
    Base64 {
        text: &'a [u8],
        pos: usize,
        pending: Vec<u8>,
    },
}

impl Stream<'_> {
    /// The next `n` bytes, or an error if fewer are left.
    fn take(&mut self, n: usize, name: &str) -> Result<Vec<u8>, String> {
        let short = |have: usize| {
            format!(
                "the data of the array '{name}' end early: {n} bytes needed, at most {have} left; \
                 the file is truncated or corrupt"
            )
        };
        match self {
            Stream::Raw { bytes, pos } => {
                let left = bytes.len().saturating_sub(*pos);
                let chunk = bytes.get(*pos..).and_then(|rest| rest.get(..n)).ok_or_else(|| short(left))?;
                *pos += n;
                Ok(chunk.to_vec())
            }
            Stream::Base64 { text, pos, pending } => {
                let most = text.len().saturating_sub(*pos) / 4 * 3 + pending.len();
                if n > most {
                    return Err(short(most));
                }
                let mut out = Vec::with_capacity(n);
                let k = n.min(pending.len());
                out.extend(pending.drain(..k));
                while out.len() < n {
                    let group = next_group(text, pos).map_err(|e| format!("the array '{name}': {e}"))?;
                    let group = group.ok_or_else(|| short(out.len()))?;
                    let rest = n - out.len();
                    out.extend_from_slice(&group[..rest.min(group.len())]);
                    pending.extend_from_slice(&group[rest.min(group.len())..]);
                }
                Ok(out)
            }
        }
    }
}

/// Decodes the next 4-character base64 group at `pos` (skipping whitespace)
/// into 1 to 3 bytes; `None` at the end of the base64 text.
fn next_group(text: &[u8], pos: &mut usize) -> Result<Option<Vec<u8>>, String> {
    let mut chars = [0u8; 4];
    let mut got = 0;
    while got < 4 {
        match text.get(*pos) {
            Some(c) if c.is_ascii_whitespace() => *pos += 1,
            // The end of the text, or of the base64 run in AppendedData.
            None | Some(b'<') => break,
            Some(&c) => {
                chars[got] = c;
                got += 1;
                *pos += 1;
            }
        }
    }
    if got == 0 {
        return Ok(None);
    }
    if got < 4 {
        return Err(format!("the base64 data end in an incomplete group near byte {}; the file is truncated", *pos));
    }
    let value = |c: u8| -> Result<u32, String> {
        Ok(match c {
            b'A'..=b'Z' => c - b'A',
            b'a'..=b'z' => c - b'a' + 26,
            b'0'..=b'9' => c - b'0' + 52,
            b'+' => 62,
            b'/' => 63,
            _ => {
                return Err(format!("bad base64 character {:?} near byte {}; the file is corrupt", char::from(c), *pos))
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
    Ok(Some(bits.to_be_bytes()[1..=len].to_vec()))
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

/// `count` whitespace-separated numbers of type `ty`.
fn parse_ascii(text: &str, ty: ScalarType, count: usize, name: &str) -> Result<SampleBuf, String> {
    fn parse<T: std::str::FromStr>(text: &str, count: usize, name: &str) -> Result<Vec<T>, String> {
        let mut words = text.split_ascii_whitespace();
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
        ScalarType::I8 => SampleBuf::I8(parse(text, count, name)?),
        ScalarType::U8 => SampleBuf::U8(parse(text, count, name)?),
        ScalarType::I16 => SampleBuf::I16(parse(text, count, name)?),
        ScalarType::U16 => SampleBuf::U16(parse(text, count, name)?),
        ScalarType::I32 => SampleBuf::I32(parse(text, count, name)?),
        ScalarType::U32 => SampleBuf::U32(parse(text, count, name)?),
        ScalarType::F32 => SampleBuf::F32(parse(text, count, name)?),
        ScalarType::F64 => SampleBuf::F64(parse(text, count, name)?),
    })
}
