//! The library below the scenes: an elastic half-space grid, a rigid indenter whose shape is
//! the initial gap given as a numpy array, every contact solver with its settings and
//! defaults, and a solve that returns the pressure, the gap, the approach and how it ended.
//!
//! Units are the library's: lengths in mm, moduli and pressures in MPa, forces in N. A grid's
//! arrays have shape (ny, nx) in C order: `a[j, i]` is the cell at x = x0 + i·dx,
//! y = y0 + j·dy (the library lists points x fastest, so the flat order is the same).

use std::sync::Arc;

use contopt_contact::{ContactSolver, InterfaceProblem, SolverSettings};
use contopt_core::{ContactState, ElasticBody, Material, RigidBody};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{array, finite_array, from_python, to_python};
use crate::dense::DenseBody;
use crate::edge::{warn, Cells};
use crate::errors::{invalid, library_error};
use crate::termination::Termination;
use crate::watch::{watched_here, Watch};

/// An elastic half-space under a regular grid of nx × ny rectangular cells of dx × dy mm
/// (Love's solution per cell, FFT products): the grid of Johnson's eq. 3.25.
#[pyclass(module = "contopt", frozen)]
pub struct HalfSpace {
    body: Arc<contopt_greens::HalfSpace>,
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    origin: [f64; 2],
    material: Material,
    periodic: bool,
}

#[pymethods]
impl HalfSpace {
    /// A half-space of Young's modulus `e_mpa` [MPa] and Poisson's ratio `nu` under `nx` × `ny`
    /// cells of `dx_mm` × `dy_mm` [mm]; the first cell's centre at `origin_mm` (x, y) [mm], or
    /// by default the grid centred on (0, 0). `periodic` repeats the grid both ways.
    #[new]
    #[pyo3(signature = (*, nx, ny, dx_mm, dy_mm, e_mpa, nu, origin_mm=None, periodic=false))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        nx: usize,
        ny: usize,
        dx_mm: f64,
        dy_mm: f64,
        e_mpa: f64,
        nu: f64,
        origin_mm: Option<(f64, f64)>,
        periodic: bool,
    ) -> PyResult<Self> {
        let material = Material::new(e_mpa, nu).map_err(|e| library_error(py, e))?;
        let centred = (
            -0.5 * (nx as f64 - 1.0) * dx_mm,
            -0.5 * (ny as f64 - 1.0) * dy_mm,
        );
        let (x0, y0) = origin_mm.unwrap_or(centred);
        let origin = [x0, y0];
        let make = if periodic {
            contopt_greens::HalfSpace::periodic
        } else {
            contopt_greens::HalfSpace::grid
        };
        let body = py
            .detach(|| make("half-space", material, nx, ny, dx_mm, dy_mm, origin))
            .map_err(|e| library_error(py, e))?;
        Ok(Self {
            body: Arc::new(body),
            nx,
            ny,
            dx: dx_mm,
            dy: dy_mm,
            origin,
            material,
            periodic,
        })
    }

    /// The arrays' shape: (ny, nx).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.ny, self.nx)
    }

    /// The cells' centres' x [mm], shape (ny, nx).
    #[getter]
    fn x_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.coordinate(py, 0)
    }

    /// The cells' centres' y [mm], shape (ny, nx).
    #[getter]
    fn y_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        self.coordinate(py, 1)
    }

    /// The cell's sides (dx, dy) [mm].
    #[getter]
    fn cell_mm(&self) -> (f64, f64) {
        (self.dx, self.dy)
    }

    /// The first cell's centre (x, y) [mm].
    #[getter]
    fn origin_mm(&self) -> (f64, f64) {
        (self.origin[0], self.origin[1])
    }

    /// The area of a cell [mm²]: the weight of its pressure in the force, F = Σ p·A.
    #[getter]
    fn cell_area_mm2(&self) -> f64 {
        self.dx * self.dy
    }

    /// Young's modulus [MPa].
    #[getter]
    fn e_mpa(&self) -> f64 {
        self.material.e()
    }

    /// Poisson's ratio.
    #[getter]
    fn nu(&self) -> f64 {
        self.material.nu()
    }

    /// Whether the grid repeats both ways.
    #[getter]
    fn periodic(&self) -> bool {
        self.periodic
    }

    fn __repr__(&self) -> String {
        format!(
            "HalfSpace(nx={}, ny={}, dx_mm={}, dy_mm={}, e_mpa={}, nu={}, periodic={})",
            self.nx,
            self.ny,
            self.dx,
            self.dy,
            self.material.e(),
            self.material.nu(),
            if self.periodic { "True" } else { "False" }
        )
    }
}

