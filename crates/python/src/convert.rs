//! Values between Python and the library: JSON trees (settings, reports) through Python's
//! `json` module, numpy arrays checked for shape and finiteness, and scene edits as TOML text.

use numpy::{
    PyArray1, PyArrayMethods, PyReadonlyArray2, PyReadonlyArrayDyn, PyUntypedArrayMethods,
};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

use crate::errors::invalid;

/// A JSON value as Python's objects (dict, list, str, int, float, bool, None).
pub fn to_python<'py>(py: Python<'py>, value: &serde_json::Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// A Python object as JSON, through `json.dumps` (NaN refused, as JSON has none).
pub fn from_python(value: &Bound<'_, PyAny>, key: &str) -> PyResult<serde_json::Value> {
    let py = value.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("allow_nan", false)?;
    let text: String = py
        .import("json")?
        .call_method("dumps", (value,), Some(&kwargs))
        .and_then(|t| t.extract())
        .map_err(|e| invalid(py, key, value_text(value), &format!("JSON data: {e}")))?;
    serde_json::from_str(&text).map_err(|e| invalid(py, key, text, &e.to_string()))
}

/// A short text of a Python value for messages.
fn value_text(value: &Bound<'_, PyAny>) -> String {
    let text = value
        .repr()
        .map(|r| r.to_string())
        .unwrap_or_else(|_| "?".into());
    match text.char_indices().nth(80) {
        Some((cut, _)) => format!("{}…", &text[..cut]),
        None => text,
    }
}

/// A float array of the exact `shape` (any layout; copied to C order), every value finite:
/// its values in C order.
pub fn finite_array(array: &Bound<'_, PyAny>, key: &str, shape: &[usize]) -> PyResult<Vec<f64>> {
    let py = array.py();
    let allowed = format!("a float array of shape {shape:?}");
    let array: PyReadonlyArrayDyn<'_, f64> = match array.extract() {
        Ok(a) => a,
        Err(_) => {
            let numpy = py.import("numpy")?;
            let converted = numpy
                .call_method1("asarray", (array, "float64"))
                .map_err(|_| invalid(py, key, value_text(array), &allowed))?;
            converted
                .extract()
                .map_err(|_| invalid(py, key, value_text(array), &allowed))?
        }
    };
    if array.shape() != shape {
        return Err(invalid(
            py,
            key,
            format!("an array of shape {:?}", array.shape()),
            &allowed,
        ));
    }
    let values: Vec<f64> = array.as_array().iter().copied().collect();
    if let Some(k) = values.iter().position(|v| !v.is_finite()) {
        let at = unravel(k, shape);
        return Err(invalid(
            py,
            &format!("{key}{at:?}"),
            values[k],
            "finite values only",
        ));
    }
    Ok(values)
}

/// `read` given a 2-D float array as its shape (rows, columns) and its entries in row-major
/// order, borrowed from numpy without a copy when it is already a C-ordered float64 array
/// (numpy makes one otherwise): a large matrix is checked (its size, its memory) before the
/// library allocates anything of its own.
pub fn with_matrix<T>(
    matrix: &Bound<'_, PyAny>,
    key: &str,
    read: impl FnOnce([usize; 2], &[f64]) -> T,
) -> PyResult<T> {
    let py = matrix.py();
    let allowed = "a 2-D float array";
    let contiguous = py
        .import("numpy")?
        .call_method1("ascontiguousarray", (matrix, "float64"))
        .map_err(|_| invalid(py, key, value_text(matrix), allowed))?;
    let array: PyReadonlyArray2<'_, f64> = contiguous.extract().map_err(|_| {
        let ndim: usize = contiguous
            .getattr("ndim")
            .and_then(|d| d.extract())
            .unwrap_or(0);
        invalid(py, key, format!("an array of {ndim} dimensions"), allowed)
    })?;
    let shape = [array.shape()[0], array.shape()[1]];
    let entries = array
        .as_slice()
        .map_err(|e| invalid(py, key, value_text(matrix), &e.to_string()))?;
    Ok(read(shape, entries))
}

/// The index of the `k`-th value in C order of an array of `shape`.
fn unravel(mut k: usize, shape: &[usize]) -> Vec<usize> {
    let mut index = vec![0; shape.len()];
    for (i, n) in shape.iter().enumerate().rev() {
        index[i] = k % n.max(&1);
        k /= n.max(&1);
    }
    index
}

/// `values` as a numpy array of `shape` (C order).
pub fn array<'py>(
    py: Python<'py>,
    values: Vec<f64>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    let flat = PyArray1::from_vec(py, values);
    Ok(flat.reshape(shape.to_vec())?.into_any())
}

/// A Python value as TOML text for a scene edit (`{"contact.load.force_n": 500.0}`): numbers,
/// booleans, strings, lists and dicts (as inline tables).
pub fn toml_text(value: &Bound<'_, PyAny>, key: &str) -> PyResult<String> {
    let py = value.py();
    let bad = || {
        invalid(
            py,
            key,
            value_text(value),
            "a number, bool, str, list or dict",
        )
    };
    if value.is_instance_of::<PyBool>() {
        return Ok(if value.extract::<bool>()? {
            "true"
        } else {
            "false"
        }
        .into());
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(value.extract::<i64>().map_err(|_| bad())?.to_string());
    }
    if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract()?;
        return Ok(match x {
            x if x.is_nan() => "nan".into(),
            x if x.is_infinite() => if x > 0.0 { "inf" } else { "-inf" }.into(),
            x => format!("{x:?}"),
        });
    }
    if let Ok(text) = value.cast::<PyString>() {
        let text = serde_json::Value::String(text.to_string());
        return Ok(text.to_string());
    }
    if value.is_instance_of::<PyList>() || value.is_instance_of::<PyTuple>() {
        let items = value
            .try_iter()?
            .map(|item| toml_text(&item?, key))
            .collect::<PyResult<Vec<_>>>()?;
        return Ok(format!("[{}]", items.join(", ")));
    }
    if let Ok(dict) = value.cast::<PyDict>() {
        let mut items = vec![];
        for (k, v) in dict.iter() {
            let name = serde_json::Value::String(k.str()?.to_string()).to_string();
            items.push(format!("{name} = {}", toml_text(&v, key)?));
        }
        return Ok(format!("{{ {} }}", items.join(", ")));
    }
    Err(bad())
}
