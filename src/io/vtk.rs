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

use super::format_error;
use super::vtk_attributes::{attribute, skip_field, skip_metadata, Array};
use super::vtk_tokens::{number, parse_number, triple, upper, Cursor, Parse};
use crate::base::error::Result;
use crate::base::limits::{check_memory, excerpt, excerpt_bytes};
use crate::data::grid::{GridShape, ScalarType};
use crate::data::volume::{SampleBuf, Volume};

/// Reads the legacy `.vtk` file `bytes` (`label` names it in errors).
pub fn read_vtk_bytes(label: &str, bytes: &[u8]) -> Result<Volume> {
    let (shape, binary, array) = parse(bytes).map_err(|m| format_error(label, m))?;
    let count = shape
        .point_count()
        .checked_mul(array.components)
        .ok_or("too many values")
        .map_err(|m| format_error(label, m.to_string()))?;
    let ty = scalar_type(&array).ok_or_else(|| {
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

/// The scalar type of `array`, `None` when the Hybrid Octree does not take it.
fn scalar_type(array: &Array) -> Option<ScalarType> {
    match array.type_name.to_ascii_lowercase().as_str() {
        "unsigned_char" => Some(ScalarType::U8),
        "char" | "signed_char" => Some(ScalarType::I8),
        "unsigned_short" => Some(ScalarType::U16),
        "short" => Some(ScalarType::I16),
        "unsigned_int" => Some(ScalarType::U32),
        "int" => Some(ScalarType::I32),
        "float" => Some(ScalarType::F32),
        "double" => Some(ScalarType::F64),
        _ => None,
    }
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
