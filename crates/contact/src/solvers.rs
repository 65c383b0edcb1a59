//! The contact solvers behind [`ContactSolver`].

use contopt_core::observe::Observer;
use contopt_core::{ContactState, Error, Result};

use crate::{kalker, InterfaceProblem};

/// A method that solves the interface problem: p ≥ 0, d ≥ 0, pᵀd = 0 and equilibrium (2.15).
///
/// The outcome of a solve is a state with a [`Status`](contopt_core::Status): a method that
/// stops short returns its last iterate and residuals ([`ContactState::solved`] turns that into
/// an error). Errors are for bad input, and for dense matrices past the problem's memory limit.
pub trait ContactSolver {
    /// Name for messages and reports.
    fn name(&self) -> &str;
    /// Solves `problem`.
    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState>;
    /// Solves `problem` starting from the pressure `start` (one value per point, a previous
    /// solution: a warm start). Solvers that cannot use one solve from scratch (the default).
    fn solve_from(&self, problem: &InterfaceProblem, start: &[f64]) -> Result<ContactState> {
        let _ = start;
        self.solve(problem)
    }
    /// Solves `problem` (from `start` when given), reporting each iteration to `observer`,
    /// which may stop the method early ([`Flow::Stop`](contopt_core::observe::Flow::Stop)).
    /// Methods without iterations of their own to report (the default) solve unobserved.
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        let _ = observer;
        match start {
            Some(start) => self.solve_from(problem, start),
            None => self.solve(problem),
        }
    }
}

fn check_penalty(c: f64) -> Result<()> {
    if c.is_finite() && c > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            "solver.c",
            c,
            "the penalty parameter must be positive and finite [MPa/mm]",
        ))
    }
}

/// The penalty method (§2.2, eq. 2.18 without the multiplier): contact points carry
/// p = c·(penetration), so the gap closes only to O(1/c). Solved in its dual form on the
/// condensed interface, (H + W/c) p = …, which stays well conditioned as c grows.
#[derive(Clone, Copy, Debug)]
pub struct Penalty {
    /// Penalty parameter c \[MPa/mm\] (the paper uses c = E·10⁴).
    pub c: f64,
}

impl ContactSolver for Penalty {
    fn name(&self) -> &str {
        "penalty"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        check_penalty(self.c)?;
        kalker::penalty(problem, self.c)
    }
}

/// The augmented Lagrangian technique (§2.2, eqs. 2.18–2.20): Uzawa updates
/// p ← ⟨p − c d⟩, each solved by Kalker's active-set iteration, whose solves are counted as
/// `iterp` and its penetration checks as `iterd` (the paper's counts). Converges to the
/// solution of the QP (2.14) for any c > 0; a small c costs more Uzawa steps.
#[derive(Clone, Copy, Debug)]
pub struct AugmentedLagrangian {
    /// Penalty parameter c \[MPa/mm\].
    pub c: f64,
    /// Stop when no pressure changes by more than `tolerance`·p_max in a step.
    pub tolerance: f64,
    /// Largest number of Uzawa steps.
    pub max_steps: usize,
    /// Once a step leaves the contact set unchanged, solve for the iteration's limit directly
    /// (default). Without it, plain Uzawa steps continue to the tolerance; along directions the
    /// interface hardly feels (elements partly in contact) that can take thousands of steps.
    pub accelerate: bool,
}

impl AugmentedLagrangian {
    /// Penalty parameter `c`, tolerance 10⁻¹⁰, at most 2000 steps, accelerated.
    pub fn new(c: f64) -> Self {
        Self {
            c,
            tolerance: 1e-10,
            max_steps: 2000,
            accelerate: true,
        }
    }
}

impl ContactSolver for AugmentedLagrangian {
    fn name(&self) -> &str {
        "augmented Lagrangian"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        check_penalty(self.c)?;
        if !(self.tolerance > 0.0) {
            return Err(Error::invalid(
                "solver.tolerance",
                self.tolerance,
                "must be positive",
            ));
        }
        kalker::uzawa(
            problem,
            self.c,
            self.tolerance,
            self.max_steps,
            self.accelerate,
        )
    }
}

/// A dedicated solver for the QP (2.14): Kalker's active-set iteration with direct dense
/// solves on the contact set. One penalty solve (Cholesky, c = 10⁶ / maxᵢ(Aᵢᵢ wᵢ)) finds the
/// contact set; the exact QP is then solved on it with the pseudo-inverse, which selects the
/// pressure of least Σ wᵢ pᵢ² when H is only semi-definite (three Gauss points per quadratic
/// finite-element face outnumber the face's displacement unknowns): the limit of the penalty
/// method, and the paper's C⁰ pressure field. Much faster than the interior point on large
/// interfaces.
#[derive(Clone, Copy, Debug, Default)]
pub struct ActiveSet;

impl ContactSolver for ActiveSet {
    fn name(&self) -> &str {
        "active set"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        kalker::exact(problem, None)
    }
}
