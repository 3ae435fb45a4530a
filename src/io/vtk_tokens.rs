//! A cursor over a legacy VTK file: whitespace-separated words for the
//! keywords and ASCII data, raw byte runs for BINARY data.

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