impl HalfSpace {
    fn coordinate<'py>(&self, py: Python<'py>, axis: usize) -> PyResult<Bound<'py, PyAny>> {
        let values = self.body.interface().points().iter().map(|x| x[axis]);
        array(py, values.collect(), &[self.ny, self.nx])
    }
}

/// A body on a grid of cells as a contact takes it: its own copy, the arrays' shape (ny, nx),
/// the first cell's centre and the cell's sides [mm].
struct OnGrid {
    body: Box<dyn ElasticBody>,
    cells: Cells,
}

impl OnGrid {
    /// A `HalfSpace` or a `DenseBody`; a `TypeError` for anything else.
    fn of(body: &Bound<'_, PyAny>) -> PyResult<Self> {
        if let Ok(h) = body.extract::<PyRef<'_, HalfSpace>>() {
            return Ok(Self {
                body: Box::new((*h.body).clone()),
                cells: Cells {
                    shape: [h.ny, h.nx],
                    origin: h.origin,
                    cell: [h.dx, h.dy],
                    grid: Some(h.body.clone()),
                    indenter_ends: [false; 2],
                },
            });
        }
        let d = body.extract::<PyRef<'_, DenseBody>>().map_err(|_| {
            let type_name = body.get_type().name().map(|n| n.to_string());
            PyTypeError::new_err(format!(
                "body: a HalfSpace or a DenseBody, not {}",
                type_name.unwrap_or_else(|_| "?".into())
            ))
        })?;
        Ok(Self {
            body: Box::new((*d.body).clone()),
            cells: Cells {
                shape: [d.ny, d.nx],
                origin: d.origin,
                cell: d.cell,
                grid: None,
                indenter_ends: [false; 2],
            },
        })
    }
}

/// A rigid indenter on a half-space grid or a dense body: its shape is the initial gap h [mm]
/// at each cell (h ≥ 0 where it first touches), pressed by a force `force_n` [N] (the
/// approach follows) or pushed in by `approach_mm` [mm] (the force follows).
#[pyclass(module = "contopt", frozen)]
pub struct Contact {
    problem: InterfaceProblem<'static>,
    /// The grid: its shape (ny, nx), the first cell's centre and the cell's sides [mm].
    cells: Cells,
    area: Vec<f64>,
    approach: Option<f64>,
}

impl Contact {
    /// The contact problem.
    pub(crate) fn problem(&self) -> &InterfaceProblem<'static> {
        &self.problem
    }

    /// The grid's shape (ny, nx).
    pub(crate) fn grid(&self) -> [usize; 2] {
        self.cells.shape
    }

    /// The grid's cells, whose edge a contact must not reach.
    pub(crate) fn cells(&self) -> &Cells {
        &self.cells
    }

    /// The cells' centres, C order.
    pub(crate) fn points(&self) -> &[[f64; 3]] {
        self.problem.interface().points()
    }

    /// The index of the cell whose centre is nearest the point `x` of the grid.
    pub(crate) fn indexer(&self) -> impl Fn([f64; 3]) -> usize + '_ {
        let Cells {
            shape: [ny, nx],
            origin,
            cell,
            ..
        } = self.cells;
        move |x: [f64; 3]| {
            let i = ((x[0] - origin[0]) / cell[0])
                .round()
                .clamp(0.0, (nx - 1) as f64) as usize;
            let j = ((x[1] - origin[1]) / cell[1])
                .round()
                .clamp(0.0, (ny - 1) as f64) as usize;
            j * nx + i
        }
    }
}

