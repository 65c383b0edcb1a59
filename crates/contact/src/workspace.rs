//! The buffers a caller keeps across the solves of a design loop (faer's explicit scratch):
//! one [`Workspace`] holds each solver family's own, so that any
//! [`ContactSolver`](crate::ContactSolver) solves in it
//! ([`ContactSolver::solve_in`](crate::ContactSolver::solve_in)).

use crate::{KalkerWorkspace, PolonskyKeerWorkspace};

/// The workspaces of the solvers that keep one: Polonsky–Keer's
/// ([`PolonskyKeerWorkspace`]) and Kalker's iteration's, behind the active-set, penalty and
/// augmented-Lagrangian solvers ([`KalkerWorkspace`]). Empty until a solve sizes the part it
/// uses; each thread that solves keeps its own. Kept, it holds what a solve derives for the
/// next (see [`PolonskyKeerWorkspace`]): for a single solve, [`Workspace::one_off`].
///
/// ```
/// # use contopt_contact::{ContactSolver, Workspace};
/// # fn design(solver: &dyn ContactSolver, problems: &[contopt_contact::InterfaceProblem])
/// # -> contopt_core::Result<()> {
/// let mut workspace = Workspace::default();
/// for problem in problems {
///     let state = solver.solve_in(problem, None, &contopt_core::observe::Silent, &mut workspace)?;
///     println!("p_max {}", state.p_max());
/// }
/// # Ok(())
/// # }
/// ```
#[derive(Default)]
pub struct Workspace {
    /// Polonsky–Keer's vectors.
    pub polonsky_keer: PolonskyKeerWorkspace,
    /// Kalker's iteration's vectors and matrices.
    pub kalker: KalkerWorkspace,
}

impl Workspace {
    /// A workspace for one solve, dropped after it: it keeps none of the problems a solve
    /// derives (Polonsky–Keer's parts and coarser grids), which are then dropped as soon as
    /// used, and the solve's peak memory is the least. For a workspace a caller keeps across
    /// solves, [`Workspace::default`].
    pub fn one_off() -> Self {
        Self {
            polonsky_keer: PolonskyKeerWorkspace::one_off(),
            kalker: KalkerWorkspace::default(),
        }
    }
}

/// Makes `v` hold `n` copies of `value`, reallocating only when its capacity is below `n`.
pub(crate) fn refill<T: Clone>(v: &mut Vec<T>, n: usize, value: T) {
    v.clear();
    v.resize(n, value);
}
