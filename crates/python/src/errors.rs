//! The errors Python sees: a scene's mistakes as [`SceneError`] and the library's bad input as
//! [`InputError`], both `ValueError`s that carry where and what, so that a caller can act on
//! them (`except contopt.SceneError as e: e.key, e.line`); a missing file as Python's own
//! `FileNotFoundError`.

use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::{create_exception, IntoPyObjectExt, PyErr};

create_exception!(
    contopt,
    SceneError,
    PyValueError,
    "A scene that cannot be read, checked or run. Attributes: file, line, column (from 1, or \
     None), case (None for a scene of one case), key (the dotted key path), value (as written, \
     or None), allowed (what the value must be), message (the whole sentence)."
);

create_exception!(
    contopt,
    InputError,
    PyValueError,
    "Bad input to the library: a NaN, an array of the wrong shape, a negative modulus. \
     Attributes: key (the argument or field), value (as given), allowed (what it must be)."
);

/// A scene's error as Python's exception: a missing or unreadable file as `OSError`
/// (`FileNotFoundError` when it is not there), every other as [`SceneError`] with its place.
pub fn scene_error(py: Python<'_>, e: contopt_scene::SceneError) -> PyErr {
    match e {
        contopt_scene::SceneError::Io { file, source } => {
            let text = format!("{}: {source}", file.display());
            let path = file.display().to_string();
            if source.kind() == std::io::ErrorKind::NotFound {
                PyFileNotFoundError::new_err((2, text, path))
            } else {
                PyOSError::new_err((source.raw_os_error().unwrap_or(0), text, path))
            }
        }
        contopt_scene::SceneError::Invalid(located) => {
            let err = SceneError::new_err(located.to_string());
            let (line, column) = located.place.unzip();
            let (value, allowed) = match &located.field {
                Some(field) => (Some(field.value.clone()), field.allowed.clone()),
                None => (None, located.message.clone()),
            };
            let instance = err.value(py);
            let attributes: [(&str, Py<PyAny>); 8] = [
                (
                    "file",
                    located
                        .file
                        .display()
                        .to_string()
                        .into_py_any(py)
                        .unwrap_or_else(|_| py.None()),
                ),
                ("line", line.into_py_any(py).unwrap_or_else(|_| py.None())),
                (
                    "column",
                    column.into_py_any(py).unwrap_or_else(|_| py.None()),
                ),
                (
                    "case",
                    located
                        .case
                        .clone()
                        .into_py_any(py)
                        .unwrap_or_else(|_| py.None()),
                ),
                (
                    "key",
                    located
                        .path
                        .clone()
                        .into_py_any(py)
                        .unwrap_or_else(|_| py.None()),
                ),
                ("value", value.into_py_any(py).unwrap_or_else(|_| py.None())),
                (
                    "allowed",
                    allowed.into_py_any(py).unwrap_or_else(|_| py.None()),
                ),
                (
                    "message",
                    located
                        .message
                        .clone()
                        .into_py_any(py)
                        .unwrap_or_else(|_| py.None()),
                ),
            ];
            set_all(instance, attributes);
            err
        }
    }
}

/// The library's error as [`InputError`] (bad input) with the field, its value and what it
/// must be when it names them.
pub fn library_error(py: Python<'_>, e: contopt_core::Error) -> PyErr {
    let err = InputError::new_err(e.to_string());
    let (key, value, allowed) = match e.field_error() {
        Some(f) => (Some(f.field), Some(f.value), f.allowed),
        None => (None, None, e.to_string()),
    };
    let attributes: [(&str, Py<PyAny>); 3] = [
        ("key", key.into_py_any(py).unwrap_or_else(|_| py.None())),
        ("value", value.into_py_any(py).unwrap_or_else(|_| py.None())),
        (
            "allowed",
            allowed.into_py_any(py).unwrap_or_else(|_| py.None()),
        ),
    ];
    set_all(err.value(py), attributes);
    err
}

/// Bad input named by the binding itself (an array's shape, a missing argument).
pub fn invalid(py: Python<'_>, key: &str, value: impl std::fmt::Display, allowed: &str) -> PyErr {
    library_error(py, contopt_core::Error::invalid(key, value, allowed))
}

/// Sets each attribute on an exception instance (which always takes them).
fn set_all<const N: usize>(
    instance: &Bound<'_, pyo3::exceptions::PyBaseException>,
    attributes: [(&str, Py<PyAny>); N],
) {
    for (name, value) in attributes {
        let _ = instance.setattr(name, value);
    }
}
