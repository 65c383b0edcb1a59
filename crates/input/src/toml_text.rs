//! TOML documents: toml's spanned parse tree turned into a [`Node`] tree.

use std::ops::Range;

use toml::de::{DeFloat, DeInteger, DeTable, DeValue};
use toml::Spanned;

use crate::node::{Key, Node, Value};
use crate::path::Path;
use crate::{InputError, Limits};

/// Reads a TOML document within `limits`.
pub(crate) fn parse(text: &str, limits: &Limits) -> Result<Node, InputError> {
    limits.check_size(text)?;
    check_nesting(text, limits)?;
    let table =
        DeTable::parse(text).map_err(|error| InputError::new("", error.span(), error.message()))?;
    let root = Path::Root("");
    let span = table.span();
    table_node(table.get_ref(), span, &root, 0, limits)
}

/// Refuses brackets nested deeper than `limits.max_depth` before toml's recursive parser sees
/// them: brackets in strings (of the four kinds) and comments do not count, a table header
/// `[a]` counts 1 and an array-of-tables header `[[a]]` counts 2. Dotted keys (`a.b.c = 1`)
/// nest without brackets; the conversion refuses those. The scan looks at ASCII bytes only, so
/// it never splits a character.
fn check_nesting(text: &str, limits: &Limits) -> Result<(), InputError> {
    let bytes = text.as_bytes();
    let (mut at, mut depth, mut string) = (0, 0usize, None);
    while let Some(&byte) = bytes.get(at) {
        let rest = &bytes[at..];
        if let Some(delimiter) = string {
            at += if rest.starts_with(delimiter) {
                string = None;
                closing_len(rest, delimiter)
            } else if byte == b'\\' && delimiter.starts_with(b"\"") {
                ESCAPE_LEN
            } else {
                1
            };
            continue;
        }
        match byte {
            b'"' | b'\'' => {
                let delimiter = STRING_DELIMITERS.iter().find(|d| rest.starts_with(d));
                string = delimiter.copied();
                at += string.map_or(1, <[u8]>::len) - 1;
            }
            b'#' => at += rest.iter().position(|&b| b == b'\n').unwrap_or(rest.len()),
            b'[' | b'{' => {
                depth += 1;
                if depth > limits.depth() {
                    return Err(limits.too_deep(&Path::Root(""), at..at + 1));
                }
            }
            b']' | b'}' => depth = depth.saturating_sub(1),
            _ => {}
        }
        at += 1;
    }
    Ok(())
}

/// TOML's string delimiters, multi-line ones first.
const STRING_DELIMITERS: [&[u8]; 4] = [b"\"\"\"", b"'''", b"\"", b"'"];
/// A backslash and the byte it escapes.
const ESCAPE_LEN: usize = 2;
/// A multi-line string may end in up to two quotes of its own before its delimiter.
const MAX_CLOSING_QUOTES: usize = 5;

/// The length of the closing `delimiter` at the start of `rest`, with the quotes a multi-line
/// string may end in.
fn closing_len(rest: &[u8], delimiter: &[u8]) -> usize {
    if delimiter.len() == 1 {
        return 1;
    }
    let quotes = rest
        .iter()
        .take_while(|&&byte| Some(&byte) == delimiter.first());
    quotes.count().min(MAX_CLOSING_QUOTES)
}

/// A toml value as a node at `path`, `depth` tables and arrays below the root.
fn node(
    value: &Spanned<DeValue<'_>>,
    path: &Path<'_>,
    depth: usize,
    limits: &Limits,
) -> Result<Node, InputError> {
    let span = value.span();
    let at = |message: String| InputError::new(path.render(), Some(span.clone()), message);
    let value = match value.get_ref() {
        DeValue::String(text) => Value::String(text.to_string()),
        DeValue::Integer(integer) => Value::Integer(to_i64(integer).ok_or_else(|| {
            at(format!(
                "the integer {integer} is out of range: TOML integers are from {} to {}",
                i64::MIN,
                i64::MAX
            ))
        })?),
        DeValue::Float(float) => Value::Float(to_f64(float).ok_or_else(|| {
            at(format!(
                "the float {float} is out of range of f64 (write inf for infinity)"
            ))
        })?),
        DeValue::Boolean(value) => Value::Bool(*value),
        DeValue::Datetime(datetime) => Value::String(datetime.to_string()),
        DeValue::Array(items) => {
            check_depth(path, depth, &span, limits)?;
            let nodes = items
                .iter()
                .enumerate()
                .map(|(index, item)| node(item, &Path::Index(path, index), depth + 1, limits));
            Value::Array(nodes.collect::<Result<_, _>>()?)
        }
        DeValue::Table(table) => return table_node(table, span, path, depth, limits),
    };
    Ok(Node::spanned(value, span))
}

/// A toml table as a node with its keys in document order (toml may hold them sorted).
fn table_node(
    table: &DeTable<'_>,
    span: Range<usize>,
    path: &Path<'_>,
    depth: usize,
    limits: &Limits,
) -> Result<Node, InputError> {
    check_depth(path, depth, &span, limits)?;
    let mut entries: Vec<_> = table.iter().collect();
    entries.sort_by_key(|(key, _)| key.span().start);
    let entries = entries.into_iter().map(|(key, value)| {
        let name = key.get_ref().to_string();
        let value = node(value, &Path::Key(path, &name), depth + 1, limits)?;
        Ok((Key::spanned(name, key.span()), value))
    });
    Ok(Node::spanned(
        Value::Table(entries.collect::<Result<_, _>>()?),
        span,
    ))
}

/// Refuses a table or array nested deeper than `limits.max_depth`.
fn check_depth(
    path: &Path<'_>,
    depth: usize,
    span: &Range<usize>,
    limits: &Limits,
) -> Result<(), InputError> {
    if depth > limits.depth() {
        Err(limits.too_deep(path, span.clone()))
    } else {
        Ok(())
    }
}

/// A TOML integer as an `i64`: TOML's own range.
fn to_i64(integer: &DeInteger<'_>) -> Option<i64> {
    i64::from_str_radix(integer.as_str(), integer.radix()).ok()
}

/// A TOML float as an `f64`; `None` when a finite literal overflows (toml's own rule).
fn to_f64(float: &DeFloat<'_>) -> Option<f64> {
    let value: f64 = float.as_str().parse().ok()?;
    (!value.is_infinite() || float.as_str().contains("inf")).then_some(value)
}
