//! A roller's crown of a family tuned for its envelope (or its own load) by a Nelder–Mead
//! search: Fujiwara–Kawase's profile, the published practice the optimised crowns are
//! compared with, or a circular crown.

use std::marker::PhantomData;

use contopt_contact::{ContactSolver, InterfaceProblem};
use contopt_core::observe::Method;
use contopt_core::{Error, Result};
use contopt_optimise::SearchSettings;
use contopt_results::{CaseReport, TunedProfile};
use contopt_roller::{solve_cases, Crown, ProfileFamily, TunedCrown};
use serde::{Deserialize, Serialize};

use super::{
    contacts, roller_figures, straight_roller, BearingCrown, Check, Context, Design, Designed,
};

/// A family of crowns a profile search tunes.
pub trait Family: Send + Sync + 'static {
    /// The family.
    const FAMILY: ProfileFamily;
}

/// Fujiwara–Kawase's logarithmic profile (K1, K2, z_m).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FujiwaraKawase;

impl Family for FujiwaraKawase {
    const FAMILY: ProfileFamily = ProfileFamily::FujiwaraKawase;
}

/// A circular crown (its crowned fraction and end drop).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Circular;

impl Family for Circular {
    const FAMILY: ProfileFamily = ProfileFamily::Circular;
}

/// A roller's crown of the family `F` with its parameters tuned by a Nelder–Mead search to the
/// least worst-case p_max over its `[envelope]` (or its own load), edge-loaded crowns
/// penalised.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct ProfileSearch<F> {
    /// The search's settings.
    pub settings: SearchSettings,
    #[serde(skip)]
    family: PhantomData<F>,
}

/// Fujiwara–Kawase's K1, K2 and z_m tuned (`profile_search`).
pub type FujiwaraKawaseSearch = ProfileSearch<FujiwaraKawase>;

/// A circular crown's crowned fraction and end drop tuned (`circular_search`).
pub type CircularSearch = ProfileSearch<Circular>;

impl<F: Family> Design for ProfileSearch<F> {
    fn check(&self, c: &Check) -> Result<()> {
        Search(self.settings, F::FAMILY).check(c)
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        Search(self.settings, F::FAMILY).run(c, report)
    }

    fn bearing_crown(&self) -> Option<BearingCrown> {
        Some(BearingCrown::Search(F::FAMILY, self.settings))
    }
}

/// The profile search of a family.
struct Search(SearchSettings, ProfileFamily);

/// A tuned crown's parameters, as the report gives them.
pub(crate) fn tuned_profile(tuned: &TunedCrown) -> TunedProfile {
    let (family, radius_mm) = match (&tuned.family, &tuned.crown) {
        (ProfileFamily::Circular, Crown::Circular { radius, .. }) => ("circular", Some(*radius)),
        (ProfileFamily::Circular, _) => ("circular", None),
        (ProfileFamily::FujiwaraKawase, _) => ("fujiwara_kawase", None),
    };
    TunedProfile {
        family: family.into(),
        k1: tuned.k1,
        k2: tuned.k2,
        z_m_um: 1e3 * tuned.z_m_mm,
        radius_mm,
        evaluations: tuned.evaluations,
    }
}

impl Search {
    fn check(&self, c: &Check) -> Result<()> {
        if c.case.roller.is_none() {
            return Err(Error::invalid(
                "method",
                c.case.method,
                "tunes a roller's crown: contact.gap = { kind = \"roller\", … }",
            ));
        }
        if c.case.controller.is_some() {
            return Err(Error::invalid(
                "controller",
                "given",
                "a profile search tunes its family's parameters and takes no controller",
            ));
        }
        self.0.check()?;
        straight_roller(c, c.case.method)
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let roller = (c.case.roller)
            .ok_or_else(|| Error::invalid("method", c.case.method, "needs a roller gap"))?;
        let started = std::time::Instant::now();
        let points = c.problem.interface().points();
        let mut worst = |states: &[contopt_core::ContactState]| {
            Ok(contopt_roller::penalised_worst(points, states))
        };
        let loose = search_solver(c.solver, c.problem);
        let searcher = loose.as_deref().unwrap_or(c.solver);
        let mut tuned = contopt_roller::tune_profile(
            c.cases, roller, self.1, searcher, &self.0, &mut worst, c.observer,
        )?;
        if loose.is_some() && tuned.states.len() == c.cases.len() {
            // The designed crown's contacts again, at the scene's own tolerance.
            let start = Some(tuned.states.as_slice());
            tuned.states = solve_cases(c.cases, &tuned.drop, c.solver, start, c.observer)?;
        }
        report.time("search", started);
        let profile = tuned_profile(&tuned);
        let own = tuned.states.first();
        let complete = tuned.states.len() == c.cases.len() && !tuned.termination.is_stopped();
        let figures = complete
            .then(|| roller_figures(c, &contacts(c, &tuned.states), &tuned.drop, Some(profile)))
            .flatten();
        Ok(Designed {
            method: Some(Method::ProfileSearch),
            solver: Some(c.solver.method_for(c.problem)),
            termination: tuned.termination.clone(),
            pressure: own.map(|s| s.pressure.clone()).unwrap_or_default(),
            gap: own.map(|s| s.gap.clone()).unwrap_or_default(),
            rigid: own.map(|s| s.rigid.clone()).unwrap_or_default(),
            bound_p_max: None,
            dh_max: None,
            omega_nv_excess: None,
            gap_change: tuned.drop,
            crown: None,
            passes: vec![],
            roller: figures,
            shown_gap: None,
        })
    }
}

/// The relative tolerance of the contact solves of a profile search's crowns, when the
/// scene's is tighter: Polonsky–Keer's relative pressure change per step (its
/// [`PolonskyKeerSettings::tolerance`]). A search compares objectives to about 10⁻⁵ of the
/// worst p_max (its tolerance, 0.05 MPa on 2300 MPa); solved to 10⁻⁶ instead of 10⁻¹² the
/// bundled bearing's Fujiwara–Kawase search takes the same 107 crowns to the same crown in
/// half the time, its worst p_max 0.002 MPa off; `roller-envelope`'s, the same crowns to the
/// printed digit. The designed crown's contacts are solved
/// again at the scene's tolerance.
const SEARCH_SOLVE_TOLERANCE: f64 = 1e-6;

/// The contact solver of a profile search's crowns: the scene's solver loosened to
/// [`SEARCH_SOLVE_TOLERANCE`] where it solves `problem` by Polonsky–Keer (named, or chosen by
/// `auto`) at a tighter tolerance; `None` to search with the scene's solver.
pub(crate) fn search_solver(
    solver: &dyn ContactSolver,
    problem: &InterfaceProblem,
) -> Option<Box<dyn ContactSolver>> {
    (solver.method_for(problem) == Method::PolonskyKeer)
        .then(|| solver.loosened(SEARCH_SOLVE_TOLERANCE))
        .flatten()
}
