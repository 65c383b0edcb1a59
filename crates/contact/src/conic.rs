//! The one place clarabel is set up and read: its settings and the meaning of its status, for
//! the contact QP (2.14) ([`crate::Qp`]) and the optimisation's linear programme (3.5).
//!
//! A programme is min ½ xᵀ P x + cᵀ x subject to A x + s = b, with the slack s in the zero
//! cone on the first `zero_rows` rows (equalities A x = b) and non-negative on the others
//! (inequalities A x ≤ b), clarabel's standard form.
//!
//! ```
//! use contopt_contact::conic::{self, CscMatrix, Outcome};
//!
//! // min x₀ subject to x₀ + x₁ = 2 (the zero cone), x₀ ≥ 0.5 and x₁ ≥ 0.5 (as −x ≤ −0.5):
//! // x = (0.5, 1.5).
//! let (rows, columns) = (vec![0, 0, 1, 2], vec![0, 1, 0, 1]);
//! let a = CscMatrix::new_from_triplets(3, 2, rows, columns, vec![1.0, 1.0, -1.0, -1.0]);
//! let (p, b) = (CscMatrix::zeros((2, 2)), [2.0, -0.5, -0.5]);
//! let solved = conic::solve(&p, &[1.0, 0.0], &a, &b, 1, conic::TOLERANCE, "demo")?;
//! assert_eq!(solved.outcome, Outcome::Solved);
//! assert!((solved.x[0] - 0.5).abs() < 1e-8 && (solved.x[1] - 1.5).abs() < 1e-8);
//! # Ok::<(), contopt_core::Error>(())
//! ```

use clarabel::solver::{
    DefaultSettings, DefaultSettingsBuilder, DefaultSolution, DefaultSolver, IPSolver,
    SolverStatus, SupportedConeT,
};
use contopt_core::{Error, InteriorPointStatus, Result, Stall, Termination};

pub use clarabel::algebra::CscMatrix;

/// The default feasibility and duality-gap tolerance of a programme (clarabel's tol_feas,
/// tol_gap_abs and tol_gap_rel): far tighter than the pressures need, so that the contact set
/// read from the solution is exact (convergence).
pub const TOLERANCE: f64 = 1e-10;

/// Interior-point iterations before a programme counts as stopped: clarabel needs a few tens.
pub const MAX_ITERATIONS: u32 = 200;

/// How a programme ended, from clarabel's status.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// Solved to the tolerance (`Solved`).
    Solved,
    /// Solved to clarabel's reduced tolerances only (`AlmostSolved`), with how far it got
    /// ([`Termination::ReducedAccuracy`]): an answer that stands, said to be less accurate.
    ReducedAccuracy(Termination),
    /// No x satisfies the constraints (`PrimalInfeasible` or `AlmostPrimalInfeasible`).
    Infeasible,
    /// The objective is unbounded below on the constraints (`DualInfeasible` or
    /// `AlmostDualInfeasible`).
    Unbounded,
    /// Stopped short of the tolerance: the iteration limit ([`Termination::StepLimit`]) or
    /// numerical trouble ([`Termination::Stalled`] by [`Stall::InteriorPoint`], with clarabel's
    /// status and residuals).
    /// `x` and `z` hold the last iterate.
    Stopped(Termination),
}
/// The solution of a programme: the primal x and the dual z (one per constraint row), as
/// clarabel left them.
#[derive(Clone, Debug)]
pub struct Solution {
    /// How the programme ended.
    pub outcome: Outcome,
    /// Primal variables.
    pub x: Vec<f64>,
    /// Dual variables, one per row of A: the multipliers of the equalities first.
    pub z: Vec<f64>,
    /// Interior-point iterations taken.
    pub iterations: usize,
}

/// clarabel's settings for a programme: silent, `tolerance` on feasibility and both gaps,
/// at most [`MAX_ITERATIONS`] iterations.
pub fn settings(tolerance: f64) -> Result<DefaultSettings<f64>> {
    contopt_core::check::positive("tolerance", tolerance)?;
    DefaultSettingsBuilder::default()
        .verbose(false)
        .tol_feas(tolerance)
        .tol_gap_abs(tolerance)
        .tol_gap_rel(tolerance)
        .max_iter(MAX_ITERATIONS)
        .build()
        .map_err(|e| Error::invalid("tolerance", tolerance, format!("{e:?}")))
}

/// Solves min ½ xᵀ P x + cᵀ x subject to A x = b on the first `zero_rows` rows of A and
/// A x ≤ b on the others, with P = `hessian` (its upper triangle; zeros for a linear
/// programme), c = `linear`, A = `constraints`. `what` names the programme in an error: an
/// error is for data clarabel rejects, a programme that ends short is an [`Outcome`].
pub fn solve(
    hessian: &CscMatrix<f64>,
    linear: &[f64],
    constraints: &CscMatrix<f64>,
    b: &[f64],
    zero_rows: usize,
    tolerance: f64,
    what: &str,
) -> Result<Solution> {
    let rows = constraints.m;
    if zero_rows > rows || b.len() != rows {
        return Err(Error::invalid(
            what,
            format!(
                "{rows} rows, {} right-hand sides, {zero_rows} equalities",
                b.len()
            ),
            "one right-hand side per row, at most as many equalities as rows",
        ));
    }
    let mut cones = vec![];
    if zero_rows > 0 {
        cones.push(SupportedConeT::ZeroConeT(zero_rows));
    }
    if rows > zero_rows {
        cones.push(SupportedConeT::NonnegativeConeT(rows - zero_rows));
    }
    let settings = settings(tolerance)?;
    let mut solver = DefaultSolver::new(hessian, linear, constraints, b, &cones, settings)
        .map_err(|e| Error::invalid(what, format!("{e:?}"), "clarabel rejected the programme"))?;
    solver.solve();
    let sol = &solver.solution;
    Ok(Solution {
        outcome: outcome(sol, tolerance),
        x: sol.x.clone(),
        z: sol.z.clone(),
        iterations: sol.iterations as usize,
    })
}

