//! What can go wrong with a scene, said where it happens: every error names the file, the line
//! and column of the offending key (from the reader's spans), the case, the key path, the
//! value and what it must be.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use contopt_core::FieldError;
use contopt_input::{InputError, Node};

/// What can go wrong with a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A key, a value or a combination the scene cannot have, or work refused before it
    /// starts (a case past its memory limit).
    #[error("{0}")]
    Invalid(Box<Located>),
}

/// An error at a place of a scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Located {
    /// The file.
    pub file: PathBuf,
    /// Line and column (from 1) of the offending key or value, when it has a place in the
    /// file.
    pub place: Option<(usize, usize)>,
    /// The case, when the scene has several.
    pub case: Option<String>,
    /// The dotted key path (`body[0].material.nu`), empty for the whole scene.
    pub path: String,
    /// What is wrong, with the value and what it must be.
    pub message: String,
    /// The field, its value and what it must be as data, when the error is a bad value (a
    /// library's [`contopt_core::Error::InvalidInput`]); `None` for a missing key, an
    /// unknown kind, a wrong type.
    pub field: Option<FieldError>,
}

impl std::fmt::Display for Located {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}", self.file.display())?;
        if let Some((line, column)) = self.place {
            write!(f, ":{line}:{column}")?;
        }
        write!(f, ": ")?;
        if let Some(case) = &self.case {
            write!(f, "[{case}] ")?;
        }
        if !self.path.is_empty() {
            write!(f, "{}: ", self.path)?;
        }
        write!(f, "{}", self.message)
    }
}

impl SceneError {
    /// The place of the error, when it is one.
    pub fn located(&self) -> Option<&Located> {
        match self {
            SceneError::Invalid(located) => Some(located),
            SceneError::Io { .. } => None,
        }
    }
}

/// Places errors in a scene's text: the file, its text and the tree of the case at hand.
#[derive(Clone, Debug)]
pub struct Locator {
    pub(crate) file: PathBuf,
    pub(crate) text: Arc<str>,
    pub(crate) tree: Arc<Node>,
    pub(crate) case: Option<String>,
}

impl Locator {
    /// A locator of a whole scene (`case` none) or of one of its cases.
    pub fn new(file: &Path, text: Arc<str>, tree: Arc<Node>, case: Option<String>) -> Self {
        Self {
            file: file.to_owned(),
            text,
            tree,
            case,
        }
    }

    /// The folder of the scene file, where the files it names are read.
    pub fn dir(&self) -> &Path {
        self.file
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
    }

    /// An error of the reader, at its own path and span.
    pub fn input(&self, e: InputError) -> SceneError {
        let place = e.line_column(&self.text);
        // A kind's own checks reach the reader through serde's `custom`, as text.
        let field = FieldError::from_message(&e.message);
        self.error(place, e.path, e.message, field)
    }

    /// A message about the key at `path` (its line and column, or its nearest present
    /// ancestor's).
    pub fn at(&self, path: &str, message: impl Into<String>) -> SceneError {
        let place = self.place_of(path);
        self.error(place, path.to_string(), message.into(), None)
    }

    /// A library error about the section at `path`: an invalid field is placed at
    /// `path.field` when that key is in the scene (a body's `radius_mm`), its message then
    /// `= value: reason`.
    pub fn library(&self, path: &str, e: contopt_core::Error) -> SceneError {
        match e.field_error() {
            Some(field) => {
                let full = join(path, &field.field);
                let message = format!("invalid value {}: {}", field.value, field.allowed);
                self.error(self.place_of(&full), full, message, Some(field))
            }
            None => self.at(path, e.to_string()),
        }
    }

    fn error(
        &self,
        place: Option<(usize, usize)>,
        path: String,
        message: String,
        field: Option<FieldError>,
    ) -> SceneError {
        SceneError::Invalid(Box::new(Located {
            file: self.file.clone(),
            place,
            case: self.case.clone(),
            path,
            message,
            field,
        }))
    }

    /// Line and column of the key at `path`, or of its nearest ancestor in the tree.
    fn place_of(&self, path: &str) -> Option<(usize, usize)> {
        let dotted = dotted(path);
        let mut prefix = dotted.as_str();
        loop {
            if let Some(span) = self.tree.get(prefix).and_then(Node::span) {
                return Some(contopt_input::line_column(&self.text, span.start));
            }
            match prefix.rfind('.') {
                Some(k) => prefix = &prefix[..k],
                None if !prefix.is_empty() => prefix = "",
                None => return None,
            }
        }
    }
}

/// `path.field`, or either alone when the other is empty.
pub fn join(path: &str, field: &str) -> String {
    match (path.is_empty(), field.is_empty()) {
        (true, _) => field.to_string(),
        (_, true) => path.to_string(),
        _ => format!("{path}.{field}"),
    }
}

/// A path as the tree takes it: `body[1].cells[0]` → `body.1.cells.0`.
pub(crate) fn dotted(path: &str) -> String {
    path.replace('[', ".").replace(']', "")
}
