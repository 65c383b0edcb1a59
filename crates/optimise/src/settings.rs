//! The settings of the optimisation methods, with the library's defaults, as code builds them
//! and scene files write them, and [`OptimisationMethod`], which names a method and runs it.

use contopt_contact::conic;
use contopt_contact::ContactSolver;
use contopt_core::observe::Method;
use contopt_core::{check, Result};
use serde::{Deserialize, Serialize};

use crate::{Mode, Optimisation, Optimum};

/// The settings of the iteration of §3.2 ([`Optimisation::iterate`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct IterationSettings {
    /// Stop when TOLH (4.2), Σⱼ (Δhⱼ⁽ᵏ⁾ − Δhⱼ⁽ᵏ⁻¹⁾)², falls to this \[mm²\].
    pub tolh_mm2: f64,
    /// The largest number of passes (steps 3–7).
    pub max_iterations: usize,
}

impl IterationSettings {
    /// The paper's criterion, TOLH ≤ 0.5·10⁻⁶ mm² (§4, Table 2).
    pub const TOLH_MM2: f64 = 0.5e-6;
    /// Passes before the loop stops short: the paper's tables need at most seven.
    pub const MAX_ITERATIONS: usize = 100;

    /// The settings, checked: TOLH positive and finite, at least one pass.
    pub fn check(&self) -> Result<()> {
        check::positive("tolh_mm2", self.tolh_mm2)?;
        check::count("max_iterations", self.max_iterations, 1, usize::MAX)?;
        Ok(())
    }
}

impl Default for IterationSettings {
    fn default() -> Self {
        Self {
            tolh_mm2: Self::TOLH_MM2,
            max_iterations: Self::MAX_ITERATIONS,
        }
    }
}

/// The settings of the load split ([`Optimisation::load_split`],
/// [`Optimisation::envelope_split`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LoadSplitSettings {
    /// Stop when every column's Ω_v pressure is within this fraction of p_max of v·p_max.
    pub tolerance: f64,
    /// The largest number of updates of the columns' loads (one contact solve per case each).
    pub max_iterations: usize,
}

impl LoadSplitSettings {
    /// The default relative miss of v·p_max: far below what a pressure is read to
    /// (convergence), reached in tens of updates.
    pub const TOLERANCE: f64 = 1e-8;
    /// Updates before the split stops short.
    pub const MAX_ITERATIONS: usize = 100;

    /// The settings, checked: the tolerance in (0, 1), at least one update.
    pub fn check(&self) -> Result<()> {
        check::between("tolerance", self.tolerance, 0.0, 1.0)?;
        check::count("max_iterations", self.max_iterations, 1, usize::MAX)?;
        Ok(())
    }
}

impl Default for LoadSplitSettings {
    fn default() -> Self {
        Self {
            tolerance: Self::TOLERANCE,
            max_iterations: Self::MAX_ITERATIONS,
        }
    }
}

/// The settings of the linear programme (3.5) ([`Optimisation::linear_programme`]).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct LinearProgrammeSettings {
    /// The largest number of passes, each a programme restricted by the contact set of the
    /// last (the complementarity pᵀd = 0 of 3.5).
    pub max_passes: usize,
    /// The interior point's feasibility and duality-gap tolerance ([`conic::settings`]), on
    /// the directions a pass leaves free once its equalities are eliminated.
    pub tolerance: f64,
}

impl LinearProgrammeSettings {
    /// Passes before the programme stops short: one when the seed's contact set is the
    /// optimum's (a roller seeded by the load split, a region that is all Ω_v), a few when a
    /// pass moves the edge of contact.
    pub const MAX_PASSES: usize = 10;
    /// The interior point's default tolerance.
    pub const TOLERANCE: f64 = conic::TOLERANCE;
    /// The n × n matrices a pass holds at once on n interface points: the influence matrix,
    /// its equalities Eᵀ and their QR.
    pub const DENSE_COPIES: u64 = 3;

    /// The settings, checked: at least one pass, the tolerance positive and finite.
    pub fn check(&self) -> Result<()> {
        check::count("max_passes", self.max_passes, 1, usize::MAX)?;
        check::positive("tolerance", self.tolerance)?;
        Ok(())
    }
}

