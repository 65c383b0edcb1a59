//! JSON documents (RFC 8259) read into a [`Node`] tree with the span of every value and key.

use std::collections::HashMap;
use std::ops::Range;

use crate::node::{Key, Node, Value};
use crate::path::Path;
use crate::{line_column, InputError, Limits};

/// Reads a JSON document within `limits`.
pub(crate) fn parse(text: &str, limits: &Limits) -> Result<Node, InputError> {
    limits.check_size(text)?;
    let mut parser = Parser {
        text,
        at: 0,
        limits,
    };
    parser.skip_whitespace();
    let node = parser.value(&Path::Root(""), 0)?;
    parser.skip_whitespace();
    if parser.at < text.len() {
        return Err(parser.unexpected("after the document"));
    }
    Ok(node)
}

/// The first code unit of a UTF-16 surrogate pair, and the range of the second.
const HIGH_SURROGATES: Range<u32> = 0xD800..0xDC00;
const LOW_SURROGATES: Range<u32> = 0xDC00..0xE000;
/// The first code point a surrogate pair encodes.
const SUPPLEMENTARY_START: u32 = 0x1_0000;
/// The bits of a code point that each surrogate carries.
const SURROGATE_BITS: u32 = 10;
/// `\uXXXX` escapes are hexadecimal.
const HEX_RADIX: u32 = 16;

/// A position in a JSON text; it only stops on ASCII bytes, so always at a character boundary.
struct Parser<'t> {
    text: &'t str,
    at: usize,
    limits: &'t Limits,
}

