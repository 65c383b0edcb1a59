//! Read a TOML or JSON document into typed values; every error at the line and column of its key.
//!
//! A document is parsed into a [`Node`] tree that keeps the byte range of every value and key in
//! the source text. [`Node::deserialize`] then reads the tree into any `serde` type; an error
//! comes out as an [`InputError`] holding the path of the offending key (`contact.load.force_n`,
//! `body[1].material`), its byte range and a message. [`InputError::line_column`] turns the range
//! into the 1-based line and column (in characters) that a caller prints before it:
//!
//! ```
//! use contopt_input::Node;
//! use serde::Deserialize;
//!
//! #[derive(Deserialize, Debug)]
//! #[serde(deny_unknown_fields)]
//! struct Load {
//!     force_n: f64,
//! }
//!
//! let text = "[load]\nforce_n = \"1 kN\"\n";
//! let node = Node::parse_toml(text).unwrap();
//! let error = node.deserialize_at::<Load>("load").unwrap_err();
//! assert_eq!(error.path, "load.force_n");
//! assert_eq!(error.line_column(text), Some((2, 11)));
//! assert_eq!(
//!     format!("scene.toml:2:11: {error}"),
//!     "scene.toml:2:11: load.force_n: invalid type: string \"1 kN\", expected f64"
//! );
//! ```
//!
//! # Where an error points
//! - A value of the wrong type, or one that serde cannot take (a float into an integer, an
//!   integer out of range): the value.
//! - A value that the target type itself refuses (its `Deserialize` calls `Error::custom`, or a
//!   `#[serde(try_from = "Raw")]` conversion fails): the node being read when the refusal came.
//!   When that node is a table and the message names one of its keys, as `invalid <key> = …`
//!   anywhere in it or as `<key>: …` at its start, the error points at that key's value
//!   instead: a validated `Material { e_mpa, nu }` saying `invalid nu = 0.5: …` points at `nu`.
//! - An unknown field (`#[serde(deny_unknown_fields)]`): the key, with serde's list of the
//!   expected fields.
//! - A missing field: the table that lacks it, with the path `<table>.<field>`.
//! - An unknown enum variant: the name of the variant as written, with the allowed ones.
//!
//! # Enums
//! Enums use serde's default, external tagging (optionally `#[serde(rename_all = "…")]`), and a
//! document may spell a variant in three ways, all read alike:
//! 1. a string naming a unit variant: `method = "active_set"`;
//! 2. a table whose only key names the variant: `plane = { plane_stress = { thickness_mm = 10.0 } }`;
//! 3. a table whose `kind` key names the variant, the other keys being its content:
//!    `law = { kind = "penalty", c_mpa_per_mm = 2e9 }` (a unit variant then takes no other key).
//!
//! Internally tagged enums (`#[serde(tag = "kind")]`), untagged enums and `#[serde(flatten)]`
//! must not be used with this crate: serde buffers their content before reading it, and the
//! buffered values have lost their positions, so errors inside them point at the enclosing
//! node.
//!
//! # Hostile input
//! Both parsers refuse a text longer than [`Limits::max_bytes`] and tables and arrays nested
//! deeper than [`Limits::max_depth`] before they recurse, and neither panics on any input.

mod de;
mod json;
mod node;
mod path;
mod toml_text;

use std::ops::Range;

pub use node::{Key, Node, Value};

/// The longest document accepted by default \[bytes\]: a scene holds settings, not data.
pub const DEFAULT_MAX_BYTES: u64 = 1_000_000;

/// The deepest nesting of tables and arrays accepted by default.
pub const DEFAULT_MAX_DEPTH: usize = 32;

/// The deepest nesting followed whatever [`Limits::max_depth`] says: the parsers and the
/// deserializer recurse once per level, and the stack is finite.
pub const DEPTH_CEILING: usize = 128;

/// What a parser accepts before it reads a document.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The longest text \[bytes\].
    pub max_bytes: u64,
    /// The deepest nesting of tables and arrays below the document's root (the root table is
    /// depth 0, a table or array inside it depth 1, and so on); at most [`DEPTH_CEILING`] counts.
    pub max_depth: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            max_bytes: DEFAULT_MAX_BYTES,
            max_depth: DEFAULT_MAX_DEPTH,
        }
    }
}

impl Limits {
    /// Refuses a text longer than [`Limits::max_bytes`].
    fn check_size(&self, text: &str) -> Result<(), InputError> {
        let bytes = text.len() as u64;
        if bytes > self.max_bytes {
            return Err(InputError::new(
                "",
                None,
                format!(
                    "the document is {bytes} bytes, over the limit of {} bytes",
                    self.max_bytes
                ),
            ));
        }
        Ok(())
    }

    /// The deepest nesting the parsers follow: [`Limits::max_depth`], at most
    /// [`DEPTH_CEILING`].
    fn depth(&self) -> usize {
        self.max_depth.min(DEPTH_CEILING)
    }

    /// The error for a table or array at `path`, starting at `span`, nested too deep.
    fn too_deep(&self, path: &path::Path<'_>, span: Range<usize>) -> InputError {
        InputError::new(
            path.render(),
            Some(span),
            format!(
                "tables and arrays are nested more than {} deep",
                self.depth()
            ),
        )
    }
}

/// A document that could not be read, or a value that does not fit its type.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}{}", path::prefix(.path), .message)]
pub struct InputError {
    /// Where in the document: keys joined by `.`, array indices in brackets
    /// (`contact.load.force_n`, `body[1].material`); empty for the whole document.
    pub path: String,
    /// The byte range in the source text of the offending key or value; `None` when the error
    /// has no place in the text (a value made in code, a text over the size limit).
    pub span: Option<Range<usize>>,
    /// What is wrong, with the allowed values or kinds where known.
    pub message: String,
}

impl InputError {
    /// An error at `path` and `span`.
    pub fn new(
        path: impl Into<String>,
        span: Option<Range<usize>>,
        message: impl Into<String>,
    ) -> Self {
        Self {
            path: path.into(),
            span,
            message: message.into(),
        }
    }

    /// The 1-based line and column (in characters) of the error's start in `text`, the text the
    /// document was parsed from; `None` when the error has no span.
    pub fn line_column(&self, text: &str) -> Option<(usize, usize)> {
        self.span.as_ref().map(|span| line_column(text, span.start))
    }
}

/// The 1-based line and column (in characters, not bytes) of byte `offset` in `text`.
///
/// An offset inside a character counts as that character; one past the end as the end.
pub fn line_column(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line_start = before.rfind('\n').map_or(0, |newline| newline + 1);
    let line = before.bytes().filter(|&byte| byte == b'\n').count() + 1;
    let column = before[line_start..].chars().count() + 1;
    (line, column)
}
