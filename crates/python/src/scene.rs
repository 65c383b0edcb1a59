//! Scenes from Python: read from a file, TOML text, a dict or a bundled name (with edits, as
//! `[[case]] set` makes them), checked as they are read, and run with the GIL released.

use std::path::PathBuf;

use contopt_scene::{Format, BUNDLED};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{from_python, toml_text};
use crate::errors::{invalid, scene_error};
use crate::kinds::{raised, Failure, Registry};
use crate::report::Report;
use crate::watch::watched;

/// A scene: its cases read and checked (every error a `SceneError` with its place). Lengths in
/// mm, moduli and pressures in MPa, forces in N, as in scene files.
#[pyclass(module = "contopt", frozen)]
pub struct Scene {
    scene: contopt_scene::Scene,
    /// Where the factories of the kinds added from Python keep their exceptions.
    failures: Vec<Failure>,
}

/// The registry a scene is read with (the standard one by default) and its factories' slots.
fn chosen(registry: Option<PyRef<'_, Registry>>) -> (contopt_scene::Registry, Vec<Failure>) {
    match registry {
        Some(r) => (r.registry.clone(), r.failures.clone()),
        None => (contopt_scene::Registry::standard(), vec![]),
    }
}

/// Edits `{dotted key: value}` as the library takes them: (key, TOML text), or no text for
/// None (the key removed).
fn edits_of(edits: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, Option<String>)>> {
    let Some(edits) = edits else {
        return Ok(vec![]);
    };
    edits
        .iter()
        .map(|(key, value)| {
            let key: String = key.extract()?;
            let text = match value.is_none() {
                true => None,
                false => Some(toml_text(&value, &key)?),
            };
            Ok((key, text))
        })
        .collect()
}

/// The edits borrowed as the library's `(&str, Option<&str>)` pairs.
fn borrowed(edits: &[(String, Option<String>)]) -> Vec<(&str, Option<&str>)> {
    edits
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_deref()))
        .collect()
}

#[pymethods]
impl Scene {
    /// Reads and checks a scene file (TOML, or JSON when its name ends in `.json`); the files
    /// it names are read from its folder. `registry` has the kinds it may name (by default
    /// the library's).
    #[staticmethod]
    #[pyo3(signature = (path, *, registry=None))]
    fn from_file(
        py: Python<'_>,
        path: PathBuf,
        registry: Option<PyRef<'_, Registry>>,
    ) -> PyResult<Self> {
        let (registry, failures) = chosen(registry);
        let scene = py.detach(|| registry.load(&path));
        Self::made(py, scene, failures)
    }