impl Parser<'_> {
    /// The byte at the position.
    fn peek(&self) -> Option<u8> {
        self.text.as_bytes().get(self.at).copied()
    }

    fn skip_whitespace(&mut self) {
        while matches!(self.peek(), Some(b' ' | b'\t' | b'\n' | b'\r')) {
            self.at += 1;
        }
    }

    /// An error at `span`.
    fn error(&self, span: Range<usize>, message: impl Into<String>) -> InputError {
        InputError::new("", Some(span), message)
    }

    /// An error at the character at the position, or at the end: `found … <context>`.
    fn unexpected(&self, context: &str) -> InputError {
        let rest = self.text.get(self.at..).unwrap_or("");
        match rest.chars().next() {
            Some(c) => self.error(
                self.at..self.at + c.len_utf8(),
                format!("unexpected {c:?} {context}"),
            ),
            None => self.error(
                self.at..self.at,
                format!("unexpected end of text {context}"),
            ),
        }
    }

    /// Steps over `byte` (after whitespace), or fails naming what was expected.
    fn expect(&mut self, byte: u8, context: &str) -> Result<(), InputError> {
        self.skip_whitespace();
        if self.peek() == Some(byte) {
            self.at += 1;
            Ok(())
        } else {
            Err(self.unexpected(context))
        }
    }

    /// The value at the position, `depth` tables and arrays below the root.
    fn value(&mut self, path: &Path<'_>, depth: usize) -> Result<Node, InputError> {
        let start = self.at;
        let value = match self.peek() {
            Some(b'{') => self.object(path, depth)?,
            Some(b'[') => self.array(path, depth)?,
            Some(b'"') => Value::String(self.string()?),
            Some(b'-' | b'0'..=b'9') => self.number()?,
            Some(b't') => self.word("true", Value::Bool(true))?,
            Some(b'f') => self.word("false", Value::Bool(false))?,
            Some(b'n') => self.word("null", Value::Null)?,
            _ => return Err(self.unexpected("where a value should be")),
        };
        Ok(Node::spanned(value, start..self.at))
    }

    /// `true`, `false` or `null`.
    fn word(&mut self, word: &str, value: Value) -> Result<Value, InputError> {
        let end = self.at + word.len();
        if self.text.as_bytes().get(self.at..end) == Some(word.as_bytes()) {
            self.at = end;
            Ok(value)
        } else {
            Err(self.unexpected("where a value should be"))
        }
    }

    /// Refuses a table or array at `depth` nested deeper than the limit, before reading it.
    fn enter(&self, path: &Path<'_>, depth: usize) -> Result<(), InputError> {
        if depth > self.limits.depth() {
            Err(self.limits.too_deep(path, self.at..self.at + 1))
        } else {
            Ok(())
        }
    }

    fn array(&mut self, path: &Path<'_>, depth: usize) -> Result<Value, InputError> {
        self.enter(path, depth)?;
        self.at += 1;
        let mut items = Vec::new();
        self.skip_whitespace();
        if self.peek() == Some(b']') {
            self.at += 1;
            return Ok(Value::Array(items));
        }
        loop {
            self.skip_whitespace();
            items.push(self.value(&Path::Index(path, items.len()), depth + 1)?);
            self.skip_whitespace();
            match self.peek() {
                Some(b',') => self.at += 1,
                Some(b']') => break,
                _ => return Err(self.unexpected("in an array: expected `,` or `]`")),
            }
        }
        self.at += 1;
        Ok(Value::Array(items))
    }

    fn object(&mut self, path: &Path<'_>, depth: usize) -> Result<Value, InputError> {
        self.enter(path, depth)?;
        self.at += 1;
        let mut entries = Vec::new();
        let mut seen = HashMap::new();
        self.skip_whitespace();
        if self.peek() == Some(b'}') {
            self.at += 1;
            return Ok(Value::Table(entries));
        }
        loop {
            self.skip_whitespace();
            let key = self.key(path, &mut seen)?;
            self.expect(b':', "after a key: expected `:`")?;
            self.skip_whitespace();
            let value = self.value(&Path::Key(path, key.name()), depth + 1)?;
            entries.push((key, value));
            self.skip_whitespace();
            match self.peek() {
                Some(b',') => self.at += 1,
                Some(b'}') => break,
                _ => return Err(self.unexpected("in an object: expected `,` or `}`")),
            }
        }
        self.at += 1;
        Ok(Value::Table(entries))
    }

    /// A key of an object; `seen` holds the object's keys so far and where each starts.
    fn key(
        &mut self,
        path: &Path<'_>,
        seen: &mut HashMap<String, usize>,
    ) -> Result<Key, InputError> {
        if self.peek() != Some(b'"') {
            return Err(self.unexpected("in an object: expected a key in quotes"));
        }
        let start = self.at;
        let name = self.string()?;
        if let Some(&first) = seen.get(&name) {
            let (line, column) = line_column(self.text, first);
            let path = Path::Key(path, &name).render();
            let message = format!("duplicate key, first at line {line}, column {column}");
            return Err(InputError::new(path, Some(start..self.at), message));
        }
        seen.insert(name.clone(), start);
        Ok(Key::spanned(name, start..self.at))
    }

    /// A string at the position (on its opening quote), escapes resolved.
    fn string(&mut self) -> Result<String, InputError> {
        let start = self.at;
        self.at += 1;
        let mut out = String::new();
        loop {
            let run = self.at;
            while matches!(self.peek(), Some(byte) if byte != b'"' && byte != b'\\' && byte >= b' ')
            {
                self.at += 1;
            }
            out.push_str(self.text.get(run..self.at).unwrap_or(""));
            match self.peek() {
                Some(b'"') => {
                    self.at += 1;
                    return Ok(out);
                }
                Some(b'\\') => out.push(self.escape()?),
                Some(_) => {
                    return Err(self.unexpected("in a string: control characters must be escaped"))
                }
                None => return Err(self.error(start..start + 1, "unterminated string")),
            }
        }
    }

    /// The character an escape at the position (on its backslash) stands for.
    fn escape(&mut self) -> Result<char, InputError> {
        let start = self.at;
        self.at += 1;
        let byte = self.peek();
        self.at += 1;
        let c = match byte {
            Some(b'"') => '"',
            Some(b'\\') => '\\',
            Some(b'/') => '/',
            Some(b'b') => '\u{8}',
            Some(b'f') => '\u{c}',
            Some(b'n') => '\n',
            Some(b'r') => '\r',
            Some(b't') => '\t',
            Some(b'u') => return self.unicode_escape(start),
            _ => {
                self.at = start + 1;
                return Err(self.unexpected("after `\\` in a string"));
            }
        };
        Ok(c)
    }

    /// The character of a `\uXXXX` escape whose backslash is at `start` (the position is after
    /// its `u`); a surrogate must be followed by its pair.
    fn unicode_escape(&mut self, start: usize) -> Result<char, InputError> {
        let first = self.hex4(start)?;
        let code = if HIGH_SURROGATES.contains(&first) {
            let pair = self.text.as_bytes().get(self.at..self.at + 2) == Some(b"\\u");
            let second = if pair {
                self.at += 2;
                self.hex4(start)?
            } else {
                0
            };
            if !LOW_SURROGATES.contains(&second) {
                return Err(self.error(start..self.at, "unpaired UTF-16 surrogate in a string"));
            }
            SUPPLEMENTARY_START
                + ((first - HIGH_SURROGATES.start) << SURROGATE_BITS)
                + (second - LOW_SURROGATES.start)
        } else {
            first
        };
        char::from_u32(code)
            .ok_or_else(|| self.error(start..self.at, "unpaired UTF-16 surrogate in a string"))
    }

    /// Four hex digits at the position, of an escape starting at `start`.
    fn hex4(&mut self, start: usize) -> Result<u32, InputError> {
        let digits = self.text.as_bytes().get(self.at..self.at + 4);
        let digits = digits.filter(|digits| digits.iter().all(u8::is_ascii_hexdigit));
        let Some(digits) = digits else {
            return Err(self.error(start..self.at, "`\\u` needs four hex digits"));
        };
        let code = digits.iter().fold(0, |code, &digit| {
            code * HEX_RADIX + char::from(digit).to_digit(HEX_RADIX).unwrap_or(0)
        });
        self.at += 4;
        Ok(code)
    }

    /// A number at the position: an integer when it has no fraction or exponent and fits an
    /// `i64`, else a float (which may be infinite).
    fn number(&mut self) -> Result<Value, InputError> {
        let start = self.at;
        if self.peek() == Some(b'-') {
            self.at += 1;
        }
        match self.peek() {
            Some(b'0') => self.at += 1,
            Some(b'1'..=b'9') => self.digits(),
            _ => return Err(self.unexpected("in a number: expected a digit")),
        }
        let mut integral = true;
        if self.peek() == Some(b'.') {
            self.at += 1;
            self.required_digits("after the decimal point")?;
            integral = false;
        }
        if matches!(self.peek(), Some(b'e' | b'E')) {
            self.at += 1;
            if matches!(self.peek(), Some(b'+' | b'-')) {
                self.at += 1;
            }
            self.required_digits("in an exponent")?;
            integral = false;
        }
        let literal = self.text.get(start..self.at).unwrap_or("");
        let integer = integral.then(|| literal.parse::<i64>().ok()).flatten();
        match integer {
            Some(integer) => Ok(Value::Integer(integer)),
            None => literal
                .parse::<f64>()
                .map(Value::Float)
                .map_err(|error| self.error(start..self.at, format!("number {literal}: {error}"))),
        }
    }

    fn digits(&mut self) {
        while matches!(self.peek(), Some(b'0'..=b'9')) {
            self.at += 1;
        }
    }

    /// At least one digit.
    fn required_digits(&mut self, context: &str) -> Result<(), InputError> {
        let start = self.at;
        self.digits();
        if self.at == start {
            Err(self.unexpected(&format!("{context}: expected a digit")))
        } else {
            Ok(())
        }
    }
}
