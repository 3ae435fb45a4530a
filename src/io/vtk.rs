//! Legacy VTK `.vtk` STRUCTURED_POINTS, ASCII or BINARY (big-endian), read by
//! its own parser so that every count is checked before anything is
//! allocated.
//!
//! ```text
//! # vtk DataFile Version 3.0
//! title
//! ASCII | BINARY
//! DATASET STRUCTURED_POINTS
//! DIMENSIONS nx ny nz          (these three in any order; ORIGIN defaults
//! ORIGIN x y z                  to 0, SPACING (or ASPECT_RATIO) to 1)
//! SPACING sx sy sz
//! POINT_DATA n                 (n = nx ny nz)
//! SCALARS name type [ncomp]
//! LOOKUP_TABLE default         (optional)
//! values ...
//! ```
//!
//! The volume takes the first `SCALARS` of the point data or, without one,
//! the first other point attribute (`VECTORS`, `NORMALS`, `TENSORS`,
//! `TEXTURE_COORDINATES`, `COLOR_SCALARS`), with its name and component
//! count; `FIELD` arrays, lookup tables, `CELL_DATA` and `METADATA` are
//! skipped. ASCII floats may be `nan`, `inf`, `-inf` in any case: the reader
//! passes them on as values.

use super::read::format_error;
use super::vtk_tokens::Cursor;
use crate::error::Result;
use crate::grid::{GridShape, ScalarType};
use crate::limits::{check_memory, excerpt, excerpt_bytes};
use crate::volume::{SampleBuf, Volume};

type Parse<T> = std::result::Result<T, String>;

/// One point or cell attribute: where its values start and how many.
#[derive(Debug, Clone)]
struct Array {
    name: String,
    scalars: bool,
    type_name: String,
    /// Values per tuple.
    components: usize,
    /// Byte offset of the first value.
    start: usize,
}

/// Reads the legacy `.vtk` file `bytes` (`label` names it in errors).
pub fn read_vtk_bytes(label: &str, bytes: &[u8]) -> Result<Volume> {
    let (shape, binary, array) = parse(bytes).map_err(|m| format_error(label, m))?;
    let count = shape
        .point_count()
        .checked_mul(array.components)
        .ok_or("too many values")
        .map_err(|m| format_error(label, m.to_string()))?;
    let ty = scalar_type(&array)?.ok_or_else(|| {
        format_error(
            label,
            format!(
                "the point array '{}' holds {} values, which the Hybrid Octree does not take; convert them to \
                 float, double or a 32-bit integer type",
                excerpt(&array.name),
                excerpt(&array.type_name)
            ),
        )
    })?;
    let [x, y, z] = shape.dims;
    check_memory(
        count as u128 * ty.size() as u128,
        &format!("the {x}x{y}x{z} {} volume of '{label}'", ty.name()),
        "crop or subsample the volume, or free memory",
    )?;
    let mut cursor = Cursor::new(bytes);
    cursor.take(array.start);
    let samples = if binary { read_binary(&mut cursor, ty, count) } else { read_ascii(&mut cursor, ty, count) }
        .map_err(|m| format_error(label, format!("the point array '{}': {m}", excerpt(&array.name))))?;
    Ok(Volume { samples, shape, components: array.components, name: array.name })
}

