//! A cursor over the bytes of a mesh file: the ASCII records of a text file (one per line), or
//! the little-endian values of a binary one. Every error names the file and the line.

use std::fmt::Display;

use contopt_core::{Error, Result};

/// How a section's numbers are written (`$MeshFormat`'s file-type).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Encoding {
    /// Text: numbers separated by spaces, one record a line.
    Ascii,
    /// Binary: `int` 4 bytes, `size_t` and `double` 8 bytes, little-endian.
    Binary,
}

/// Bytes of a binary `int`.
const INT_BYTES: usize = 4;
/// Bytes of a binary `size_t` (the data-size of `$MeshFormat`, the only one read) and of a
/// `double`.
pub(crate) const SIZE_BYTES: usize = 8;
/// The fewest bytes an ASCII number takes: one digit and its separator.
const ASCII_NUMBER_BYTES: usize = 2;
/// Characters of a token quoted in an error, at most.
const QUOTED_CHARS: usize = 40;

/// The fewest bytes that `numbers` ASCII numbers (or `ints`, `sizes` and `doubles` binary
/// values) take: what a count of such records is checked against before it is allocated.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RecordBytes {
    /// Bytes in a text file.
    pub ascii: usize,
    /// Bytes in a binary file.
    pub binary: usize,
}

impl RecordBytes {
    /// A record of `ints` ints, `sizes` size_t and `doubles` doubles.
    pub const fn of(ints: usize, sizes: usize, doubles: usize) -> Self {
        Self {
            ascii: (ints + sizes + doubles) * ASCII_NUMBER_BYTES,
            binary: ints * INT_BYTES + (sizes + doubles) * SIZE_BYTES,
        }
    }
}

/// A position in a mesh file's bytes.
pub(crate) struct Cursor<'a> {
    source: &'a str,
    bytes: &'a [u8],
    pos: usize,
    encoding: Encoding,
}

impl<'a> Cursor<'a> {
    /// A cursor at the start of `bytes`, the file `source` (named in errors), reading text.
    pub fn new(source: &'a str, bytes: &'a [u8]) -> Self {
        Self {
            source,
            bytes,
            pos: 0,
            encoding: Encoding::Ascii,
        }
    }

    /// How the numbers are read from here on.
    pub fn set_encoding(&mut self, encoding: Encoding) {
        self.encoding = encoding;
    }