/// How a solution of clarabel's ended, by its status, `tolerance` the one it had to reach.
fn outcome(sol: &DefaultSolution<f64>, tolerance: f64) -> Outcome {
    let measure = sol.r_prim.max(sol.r_dual);
    let stalled = |status| {
        Outcome::Stopped(Termination::Stalled {
            cause: Stall::InteriorPoint {
                status,
                primal_residual: sol.r_prim,
                dual_residual: sol.r_dual,
            },
        })
    };
    match sol.status {
        SolverStatus::Solved => Outcome::Solved,
        SolverStatus::AlmostSolved => {
            Outcome::ReducedAccuracy(Termination::ReducedAccuracy { measure, tolerance })
        }
        SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
            Outcome::Infeasible
        }
        SolverStatus::DualInfeasible | SolverStatus::AlmostDualInfeasible => Outcome::Unbounded,
        SolverStatus::MaxIterations => Outcome::Stopped(Termination::StepLimit {
            steps: sol.iterations as usize,
            measure,
            tolerance,
        }),
        SolverStatus::Unsolved => stalled(InteriorPointStatus::Unsolved),
        SolverStatus::MaxTime => stalled(InteriorPointStatus::TimeLimit),
        SolverStatus::NumericalError => stalled(InteriorPointStatus::NumericalError),
        SolverStatus::InsufficientProgress => stalled(InteriorPointStatus::InsufficientProgress),
        SolverStatus::CallbackTerminated => stalled(InteriorPointStatus::CallbackTerminated),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An infeasible programme is an outcome, not an error; bad data is an error.
    #[test]
    fn infeasible_and_bad_data() {
        // x = 1 and x ≤ 0.
        let a = CscMatrix::new_from_triplets(2, 1, vec![0, 1], vec![0, 0], vec![1.0, 1.0]);
        let p = CscMatrix::zeros((1, 1));
        let s = solve(&p, &[1.0], &a, &[1.0, 0.0], 1, TOLERANCE, "t").unwrap();
        assert_eq!(s.outcome, Outcome::Infeasible);
        let err = solve(&p, &[1.0], &a, &[1.0], 1, TOLERANCE, "t").unwrap_err();
        assert!(
            err.to_string().contains("one right-hand side per row"),
            "{err}"
        );
        let err = settings(f64::NAN).unwrap_err();
        assert!(err.to_string().contains("invalid tolerance = NaN"), "{err}");
    }

    /// clarabel's reduced accuracy is an outcome of its own, with the residual it reached; a
    /// numerical error stalls, naming the status and both residuals.
    #[test]
    fn almost_solved_is_reduced_accuracy() {
        let mut sol = DefaultSolution::<f64>::new(1, 1);
        (sol.status, sol.r_prim, sol.r_dual) = (SolverStatus::AlmostSolved, 1e-7, 3e-7);
        let reduced = Termination::ReducedAccuracy {
            measure: 3e-7,
            tolerance: TOLERANCE,
        };
        assert_eq!(outcome(&sol, TOLERANCE), Outcome::ReducedAccuracy(reduced));
        sol.status = SolverStatus::NumericalError;
        let stalled = Termination::Stalled {
            cause: Stall::InteriorPoint {
                status: InteriorPointStatus::NumericalError,
                primal_residual: 1e-7,
                dual_residual: 3e-7,
            },
        };
        assert_eq!(outcome(&sol, TOLERANCE), Outcome::Stopped(stalled));
    }

    /// A QP with a known minimiser: min ½(x₀² + x₁²) − x₀ − 2x₁ with x₀ + x₁ ≤ 1 is at
    /// (0, 1), where the constraint's multiplier is 1.
    #[test]
    fn quadratic_programme() {
        let p = CscMatrix::new_from_triplets(2, 2, vec![0, 1], vec![0, 1], vec![1.0, 1.0]);
        let a = CscMatrix::new_from_triplets(1, 2, vec![0, 0], vec![0, 1], vec![1.0, 1.0]);
        let s = solve(&p, &[-1.0, -2.0], &a, &[1.0], 0, TOLERANCE, "t").unwrap();
        assert_eq!(s.outcome, Outcome::Solved);
        assert!(
            s.x[0].abs() < 1e-7 && (s.x[1] - 1.0).abs() < 1e-7,
            "{:?}",
            s.x
        );
        assert!((s.z[0] - 1.0).abs() < 1e-7, "{:?}", s.z);
    }
}
