//! How a method ended, as Python sees it: the kind (`"converged"`, `"step_limit"`,
//! `"stopped"`, …, the `kind` of `result.json`'s `termination`), its details and the sentence.

use pyo3::prelude::*;

use crate::convert::to_python;

/// How a method ended: `kind` as in `result.json` (`"converged"`, `"reduced_accuracy"`,
/// `"step_limit"`, `"stalled"`, `"non_finite"`, `"large_displacement"`, `"infeasible"`,
/// `"unbounded"`, `"stopped"`, `"inner"`), its `details` and the `message`.
#[pyclass(module = "contopt", frozen)]
#[derive(Clone)]
pub struct Termination {
    termination: contopt_core::Termination,
}

impl From<&contopt_core::Termination> for Termination {
    fn from(termination: &contopt_core::Termination) -> Self {
        Self {
            termination: termination.clone(),
        }
    }
}

impl Termination {
    fn json(&self) -> serde_json::Map<String, serde_json::Value> {
        match serde_json::to_value(&self.termination) {
            Ok(serde_json::Value::Object(map)) => map,
            _ => serde_json::Map::new(),
        }
    }
}

#[pymethods]
impl Termination {
    /// The kind.
    #[getter]
    fn kind(&self) -> String {
        let kind = self.json().remove("kind");
        kind.and_then(|k| k.as_str().map(str::to_string))
            .unwrap_or_default()
    }

    /// Whether the method met its tolerance.
    #[getter]
    fn converged(&self) -> bool {
        self.termination.is_converged()
    }

    /// Its fields besides the kind (`steps`, `measure`, `tolerance`, `after`, …).
    #[getter]
    fn details<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let mut map = self.json();
        map.remove("kind");
        to_python(py, &serde_json::Value::Object(map))
    }

    /// The sentence that says how it ended.
    #[getter]
    fn message(&self) -> String {
        self.termination.to_string()
    }

    fn __str__(&self) -> String {
        self.termination.to_string()
    }

    fn __repr__(&self) -> String {
        format!(
            "Termination(kind={:?}, message={:?})",
            self.kind(),
            self.message()
        )
    }

    fn __eq__(&self, other: &Self) -> bool {
        self.termination == other.termination
    }
}
