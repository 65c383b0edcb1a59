//! The document tree: values with the byte ranges they came from.

use std::ops::Range;

use serde::de::DeserializeSeed;
use serde::Deserialize;

use crate::path::{push_index, push_key};
use crate::{de, json, toml_text, InputError, Limits};

/// A value of a document with the byte range it was read from.
///
/// Equality compares values only, not positions: a tree read from TOML equals the same tree read
/// from JSON.
#[derive(Debug, Clone)]
pub struct Node {
    value: Value,
    span: Option<Range<usize>>,
}

/// What a [`Node`] holds.
///
/// TOML has no null; its dates and times are read as strings in TOML's own form.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// JSON's `null`.
    Null,
    /// `true` or `false`.
    Bool(bool),
    /// A number written without fraction or exponent that fits an `i64`.
    Integer(i64),
    /// Any other number, including TOML's `nan` and `inf`.
    Float(f64),
    /// A string, escapes resolved.
    String(String),
    /// An array.
    Array(Vec<Node>),
    /// A table (a JSON object), its keys in document order.
    Table(Vec<(Key, Node)>),
}

/// A key of a table with the byte range it was read from.
///
/// Equality compares names only.
#[derive(Debug, Clone)]
pub struct Key {
    name: String,
    span: Option<Range<usize>>,
}

impl Key {
    /// A key made in code: it has no place in a text.
    pub fn new(name: impl Into<String>) -> Self {
        Self {
            name: name.into(),
            span: None,
        }
    }

    /// A key read from a text.
    pub(crate) fn spanned(name: String, span: Range<usize>) -> Self {
        Self {
            name,
            span: Some(span),
        }
    }

    /// The key's name, escapes resolved.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The byte range of the key in the source text (quotes included for a quoted key).
    pub fn span(&self) -> Option<Range<usize>> {
        self.span.clone()
    }
}

impl PartialEq for Key {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name
    }
}

impl PartialEq for Node {
    fn eq(&self, other: &Self) -> bool {
        self.value == other.value
    }
}

impl Value {
    /// What kind of value this is, as messages name it: `integer`, `table`…
    pub fn kind(&self) -> &'static str {
        match self {
            Value::Null => "null",
            Value::Bool(_) => "boolean",
            Value::Integer(_) => "integer",
            Value::Float(_) => "float",
            Value::String(_) => "string",
            Value::Array(_) => "array",
            Value::Table(_) => "table",
        }
    }
}

impl Node {
    /// A value made in code: it has no place in a text.
    pub fn new(value: Value) -> Self {
        Self { value, span: None }
    }

    /// An empty table made in code.
    pub(crate) const fn empty_table() -> Self {
        Self {
            value: Value::Table(Vec::new()),
            span: None,
        }
    }

    /// A value read from a text.
    pub(crate) fn spanned(value: Value, span: Range<usize>) -> Self {
        Self {
            value,
            span: Some(span),
        }
    }

    /// The same value placed at `span` of the text (a value made in code that stands for one
    /// read from there).
    pub fn with_span(mut self, span: Option<Range<usize>>) -> Self {
        self.span = span;
        self
    }

    /// A table made in code from its entries, in order.
    pub fn table<K: Into<String>>(entries: impl IntoIterator<Item = (K, Node)>) -> Self {
        let entries = entries
            .into_iter()
            .map(|(name, node)| (Key::new(name), node))
            .collect();
        Self::new(Value::Table(entries))
    }

    /// Reads a TOML document within the default [`Limits`].
    pub fn parse_toml(text: &str) -> Result<Node, InputError> {
        Self::parse_toml_with(text, &Limits::default())
    }

    /// Reads a TOML document within `limits`; a syntax error has the span toml gives it.
    pub fn parse_toml_with(text: &str, limits: &Limits) -> Result<Node, InputError> {
        toml_text::parse(text, limits)
    }

    /// Reads a JSON document within the default [`Limits`].
    pub fn parse_json(text: &str) -> Result<Node, InputError> {
        Self::parse_json_with(text, &Limits::default())
    }

    /// Reads a JSON document within `limits`.
    ///
    /// A number without fraction or exponent is an [`Value::Integer`] when it fits an `i64`, a
    /// [`Value::Float`] otherwise (`1e400` is infinite); a duplicate key is an error.
    pub fn parse_json_with(text: &str, limits: &Limits) -> Result<Node, InputError> {
        json::parse(text, limits)
    }

    /// The value.
    pub fn value(&self) -> &Value {
        &self.value
    }

    /// The byte range of the value in the source text; `None` for a value made in code.
    pub fn span(&self) -> Option<Range<usize>> {
        self.span.clone()
    }

    /// The node at a dotted `path` below this one (`"body.1.material.nu"`: a segment indexes an
    /// array when it is a number); the empty path is this node. Keys holding a `.` cannot be
    /// reached.
    pub fn get(&self, path: &str) -> Option<&Node> {
        self.walk(path).ok().map(|(node, _)| node)
    }

    /// Replaces the value at `path` (as in [`Node::get`]), which must exist, and returns the old
    /// one; the new node keeps its own span. The error names the first segment not found.
    pub fn set(&mut self, path: &str, value: Node) -> Result<Node, InputError> {
        let mut node = self;
        let mut rendered = String::new();
        for segment in segments(path) {
            let index = node.child_index(segment, &mut rendered)?;
            node = node.child_mut(index);
        }
        Ok(std::mem::replace(node, value))
    }

