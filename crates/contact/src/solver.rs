//! The [`ContactSolver`] trait that every method of §2 implements.

use contopt_core::observe::{Method, Observer, Silent};
use contopt_core::{ContactState, Result};

use crate::{InterfaceProblem, Workspace};

/// A method that solves the interface problem: p ≥ 0, d ≥ 0, pᵀd = 0 and equilibrium (2.15).
///
/// The outcome of a solve is a state with a [`Termination`](contopt_core::Termination): a
/// method that stops short returns its last iterate and residuals, and says why. Errors are
/// for bad input, and for dense matrices past the problem's memory limit.
///
/// Build a solver from its settings ([`SolverSettings`](crate::SolverSettings), or each type's
/// own `new(settings)`): every setting has its default in the library.
///
/// A solver is `Send + Sync`: one solver solves an envelope's cases at once on several threads
/// ([`crate::parallel`]); what a solve needs to change it takes from the caller's
/// [`Workspace`] ([`ContactSolver::solve_in`]), allocates per solve (its work vectors) or takes
/// from the problem ([`InterfaceProblem::dense_influence`], built once).
pub trait ContactSolver: Send + Sync {
    /// The method, in events and reports.
    fn method(&self) -> Method;

    /// The method that solves `problem`: [`ContactSolver::method`], unless the solver chooses
    /// one per problem ([`crate::Auto`]).
    fn method_for(&self, _problem: &InterfaceProblem) -> Method {
        self.method()
    }

    /// The n × n matrices the solver holds at once on an interface of `points` points (0 for
    /// a matrix-free solver): what a memory estimate counts before it builds anything.
    fn dense_copies(&self, points: usize) -> u64;

    /// Solves `problem` (from the pressure `start` when given: a warm start, one value per
    /// point) in the caller's `workspace`, reporting each iteration to `observer` as an event
    /// of [`ContactSolver::method`] and the last with how it ended. The observer may stop the
    /// method early ([`Flow::Stop`](contopt_core::observe::Flow)): it then returns its last
    /// iterate, finite, with [`Termination::Stopped`](contopt_core::Termination). Solvers that
    /// cannot use a start solve from scratch.
    ///
    /// A design loop keeps the `workspace` across its solves, so that the solver sizes its
    /// buffers once (faer's explicit scratch); a solver that keeps none ignores it.
    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState>;

    /// [`ContactSolver::solve_in`] in a workspace of its own, dropped after the solve
    /// ([`Workspace::one_off`]).
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        self.solve_in(problem, start, observer, &mut Workspace::one_off())
    }

    /// The same solver stopping at the looser `tolerance` (in the measure of its own), for an
    /// inexact solve inside an outer iteration whose own error is far above it; `None` when it
    /// has no tolerance to loosen (a direct method) or `tolerance` is not looser than its own.
    fn loosened(&self, _tolerance: f64) -> Option<Box<dyn ContactSolver>> {
        None
    }

    /// Solves `problem` from scratch, unobserved.
    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        self.solve_observed(problem, None, &Silent)
    }

    /// Solves `problem` from the pressure `start`, unobserved.
    fn solve_from(&self, problem: &InterfaceProblem, start: &[f64]) -> Result<ContactState> {
        self.solve_observed(problem, Some(start), &Silent)
    }
}
