//! A roller's crown of a family tuned for its envelope (or its own load) by a Nelder–Mead
//! search: Fujiwara–Kawase's profile, the published practice the optimised crowns are
//! compared with, or a circular crown.

use contopt_core::observe::Method;
use contopt_core::{Error, Result};
use contopt_optimise::SearchSettings;
use contopt_results::{CaseReport, TunedProfile};
use contopt_roller::{Crown, ProfileFamily, TunedCrown};

use super::{contacts, roller_figures, straight_roller, Check, Context, Design, Designed};

/// The profile search of a family.
pub(crate) struct ProfileSearch(pub SearchSettings, pub ProfileFamily);

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

impl ProfileSearch {
    /// The method's name in a scene.
    fn name(&self) -> &'static str {
        match self.1 {
            ProfileFamily::FujiwaraKawase => "profile_search",
            ProfileFamily::Circular => "circular_search",
        }
    }
}

impl Design for ProfileSearch {
    fn check(&self, c: &Check) -> Result<()> {
        if !c.roller {
            return Err(Error::invalid(
                "method",
                self.name(),
                "tunes a roller's crown: contact.gap = { kind = \"roller\", … }",
            ));
        }
        if c.spec
            .optimisation
            .as_ref()
            .is_some_and(|o| o.controller.is_some())
        {
            return Err(Error::invalid(
                "controller",
                "given",
                "a profile search tunes its family's parameters and takes no controller",
            ));
        }
        self.0.check()?;
        straight_roller(c, self.name())
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let roller = c
            .plan
            .roller
            .as_ref()
            .ok_or_else(|| Error::invalid("method", self.name(), "needs a roller gap"))?;
        let started = std::time::Instant::now();
        let points = c.problem.interface().points();
        let mut worst = |states: &[contopt_core::ContactState]| {
            Ok(contopt_roller::penalised_worst(points, states))
        };
        let tuned = contopt_roller::tune_profile(
            c.cases, roller, self.1, c.solver, &self.0, &mut worst, c.observer,
        )?;
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
        })
    }
}
