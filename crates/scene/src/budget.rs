//! The memory a case needs, estimated from its scene before anything is built, and refused
//! past the scene's limit with the number.

use contopt_core::{memory, Error, Result};
use contopt_greens::{dense_surface_bytes, HalfSpace};

use crate::geometry::{BLOCK_DEPTH_ELEMENTS, BLOCK_OUTER_ELEMENTS, MAX_OUTER_ELEMENTS};
use crate::spec::{ModeSpec, Problem, SceneSpec, SolverSpec};

/// The memory limit of a case unless the scene sets `memory_limit_mb` \[bytes\]: a sixth of
/// the 24 GB machine we plan for.
pub const DEFAULT_MEMORY_LIMIT_BYTES: u64 = 4_000_000_000;

/// The n × n matrices a dense contact solver holds at once (clarabel's QP: five).
const SOLVER_COPIES: usize = 5;
/// The n × n matrices a dense optimisation holds at once (the LP and §3.2's iteration).
const OPTIMISER_COPIES: usize = 10;
/// Memory per interface point that every case holds: the problem's vectors, the solver's
/// buffers and the reports (values, and their JSON text) \[bytes\].
const POINT_BYTES: u64 = 2_000;

/// The case's estimate \[bytes\] when it is within `limit`, else [`Error::TooLarge`]
/// naming what dominates it.
pub(crate) fn check(spec: &SceneSpec, limit: u64) -> Result<u64> {
    let (bodies, points) = bodies(&spec.problem);
    let dense_solver = !matches!(spec.solver, SolverSpec::PolonskyKeer { .. });
    let dense_optimiser = spec
        .optimisation
        .as_ref()
        .is_some_and(|o| o.mode != ModeSpec::LoadSplit || dense_solver);
    let copies = match (dense_solver, dense_optimiser) {
        (_, true) => OPTIMISER_COPIES,
        (true, false) => SOLVER_COPIES,
        (false, false) => 0,
    };
    let dense = points.and_then(|n| memory::bytes(&[n, n, copies], 8));
    let vectors = points.and_then(|n| memory::bytes(&[n], POINT_BYTES));
    let total = memory::sum(&[bodies, dense, vectors]);
    let what = match points {
        Some(n) if copies > 0 => format!(
            "the case ({n} interface points, their bodies, and {copies} dense {n} × {n} matrices \
             for the dense solver or optimisation)"
        ),
        Some(n) => format!("the case ({n} interface points and their bodies)"),
        None => "the case (its point count overflows)".to_string(),
    };
    let advice = if copies > 0 {
        "use fewer points, the matrix-free solver (polonsky_keer) with the load split, or raise \
         memory_limit_mb"
    } else {
        "use fewer points or raise memory_limit_mb"
    };
    memory::require(what, total, limit, advice)
}

/// The memory of the bodies and the number of interface points, `None` on overflow.
fn bodies(problem: &Problem) -> (Option<u64>, Option<usize>) {
    let grid = |cells: &[usize; 2]| {
        (
            HalfSpace::grid_bytes(cells[0], cells[1]),
            cells[0].checked_mul(cells[1]),
        )
    };
    match problem {
        Problem::RigidOnHalfSpace { cells, .. } => grid(cells),
        Problem::Roller { cells, .. } => {
            let (one, n) = grid(cells);
            (one.and_then(|b| b.checked_mul(2)), n)
        }
        Problem::RigidOnAxisymmetricHalfSpace { rings: n, .. }
        | Problem::RigidOnHalfPlane { strips: n, .. } => (dense_surface_bytes(*n), Some(*n)),
        Problem::PunchOnBase(spec) => {
            let mesh = &spec.mesh;
            let layers = mesh.layers();
            let base = mesh
                .elements
                .checked_add(MAX_OUTER_ELEMENTS)
                .and_then(|e| contopt_fem::body_bytes(e, layers));
            let punch = contopt_fem::body_bytes(mesh.elements, layers);
            (memory::sum(&[base, punch]), mesh.elements.checked_mul(3))
        }
        Problem::RigidOnBlock { elements, .. } => {
            let block = elements.checked_add(BLOCK_OUTER_ELEMENTS).and_then(|e| {
                let depth = e.min(BLOCK_OUTER_ELEMENTS) * 2 + BLOCK_DEPTH_ELEMENTS;
                contopt_fem::body_bytes(e, depth)
            });
            (block, elements.checked_mul(3))
        }
    }
}

/// The limit of a scene's `memory_limit_mb` \[bytes\].
pub(crate) fn limit(memory_limit_mb: Option<f64>) -> Result<u64> {
    match memory_limit_mb {
        None => Ok(DEFAULT_MEMORY_LIMIT_BYTES),
        Some(mb) if mb > 0.0 && mb.is_finite() => Ok((mb * 1e6) as u64),
        Some(mb) => Err(Error::invalid(
            "memory_limit_mb",
            mb,
            "must be positive and finite",
        )),
    }
}