#[pymethods]
impl Contact {
    /// The contact of `body` (a `HalfSpace` or a `DenseBody`) with a rigid indenter whose gap
    /// to it is `gap_mm`, shape (ny, nx) [mm]; give exactly one of `force_n` [N] and
    /// `approach_mm` [mm]. `indenter_ends` (`"x"`, `"y"` or `"xy"`) says the indenter ends at
    /// the grid's edges along those axes (a roller as long as the grid): a contact that
    /// reaches them is its end, not a grid too small, and is not warned of.
    #[new]
    #[pyo3(signature = (body, gap_mm, *, force_n=None, approach_mm=None, indenter_ends=None))]
    fn new(
        py: Python<'_>,
        body: &Bound<'_, PyAny>,
        gap_mm: &Bound<'_, PyAny>,
        force_n: Option<f64>,
        approach_mm: Option<f64>,
        indenter_ends: Option<&str>,
    ) -> PyResult<Self> {
        let mut grid = OnGrid::of(body)?;
        let ends = match indenter_ends {
            None => [false; 2],
            Some("x") => [true, false],
            Some("y") => [false, true],
            Some("xy") => [true; 2],
            Some(other) => {
                return Err(invalid(
                    py,
                    "indenter_ends",
                    other,
                    "\"x\", \"y\" or \"xy\"",
                ));
            }
        };
        grid.cells.indenter_ends = ends;
        let shape = grid.cells.shape;
        let gap = finite_array(gap_mm, "gap_mm", &shape)?;
        let surface = grid.body.interface();
        let (indenter, gap, approach) = match (force_n, approach_mm) {
            (Some(force), None) => {
                let rigid = RigidBody::pressed("indenter", surface, [0.0, 0.0, 1.0], force)
                    .map_err(|e| library_error(py, e))?;
                (rigid, gap, None)
            }
            (None, Some(approach)) if approach.is_finite() => {
                let rigid = RigidBody::fixed("indenter", surface);
                let gap = gap.iter().map(|h| h - approach).collect();
                (rigid, gap, Some(approach))
            }
            (None, Some(approach)) => {
                return Err(invalid(py, "approach_mm", approach, "a finite value"));
            }
            _ => {
                // As Python writes them: None, or the float's repr.
                let python = |v: Option<f64>| v.map_or("None".into(), |v| format!("{v:?}"));
                let given = format!(
                    "{} (and approach_mm = {})",
                    python(force_n),
                    python(approach_mm)
                );
                return Err(invalid(
                    py,
                    "force_n",
                    given,
                    "exactly one of force_n and approach_mm",
                ));
            }
        };
        let area = surface.weights().to_vec();
        let problem = InterfaceProblem::owned(grid.body, Box::new(indenter), &gap)
            .map_err(|e| library_error(py, e))?;
        Ok(Self {
            area,
            problem,
            cells: grid.cells,
            approach,
        })
    }

    /// The arrays' shape: (ny, nx).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        let [ny, nx] = self.cells.shape;
        (ny, nx)
    }
}

/// A contact solver and its settings: `Solver("polonsky_keer", tolerance=1e-10)`; every
/// setting not given takes the library's default (`Solver.defaults(kind)`).
#[pyclass(module = "contopt", frozen)]
pub struct Solver {
    settings: SolverSettings,
    solver: Box<dyn ContactSolver>,
}

/// The solvers' kinds, as scenes name them.
const KINDS: [&str; 6] = [
    "auto",
    "qp",
    "active_set",
    "penalty",
    "augmented_lagrangian",
    "polonsky_keer",
];

/// The default settings of the solver `kind`: each setting with its default, or None for a
/// setting that has none and must be given (the penalty's `c_mpa_per_mm`).
fn defaults_of(kind: &str) -> Option<serde_json::Map<String, serde_json::Value>> {
    if serde_json::from_value::<SolverSettings>(serde_json::json!(kind)).is_ok() {
        return Some(serde_json::Map::new());
    }
    let mut required: Vec<String> = vec![];
    let mut given = serde_json::Map::new();
    // Each missing setting is given a placeholder in turn, until the settings read.
    for _ in 0..=KINDS.len() {
        let json = serde_json::json!({ kind: given.clone() });
        match serde_json::from_value::<SolverSettings>(json) {
            Ok(settings) => {
                let (_, values) = kind_and_settings(&settings);
                let mut values = values.as_object().cloned().unwrap_or_default();
                for key in &required {
                    values.insert(key.clone(), serde_json::Value::Null);
                }
                return Some(values);
            }
            Err(e) => {
                let message = e.to_string();
                let missing = message.strip_prefix("missing field `")?.split('`').next()?;
                required.push(missing.to_string());
                given.insert(missing.to_string(), serde_json::json!(1.0));
            }
        }
    }
    None
}

