//! Kalker's active set with exact dense solves: a dedicated solver for the QP (2.14).

use contopt_core::observe::{Method, Observer};
use contopt_core::{ContactState, Result};
use serde::{Deserialize, Serialize};

use crate::kalker;
use crate::watch::{self, Watch};
use crate::{ContactSolver, InterfaceProblem, Workspace};

/// The settings of the [`ActiveSet`] solver: none yet (it is exact, and its iteration is
/// finite), kept so that every solver is built alike.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ActiveSetSettings {}

/// A dedicated solver for the QP (2.14): Kalker's active-set iteration with direct dense
/// solves on the contact set. One penalty solve (Cholesky, c = 10⁶ / maxᵢ(Aᵢᵢ wᵢ)) finds the
/// contact set; the exact QP is then solved on it with the pseudo-inverse, which selects the
/// pressure of least Σ wᵢ pᵢ² when H is only semi-definite (three Gauss points per quadratic
/// finite-element face outnumber the face's displacement unknowns): the limit of the penalty
/// method, and the paper's C⁰ pressure field. Much faster than the interior point on large
/// interfaces.
#[derive(Clone, Copy, Debug)]
pub struct ActiveSet {
    settings: ActiveSetSettings,
}

impl ActiveSet {
    /// The solver with `settings`.
    pub fn new(settings: ActiveSetSettings) -> Result<Self> {
        Ok(Self { settings })
    }

    /// Its settings.
    pub fn settings(&self) -> &ActiveSetSettings {
        &self.settings
    }
}

impl ContactSolver for ActiveSet {
    fn method(&self) -> Method {
        Method::ActiveSet
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        kalker::DENSE_COPIES
    }

    /// Reports each of Kalker's solves (`iterp`: the penalty solve's, then the exact ones)
    /// with the number of points that break a sign condition as the measure (tolerance 0).
    /// Solves from scratch: a `start` is not used.
    ///
    /// In the workspace's [`KalkerWorkspace`](crate::KalkerWorkspace).
    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState> {
        let watch = Watch::new(observer, self.method());
        let state = kalker::exact_observed(problem, None, watch, &mut workspace.kalker)?;
        watch::announce(observer, &state);
        Ok(state)
    }
}
