use thiserror::Error;

/// Result with the workspace's [`Error`](enum@Error) unless another is named, so that
/// `Result<T, Box<dyn std::error::Error>>` still reads as std's under `use contopt::prelude::*`.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Everything that can go wrong in contopt.
///
/// Errors are for bad input and for work refused before it starts (a matrix past the memory
/// limit): reported with the field that holds it and its value, never by a panic or a NaN in
/// the output. A method that starts and stops short is not an error: its result carries a
/// [`Termination`](crate::Termination). `Debug` prints the message too, so that a `main`
/// returning [`Result`] shows it as a sentence.
#[derive(Error)]
pub enum Error {
    /// A parameter outside its admissible range.
    #[error("invalid {field} = {value}: {reason}")]
    InvalidInput {
        /// Dotted path of the offending field, e.g. `material.nu`.
        field: String,
        /// The value as given.
        value: String,
        /// What the value must satisfy.
        reason: String,
    },
    /// A mesh that cannot be used (inverted element, unknown node, face not on the boundary…).
    #[error("mesh: {0}")]
    Mesh(String),
    /// The stiffness matrix of a body is singular even after its rigid-body modes were
    /// removed: a mechanism, or an element with a degenerate Jacobian.
    #[error("body `{body}`: stiffness matrix is not positive definite ({detail})")]
    Singular {
        /// Name of the body.
        body: String,
        /// What the factorisation reported.
        detail: String,
    },
    /// Two contact surfaces that should share their points do not.
    #[error("interfaces do not match at point {index}: {detail}")]
    InterfaceMismatch {
        /// Index of the first mismatching point.
        index: usize,
        /// The two values that differ.
        detail: String,
    },
    /// An allocation refused before it was made: it would exceed the memory limit.
    #[error("{what} would take {}, over the limit of {} MB: {advice}", megabytes(*bytes), limit / 1_000_000)]
    TooLarge {
        /// What would have been allocated, with its size.
        what: String,
        /// Its estimated memory \[bytes\].
        bytes: u64,
        /// The limit in force \[bytes\].
        limit: u64,
        /// What to do instead.
        advice: String,
    },
}

/// A size in MB, or the words for one too large to count in bytes.
fn megabytes(bytes: u64) -> String {
    if bytes == u64::MAX {
        "more bytes than 64 bits count".to_string()
    } else {
        format!("{} MB", bytes / 1_000_000)
    }
}

impl Error {
    /// Shorthand for [`Error::InvalidInput`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Error::InvalidInput {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }
}

/// A field's bad value as data: the parts of an [`Error::InvalidInput`], for a caller that
/// acts on them (a binding's exception attributes, a form that marks the field) rather than
/// reading the sentence. A scene places it in its file (`contopt_scene::Located`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FieldError {
    /// The field as the library named it (`nu`, `compliance[0, 1]`).
    pub field: String,
    /// The value as given.
    pub value: String,
    /// What the value must satisfy.
    pub allowed: String,
}

/// The words that open an [`Error::InvalidInput`]'s sentence and part its field from its
/// value and its value from what is allowed: `invalid FIELD = VALUE: ALLOWED`.
const INVALID: (&str, &str, &str) = ("invalid ", " = ", ": ");

impl FieldError {
    /// The field error an [`Error::InvalidInput`]'s sentence states, for one that crossed a
    /// boundary as text only (serde's `de::Error::custom` takes a `Display`): the inverse of
    /// the error's `Display`, kept beside it. `None` for any other sentence.
    pub fn from_message(message: &str) -> Option<Self> {
        let (open, equals, colon) = INVALID;
        let (field, rest) = message.strip_prefix(open)?.split_once(equals)?;
        let (value, allowed) = rest.split_once(colon)?;
        Some(Self {
            field: field.to_string(),
            value: value.to_string(),
            allowed: allowed.to_string(),
        })
    }
}

impl Error {
    /// The field, value and what is allowed of an [`Error::InvalidInput`]; `None` for the
    /// other errors, which name no field.
    pub fn field_error(&self) -> Option<FieldError> {
        match self {
            Error::InvalidInput {
                field,
                value,
                reason,
            } => Some(FieldError {
                field: field.clone(),
                value: value.clone(),
                allowed: reason.clone(),
            }),
            _ => None,
        }
    }
}

impl std::fmt::Debug for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_field_error_reads_back_from_its_sentence() {
        let e = Error::invalid("material.nu", 0.7, "must lie strictly between -1 and 0.5");
        let typed = e.field_error().unwrap();
        assert_eq!(typed.field, "material.nu");
        assert_eq!(typed.value, "0.7");
        assert_eq!(typed.allowed, "must lie strictly between -1 and 0.5");
        assert_eq!(FieldError::from_message(&e.to_string()), Some(typed));
        assert_eq!(FieldError::from_message("mesh: inverted element 3"), None);
        let other = Error::Mesh("inverted element 3".into());
        assert_eq!(other.field_error(), None);
    }
}