/// A solver's kind and settings as a scene writes them.
fn kind_and_settings(settings: &SolverSettings) -> (String, serde_json::Value) {
    match serde_json::to_value(settings) {
        Ok(serde_json::Value::String(kind)) => (kind, serde_json::json!({})),
        Ok(serde_json::Value::Object(map)) => match map.into_iter().next() {
            Some((kind, values)) => (kind, values),
            None => (String::new(), serde_json::Value::Null),
        },
        _ => (String::new(), serde_json::Value::Null),
    }
}

impl Solver {
    /// The library's solver.
    pub(crate) fn solver(&self) -> &dyn ContactSolver {
        self.solver.as_ref()
    }
}

#[pymethods]
impl Solver {
    /// The solver `kind` (one of `Solver.kinds()`) with `settings` (the keys of
    /// `Solver.defaults(kind)`; tolerances are relative, `c_mpa_per_mm` in MPa/mm).
    #[new]
    #[pyo3(signature = (kind="auto", **settings))]
    fn new(py: Python<'_>, kind: &str, settings: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        let given = match settings {
            Some(s) if !s.is_empty() => from_python(s.as_any(), "solver")?,
            _ => serde_json::json!({}),
        };
        let json = match (kind, given.as_object().is_some_and(|m| m.is_empty())) {
            ("auto", true) => serde_json::json!("auto"),
            _ => serde_json::json!({ kind: given }),
        };
        if !KINDS.contains(&kind) {
            return Err(invalid(
                py,
                "kind",
                kind,
                &format!("one of {}", KINDS.join(", ")),
            ));
        }
        let settings: SolverSettings = serde_json::from_value(json)
            .map_err(|e| invalid(py, &format!("solver.{kind}"), &given, &e.to_string()))?;
        let solver = settings.build().map_err(|e| library_error(py, e))?;
        Ok(Self { settings, solver })
    }

    /// The solvers' kinds.
    #[staticmethod]
    fn kinds() -> Vec<&'static str> {
        KINDS.to_vec()
    }

    /// The default settings of the solver `kind`; a setting whose default is None has none
    /// and must be given.
    #[staticmethod]
    fn defaults<'py>(py: Python<'py>, kind: &str) -> PyResult<Bound<'py, PyAny>> {
        match KINDS.contains(&kind).then(|| defaults_of(kind)).flatten() {
            Some(settings) => to_python(py, &serde_json::Value::Object(settings)),
            None => Err(invalid(
                py,
                "kind",
                kind,
                &format!("one of {}", KINDS.join(", ")),
            )),
        }
    }

    /// The solver's kind.
    #[getter]
    fn kind(&self) -> String {
        kind_and_settings(&self.settings).0
    }

    /// Its settings, every default written out.
    #[getter]
    fn settings<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        to_python(py, &kind_and_settings(&self.settings).1)
    }

    /// Solves `contact` (from the pressure `start_mpa`, shape (ny, nx), when given), with the
    /// GIL released; Ctrl-C stops it at its next iteration. A solve that stops short is
    /// returned with its termination, not raised.
    #[pyo3(signature = (contact, *, start_mpa=None))]
    fn solve(
        &self,
        py: Python<'_>,
        contact: &Contact,
        start_mpa: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Solution> {
        let start = match start_mpa {
            Some(s) => Some(finite_array(s, "start_mpa", &contact.cells.shape)?),
            None => None,
        };
        let solver = self.solver.as_ref();
        let problem = &contact.problem;
        let (state, seconds) = watched_here(py, |watch| {
            let clock = std::time::Instant::now();
            let state = solver.solve_observed(problem, start.as_deref(), watch);
            (state, clock.elapsed().as_secs_f64())
        })?;
        let state = state.map_err(|e| library_error(py, e))?;
        let solution = Solution::new(state, contact, seconds);
        warn(py, &solution.warnings)?;
        Ok(solution)
    }

    fn __repr__(&self) -> String {
        format!(
            "Solver({:?}, **{})",
            self.kind(),
            kind_and_settings(&self.settings).1
        )
    }
}

/// The solve of `contact` by `solver` alone, the same call that `Solver.solve` makes, on the
/// calling thread with the GIL held and nothing converted: its time in Rust [s]. It measures
/// what the binding adds to a solve (`crates/python/peers.py --overhead`).
#[pyfunction]
pub fn solve_in_rust(py: Python<'_>, solver: &Solver, contact: &Contact) -> PyResult<f64> {
    let watch = Watch::default();
    let clock = std::time::Instant::now();
    let state = solver.solver.solve_observed(&contact.problem, None, &watch);
    let seconds = clock.elapsed().as_secs_f64();
    state.map(|_| seconds).map_err(|e| library_error(py, e))
}

