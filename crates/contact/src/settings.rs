//! Every contact solver by its settings, for files and for code that chooses a solver at run
//! time: [`SolverSettings`] names one and [`SolverSettings::build`] makes it, checked.

use contopt_core::observe::{Method, Observer};
use contopt_core::{ContactState, Result};
use serde::{Deserialize, Serialize};

use crate::{
    ActiveSet, ActiveSetSettings, AugmentedLagrangian, AugmentedLagrangianSettings, ContactSolver,
    InterfaceProblem, Penalty, PenaltySettings, PolonskyKeer, PolonskyKeerSettings, Qp, QpSettings,
    Workspace,
};

/// A contact solver and its settings, as a scene names it (`{ kind = "polonsky_keer",
/// tolerance = 1e-10 }`): every field not given takes the library's default.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverSettings {
    /// Chosen per problem: the dense active set for small interfaces, Polonsky–Keer for large
    /// ones ([`Auto`]).
    #[default]
    Auto,
    /// The QP (2.14) by clarabel ([`Qp`]).
    Qp(QpSettings),
    /// Kalker's active set with exact dense solves ([`ActiveSet`]).
    ActiveSet(ActiveSetSettings),
    /// The penalty method ([`Penalty`]).
    Penalty(PenaltySettings),
    /// The augmented Lagrangian with Uzawa updates ([`AugmentedLagrangian`]).
    AugmentedLagrangian(AugmentedLagrangianSettings),
    /// Polonsky–Keer's matrix-free conjugate gradients ([`PolonskyKeer`]).
    PolonskyKeer(PolonskyKeerSettings),
}

impl SolverSettings {
    /// The solver, its settings checked.
    pub fn build(&self) -> Result<Box<dyn ContactSolver>> {
        Ok(match self {
            SolverSettings::Auto => Box::new(Auto::new()?),
            SolverSettings::Qp(s) => Box::new(Qp::new(*s)?),
            SolverSettings::ActiveSet(s) => Box::new(ActiveSet::new(*s)?),
            SolverSettings::Penalty(s) => Box::new(Penalty::new(*s)?),
            SolverSettings::AugmentedLagrangian(s) => Box::new(AugmentedLagrangian::new(*s)?),
            SolverSettings::PolonskyKeer(s) => Box::new(PolonskyKeer::new(*s)?),
        })
    }
}

/// The solver chosen per problem, the faster of the two exact ones: [`PolonskyKeer`] when a
/// body offers an inverse of its operator ([`InterfaceProblem::precondition`]: a half-space
/// grid's circulant, a bed's stiffness), whose few preconditioned steps through the bodies'
/// operators beat a dense matrix at any size, or when the interface has more than
/// [`Auto::DENSE_POINTS`] points; Kalker's [`ActiveSet`] on the other small interfaces
/// (finite-element bodies' condensed operators, Flamant strips), whose dense solves are direct
/// where unpreconditioned conjugate gradients take many steps. Both are exact: they agree to
/// their tolerances. [`ContactSolver::method_for`] and each state ([`ContactState::method`])
/// say which solved. `cargo run --release --example solver_auto` times the choice against
/// both on every bundled scene.
#[derive(Clone, Copy, Debug)]
pub struct Auto {
    dense: ActiveSet,
    iterative: PolonskyKeer,
}

impl Auto {
    /// The largest interface solved densely: a dense n × n solve costs n³/3 flops, about 3 s
    /// at 2000 points on one core, and its matrices 4·8n² bytes (128 MB).
    pub const DENSE_POINTS: usize = 2000;

    /// The choice with each solver's default settings.
    pub fn new() -> Result<Self> {
        Ok(Self {
            dense: ActiveSet::new(ActiveSetSettings::default())?,
            iterative: PolonskyKeer::new(PolonskyKeerSettings::default())?,
        })
    }

    /// The solver a problem of `points` points gets when no body offers an inverse (the
    /// largest choice: what a memory estimate before any body is built must count).
    pub fn choice(&self, points: usize) -> &dyn ContactSolver {
        if points <= Self::DENSE_POINTS {
            &self.dense
        } else {
            &self.iterative
        }
    }

    /// The solver `problem` gets.
    pub fn choice_for(&self, problem: &InterfaceProblem) -> &dyn ContactSolver {
        if problem.len() <= Self::DENSE_POINTS && problem.offers_inverse() {
            &self.iterative
        } else {
            self.choice(problem.len())
        }
    }
}

impl ContactSolver for Auto {
    /// The method of the choice on the smallest interfaces without an inverse; each state,
    /// and [`ContactSolver::method_for`], names its own.
    fn method(&self) -> Method {
        self.dense.method()
    }

    fn method_for(&self, problem: &InterfaceProblem) -> Method {
        self.choice_for(problem).method()
    }

    fn dense_copies(&self, points: usize) -> u64 {
        self.choice(points).dense_copies(points)
    }

    /// The choice with its iterative solver loosened (the dense one solves exactly).
    fn loosened(&self, tolerance: f64) -> Option<Box<dyn ContactSolver>> {
        let iterative = self.iterative.looser(tolerance)?;
        Some(Box::new(Self {
            dense: self.dense,
            iterative,
        }))
    }

    /// The choice's own solve in a workspace of its own (Polonsky–Keer's keeps its state
    /// there).
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        self.choice_for(problem)
            .solve_observed(problem, start, observer)
    }

    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState> {
        self.choice_for(problem)
            .solve_in(problem, start, observer, workspace)
    }
}