    /// Sets the value at `path` (as in [`Node::get`]): replaces it when it exists, or adds its
    /// last key to the table that `path` leads to, which must exist. Returns the old value,
    /// if any. The error names the first segment not found.
    pub fn insert(&mut self, path: &str, value: Node) -> Result<Option<Node>, InputError> {
        if self.get(path).is_some() {
            return self.set(path, value).map(Some);
        }
        let (parent, key) = match path.rsplit_once('.') {
            Some((parent, key)) => (parent, key),
            None => ("", path),
        };
        let mut node = self;
        let mut rendered = String::new();
        for segment in segments(parent) {
            let index = node.child_index(segment, &mut rendered)?;
            node = node.child_mut(index);
        }
        let span = node.span();
        match &mut node.value {
            Value::Table(entries) => {
                entries.push((Key::new(key), value));
                Ok(None)
            }
            other => {
                push_key(&mut rendered, key);
                let kind = other.kind();
                Err(InputError::new(
                    rendered,
                    span,
                    format!("a {kind} has no keys"),
                ))
            }
        }
    }

    /// Removes the key at a dotted `path` (as in [`Node::get`]; a top-level key is its own
    /// path) and returns its value; `None` when there is no such key or what holds it is not a
    /// table.
    pub fn remove(&mut self, path: &str) -> Option<Node> {
        let (parent, key) = path.rsplit_once('.').unwrap_or(("", path));
        let mut node = self;
        let mut rendered = String::new();
        for segment in segments(parent) {
            let index = node.child_index(segment, &mut rendered).ok()?;
            node = node.child_mut(index);
        }
        let Value::Table(entries) = &mut node.value else {
            return None;
        };
        let index = entries.iter().position(|(name, _)| name.name == key)?;
        Some(entries.remove(index).1)
    }

    /// Reads this node into a `T`; an error names the path, span and reason of the innermost
    /// value that `T` refused (see the [crate] documentation).
    pub fn deserialize<'a, T: Deserialize<'a>>(&'a self) -> Result<T, InputError> {
        de::from_node(self, "")
    }

    /// Reads the node at `path` (as in [`Node::get`]) into a `T`; errors carry paths from this
    /// node (`body[1].material.nu`), and a missing `path` is an error naming its first segment
    /// not found.
    pub fn deserialize_at<'a, T: Deserialize<'a>>(&'a self, path: &str) -> Result<T, InputError> {
        let (node, rendered) = self.walk(path)?;
        de::from_node(node, &rendered)
    }

    /// Reads this node through `seed` as the node at `path` of its document, `path` rendered
    /// as errors render it (`body[1]`): the errors carry paths from there. A reader of kinds
    /// registered at run time (a `DeserializeSeed` that holds the registry) reads its part of
    /// the document this way, with every span kept.
    pub fn deserialize_seed<'a, S: DeserializeSeed<'a>>(
        &'a self,
        seed: S,
        path: &str,
    ) -> Result<S::Value, InputError> {
        de::from_node_seed(self, path, seed)
    }

    /// The node at `path` and its path as errors render it.
    fn walk(&self, path: &str) -> Result<(&Node, String), InputError> {
        let mut node = self;
        let mut rendered = String::new();
        for segment in segments(path) {
            let index = node.child_index(segment, &mut rendered)?;
            node = node.child(index);
        }
        Ok((node, rendered))
    }

    /// Where `segment` is among this node's entries or elements; appends it to `rendered`, the
    /// path so far, and names it in the error when it is not there.
    fn child_index(&self, segment: &str, rendered: &mut String) -> Result<usize, InputError> {
        let found = match &self.value {
            Value::Table(entries) => {
                push_key(rendered, segment);
                let position = entries.iter().position(|(key, _)| key.name == segment);
                position.ok_or_else(|| format!("no key `{segment}` in this table"))
            }
            Value::Array(items) => match segment.parse::<usize>() {
                Ok(index) => {
                    push_index(rendered, index);
                    let length = items.len();
                    (index < length)
                        .then_some(index)
                        .ok_or_else(|| format!("no element {index}: the array has {length}"))
                }
                Err(_) => {
                    push_key(rendered, segment);
                    Err(format!("`{segment}` is not an index into an array"))
                }
            },
            other => {
                push_key(rendered, segment);
                Err(format!("no `{segment}` in this {}", other.kind()))
            }
        };
        found.map_err(|message| InputError::new(rendered.clone(), self.span(), message))
    }

    /// The entry or element at `index`, as found by [`Node::child_index`].
    fn child(&self, index: usize) -> &Node {
        match &self.value {
            Value::Table(entries) => &entries[index].1,
            Value::Array(items) => &items[index],
            _ => self,
        }
    }

    /// The entry or element at `index`, as found by [`Node::child_index`].
    fn child_mut(&mut self, index: usize) -> &mut Node {
        match self.value {
            Value::Table(ref mut entries) => &mut entries[index].1,
            Value::Array(ref mut items) => &mut items[index],
            _ => self,
        }
    }
}

/// The segments of a dotted path; none for the empty path.
fn segments(path: &str) -> impl Iterator<Item = &str> {
    path.split('.').filter(move |_| !path.is_empty())
}

impl From<Value> for Node {
    fn from(value: Value) -> Self {
        Self::new(value)
    }
}

impl From<bool> for Node {
    fn from(value: bool) -> Self {
        Self::new(Value::Bool(value))
    }
}

impl From<i64> for Node {
    fn from(value: i64) -> Self {
        Self::new(Value::Integer(value))
    }
}

impl From<f64> for Node {
    fn from(value: f64) -> Self {
        Self::new(Value::Float(value))
    }
}

impl From<&str> for Node {
    fn from(value: &str) -> Self {
        Self::new(Value::String(value.to_owned()))
    }
}

impl From<String> for Node {
    fn from(value: String) -> Self {
        Self::new(Value::String(value))
    }
}

impl From<Vec<Node>> for Node {
    fn from(items: Vec<Node>) -> Self {
        Self::new(Value::Array(items))
    }
}
