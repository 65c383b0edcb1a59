//! A serde deserializer over a [`Node`] tree: every error placed at the innermost node where it
//! arose (the rules are in the crate documentation).

use std::fmt;
use std::ops::Range;

use serde::de::value::BorrowedStrDeserializer;
use serde::de::{
    self, DeserializeSeed, EnumAccess, Expected, MapAccess, SeqAccess, Unexpected, VariantAccess,
    Visitor,
};
use serde::Deserialize;

use crate::node::{Key, Node, Value};
use crate::path::Path;
use crate::InputError;

/// The key whose string value names an enum's variant, the other keys being its content.
const KIND_KEY: &str = "kind";

/// How errors name JSON's `null`.
const NULL: Unexpected<'static> = Unexpected::Other("null");

/// Reads `node`, at the rendered path `root`, into a `T`.
pub(crate) fn from_node<'de, T: Deserialize<'de>>(
    node: &'de Node,
    root: &str,
) -> Result<T, InputError> {
    let path = Path::Root(root);
    located(NodeDe::new(node, &path), T::deserialize).map_err(DeError::into_input_error)
}

/// Reads `node` through `seed`, as the node at the rendered path `root` of its document.
pub(crate) fn from_node_seed<'de, S: DeserializeSeed<'de>>(
    node: &'de Node,
    root: &str,
    seed: S,
) -> Result<S::Value, InputError> {
    let path = Path::Root(root);
    located(NodeDe::new(node, &path), |de| seed.deserialize(de)).map_err(DeError::into_input_error)
}

/// An error while reading, placed (given a path and span) by the innermost node it passed.
#[derive(Debug)]
pub(crate) struct DeError {
    message: String,
    place: Option<(String, Option<Range<usize>>)>,
    /// The field of a missing-field error: its path is the table's and the field.
    missing: Option<&'static str>,
}

impl DeError {
    fn into_input_error(self) -> InputError {
        let (path, span) = self.place.unwrap_or_default();
        InputError::new(path, span, self.message)
    }

    /// Places an error not yet placed at `path` and `span`.
    fn at(mut self, path: &Path<'_>, span: Option<Range<usize>>) -> Self {
        if self.place.is_none() {
            self.place = Some((path.render(), span));
        }
        self
    }
}

impl fmt::Display for DeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

impl std::error::Error for DeError {}

impl de::Error for DeError {
    fn custom<T: fmt::Display>(message: T) -> Self {
        Self {
            message: message.to_string(),
            place: None,
            missing: None,
        }
    }

    /// Serde's message, with JSON's `null` named so (a visitor sees it as `()`).
    fn invalid_type(unexpected: Unexpected<'_>, expected: &dyn Expected) -> Self {
        let unexpected = match unexpected {
            Unexpected::Unit => NULL,
            other => other,
        };
        Self::custom(format_args!(
            "invalid type: {unexpected}, expected {expected}"
        ))
    }

    fn missing_field(field: &'static str) -> Self {
        Self {
            missing: Some(field),
            ..Self::custom(format_args!("missing field `{field}`"))
        }
    }
}

/// Runs `read` on `de` and places an error not yet placed at `de`'s node: a missing field at
/// the table's span with the field's path, a message naming a key of the table (`invalid <key>
/// = …` anywhere, or `<key>: …` at its start) at that key's value, anything else at the node.
fn located<'de, 'p, T>(
    de: NodeDe<'de, 'p>,
    read: impl FnOnce(NodeDe<'de, 'p>) -> Result<T, DeError>,
) -> Result<T, DeError> {
    read(de).map_err(|mut error| {
        if error.place.is_some() {
            return error;
        }
        if let Some(field) = error.missing.take() {
            return error.at(&Path::Key(de.path, field), de.node.span());
        }
        match named_key(&error.message, de.node) {
            Some((key, value)) => error.at(&Path::Key(de.path, key.name()), value.span()),
            None => error.at(de.path, de.node.span()),
        }
    })
}

/// The entry of a table whose key a message names as `invalid <key> = ` or `<key>:` (first).
fn named_key<'n>(message: &str, node: &'n Node) -> Option<&'n (Key, Node)> {
    let Value::Table(entries) = node.value() else {
        return None;
    };
    entries.iter().find(|(key, _)| {
        let name = key.name();
        message.contains(&format!("invalid {name} = ")) || message.starts_with(&format!("{name}:"))
    })
}

