//! A roller's Fujiwara–Kawase profile tuned for its envelope (or its own load) by a
//! Nelder–Mead search: the published practice the optimised crowns are compared with.

use contopt_core::observe::Method;
use contopt_core::{Error, Result};
use contopt_optimise::SearchSettings;
use contopt_results::{CaseReport, TunedProfile};

use super::{contacts, roller_figures, straight_roller, Check, Context, Design, Designed};

/// The profile search.
pub(crate) struct ProfileSearch(pub SearchSettings);

impl Design for ProfileSearch {
    fn check(&self, c: &Check) -> Result<()> {
        if !c.roller {
            return Err(Error::invalid(
                "method",
                "profile_search",
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
                "the profile search tunes Fujiwara–Kawase's parameters and takes no controller",
            ));
        }
        self.0.check()?;
        straight_roller(c, "profile_search")
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let roller = c
            .plan
            .roller
            .as_ref()
            .ok_or_else(|| Error::invalid("method", "profile_search", "needs a roller gap"))?;
        let started = std::time::Instant::now();
        let tuned =
            contopt_roller::tune_fujiwara_kawase(c.cases, roller, c.solver, &self.0, c.observer)?;
        report.time("search", started);
        let profile = TunedProfile {
            k1: tuned.k1,
            k2: tuned.k2,
            z_m_um: 1e3 * tuned.z_m_mm,
            evaluations: tuned.evaluations,
        };
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