    /// Reads and checks scene text in TOML, with `edits` (`{"contact.load.force_n": 500.0}`;
    /// None removes a top-level key) made first; `file` names it in messages and its folder is
    /// where the files it names are read.
    #[staticmethod]
    #[pyo3(
        signature = (text, *, edits=None, file=PathBuf::from("scene.toml"), registry=None),
        text_signature = "(text, *, edits=None, file='scene.toml', registry=None)"
    )]
    fn from_toml(
        py: Python<'_>,
        text: &str,
        edits: Option<&Bound<'_, PyDict>>,
        file: PathBuf,
        registry: Option<PyRef<'_, Registry>>,
    ) -> PyResult<Self> {
        let edits = edits_of(edits)?;
        let (registry, failures) = chosen(registry);
        let scene = py.detach(|| registry.parse_with(text, Format::Toml, &file, &borrowed(&edits)));
        Self::made(py, scene, failures)
    }

    /// Reads and checks a scene given as a dict (the tables of a scene file as dicts, its
    /// arrays of tables as lists); `file` names it in messages.
    #[staticmethod]
    #[pyo3(
        signature = (data, *, file=PathBuf::from("<dict>"), registry=None),
        text_signature = "(data, *, file='<dict>', registry=None)"
    )]
    fn from_dict(
        py: Python<'_>,
        data: &Bound<'_, PyDict>,
        file: PathBuf,
        registry: Option<PyRef<'_, Registry>>,
    ) -> PyResult<Self> {
        let json = from_python(data.as_any(), "data")?;
        let text = serde_json::to_string_pretty(&json)
            .map_err(|e| invalid(py, "data", "?", &e.to_string()))?;
        let (registry, failures) = chosen(registry);
        let scene = py.detach(|| registry.parse(&text, Format::Json, &file));
        Self::made(py, scene, failures)
    }

    /// The bundled scene `name` (one of `Scene.bundled_names()`), with `edits` as in
    /// `from_toml`.
    #[staticmethod]
    #[pyo3(signature = (name, *, edits=None))]
    fn bundled(py: Python<'_>, name: &str, edits: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let edits = edits_of(edits)?;
        let registry = contopt_scene::Registry::standard();
        let scene = py.detach(|| registry.bundled_with(name, &borrowed(&edits)));
        Self::made(py, scene, vec![])
    }

    /// The bundled scenes' names (`contopt list`).
    #[staticmethod]
    fn bundled_names() -> Vec<&'static str> {
        BUNDLED.iter().map(|b| b.name).collect()
    }

    /// The text of the bundled scene `name` (`contopt show`).
    #[staticmethod]
    fn bundled_text(py: Python<'_>, name: &str) -> PyResult<&'static str> {
        match BUNDLED.iter().find(|b| b.name == name) {
            Some(b) => Ok(b.text),
            None => Err(invalid(
                py,
                "name",
                name,
                &format!("one of {}", Self::bundled_names().join(", ")),
            )),
        }
    }

    /// The scene's name, which names its results folder.
    #[getter]
    fn name(&self) -> &str {
        &self.scene.name
    }

    /// What it shows.
    #[getter]
    fn description(&self) -> &str {
        &self.scene.description
    }

    /// Where it came from.
    #[getter]
    fn file(&self) -> PathBuf {
        self.scene.file.clone()
    }

    /// The cases' labels, in order.
    #[getter]
    fn cases(&self) -> Vec<String> {
        self.scene.cases().iter().map(|c| c.label.clone()).collect()
    }

    /// What the check found for each case (`contopt check`): its label, the keys it changes,
    /// the memory it needs as estimated before anything is built and the limit [bytes].
    /// Every case was checked when the scene was read: an error was raised then.
    fn check<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        self.scene
            .cases()
            .iter()
            .map(|case| {
                let d = PyDict::new(py);
                d.set_item("label", &case.label)?;
                d.set_item("params", case.params.clone())?;
                d.set_item("memory_estimate_bytes", case.memory().estimate_bytes)?;
                d.set_item("memory_limit_bytes", case.memory().limit_bytes)?;
                Ok(d)
            })
            .collect()
    }

    /// Runs every case on `threads` threads (cases, and a case's independent contacts, at
    /// once; the results are the same for any number) with the GIL released, calling
    /// `progress(Progress)` on this thread as the run moves (at most 20 times a second).
    /// Ctrl-C, or an exception the callback raises, stops the run at its next iteration and
    /// is raised once it has ended; a bad case raises `SceneError`.
    #[pyo3(signature = (*, threads=1, progress=None))]
    fn run(
        &self,
        py: Python<'_>,
        threads: usize,
        progress: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Report> {
        if threads == 0 {
            return Err(invalid(py, "threads", 0, "a whole number ≥ 1"));
        }
        let scene = &self.scene;
        let cases = scene.cases().len();
        let ran = watched(py, progress, cases, |watch| {
            let done = || watch.case_done();
            scene.run_parallel_observed(0..cases, threads, watch, &done)
        })?
        .map_err(|e| self.error(py, e))?;
        let cases = ran
            .results
            .into_iter()
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| self.error(py, e))?;
        Ok(Report::new(contopt_results::Report {
            schema_version: contopt_results::SCHEMA_VERSION,
            scene: scene.name.clone(),
            description: scene.description.clone(),
            cases,
        }))
    }

    fn __repr__(&self) -> String {
        format!(
            "Scene(name={:?}, file={:?}, cases={})",
            self.scene.name,
            self.scene.file.display().to_string(),
            self.scene.cases().len()
        )
    }
}

impl Scene {
    fn made(
        py: Python<'_>,
        scene: Result<contopt_scene::Scene, contopt_scene::SceneError>,
        failures: Vec<Failure>,
    ) -> PyResult<Self> {
        scene
            .map(|scene| Self { scene, failures })
            .map_err(|e| scene_error(py, e))
    }

    /// A run's error: the exception a factory of a kind added from Python raised, as itself,
    /// or the scene's error.
    fn error(&self, py: Python<'_>, e: contopt_scene::SceneError) -> PyErr {
        raised(&self.failures).unwrap_or_else(|| scene_error(py, e))
    }
}