impl Default for LinearProgrammeSettings {
    fn default() -> Self {
        Self {
            max_passes: Self::MAX_PASSES,
            tolerance: Self::TOLERANCE,
        }
    }
}

/// An optimisation method and its settings, as a scene names it
/// (`{ kind = "given_load", tolh_mm2 = 1e-8 }`): every field not given takes the library's
/// default.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OptimisationMethod {
    /// The iteration of §3.2 under a given load (Tables 1 and 3).
    GivenLoad(IterationSettings),
    /// The iteration of §3.2 under a given displacement (Table 2).
    GivenDisplacement(IterationSettings),
    /// The restricted linear programme (3.5) on the dense influence matrix.
    LinearProgramme(LinearProgrammeSettings),
    /// The optimum of (3.5) from the loads carried by the design columns.
    LoadSplit(LoadSplitSettings),
}

impl Default for OptimisationMethod {
    /// The paper's iteration under a given load.
    fn default() -> Self {
        OptimisationMethod::GivenLoad(IterationSettings::default())
    }
}

impl OptimisationMethod {
    /// Runs the method on `optimisation` with `solver` for its contact solves.
    pub fn run(&self, optimisation: &Optimisation, solver: &dyn ContactSolver) -> Result<Optimum> {
        match self {
            OptimisationMethod::GivenLoad(s) => optimisation.iterate(Mode::GivenLoad, solver, s),
            OptimisationMethod::GivenDisplacement(s) => {
                optimisation.iterate(Mode::GivenDisplacement, solver, s)
            }
            OptimisationMethod::LinearProgramme(s) => optimisation.linear_programme(solver, s),
            OptimisationMethod::LoadSplit(s) => optimisation.load_split(solver, s),
        }
    }

    /// The method, as its events name it.
    pub fn method(&self) -> Method {
        match self {
            OptimisationMethod::GivenLoad(_) | OptimisationMethod::GivenDisplacement(_) => {
                Method::GapIteration
            }
            OptimisationMethod::LinearProgramme(_) => Method::LinearProgramme,
            OptimisationMethod::LoadSplit(_) => Method::LoadSplit,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Defaults fill what a file leaves out; unknown fields and bad values are named.
    #[test]
    fn settings_read_with_defaults_and_are_checked() {
        let m: OptimisationMethod = serde_json::from_str(r#"{"given_load": {}}"#).unwrap();
        assert_eq!(m, OptimisationMethod::default());
        assert_eq!(m.method(), Method::GapIteration);
        let m: OptimisationMethod =
            serde_json::from_str(r#"{"load_split": {"tolerance": 1e-6}}"#).unwrap();
        assert_eq!(
            m,
            OptimisationMethod::LoadSplit(LoadSplitSettings {
                tolerance: 1e-6,
                max_iterations: 100
            })
        );
        let e = serde_json::from_str::<OptimisationMethod>(r#"{"given_load": {"tolh": 1}}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown field `tolh`"), "{e}");
        let s = IterationSettings {
            tolh_mm2: f64::NAN,
            ..IterationSettings::default()
        };
        assert!(s.check().unwrap_err().to_string().contains("tolh_mm2"));
        let s = IterationSettings {
            max_iterations: 0,
            ..IterationSettings::default()
        };
        assert!(s
            .check()
            .unwrap_err()
            .to_string()
            .contains("max_iterations"));
        let s = LinearProgrammeSettings {
            tolerance: 0.0,
            ..LinearProgrammeSettings::default()
        };
        assert!(s.check().unwrap_err().to_string().contains("tolerance"));
        let s = LinearProgrammeSettings {
            max_passes: 0,
            ..LinearProgrammeSettings::default()
        };
        assert!(s.check().unwrap_err().to_string().contains("max_passes"));
        let s = LoadSplitSettings {
            tolerance: 1.0,
            ..LoadSplitSettings::default()
        };
        assert!(s.check().unwrap_err().to_string().contains("tolerance"));
    }
}