/// The geometry, the encoding (true: BINARY) and the chosen point array.
fn parse(bytes: &[u8]) -> Parse<(GridShape, bool, Array)> {
    let mut c = Cursor::new(bytes);
    let version = c.line().unwrap_or_default();
    if !version.to_ascii_lowercase().starts_with(b"# vtk datafile") {
        return Err(format!(
            "this is not a legacy VTK file: it starts with '{}', not '# vtk DataFile Version'",
            excerpt_bytes(version)
        ));
    }
    c.line().ok_or("the file ends after its first line; it is truncated")?;
    let binary = match upper(c.word()).as_str() {
        "ASCII" => false,
        "BINARY" => true,
        other => {
            return Err(format!("the file type is '{}', not ASCII or BINARY; the file is corrupt", excerpt(other)))
        }
    };
    if upper(c.word()) != "DATASET" {
        return Err("the file has no DATASET line; it is truncated or corrupt".into());
    }
    let dataset = upper(c.word());
    if dataset != "STRUCTURED_POINTS" {
        return Err(format!(
            "the file holds a {} data set, not image data (STRUCTURED_POINTS); resample it to an image first \
             (ParaView: Resample To Image)",
            excerpt(&dataset)
        ));
    }
    let shape = geometry(&mut c, binary)?;
    let points = shape.check(1).map_err(|e| e.to_string())?;
    let cells: usize = shape.dims.iter().map(|&d| d.saturating_sub(1).max(1)).product();
    let (mut chosen, mut cell_arrays, mut section) = (None::<Array>, 0, None::<(bool, usize)>);
    while let Some(word) = c.word() {
        let keyword = upper(Some(word));
        match keyword.as_str() {
            "POINT_DATA" | "CELL_DATA" => {
                let point = keyword == "POINT_DATA";
                let n = number::<usize>(&mut c, &keyword)?;
                let expected = if point { points } else { cells };
                if n != expected {
                    return Err(format!(
                        "{keyword} {n} does not match the {expected} {} of DIMENSIONS {:?}; the file is corrupt",
                        if point { "points" } else { "cells" },
                        shape.dims
                    ));
                }
                section = Some((point, n));
            }
            "METADATA" => skip_metadata(&mut c),
            _ => {
                let (point, n) = section.ok_or_else(|| {
                    format!("unexpected '{}' before POINT_DATA; the file is corrupt", excerpt(&keyword))
                })?;
                let Some(array) = attribute(&mut c, &keyword, n, binary)? else { continue };
                if !point {
                    cell_arrays += 1;
                } else if chosen.as_ref().is_none_or(|a| !a.scalars && array.scalars) {
                    chosen = Some(array);
                }
            }
        }
    }
    let array = chosen.ok_or(if cell_arrays > 0 {
        "the file has only cell data; the Hybrid Octree needs point scalars (ParaView: Cell Data to Point Data)"
    } else {
        "the file has no point data arrays; the Hybrid Octree needs point scalars"
    })?;
    Ok((shape, binary, array))
}

/// DIMENSIONS, ORIGIN, SPACING (any order) and dataset FIELD data, up to
/// the first POINT_DATA or CELL_DATA (left for the caller).
fn geometry(c: &mut Cursor, binary: bool) -> Parse<GridShape> {
    let (mut dims, mut origin, mut spacing) = (None, [0.0; 3], [1.0; 3]);
    loop {
        match upper(c.peek_word()).as_str() {
            "DIMENSIONS" => {
                c.word();
                dims = Some(triple::<usize>(c, "DIMENSIONS")?);
            }
            "ORIGIN" => {
                c.word();
                origin = triple(c, "ORIGIN")?;
            }
            "SPACING" | "ASPECT_RATIO" => {
                c.word();
                spacing = triple(c, "SPACING")?;
            }
            "FIELD" => {
                c.word();
                skip_field(c, binary)?;
            }
            _ => break,
        }
    }
    let dims = dims.ok_or("the STRUCTURED_POINTS data set has no DIMENSIONS; the file is corrupt")?;
    Ok(GridShape { dims, spacing, origin })
}

