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

impl std::fmt::Debug for Error {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::Display::fmt(self, f)
    }
}
