//! A roller's robust crown: the symmetric crown with the least worst-case p_max over its
//! envelope of loads and tilts, by the envelope load split.

use contopt_core::observe::Method;
use contopt_core::{Error, Result};
use contopt_optimise::LoadSplitSettings;
use contopt_results::CaseReport;
use contopt_roller::CaseContact;
use serde::{Deserialize, Serialize};

use super::{
    cell_across, check_controller, controller, roller_figures, straight_roller, BearingCrown,
    Check, Context, Design, Designed,
};

/// A roller's symmetric crown with the least worst-case p_max over its `[envelope]`: max over
/// the cases of p ≤ v·p_max, by the envelope load split (`envelope_split`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(transparent)]
pub struct EnvelopeSplit(pub LoadSplitSettings);

impl Design for EnvelopeSplit {
    fn check(&self, c: &Check) -> Result<()> {
        if c.case.roller.is_none() {
            return Err(Error::invalid(
                "method",
                "envelope_split",
                "designs a roller's crown: contact.gap = { kind = \"roller\", … }",
            ));
        }
        if c.case.envelope.is_none() {
            return Err(Error::invalid(
                "method",
                "envelope_split",
                "serves an [envelope] of load cases: give its load_factors and tilts_arcmin",
            ));
        }
        check_controller(c)?;
        self.0.check()?;
        straight_roller(c, "envelope_split")
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let started = std::time::Instant::now();
        let controller = controller(c)?;
        let dy = cell_across(c.case.layout);
        let crown = contopt_roller::robust_crown(
            c.cases,
            None,
            controller.as_ref(),
            dy,
            c.solver,
            &self.0,
            c.observer,
        )?;
        report.time("optimise", started);
        let own = crown.cases.first();
        let contacts: Vec<CaseContact> = crown
            .cases
            .iter()
            .zip(c.cases)
            .map(|(s, case)| CaseContact {
                load_n: case.load_n,
                tilt_arcmin: case.tilt_arcmin,
                pressure: &s.pressure,
                approach_mm: s.approach_mm,
            })
            .collect();
        let complete = contacts.len() == c.cases.len() && crown.termination.is_solved();
        let roller = complete
            .then(|| roller_figures(c, &contacts, &crown.drop, None))
            .flatten();
        Ok(Designed {
            method: Some(Method::EnvelopeSplit),
            solver: Some(c.solver.method_for(c.problem)),
            termination: crown.termination.clone(),
            pressure: own.map(|s| s.pressure.clone()).unwrap_or_default(),
            gap: own.map(|s| s.gap.clone()).unwrap_or_default(),
            rigid: own.map(|s| vec![-s.approach_mm]).unwrap_or_default(),
            bound_p_max: Some(crown.p_max),
            dh_max: Some(crown.drop.iter().fold(0.0, |m: f64, v| m.max(*v))),
            omega_nv_excess: crown.omega_nv_excess,
            gap_change: crown.drop,
            crown: None,
            passes: vec![],
            roller,
            shown_gap: None,
        })
    }

    fn bearing_crown(&self) -> Option<BearingCrown> {
        Some(BearingCrown::Envelope(self.0))
    }
}
