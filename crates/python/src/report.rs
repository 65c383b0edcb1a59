//! A run's results as Python objects, with the names and units of `result.json` (one schema,
//! `contopt schema`): a [`Report`] of [`CaseResult`]s, each case's interface fields as numpy
//! arrays.

use std::path::PathBuf;

use contopt_results::CaseReport;
use pyo3::exceptions::{PyAttributeError, PyOSError, PyRuntimeError};
use pyo3::prelude::*;

use crate::convert::{array, to_python};
use crate::termination::Termination;

/// What a run gives: `result.json`'s report. `to_json()` is `contopt run --json`'s output.
#[pyclass(module = "contopt", frozen)]
pub struct Report {
    report: contopt_results::Report,
}

impl Report {
    pub fn new(report: contopt_results::Report) -> Self {
        Self { report }
    }

    fn json(&self) -> PyResult<serde_json::Value> {
        serde_json::to_value(&self.report).map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }
}

#[pymethods]
impl Report {
    /// The scene's name.
    #[getter]
    fn scene(&self) -> &str {
        &self.report.scene
    }

    /// What the scene shows.
    #[getter]
    fn description(&self) -> &str {
        &self.report.description
    }

    /// The version of `result.json`'s schema.
    #[getter]
    fn schema_version(&self) -> u32 {
        self.report.schema_version
    }

    /// The cases' results, in the scene's order.
    #[getter]
    fn cases(&self) -> Vec<CaseResult> {
        let cases = self.report.cases.iter().cloned();
        cases.map(|case| CaseResult { case }).collect()
    }

    /// Whether every case was solved within the model's limits (`contopt run`'s exit 0).
    #[getter]
    fn solved(&self) -> bool {
        self.report.cases.iter().all(CaseReport::is_solved)
    }

    /// The report as JSON text: exactly what `contopt run --json` prints (without its final
    /// newline).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string_pretty(&self.report)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))
    }

    /// The report as dicts and lists (`json.loads(to_json())`).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &self.json()?)
    }

    /// Writes the files `contopt run` writes into `out/<scene>/` (`result.json`,
    /// `interface.csv`, the charts, each case's fields) and returns that folder.
    #[pyo3(signature = (out=PathBuf::from("results")), text_signature = "(self, /, out='results')")]
    fn write(&self, py: Python<'_>, out: PathBuf) -> PyResult<PathBuf> {
        let report = &self.report;
        let written = py.detach(|| contopt_cli::write_results(report, &out));
        match written {
            Ok(dir) => Ok(dir),
            Err(e) => Err(PyOSError::new_err(format!(
                "could not write the results to {}: {e}",
                out.join(&report.scene).display()
            ))),
        }
    }

    fn __len__(&self) -> usize {
        self.report.cases.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Report(scene={:?}, cases={})",
            self.report.scene,
            self.report.cases.len()
        )
    }
}

/// One case's results: every key of its entry in `result.json`'s `cases` as an attribute
/// (`p_max_mpa`, `dh_max_um`, `approach_um`, `hertz`, `bearing`, …, as dicts and lists), the
/// termination typed, and the interface's fields as numpy arrays of shape (n,) — (n, 3) for
/// the points — in the order of `result.json`'s `interface` (a grid's cells x fastest, a
/// ring's or a strip's points outwards).
#[pyclass(module = "contopt", frozen)]
pub struct CaseResult {
    case: CaseReport,
}

impl CaseResult {
    fn column<'py>(
        &self,
        py: Python<'py>,
        value: impl Fn(&contopt_results::Point) -> f64,
    ) -> PyResult<Bound<'py, PyAny>> {
        let values: Vec<f64> = self.case.interface.iter().map(value).collect();
        let n = values.len();
        array(py, values, &[n])
    }
}

#[pymethods]
impl CaseResult {
    /// Its label.
    #[getter]
    fn label(&self) -> &str {
        &self.case.label
    }

    /// Whether it was solved within the model's limits.
    #[getter]
    fn solved(&self) -> bool {
        self.case.is_solved()
    }

    /// How its method ended.
    #[getter]
    fn termination(&self) -> Termination {
        Termination::from(&self.case.termination)
    }

    /// The interface points x [mm], shape (n, 3).
    #[getter]
    fn x_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let values: Vec<f64> = self.case.interface.iter().flat_map(|p| p.x_mm).collect();
        array(py, values, &[self.case.interface.len(), 3])
    }

    /// The contact pressure p [MPa], shape (n,).
    #[getter]
    fn p_mpa<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.column(py, |p| p.p_mpa)
    }

    /// The gap after deformation d [µm], shape (n,).
    #[getter]
    fn d_um<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.column(py, |p| p.d_um)
    }

    /// The designed change of the initial gap Δh [µm], shape (n,).
    #[getter]
    fn dh_um<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.column(py, |p| p.dh_um)
    }

    /// The initial gap h [µm], shape (n,).
    #[getter]
    fn h_um<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.column(py, |p| p.h_um)
    }

    /// The case as dicts and lists: its entry in `result.json`'s `cases`.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let json =
            serde_json::to_value(&self.case).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        to_python(py, &json)
    }

    /// Any other key of the case's entry in `result.json`.
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let json =
            serde_json::to_value(&self.case).map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        match json.get(name) {
            Some(value) => to_python(py, value),
            None => Err(PyAttributeError::new_err(format!(
                "a case's results have no {name:?} (the keys of result.json's cases, `contopt schema`)"
            ))),
        }
    }

    fn __repr__(&self) -> String {
        format!(
            "CaseResult(label={:?}, termination={})",
            self.case.label, self.case.termination
        )
    }
}