    /// The byte offset.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// True at the end of the file.
    pub fn at_end(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    /// `file:line` of byte `pos` (and the byte in a binary section), counted when an error
    /// needs it.
    fn place(&self, pos: usize) -> String {
        let pos = pos.min(self.bytes.len());
        let line = 1 + self.bytes[..pos].iter().filter(|&&b| b == b'\n').count();
        match self.encoding {
            Encoding::Ascii => format!("{}:{line}", self.source),
            Encoding::Binary => format!("{}:{line} (byte {pos})", self.source),
        }
    }

    /// An error at byte `pos`.
    pub fn error_at(&self, pos: usize, message: impl Display) -> Error {
        Error::Mesh(format!("{}: {message}", self.place(pos)))
    }

    /// "expected `expected`, found `found`" at byte `pos`.
    pub fn expected_at(&self, pos: usize, expected: impl Display, found: &[u8]) -> Error {
        self.error_at(pos, format!("expected {expected}, found {}", quote(found)))
    }

    /// Skips spaces, tabs and line ends.
    pub fn skip_blank(&mut self) {
        while self.pos < self.bytes.len() && self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    /// Skips spaces and tabs (and the carriage return of a CRLF line end).
    fn skip_spaces(&mut self) {
        while self.pos < self.bytes.len() && matches!(self.bytes[self.pos], b' ' | b'\t' | b'\r') {
            self.pos += 1;
        }
    }

    /// The rest of the current line (without its line end) and its start; the cursor moves to
    /// the next line.
    pub fn line(&mut self) -> (usize, &'a [u8]) {
        let start = self.pos;
        let end = self.bytes[start..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(self.bytes.len(), |k| start + k);
        self.pos = (end + 1).min(self.bytes.len());
        let mut text = &self.bytes[start..end];
        while let [rest @ .., b'\r' | b' ' | b'\t'] = text {
            text = rest;
        }
        (start, text)
    }

    /// Moves past the first line that starts with `marker` (a section's end) at or after the
    /// cursor; false when there is none.
    pub fn skip_past_line(&mut self, marker: &[u8]) -> bool {
        let mut at = self.pos;
        while at < self.bytes.len() {
            if self.bytes[at..].starts_with(marker) && (at == 0 || self.bytes[at - 1] == b'\n') {
                self.pos = at;
                self.line();
                return true;
            }
            at += 1;
        }
        false
    }

    /// Starts a record: in text, its first number may follow blank lines.
    pub fn begin_record(&mut self) {
        if self.encoding == Encoding::Ascii {
            self.skip_blank();
        }
    }

    /// Ends a record: in text nothing but spaces may follow on its line.
    pub fn end_record(&mut self, what: impl Display) -> Result<()> {
        if self.encoding == Encoding::Binary {
            return Ok(());
        }
        self.skip_spaces();
        match self.bytes.get(self.pos) {
            None => Ok(()),
            Some(b'\n') => {
                self.pos += 1;
                Ok(())
            }
            Some(_) => {
                let pos = self.pos;
                let token = self.token();
                Err(self.expected_at(pos, format!("the end of the line after {what}"), token))
            }
        }
    }

    /// The next run of non-blank bytes (empty at a line end or the file's end).
    fn token(&mut self) -> &'a [u8] {
        let start = self.pos;
        while self.pos < self.bytes.len() && !self.bytes[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        &self.bytes[start..self.pos]
    }

    /// The next number of the current text record and its position.
    fn field(&mut self, what: &dyn Display) -> Result<(usize, &'a [u8])> {
        self.skip_spaces();
        let pos = self.pos;
        let token = self.token();
        if token.is_empty() {
            let found: &[u8] = if self.at_end() {
                b"the end of the file"
            } else {
                b"the end of the line"
            };
            return Err(self.error_at(
                pos,
                format!("expected {what}, found {}", String::from_utf8_lossy(found)),
            ));
        }
        Ok((pos, token))
    }

    /// The next `n` bytes of a binary section.
    fn take(&mut self, n: usize, what: &dyn Display) -> Result<&'a [u8]> {
        if self.bytes.len() - self.pos < n {
            return Err(self.error_at(
                self.pos,
                format!("expected {what}, found the end of the file"),
            ));
        }
        let bytes = &self.bytes[self.pos..self.pos + n];
        self.pos += n;
        Ok(bytes)
    }

    /// A `size_t`: a count or a tag (a non-negative integer).
    pub fn size(&mut self, what: impl Display) -> Result<u64> {
        match self.encoding {
            Encoding::Ascii => {
                let (pos, token) = self.field(&what)?;
                parse_size(token).ok_or_else(|| {
                    self.expected_at(pos, format!("{what} (an integer >= 0)"), token)
                })
            }
            Encoding::Binary => {
                let bytes = self.take(SIZE_BYTES, &what)?;
                Ok(u64::from_le_bytes(bytes.try_into().expect("8 bytes")))
            }
        }
    }

    /// An `int`.
    pub fn int(&mut self, what: impl Display) -> Result<i32> {
        match self.encoding {
            Encoding::Ascii => {
                let (pos, token) = self.field(&what)?;
                std::str::from_utf8(token)
                    .ok()
                    .and_then(|s| s.parse::<i32>().ok())
                    .ok_or_else(|| self.expected_at(pos, format!("{what} (an integer)"), token))
            }
            Encoding::Binary => {
                let bytes = self.take(INT_BYTES, &what)?;
                Ok(i32::from_le_bytes(bytes.try_into().expect("4 bytes")))
            }
        }
    }

    /// An `int` in `low ..= high`.
    pub fn int_in(&mut self, what: impl Display, low: i32, high: i32) -> Result<i32> {
        let pos = self.pos;
        let value = self.int(&what)?;
        if (low..=high).contains(&value) {
            Ok(value)
        } else {
            Err(self.error_at(
                pos,
                format!("expected {what} in {low} ..= {high}, found {value}"),
            ))
        }
    }

    /// A finite `double`.
    pub fn float(&mut self, what: impl Display) -> Result<f64> {
        let expected = |what| format!("{what} (a finite number)");
        match self.encoding {
            Encoding::Ascii => {
                let (pos, token) = self.field(&what)?;
                match std::str::from_utf8(token).map(str::parse::<f64>) {
                    Ok(Ok(v)) if v.is_finite() => Ok(v),
                    _ => Err(self.expected_at(pos, expected(&what), token)),
                }
            }
            Encoding::Binary => {
                let pos = self.pos;
                let bytes = self.take(SIZE_BYTES, &what)?;
                let v = f64::from_le_bytes(bytes.try_into().expect("8 bytes"));
                if v.is_finite() {
                    Ok(v)
                } else {
                    Err(self.expected_at(pos, expected(&what), v.to_string().as_bytes()))
                }
            }
        }
    }

    /// A string in double quotes on the current line (a physical name), without its quotes.
    pub fn quoted(&mut self, what: impl Display) -> Result<String> {
        self.skip_spaces();
        let pos = self.pos;
        let rest = &self.bytes[pos..];
        let line = &rest[..rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len())];
        match line {
            [b'"', inner @ ..] => match inner.iter().position(|&b| b == b'"') {
                Some(end) => {
                    self.pos += end + 2;
                    Ok(String::from_utf8_lossy(&inner[..end]).into_owned())
                }
                None => Err(self.expected_at(pos, format!("{what} (no closing quote)"), line)),
            },
            _ => Err(self.expected_at(pos, what, line)),
        }
    }

    /// A count of records of at least `each` bytes, refused before anything is allocated when
    /// the rest of the file could not hold them.
    pub fn count(&mut self, what: impl Display, each: RecordBytes) -> Result<usize> {
        let pos = self.pos;
        let value = self.size(&what)?;
        let each = match self.encoding {
            Encoding::Ascii => each.ascii,
            Encoding::Binary => each.binary,
        }
        .max(1);
        let room = (self.bytes.len() - self.pos) / each;
        if value > room as u64 {
            return Err(self.error_at(
                pos,
                format!(
                    "{what} is {value}, more than the rest of the file could hold \
                     ({} bytes, at least {each} each): the file is truncated or corrupt",
                    self.bytes.len() - self.pos
                ),
            ));
        }
        Ok(value as usize)
    }

    /// A line holding exactly `expected` (a section's end).
    pub fn expect_line(&mut self, expected: &str) -> Result<()> {
        self.skip_blank();
        let (pos, text) = self.line();
        if text == expected.as_bytes() {
            Ok(())
        } else {
            Err(self.expected_at(pos, format!("`{expected}`"), text))
        }
    }
}

/// A non-negative decimal integer, `None` when it is not one or overflows 64 bits.
fn parse_size(token: &[u8]) -> Option<u64> {
    if token.is_empty() {
        return None;
    }
    token.iter().try_fold(0u64, |acc, &b| {
        let digit = b.checked_sub(b'0').filter(|d| *d < 10)?;
        acc.checked_mul(10)?.checked_add(u64::from(digit))
    })
}

/// A token as quoted in an error: in backticks, at most [`QUOTED_CHARS`] characters.
fn quote(found: &[u8]) -> String {
    if found.is_empty() {
        return "nothing".to_string();
    }
    let text = String::from_utf8_lossy(found);
    let short: String = text.chars().take(QUOTED_CHARS).collect();
    if short.len() < text.len() {
        format!("`{short}…`")
    } else {
        format!("`{short}`")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Sizes are decimal digits only, and refuse what overflows 64 bits.
    #[test]
    fn sizes() {
        assert_eq!(parse_size(b"0"), Some(0));
        assert_eq!(parse_size(b"18446744073709551615"), Some(u64::MAX));
        assert_eq!(parse_size(b"18446744073709551616"), None);
        assert_eq!(parse_size(b"-1"), None);
        assert_eq!(parse_size(b"1e3"), None);
        assert_eq!(parse_size(b""), None);
    }

    /// A record's fields stay on its line; the line end after the last one is checked; errors
    /// name the line.
    #[test]
    fn records_and_places() {
        let text = b"1 2\n3\n\n4 5 6\n";
        let mut c = Cursor::new("t.msh", text);
        c.begin_record();
        assert_eq!(c.size("a").unwrap(), 1);
        assert_eq!(c.size("b").unwrap(), 2);
        c.end_record("b").unwrap();
        c.begin_record();
        assert_eq!(c.size("c").unwrap(), 3);
        let e = c.size("d").unwrap_err().to_string();
        assert_eq!(e, "mesh: t.msh:2: expected d, found the end of the line");
        c.end_record("c").unwrap();
        c.begin_record();
        c.size("e").unwrap();
        let e = c.end_record("e").unwrap_err().to_string();
        assert_eq!(
            e,
            "mesh: t.msh:4: expected the end of the line after e, found `5`"
        );
    }

    /// A count larger than the rest of the file could hold is refused, by its number.
    #[test]
    fn counts_are_bounded_by_the_file() {
        let mut c = Cursor::new("t.msh", b"1000000000000 1 2 3\n");
        let e = c.count("the number of nodes", RecordBytes::of(0, 1, 3));
        let e = e.unwrap_err().to_string();
        assert!(
            e.contains("t.msh:1: the number of nodes is 1000000000000, more than the rest"),
            "{e}"
        );
    }
}