/// A solve's answer: the pressure and the gap on the grid, the approach, how it ended.
#[pyclass(module = "contopt", frozen)]
pub struct Solution {
    state: ContactState,
    shape: [usize; 2],
    /// Σ p·A [N].
    force: f64,
    /// The area in contact [mm²].
    contact_area: f64,
    approach: Option<f64>,
    /// The solve's own time in Rust [s].
    seconds: f64,
    /// The model's limits the answer reached (a contact cut by the grid's edge, on too few
    /// cells, peaking at a sharp edge).
    warnings: Vec<String>,
}

impl Solution {
    fn new(state: ContactState, contact: &Contact, seconds: f64) -> Self {
        let force = state
            .pressure
            .iter()
            .zip(&contact.area)
            .map(|(p, a)| p * a)
            .sum();
        let contact_area = state
            .active
            .iter()
            .zip(&contact.area)
            .filter(|(c, _)| **c)
            .map(|(_, a)| a)
            .sum();
        Self {
            approach: contact.approach.or(state.approach()),
            warnings: contact.cells.warnings(&state.pressure),
            state,
            shape: contact.cells.shape,
            force,
            contact_area,
            seconds,
        }
    }
}

#[pymethods]
impl Solution {
    /// The contact pressure p [MPa], shape (ny, nx).
    #[getter]
    fn pressure_mpa<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.state.pressure.clone(), &self.shape)
    }

    /// The gap d after deformation [mm], shape (ny, nx): 0 where in contact.
    #[getter]
    fn gap_mm<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        array(py, self.state.gap.clone(), &self.shape)
    }

    /// Whether each cell is in contact, shape (ny, nx).
    #[getter]
    fn contact<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let flags: Vec<f64> = self
            .state
            .active
            .iter()
            .map(|&c| f64::from(u8::from(c)))
            .collect();
        array(py, flags, &self.shape)?.call_method1("astype", ("bool",))
    }

    /// The indenter's approach δ [mm]: solved for under a force, as given under an approach.
    #[getter]
    fn approach_mm(&self) -> Option<f64> {
        self.approach
    }

    /// The force the pressure carries, Σ p·A [N].
    #[getter]
    fn force_n(&self) -> f64 {
        self.force
    }

    /// The area in contact [mm²].
    #[getter]
    fn contact_area_mm2(&self) -> f64 {
        self.contact_area
    }

    /// The largest pressure [MPa].
    #[getter]
    fn p_max_mpa(&self) -> f64 {
        self.state.p_max()
    }

    /// How the solve ended.
    #[getter]
    fn termination(&self) -> Termination {
        Termination::from(&self.state.termination)
    }

    /// Whether it met its tolerance.
    #[getter]
    fn converged(&self) -> bool {
        self.state.is_converged()
    }

    /// The solve's own time in Rust [s], without the call's (the arrays' copies, the thread
    /// it runs on): what the same solve costs from Rust.
    #[getter]
    fn seconds(&self) -> f64 {
        self.seconds
    }

    /// Its iterations.
    #[getter]
    fn iterations(&self) -> usize {
        self.state.iterations
    }

    /// The method that solved it (`"polonsky_keer"`, …; what `auto` chose).
    #[getter]
    fn method(&self) -> &'static str {
        self.state.method.id()
    }

    /// The model's limits the answer reached, each a sentence (a contact that reaches the
    /// edge of a grid that is not periodic: its pressure is wrong; one on too few cells; a
    /// peak at a sharp edge, a punch's rim, whose value depends on the cells); each is also
    /// raised as a `RuntimeWarning`.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.warnings.clone()
    }

    /// The residuals of the answer: equilibrium (relative), penetration [mm] and
    /// complementarity.
    #[getter]
    fn residuals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let r = &self.state.residuals;
        let dict = PyDict::new(py);
        dict.set_item("equilibrium", r.equilibrium)?;
        dict.set_item("penetration", r.penetration)?;
        dict.set_item("complementarity", r.complementarity)?;
        Ok(dict)
    }

    fn __repr__(&self) -> String {
        let approach = self.approach.map_or("None".into(), |a| a.to_string());
        format!(
            "Solution(p_max_mpa={}, force_n={}, approach_mm={approach}, termination={:?})",
            self.state.p_max(),
            self.force,
            self.state.termination.to_string()
        )
    }
}