/// The empty table a newtype variant named by a string is read from.
static EMPTY_TABLE: Node = Node::empty_table();

/// A node being read at `path`; a table may hide one entry (the `kind` of an enum's content).
#[derive(Clone, Copy)]
struct NodeDe<'de, 'p> {
    node: &'de Node,
    path: &'p Path<'p>,
    hidden: Option<usize>,
}

impl<'de, 'p> NodeDe<'de, 'p> {
    fn new(node: &'de Node, path: &'p Path<'p>) -> Self {
        Self {
            node,
            path,
            hidden: None,
        }
    }

    /// The entries of a table, without the hidden one; none for any other value (a variant
    /// named by a string reads as an empty table).
    fn entries(self) -> Entries<'de, 'p> {
        let entries = match self.node.value() {
            Value::Table(entries) => entries.as_slice(),
            _ => &[],
        };
        Entries {
            entries,
            next: 0,
            hidden: self.hidden,
            path: self.path,
            pending: None,
        }
    }
}

/// What serde is told about a value it did not expect.
fn unexpected(value: &Value) -> Unexpected<'_> {
    match value {
        Value::Null => NULL,
        Value::Bool(value) => Unexpected::Bool(*value),
        Value::Integer(value) => Unexpected::Signed(*value),
        Value::Float(value) => Unexpected::Float(*value),
        Value::String(value) => Unexpected::Str(value),
        Value::Array(_) => Unexpected::Seq,
        Value::Table(_) => Unexpected::Map,
    }
}

impl<'de> de::Deserializer<'de> for NodeDe<'de, '_> {
    type Error = DeError;

    fn deserialize_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, DeError> {
        match self.node.value() {
            Value::Null => visitor.visit_unit(),
            Value::Bool(value) => visitor.visit_bool(*value),
            Value::Integer(value) => visitor.visit_i64(*value),
            Value::Float(value) => visitor.visit_f64(*value),
            Value::String(value) => visitor.visit_borrowed_str(value),
            Value::Array(items) => {
                let mut elements = Elements {
                    items,
                    next: 0,
                    path: self.path,
                };
                let value = visitor.visit_seq(&mut elements)?;
                elements.end()?;
                Ok(value)
            }
            Value::Table(_) => visitor.visit_map(self.entries()),
        }
    }

    fn deserialize_option<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, DeError> {
        match self.node.value() {
            Value::Null => visitor.visit_none(),
            _ => visitor.visit_some(self),
        }
    }

    fn deserialize_newtype_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        visitor: V,
    ) -> Result<V::Value, DeError> {
        visitor.visit_newtype_struct(self)
    }

    /// A struct is read from a table only, never from an array of its fields in order.
    fn deserialize_struct<V: Visitor<'de>>(
        self,
        _name: &'static str,
        _fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, DeError> {
        match self.node.value() {
            Value::Table(_) => visitor.visit_map(self.entries()),
            other => Err(de::Error::invalid_type(unexpected(other), &visitor)),
        }
    }

    fn deserialize_enum<V: Visitor<'de>>(
        self,
        _name: &'static str,
        variants: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, DeError> {
        match spelling(self, variants)? {
            Spelling::Name(name) => visitor.visit_enum(Variant {
                name,
                tag: self.path,
                tag_span: self.node.span(),
                content: Content::Empty(self),
            }),
            Spelling::OnlyKey(key, value) => {
                let path = Path::Key(self.path, key.name());
                visitor.visit_enum(Variant {
                    name: key.name(),
                    tag: &path,
                    tag_span: key.span(),
                    content: Content::Node(NodeDe::new(value, &path)),
                })
            }
            Spelling::Kind(index, name, tag_span) => visitor.visit_enum(Variant {
                name,
                tag: &Path::Key(self.path, KIND_KEY),
                tag_span,
                content: Content::Node(NodeDe {
                    hidden: Some(index),
                    ..self
                }),
            }),
        }
    }

    fn deserialize_ignored_any<V: Visitor<'de>>(self, visitor: V) -> Result<V::Value, DeError> {
        visitor.visit_unit()
    }

    serde::forward_to_deserialize_any! {
        bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes byte_buf
        unit unit_struct seq tuple tuple_struct map identifier
    }
}