/// Parses one attribute after its keyword, for `n` tuples, and moves past its
/// values. `Some` for the attributes that can be the volume, `None` for those
/// skipped (FIELD, LOOKUP_TABLE).
fn attribute(c: &mut Cursor, keyword: &str, n: usize, binary: bool) -> Parse<Option<Array>> {
    let name = |c: &mut Cursor| -> Parse<String> {
        c.word().map(|w| String::from_utf8_lossy(w).into_owned()).ok_or_else(|| truncated(keyword))
    };
    let (array_name, type_name, components) = match keyword {
        "SCALARS" => {
            let line = c.line().ok_or_else(|| truncated(keyword))?;
            let mut words = line.split(u8::is_ascii_whitespace).filter(|w| !w.is_empty());
            let array_name = String::from_utf8_lossy(words.next().ok_or_else(|| truncated(keyword))?).into_owned();
            let type_name = String::from_utf8_lossy(words.next().ok_or_else(|| truncated(keyword))?).into_owned();
            let components = match words.next() {
                None => 1,
                Some(w) => parse_number::<usize>(w, "the SCALARS component count")?,
            };
            if upper(c.peek_word()) == "LOOKUP_TABLE" {
                c.word();
                c.word();
                c.end_line();
            }
            (array_name, type_name, components)
        }
        "VECTORS" | "NORMALS" => (name(c)?, name(c)?, 3),
        "TENSORS" => (name(c)?, name(c)?, 9),
        "TENSORS6" => (name(c)?, name(c)?, 6),
        "TEXTURE_COORDINATES" => {
            let array_name = name(c)?;
            let dim = number::<usize>(c, keyword)?;
            (array_name, name(c)?, dim)
        }
        "COLOR_SCALARS" => {
            let array_name = name(c)?;
            let components = number::<usize>(c, keyword)?;
            (array_name, if binary { "unsigned_char" } else { "float" }.to_string(), components)
        }
        "GLOBAL_IDS" | "PEDIGREE_IDS" => {
            let _ = name(c)?;
            let type_name = name(c)?;
            skip_values(c, &type_name, n, binary, keyword)?;
            return Ok(None);
        }
        "LOOKUP_TABLE" => {
            let _ = name(c)?;
            let size = number::<usize>(c, keyword)?;
            let values = size.checked_mul(4).ok_or_else(|| too_many(keyword))?;
            let type_name = if binary { "unsigned_char" } else { "float" };
            skip_values(c, type_name, values, binary, keyword)?;
            return Ok(None);
        }
        "FIELD" => {
            skip_field(c, binary)?;
            return Ok(None);
        }
        other => return Err(format!("unknown attribute '{}'; the file is corrupt", excerpt(other))),
    };
    if components == 0 {
        return Err(format!("the {keyword} '{}' has zero components; the file is corrupt", excerpt(&array_name)));
    }
    if binary && keyword != "SCALARS" {
        c.end_line(); // SCALARS ended its own lines
    }
    let start = c.pos();
    let values = n.checked_mul(components).ok_or_else(|| too_many(keyword))?;
    skip_values(c, &type_name, values, binary, keyword)?;
    Ok(Some(Array { name: array_name, scalars: keyword == "SCALARS", type_name, components, start }))
}

/// Skips `FIELD name count` and its arrays (`name components tuples type`
/// and the values).
fn skip_field(c: &mut Cursor, binary: bool) -> Parse<()> {
    c.word().ok_or_else(|| truncated("FIELD"))?;
    let arrays = number::<usize>(c, "FIELD")?;
    for _ in 0..arrays {
        let array_name = c.word().ok_or_else(|| truncated("FIELD"))?;
        if upper(Some(array_name)) == "NULL_ARRAY" {
            continue;
        }
        let components = number::<usize>(c, "FIELD array")?;
        let tuples = number::<usize>(c, "FIELD array")?;
        let type_name = String::from_utf8_lossy(c.word().ok_or_else(|| truncated("FIELD"))?).into_owned();
        if binary {
            c.end_line();
        }
        let values = components.checked_mul(tuples).ok_or_else(|| too_many("FIELD array"))?;
        skip_values(c, &type_name, values, binary, "FIELD array")?;
    }
    Ok(())
}

/// Moves past `values` values of `type_name`.
fn skip_values(c: &mut Cursor, type_name: &str, values: usize, binary: bool, what: &str) -> Parse<()> {
    let ok = if binary {
        let bytes = match type_name.to_ascii_lowercase().as_str() {
            "bit" => Some(values.div_ceil(8)),
            t => type_size(t).and_then(|s| values.checked_mul(s)),
        };
        let bytes = bytes.ok_or_else(|| {
            format!("the {what} has the unknown or unsupported type '{}'; the file is corrupt", excerpt(type_name))
        })?;
        c.take(bytes).is_some()
    } else {
        c.skip_words(values)
    };
    if ok {
        Ok(())
    } else {
        Err(format!("the file ends inside the values of a {what}; it is truncated"))
    }
}

/// Skips a METADATA block: lines up to the first empty one.
fn skip_metadata(c: &mut Cursor) {
    c.end_line();
    while let Some(line) = c.line() {
        if line.iter().all(u8::is_ascii_whitespace) {
            break;
        }
    }
}

