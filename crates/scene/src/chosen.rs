//! A kind a scene chose ([`Chosen`]): what every part of a case holds of the kinds of its
//! [`crate::Registry`], below them all.

use std::any::Any;
use std::fmt;
use std::ops::Deref;
use std::sync::Arc;

use serde::Serialize;

/// A kind a scene chose: its registered name, its settings as they are written back, and the
/// kind itself. Two choices are the same when their names and settings are: the identity of
/// a kind is a value, not its text.
pub struct Chosen<T: ?Sized> {
    name: &'static str,
    written: serde_json::Value,
    kind: Arc<T>,
    /// The settings as their own type, for [`Chosen::downcast`].
    settings: Arc<dyn Any + Send + Sync>,
}

impl<T: ?Sized> Chosen<T> {
    /// A kind chosen as `name`, written back as `written`.
    pub(crate) fn new<S: Any + Send + Sync>(
        name: &'static str,
        written: serde_json::Value,
        kind: Arc<T>,
        settings: Arc<S>,
    ) -> Self {
        Self {
            name,
            written,
            kind,
            settings,
        }
    }

    /// The settings as the type `S` they were read into (the kind's own type, or the enum of a
    /// family of kinds); `None` when they are of another type.
    pub fn downcast<S: Any>(&self) -> Option<&S> {
        self.settings.downcast_ref()
    }

    /// The kind's registered name.
    pub fn name(&self) -> &'static str {
        self.name
    }

    /// Its settings as `result.json` writes them (`{ "<name>": { … } }`).
    pub fn written(&self) -> &serde_json::Value {
        &self.written
    }
}

impl<T: ?Sized> Deref for Chosen<T> {
    type Target = T;

    fn deref(&self) -> &T {
        &self.kind
    }
}

impl<T: ?Sized> Clone for Chosen<T> {
    fn clone(&self) -> Self {
        Self {
            name: self.name,
            written: self.written.clone(),
            kind: self.kind.clone(),
            settings: self.settings.clone(),
        }
    }
}

impl<T: ?Sized> PartialEq for Chosen<T> {
    fn eq(&self, other: &Self) -> bool {
        self.name == other.name && self.written == other.written
    }
}

impl<T: ?Sized> fmt::Debug for Chosen<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.written)
    }
}

impl<T: ?Sized> Serialize for Chosen<T> {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        self.written.serialize(serializer)
    }
}