/// How a document names an enum's variant.
enum Spelling<'de> {
    /// A string: `"active_set"`.
    Name(&'de str),
    /// A table whose only key is the variant, its value the content.
    OnlyKey(&'de Key, &'de Node),
    /// A table whose entry at the index is `kind = "<variant>"` (with the string's span), the
    /// other entries the content.
    Kind(usize, &'de str, Option<Range<usize>>),
}

/// How `de` names a variant of an enum with `variants`; see [`Spelling`].
fn spelling<'de>(
    de: NodeDe<'de, '_>,
    variants: &'static [&'static str],
) -> Result<Spelling<'de>, DeError> {
    match de.node.value() {
        Value::String(name) => return Ok(Spelling::Name(name)),
        Value::Table(_) => {}
        other => {
            return Err(de::Error::invalid_type(
                unexpected(other),
                &"a variant name",
            ))
        }
    }
    let visible = de.entries().visible();
    if let [(_, (key, value))] = visible[..] {
        if key.name() != KIND_KEY || variants.contains(&KIND_KEY) {
            return Ok(Spelling::OnlyKey(key, value));
        }
    }
    let kind = visible
        .into_iter()
        .find(|(_, (key, _))| key.name() == KIND_KEY);
    let Some((index, (_, tag))) = kind else {
        return Err(de::Error::custom(format!(
            "expected the name of a variant (one of {}) as a string, as the only key of a \
             table, or as the value of a `{KIND_KEY}` key",
            quoted(variants)
        )));
    };
    match tag.value() {
        Value::String(name) => Ok(Spelling::Kind(index, name, tag.span())),
        other => Err(<DeError as de::Error>::invalid_type(
            unexpected(other),
            &"the name of a variant",
        )
        .at(&Path::Key(de.path, KIND_KEY), tag.span())),
    }
}

/// `` `a`, `b` ``.
fn quoted(names: &[&str]) -> String {
    let names: Vec<_> = names.iter().map(|name| format!("`{name}`")).collect();
    names.join(", ")
}

/// An enum's variant as the document names it, with its content.
struct Variant<'de, 'p> {
    name: &'de str,
    /// Where the name is: the path and span that an unknown variant is reported at.
    tag: &'p Path<'p>,
    tag_span: Option<Range<usize>>,
    content: Content<'de, 'p>,
}

/// What a variant holds.
enum Content<'de, 'p> {
    /// Nothing: the variant was named by a string (the node given).
    Empty(NodeDe<'de, 'p>),
    /// A node: the value under the variant's key, or the table around `kind`.
    Node(NodeDe<'de, 'p>),
}

impl<'de, 'p> EnumAccess<'de> for Variant<'de, 'p> {
    type Error = DeError;
    type Variant = Self;

    fn variant_seed<S: DeserializeSeed<'de>>(self, seed: S) -> Result<(S::Value, Self), DeError> {
        let name = BorrowedStrDeserializer::new(self.name);
        let value = seed
            .deserialize(name)
            .map_err(|error: DeError| error.at(self.tag, self.tag_span.clone()))?;
        Ok((value, self))
    }
}

impl<'de> VariantAccess<'de> for Variant<'de, '_> {
    type Error = DeError;

    /// A unit variant takes no content: no key besides `kind`, an empty table under its key.
    fn unit_variant(self) -> Result<(), DeError> {
        let Content::Node(content) = self.content else {
            return Ok(());
        };
        let no_content = |found: String| {
            let message = format!(
                "the unit variant `{}` takes no content, found {found}",
                self.name
            );
            <DeError as de::Error>::custom(message)
        };
        match content.node.value() {
            Value::Table(_) => match content.entries().next_entry() {
                None => Ok(()),
                Some((key, _)) => Err(no_content(format!("the key `{}`", key.name()))
                    .at(&Path::Key(content.path, key.name()), key.span())),
            },
            other => {
                Err(no_content(unexpected(other).to_string()).at(content.path, content.node.span()))
            }
        }
    }

