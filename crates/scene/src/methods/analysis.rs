//! No design: the contact of the given bodies and gap, solved once.

use contopt_core::Result;
use contopt_results::CaseReport;

use super::{contacts, envelope_contacts, roller_figures, Check, Context, Design, Designed};

/// The contact analysed as it is.
pub(crate) struct Analysis;

impl Design for Analysis {
    fn check(&self, _c: &Check) -> Result<()> {
        Ok(())
    }

    /// One contact solve; a roller's crown shown as its Δh, and its envelope's cases solved
    /// under the same crown.
    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let started = std::time::Instant::now();
        let state = c.solver.solve_observed(c.problem, None, c.observer)?;
        report.time("solve", started);
        let mut designed = Designed::contact(state.clone());
        if let (Some(roller), true) = (c.case.roller, state.termination.is_solved()) {
            let length = roller.length;
            let drop = c
                .problem
                .interface()
                .points()
                .iter()
                .map(|x| roller.crown.drop(x[0], length))
                .collect::<Result<Vec<f64>>>()?;
            match envelope_contacts(c, &state, &[], report)? {
                Ok(states) => {
                    designed.roller = roller_figures(c, &contacts(c, &states), &drop, None)
                }
                Err(why) => designed.termination = why,
            }
            designed.crown = Some(drop);
        }
        Ok(designed)
    }
}
