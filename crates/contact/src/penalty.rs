//! The penalty method (§2.2, eq. 2.18 without the multiplier) on the condensed interface.

use contopt_core::observe::{Method, Observer};
use contopt_core::{check, ContactState, Result};
use serde::{Deserialize, Serialize};

use crate::kalker;
use crate::watch::{self, Watch};
use crate::{ContactSolver, InterfaceProblem, Workspace};

/// The settings of the [`Penalty`] method: its parameter, which has no default (the paper
/// takes c = E·10⁴).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PenaltySettings {
    /// Penalty parameter c \[MPa/mm\]: the gap closes to O(p/c).
    pub c_mpa_per_mm: f64,
}

/// The penalty method: contact points carry p = c·(penetration), so the gap closes only to
/// O(1/c). Solved in its dual form on the condensed interface, (H + W/c) p = …, which stays
/// well conditioned as c grows.
#[derive(Clone, Copy, Debug)]
pub struct Penalty {
    c: f64,
}

impl Penalty {
    /// The method with `settings`, checked: c positive and finite.
    pub fn new(settings: PenaltySettings) -> Result<Self> {
        Ok(Self {
            c: check::positive("c_mpa_per_mm", settings.c_mpa_per_mm)?,
        })
    }

    /// The penalty parameter c \[MPa/mm\].
    pub fn c(&self) -> f64 {
        self.c
    }
}

impl ContactSolver for Penalty {
    fn method(&self) -> Method {
        Method::Penalty
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        kalker::DENSE_COPIES
    }

    /// Reports each of Kalker's solves (`iterp`, the one at c_stiff that starts a large c
    /// included) with the number of points that break a sign condition as the measure
    /// (tolerance 0). Solves from scratch: a `start` is not used.
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
        let state = kalker::penalty(problem, self.c, watch, &mut workspace.kalker)?;
        watch::announce(observer, &state);
        Ok(state)
    }
}
