//! A cursor over a legacy VTK file: whitespace-separated words for the
//! keywords and ASCII data, raw byte runs for BINARY data; numbers and
//! keywords read from it.

use crate::base::limits::excerpt_bytes;

/// A position in the file's bytes.
#[derive(Debug, Clone)]
pub struct Cursor<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `bytes`.
    pub fn new(bytes: &'a [u8]) -> Cursor<'a> {
        Cursor { bytes, pos: 0 }
    }

    /// The byte offset of the cursor.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// The rest of the current line without its `\r\n` or `\n`; `None` at the end.
    pub fn line(&mut self) -> Option<&'a [u8]> {
        let rest = self.bytes.get(self.pos..).filter(|r| !r.is_empty())?;
        let len = rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len());
        self.pos += (len + 1).min(rest.len());
        let line = &rest[..len];
        Some(line.strip_suffix(b"\r").unwrap_or(line))
    }

    /// The next word (skipping whitespace, newlines included); `None` at the end.
    pub fn word(&mut self) -> Option<&'a [u8]> {
        let rest = self.bytes.get(self.pos..)?;
        let start = rest.iter().position(|b| !b.is_ascii_whitespace())?;
        let len = rest[start..].iter().position(u8::is_ascii_whitespace).unwrap_or(rest.len() - start);
        self.pos += start + len;
        Some(&rest[start..start + len])
    }

    /// The next word without moving.
    pub fn peek_word(&self) -> Option<&'a [u8]> {
        self.clone().word()
    }

    /// Moves past the end of the current line (where BINARY data start).
    pub fn end_line(&mut self) {
        let rest = self.bytes.get(self.pos..).unwrap_or_default();
        self.pos += rest.iter().position(|&b| b == b'\n').map_or(rest.len(), |n| n + 1);
    }

    /// The next `n` bytes, or `None` when fewer are left (the cursor stays).
    pub fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let chunk = self.bytes.get(self.pos..)?.get(..n)?;
        self.pos += n;
        Some(chunk)
    }

    /// Skips `n` words; false when the file ends first.
    pub fn skip_words(&mut self, n: usize) -> bool {
        (0..n).all(|_| self.word().is_some())
    }
}

/// A parse result whose error is a message for [`crate::Error::Format`].
pub type Parse<T> = std::result::Result<T, String>;

/// A word as a number of type `T` (Rust's syntax: floats take `nan`, `inf`,
/// `infinity` in any case, with a sign).
pub fn parse_number<T: std::str::FromStr>(word: &[u8], what: &str) -> Parse<T> {
    std::str::from_utf8(word)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("{what} '{}' is not a number of its type; the file is corrupt", excerpt_bytes(word)))
}

/// The next word as a number.
pub fn number<T: std::str::FromStr>(c: &mut Cursor, what: &str) -> Parse<T> {
    parse_number(c.word().ok_or_else(|| truncated(what))?, &format!("the {what} count"))
}

/// Three numbers after a keyword.
pub fn triple<T: std::str::FromStr + Copy + Default>(c: &mut Cursor, what: &str) -> Parse<[T; 3]> {
    let mut out = [T::default(); 3];
    for v in &mut out {
        let word = c.word().ok_or_else(|| truncated(what))?;
        *v = parse_number(word, &format!("the {what} value"))?;
    }
    Ok(out)
}

/// A word in upper case, `""` at the end of the file.
pub fn upper(word: Option<&[u8]>) -> String {
    String::from_utf8_lossy(word.unwrap_or_default()).to_ascii_uppercase()
}

/// The message for a file that ends inside a `what` line.
pub fn truncated(what: &str) -> String {
    format!("the file ends inside its {what} line; it is truncated")
}

/// The message for a `what` whose value count overflows.
pub fn too_many(what: &str) -> String {
    format!("the {what} declares more values than can be addressed; the file is corrupt")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_lines_and_bytes() {
        let mut c = Cursor::new(b"# vtk\r\nASCII  x\n\nDIMENSIONS 2 3\n\x01\x02");
        assert_eq!(c.line(), Some(&b"# vtk"[..]));
        assert_eq!(c.word(), Some(&b"ASCII"[..]));
        assert_eq!(c.peek_word(), Some(&b"x"[..]));
        assert_eq!(c.word(), Some(&b"x"[..]));
        assert_eq!(c.word(), Some(&b"DIMENSIONS"[..]));
        assert!(c.skip_words(2));
        c.end_line();
        assert_eq!(c.take(3), None);
        assert_eq!(c.take(2), Some(&[1u8, 2][..]));
        assert_eq!(c.word(), None);
        assert_eq!(c.line(), None);
    }
}
