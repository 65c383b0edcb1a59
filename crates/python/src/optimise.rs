//! The optimisation of the initial gap (§3 of Páczelt 1994) from numpy: the controller's
//! values v at the grid's cells, the design's gap shape (every cell its own node, a profile
//! along x or y, or a matrix Q of numpy), Ω_v and Ω_opt as masks, and any of the library's
//! methods with its settings and defaults.

use contopt_core::GapShape;
use contopt_optimise::{Optimisation, OptimisationMethod, Optimum as Found};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{array, finite_array, from_python, to_python};
use crate::errors::{invalid, library_error};
use crate::library::{Contact, Solver};
use crate::termination::Termination;
use crate::watch::watched_here;

/// The methods, as scenes name them.
const METHODS: [&str; 4] = [
    "given_load",
    "given_displacement",
    "linear_programme",
    "load_split",
];

/// The gap shape Q: `None` every cell its own design node; `"x"` one node per column (a
/// profile along x, the same change across y), `"y"` one per row; or a float matrix of shape
/// (cells, nodes) in the cells' C order, its nodes placed at their rows' weighted centres.
fn gap_shape(
    py: Python<'_>,
    given: Option<&Bound<'_, PyAny>>,
    contact: &Contact,
) -> PyResult<GapShape> {
    let points = contact.points();
    let [ny, nx] = contact.grid();
    let along = |axis: usize| -> PyResult<GapShape> {
        let count = if axis == 0 { nx } else { ny };
        let node_of = |k: usize| if axis == 0 { k % nx } else { k / nx };
        let nodes = (0..count)
            .map(|m| {
                let k = if axis == 0 { m } else { m * nx };
                let mut x = points[k];
                x[1 - axis] = 0.0;
                x
            })
            .collect();
        let rows = (0..points.len()).map(|k| vec![(node_of(k), 1.0)]).collect();
        GapShape::new(nodes, rows).map_err(|e| library_error(py, e))
    };
    let Some(given) = given.filter(|g| !g.is_none()) else {
        let rows = (0..points.len()).map(|k| vec![(k, 1.0)]).collect();
        return GapShape::new(points.to_vec(), rows).map_err(|e| library_error(py, e));
    };
    if let Ok(axis) = given.extract::<String>() {
        return match axis.as_str() {
            "x" => along(0),
            "y" => along(1),
            _ => Err(invalid(
                py,
                "gap_shape",
                axis,
                "None, \"x\", \"y\" or a matrix",
            )),
        };
    }
    let columns = given
        .getattr("shape")
        .and_then(|s| s.extract::<(usize, usize)>())
        .map_err(|_| invalid(py, "gap_shape", "?", "None, \"x\", \"y\" or a 2-D matrix"))?
        .1;
    let q = finite_array(given, "gap_shape", &[points.len(), columns])?;
    let rows: Vec<Vec<(usize, f64)>> = q
        .chunks(columns.max(1))
        .map(|row| {
            row.iter()
                .enumerate()
                .filter(|(_, w)| **w != 0.0)
                .map(|(m, w)| (m, *w))
                .collect()
        })
        .collect();
    let nodes = (0..columns)
        .map(|m| {
            let (mut centre, mut total) = ([0.0; 3], 0.0);
            for (k, row) in rows.iter().enumerate() {
                for &(_, w) in row.iter().filter(|(node, _)| *node == m) {
                    (0..3).for_each(|c| centre[c] += w.abs() * points[k][c]);
                    total += w.abs();
                }
            }
            centre.map(|c| if total > 0.0 { c / total } else { 0.0 })
        })
        .collect();
    GapShape::new(nodes, rows).map_err(|e| library_error(py, e))
}

/// A mask of the grid's shape (booleans, or the numbers 0 and 1), or all points. Any other
/// number is refused with its index: a controller's 0.8 given as Ω_v is no mask.
fn mask(given: Option<&Bound<'_, PyAny>>, key: &str, shape: [usize; 2]) -> PyResult<Vec<bool>> {
    let Some(m) = given else {
        return Ok(vec![true; shape[0] * shape[1]]);
    };
    let values = finite_array(m, key, &shape)?;
    if let Some(k) = values.iter().position(|&f| f != 0.0 && f != 1.0) {
        let at = [k / shape[1], k % shape[1]];
        return Err(invalid(
            m.py(),
            &format!("{key}{at:?}"),
            values[k],
            "a boolean mask (True/False, or 1/0)",
        ));
    }
    Ok(values.iter().map(|&f| f == 1.0).collect())
}

