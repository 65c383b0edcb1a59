//! Every contact solver by its settings, for files and for code that chooses a solver at run
//! time: [`SolverSettings`] names one and [`SolverSettings::build`] makes it, checked.

use contopt_core::observe::{Method, Observer};
use contopt_core::{ContactState, Result};
use serde::{Deserialize, Serialize};

use crate::{
    ActiveSet, ActiveSetSettings, AugmentedLagrangian, AugmentedLagrangianSettings, ContactSolver,
    InterfaceProblem, Penalty, PenaltySettings, PolonskyKeer, PolonskyKeerSettings, Qp, QpSettings,
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

/// The solver chosen per problem: Kalker's exact [`ActiveSet`] on interfaces of at most
/// [`Auto::DENSE_POINTS`] points, whose dense matrix is small and whose solves are direct;
/// [`PolonskyKeer`] beyond, through the bodies' operators (FFT products on grids), never a
/// dense matrix. Both are exact: they agree to their tolerances. A state says which solved it
/// ([`ContactState::method`]).
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

    /// The solver a problem of `points` points gets.
    pub fn choice(&self, points: usize) -> &dyn ContactSolver {
        if points <= Self::DENSE_POINTS {
            &self.dense
        } else {
            &self.iterative
        }
    }
}

impl ContactSolver for Auto {
    /// The method of the choice on the smallest interfaces; each state names its own.
    fn method(&self) -> Method {
        self.dense.method()
    }

    fn dense_copies(&self, points: usize) -> u64 {
        self.choice(points).dense_copies(points)
    }

    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        self.choice(problem.len())
            .solve_observed(problem, start, observer)
    }
}