/// Bytes of one binary value of a legacy type name (lowercase).
fn type_size(type_name: &str) -> Option<usize> {
    Some(match type_name {
        "char" | "unsigned_char" | "signed_char" => 1,
        "short" | "unsigned_short" => 2,
        "int" | "unsigned_int" | "float" | "vtkidtype" => 4,
        "long" | "unsigned_long" | "double" | "vtktypeint64" | "vtktypeuint64" => 8,
        _ => return None,
    })
}

/// The scalar type of `array`, `None` when the Hybrid Octree does not take it.
fn scalar_type(array: &Array) -> Result<Option<ScalarType>> {
    Ok(match array.type_name.to_ascii_lowercase().as_str() {
        "unsigned_char" => Some(ScalarType::U8),
        "char" | "signed_char" => Some(ScalarType::I8),
        "unsigned_short" => Some(ScalarType::U16),
        "short" => Some(ScalarType::I16),
        "unsigned_int" => Some(ScalarType::U32),
        "int" => Some(ScalarType::I32),
        "float" => Some(ScalarType::F32),
        "double" => Some(ScalarType::F64),
        _ => None,
    })
}

/// `count` big-endian values of `ty`.
fn read_binary(c: &mut Cursor, ty: ScalarType, count: usize) -> Parse<SampleBuf> {
    let bytes = count.checked_mul(ty.size()).and_then(|n| c.take(n)).ok_or("the file ends inside its values")?;
    Ok(SampleBuf::from_bytes(bytes, ty, true))
}

/// `count` whitespace-separated values of `ty`.
fn read_ascii(c: &mut Cursor, ty: ScalarType, count: usize) -> Parse<SampleBuf> {
    fn values<T: std::str::FromStr>(c: &mut Cursor, count: usize) -> Parse<Vec<T>> {
        let mut out = Vec::with_capacity(count);
        for i in 0..count {
            let word = c.word().ok_or_else(|| format!("the file ends after {i} of its {count} values"))?;
            out.push(parse_number(word, "a value")?);
        }
        Ok(out)
    }
    Ok(match ty {
        ScalarType::U8 => SampleBuf::U8(values(c, count)?),
        ScalarType::I8 => SampleBuf::I8(values(c, count)?),
        ScalarType::U16 => SampleBuf::U16(values(c, count)?),
        ScalarType::I16 => SampleBuf::I16(values(c, count)?),
        ScalarType::U32 => SampleBuf::U32(values(c, count)?),
        ScalarType::I32 => SampleBuf::I32(values(c, count)?),
        ScalarType::F32 => SampleBuf::F32(values(c, count)?),
        ScalarType::F64 => SampleBuf::F64(values(c, count)?),
    })
}

/// A word as a number of type `T` (Rust's syntax: floats take `nan`, `inf`,
/// `infinity` in any case, with a sign).
fn parse_number<T: std::str::FromStr>(word: &[u8], what: &str) -> Parse<T> {
    std::str::from_utf8(word)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("{what} '{}' is not a number of its type; the file is corrupt", excerpt_bytes(word)))
}

/// The next word as a number.
fn number<T: std::str::FromStr>(c: &mut Cursor, what: &str) -> Parse<T> {
    parse_number(c.word().ok_or_else(|| truncated(what))?, &format!("the {what} count"))
}

/// Three numbers after a keyword.
fn triple<T: std::str::FromStr + Copy + Default>(c: &mut Cursor, what: &str) -> Parse<[T; 3]> {
    let mut out = [T::default(); 3];
    for v in &mut out {
        let word = c.word().ok_or_else(|| truncated(what))?;
        *v = parse_number(word, &format!("the {what} value"))?;
    }
    Ok(out)
}

/// A word in upper case, `""` at the end of the file.
fn upper(word: Option<&[u8]>) -> String {
    String::from_utf8_lossy(word.unwrap_or_default()).to_ascii_uppercase()
}

fn truncated(what: &str) -> String {
    format!("the file ends inside its {what} line; it is truncated")
}

fn too_many(what: &str) -> String {
    format!("the {what} declares more values than can be addressed; the file is corrupt")
}