/// The optimum initial gap of `contact` under the controller's values `v` (shape (ny, nx), the
/// bound p ≤ v·p_max): the gap change Δh ≥ 0 through `gap_shape`, on Ω_v `omega_v` within
/// Ω_opt `omega_opt` (masks of the grid's shape, all cells by default), by `method` (one of
/// `given_load`, `given_displacement`, `linear_programme`, `load_split`) with `settings` (each
/// with the library's default), its contact solves by `solver` (auto by default), with the GIL
/// released. An optimisation that stops short is returned with its termination.
#[pyfunction]
#[pyo3(signature = (contact, v, *, method="load_split", solver=None, gap_shape=None, omega_v=None, omega_opt=None, **settings))]
#[allow(clippy::too_many_arguments)]
pub fn optimise(
    py: Python<'_>,
    contact: &Contact,
    v: &Bound<'_, PyAny>,
    method: &str,
    solver: Option<&Solver>,
    gap_shape: Option<&Bound<'_, PyAny>>,
    omega_v: Option<&Bound<'_, PyAny>>,
    omega_opt: Option<&Bound<'_, PyAny>>,
    settings: Option<&Bound<'_, PyDict>>,
) -> PyResult<Optimum> {
    if !METHODS.contains(&method) {
        return Err(invalid(
            py,
            "method",
            method,
            &format!("one of {}", METHODS.join(", ")),
        ));
    }
    let given = match settings {
        Some(s) if !s.is_empty() => from_python(s.as_any(), "settings")?,
        _ => serde_json::json!({}),
    };
    let chosen: OptimisationMethod = serde_json::from_value(serde_json::json!({ method: given }))
        .map_err(|e| {
        invalid(
            py,
            &format!("optimisation.{method}"),
            &given,
            &e.to_string(),
        )
    })?;
    let shape = contact.grid();
    let values = finite_array(v, "v", &shape)?;
    let (omega_v, omega_opt) = (
        mask(omega_v, "omega_v", shape)?,
        mask(omega_opt, "omega_opt", shape)?,
    );
    let q = self::gap_shape(py, gap_shape, contact)?;
    let auto;
    let solver = match solver {
        Some(s) => s.solver(),
        None => {
            auto = contopt_contact::SolverSettings::Auto
                .build()
                .map_err(|e| library_error(py, e))?;
            auto.as_ref()
        }
    };
    let problem = contact.problem();
    let index = contact.indexer();
    let controller = |x: [f64; 3]| values[index(x)];
    let found = watched_here(py, |watch| {
        Optimisation::new(problem, &q, &controller)
            .and_then(|o| o.with_omega(&omega_v, &omega_opt))
            .and_then(|o| chosen.run(&o.with_observer(watch), solver))
    })?
    .map_err(|e| library_error(py, e))?;
    let warnings = contact.cells().warnings(&found.pressure);
    crate::edge::warn(py, &warnings)?;
    Ok(Optimum {
        found,
        shape,
        warnings,
    })
}

/// An optimisation's answer: p_max, the gap change, the pressure and the gap on the grid.
#[pyclass(module = "contopt", frozen)]
pub struct Optimum {
    found: Found,
    shape: [usize; 2],
    /// The model's limits the answer reached (a contact cut by the grid's edge).
    warnings: Vec<String>,
}

#[pymethods]
impl Optimum {
    /// The least largest pressure p_max [MPa].
    #[getter]
    fn p_max_mpa(&self) -> f64 {
        self.found.p_max
    }

    /// The gap change at the design nodes Δh ≥ 0 [mm], shape (nodes,).
    #[getter]
    fn dh_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.found.dh.clone(), &[self.found.dh.len()])
    }

    /// The largest gap change Δh_max [mm].
    #[getter]
    fn dh_max_mm(&self) -> f64 {
        self.found.dh_max()
    }

    /// The gap change at the cells QΔh [mm], shape (ny, nx).
    #[getter]
    fn gap_change_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.found.gap_change.clone(), &self.shape)
    }

    /// The contact pressure [MPa], shape (ny, nx).
    #[getter]
    fn pressure_mpa<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.found.pressure.clone(), &self.shape)
    }

    /// The gap after deformation, the gap change included [mm], shape (ny, nx).
    #[getter]
    fn gap_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.found.gap.clone(), &self.shape)
    }

    /// The passes of the method.
    #[getter]
    fn passes(&self) -> usize {
        self.found.passes.len()
    }

    /// The method that found it (`"load_split"`, `"gap_iteration"`, …).
    #[getter]
    fn method(&self) -> &'static str {
        self.found.method.id()
    }

    /// How it ended.
    #[getter]
    fn termination(&self) -> Termination {
        Termination::from(&self.found.termination)
    }

    /// Whether it met its tolerance.
    #[getter]
    fn converged(&self) -> bool {
        self.found.is_converged()
    }

    /// The model's limits the answer reached, each a sentence (a contact that reaches the
    /// edge of a grid that is not periodic, one on too few cells, a peak at a sharp edge);
    /// each is also raised as a `RuntimeWarning`.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The default settings of the method `kind`.
    #[staticmethod]
    fn defaults<'py>(py: Python<'py>, kind: &str) -> PyResult<Bound<'py, PyAny>> {
        let settings: OptimisationMethod = serde_json::from_value(serde_json::json!({ kind: {} }))
            .map_err(|_| {
                invalid(
                    py,
                    "method",
                    kind,
                    &format!("one of {}", METHODS.join(", ")),
                )
            })?;
        let json = serde_json::to_value(settings).unwrap_or_default();
        let values = json.get(kind).cloned().unwrap_or_default();
        to_python(py, &values)
    }

    fn __repr__(&self) -> String {
        format!(
            "Optimum(p_max_mpa={}, dh_max_mm={}, termination={:?})",
            self.found.p_max,
            self.found.dh_max(),
            self.found.termination.to_string()
        )
    }
}
