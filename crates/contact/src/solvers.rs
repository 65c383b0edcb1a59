//! The contact solvers behind [`ContactSolver`], and how they report their iterations.

use contopt_core::observe::{stopped_by_observer, Flow, Iteration, Observer, Silent};
use contopt_core::{ContactState, Error, Result, Status};

use crate::{kalker, InterfaceProblem};

/// A method that solves the interface problem: p ≥ 0, d ≥ 0, pᵀd = 0 and equilibrium (2.15).
///
/// The outcome of a solve is a state with a [`Status`]: a method that
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
    /// Solves `problem` (from `start` when given), reporting each iteration to `observer` as
    /// an [`Iteration`] named by [`ContactSolver::name`], which may stop the method early
    /// ([`Flow::Stop`]): it then returns its last iterate, finite, with the status
    /// [`Status::Stopped`] of [`stopped_by_observer`]. `solve` and `solve_from` are this with
    /// the [`Silent`] observer. Methods without iterations of their own to report (the
    /// default) solve unobserved.
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

/// Where a method reports its iterations: the observer, the name they carry
/// ([`Iteration::method`]) and how many came before in the same solve, so that the numbers run
/// on across the loops of one solve (a penalty solve's start at c_stiff and its main solve).
#[derive(Clone, Copy)]
pub(crate) struct Watch<'a> {
    observer: &'a dyn Observer,
    method: &'a str,
    before: usize,
}

impl<'a> Watch<'a> {
    pub(crate) fn new(observer: &'a dyn Observer, method: &'a str) -> Self {
        Self {
            observer,
            method,
            before: 0,
        }
    }

    /// The same watch for a loop that follows `before` iterations of the solve.
    pub(crate) fn after(self, before: usize) -> Self {
        Self { before, ..self }
    }

    /// Reports the loop's iteration `k` (from 1) with its convergence `measure` and the
    /// `tolerance` it must reach; the halt to return when the observer asks to stop.
    pub(crate) fn report(&self, k: usize, measure: f64, tolerance: f64) -> Option<Halt> {
        let iteration = self.before + k;
        let flow = self.observer.observe(&Iteration {
            method: self.method,
            iteration,
            measure,
            tolerance,
        });
        (flow == Flow::Stop).then_some(Halt::Observer(iteration))
    }
}

/// Why an iteration stopped before its tolerance, its last iterate kept.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Halt {
    /// The observer asked to stop after this iteration.
    Observer(usize),
    /// The method could not go on; the text says why.
    Failed(String),
}

impl Halt {
    /// Marks `state` stopped: by the observer ([`stopped_by_observer`]), or by the `method`
    /// with its reason. A state with a non-finite value keeps the status that says so.
    pub(crate) fn stop(self, method: &str, state: &mut ContactState) {
        if state.non_finite().is_some() {
            return;
        }
        state.status = Status::Stopped(match self {
            Halt::Observer(k) => stopped_by_observer(k),
            Halt::Failed(reason) => format!("{method}: {reason}"),
        });
    }
}

/// A penalty parameter c must be positive and finite.
pub(crate) fn check_penalty(c: f64) -> Result<()> {
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
        self.solve_observed(problem, None, &Silent)
    }

    /// Reports each of Kalker's solves (`iterp`, the one at c_stiff that starts a large c
    /// included) with the number of points that break a sign condition as the measure
    /// (tolerance 0). Solves from scratch: a `start` is not used.
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        check_penalty(self.c)?;
        kalker::penalty(problem, self.c, Watch::new(observer, self.name()))
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
    /// The default tolerance on the pressure change of a step, relative to p_max
    /// (convergence: six orders above round-off, far below any engineering need).
    pub const TOLERANCE: f64 = 1e-10;
    /// The default limit on Uzawa steps: far more than an accelerated solve takes (a few).
    pub const MAX_STEPS: usize = 2000;
    /// The method its inner Kalker solves report to an observer; its Uzawa steps report as
    /// [`ContactSolver::name`].
    pub const KALKER: &'static str = "augmented Lagrangian: Kalker";

    /// Penalty parameter `c`, tolerance [`Self::TOLERANCE`], at most [`Self::MAX_STEPS`]
    /// steps, accelerated.
    pub fn new(c: f64) -> Self {
        Self {
            c,
            tolerance: Self::TOLERANCE,
            max_steps: Self::MAX_STEPS,
            accelerate: true,
        }
    }
}

impl ContactSolver for AugmentedLagrangian {
    fn name(&self) -> &str {
        "augmented Lagrangian"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        self.solve_observed(problem, None, &Silent)
    }

    /// Reports each Uzawa step (`iterations`) with its largest pressure change relative to
    /// p_max as the measure and `tolerance`; and each inner Kalker solve (`iterp`) as the
    /// method [`Self::KALKER`], measured by the number of points that break a sign condition
    /// (tolerance 0). Solves from scratch: a `start` is not used.
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        check_penalty(self.c)?;
        if !(self.tolerance > 0.0) {
            return Err(Error::invalid(
                "solver.tolerance",
                self.tolerance,
                "must be positive",
            ));
        }
        kalker::uzawa(problem, self, observer)
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
        self.solve_observed(problem, None, &Silent)
    }

    /// Reports each of Kalker's solves (`iterp`: the penalty solve's, then the exact ones)
    /// with the number of points that break a sign condition as the measure (tolerance 0).
    /// Solves from scratch: a `start` is not used.
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        kalker::exact_observed(problem, None, Watch::new(observer, self.name()))
    }
}
