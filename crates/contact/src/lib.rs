//! The contact interface problem of two elastic bodies and the methods that solve it (§2 of
//! Páczelt 1994): the complementary-energy QP ([`Qp`] by clarabel, [`ActiveSet`]), the
//! [`Penalty`] method and the [`AugmentedLagrangian`] with Uzawa updates and Kalker's
//! active-set iteration; matrix-free for large grids applied as operators, [`PolonskyKeer`];
//! [`Auto`], which picks between the exact ones by size; and the [`FullPenalty`] method on the
//! uncondensed system of two bodies ([`FullSystem`](contopt_core::FullSystem), eq. 2.22), the
//! cross-check of the condensation.
//!
//! Every solver is built one way, from its settings, whose defaults live beside it
//! (`PolonskyKeer::new(PolonskyKeerSettings::default())`, or [`SolverSettings::build`] for a
//! solver named at run time); each reports its iterations to an
//! [`Observer`](contopt_core::observe::Observer) ([`ContactSolver::solve_observed`]) and ends
//! with a [`Termination`](contopt_core::Termination). A design loop keeps one [`Workspace`]
//! across its solves ([`ContactSolver::solve_in`]): the solvers' buffers are then sized once
//! ([`PolonskyKeerWorkspace`], [`KalkerWorkspace`]).

mod active_set;
mod augmented;
pub mod conic;
mod full;
mod kalker;
pub mod parallel;
mod penalty;
mod polonsky_keer;
mod problem;
mod prolong;
mod qp;
mod settings;
mod solver;
#[cfg(test)]
mod tests;
mod watch;
mod workspace;

pub use active_set::{ActiveSet, ActiveSetSettings};
pub use augmented::{AugmentedLagrangian, AugmentedLagrangianSettings};
pub use full::FullPenalty;
pub use kalker::KalkerWorkspace;
pub use penalty::{Penalty, PenaltySettings};
pub use polonsky_keer::{PolonskyKeer, PolonskyKeerSettings, PolonskyKeerWorkspace};
pub use problem::{FreeMode, InterfaceProblem, DEFAULT_DENSE_LIMIT_BYTES, SMALL_STRAIN};
pub use qp::{Qp, QpSettings};
pub use settings::{Auto, SolverSettings};
pub use solver::ContactSolver;
pub use workspace::Workspace;