    /// A newtype variant named by a string reads its value from an empty table: a settings
    /// struct whose fields all have defaults may be named alone (`solver = "auto"`,
    /// `method = "given_load"`); one that needs a field says which is missing.
    fn newtype_variant_seed<S: DeserializeSeed<'de>>(self, seed: S) -> Result<S::Value, DeError> {
        match self.content {
            Content::Node(content) => located(content, |content| seed.deserialize(content)),
            Content::Empty(named) => {
                let empty = NodeDe::new(&EMPTY_TABLE, named.path);
                let span = named.node.span();
                seed.deserialize(empty)
                    .map_err(|error| error.at(named.path, span))
            }
        }
    }

    fn tuple_variant<V: Visitor<'de>>(self, len: usize, visitor: V) -> Result<V::Value, DeError> {
        match self.content {
            Content::Node(content) => located(content, |content| {
                de::Deserializer::deserialize_tuple(content, len, visitor)
            }),
            Content::Empty(_) => Err(self.needs_content("tuple variant")),
        }
    }

    /// A struct variant named by a string reads as an empty table: its missing fields are
    /// reported, and one whose fields all have defaults may be named alone.
    fn struct_variant<V: Visitor<'de>>(
        self,
        fields: &'static [&'static str],
        visitor: V,
    ) -> Result<V::Value, DeError> {
        match self.content {
            Content::Node(content) => located(content, |content| {
                de::Deserializer::deserialize_struct(content, "", fields, visitor)
            }),
            Content::Empty(named) => located(named, |named| visitor.visit_map(named.entries())),
        }
    }
}

impl Variant<'_, '_> {
    /// The error for a variant with content named by a string alone.
    fn needs_content(&self, expected: &str) -> DeError {
        <DeError as de::Error>::invalid_type(Unexpected::UnitVariant, &expected)
            .at(self.tag, self.tag_span.clone())
    }
}

/// The elements of an array being read.
struct Elements<'de, 'p> {
    items: &'de [Node],
    next: usize,
    path: &'p Path<'p>,
}

impl Elements<'_, '_> {
    /// Refuses elements left unread (a tuple shorter than the array).
    fn end(&self) -> Result<(), DeError> {
        if self.next < self.items.len() {
            let expected = format!("{} elements", self.next);
            Err(de::Error::invalid_length(
                self.items.len(),
                &expected.as_str(),
            ))
        } else {
            Ok(())
        }
    }
}

impl<'de> SeqAccess<'de> for Elements<'de, '_> {
    type Error = DeError;

    fn next_element_seed<S: DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, DeError> {
        let Some(item) = self.items.get(self.next) else {
            return Ok(None);
        };
        let path = Path::Index(self.path, self.next);
        self.next += 1;
        located(NodeDe::new(item, &path), |item| seed.deserialize(item)).map(Some)
    }

    fn size_hint(&self) -> Option<usize> {
        Some(self.items.len() - self.next)
    }
}

/// The entries of a table being read, without the hidden one.
struct Entries<'de, 'p> {
    entries: &'de [(Key, Node)],
    next: usize,
    hidden: Option<usize>,
    path: &'p Path<'p>,
    /// The entry whose key was read and whose value is next.
    pending: Option<&'de (Key, Node)>,
}

impl<'de> Entries<'de, '_> {
    /// The next entry not hidden, with its index.
    fn next_indexed(&mut self) -> Option<(usize, &'de (Key, Node))> {
        while let Some(entry) = self.entries.get(self.next) {
            let index = self.next;
            self.next += 1;
            if self.hidden != Some(index) {
                return Some((index, entry));
            }
        }
        None
    }

    fn next_entry(&mut self) -> Option<&'de (Key, Node)> {
        self.next_indexed().map(|(_, entry)| entry)
    }

    /// The entries not hidden, with their indices.
    fn visible(mut self) -> Vec<(usize, &'de (Key, Node))> {
        std::iter::from_fn(|| self.next_indexed()).collect()
    }
}

impl<'de> MapAccess<'de> for Entries<'de, '_> {
    type Error = DeError;

    fn next_key_seed<S: DeserializeSeed<'de>>(
        &mut self,
        seed: S,
    ) -> Result<Option<S::Value>, DeError> {
        let Some(entry) = self.next_entry() else {
            return Ok(None);
        };
        self.pending = Some(entry);
        let (key, _) = entry;
        let name = BorrowedStrDeserializer::new(key.name());
        seed.deserialize(name)
            .map(Some)
            .map_err(|error: DeError| error.at(&Path::Key(self.path, key.name()), key.span()))
    }

    fn next_value_seed<S: DeserializeSeed<'de>>(&mut self, seed: S) -> Result<S::Value, DeError> {
        let Some((key, value)) = self.pending.take() else {
            return Err(de::Error::custom("a value asked for before its key"));
        };
        let path = Path::Key(self.path, key.name());
        located(NodeDe::new(value, &path), |value| seed.deserialize(value))
    }
}
