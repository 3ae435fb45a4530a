//! The attributes of a legacy VTK file's POINT_DATA and CELL_DATA: each
//! parsed far enough to know where its values are and to move past them,
//! with every count checked against the bytes that are there.

use super::vtk_tokens::{number, parse_number, too_many, truncated, upper, Cursor, Parse};
use crate::base::limits::excerpt;

/// One point or cell attribute: where its values start and how many.
#[derive(Debug, Clone)]
pub struct Array {
    /// The attribute's name.
    pub name: String,
    /// True for `SCALARS`, which the volume prefers.
    pub scalars: bool,
    /// The legacy type name (`float`, `unsigned_short`, ...).
    pub type_name: String,
    /// Values per tuple.
    pub components: usize,
    /// Byte offset of the first value.
    pub start: usize,
}

/// Parses one attribute after its keyword, for `n` tuples, and moves past its
/// values. `Some` for the attributes that can be the volume, `None` for those
/// skipped (FIELD, LOOKUP_TABLE).
pub fn attribute(c: &mut Cursor, keyword: &str, n: usize, binary: bool) -> Parse<Option<Array>> {
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
pub fn skip_field(c: &mut Cursor, binary: bool) -> Parse<()> {
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
pub fn skip_metadata(c: &mut Cursor) {
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
