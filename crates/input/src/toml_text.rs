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
/// them: brackets in strings and comments do not count, a table header `[a]` counts 1 and an
/// array-of-tables header `[[a]]` counts 2. Dotted keys (`a.b.c = 1`) nest without brackets;
/// the conversion refuses those.
fn check_nesting(text: &str, limits: &Limits) -> Result<(), InputError> {
    let (mut depth, mut quote) = (0usize, None);
    let mut chars = text.char_indices();
    while let Some((at, c)) = chars.next() {
        match (quote, c) {
            (Some('"'), '\\') => {
                chars.next();
            }
            (Some(open), c) if c == open => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '#') => {
                chars.by_ref().find(|&(_, c)| c == '\n');
            }
            (None, '[' | '{') => {
                depth += 1;
                if depth > limits.depth() {
                    return Err(limits.too_deep(&Path::Root(""), at..at + 1));
                }
            }
            (None, ']' | '}') => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    Ok(())
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
