//! The contact interface problem of two elastic bodies and the methods that solve it (§2 of
//! Páczelt 1994): the complementary-energy QP ([`Qp`] by clarabel, [`ActiveSet`]), the
//! [`Penalty`] method and the [`AugmentedLagrangian`] with Uzawa updates and Kalker's
//! active-set iteration; matrix-free for large grids applied as operators, [`PolonskyKeer`];
//! and the [`FullPenalty`] method on the uncondensed system of two bodies ([`FullSystem`],
//! eq. 2.22), the cross-check of the condensation. Each reports its iterations to an
//! [`Observer`](contopt_core::observe::Observer) ([`ContactSolver::solve_observed`]).

// Input checks are written `!(x > 0.0)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

pub mod conic;
mod full;
mod kalker;
mod polonsky_keer;
mod problem;
mod qp;
mod solvers;
#[cfg(test)]
mod tests;

pub use full::{FullPenalty, FullSystem};
pub use polonsky_keer::PolonskyKeer;
pub use problem::{check_gap, FreeMode, InterfaceProblem, DEFAULT_DENSE_LIMIT_BYTES, SMALL_STRAIN};
pub use qp::Qp;
pub use solvers::{ActiveSet, AugmentedLagrangian, ContactSolver, Penalty};
