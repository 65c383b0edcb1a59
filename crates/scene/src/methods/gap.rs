//! The paper's methods for the initial gap (§3): the iteration of §3.2 under a given load or a
//! given displacement, the restricted linear programme (3.5), and the load split, its optimum
//! without a dense matrix.

use contopt_core::observe::Method;
use contopt_core::{Error, Result};
use contopt_optimise::{LinearProgrammeSettings, OptimisationMethod};
use contopt_results::CaseReport;

use super::{
    check_controller, contacts, envelope_contacts, optimisation_of, roller_figures, setup,
    straight_roller, Check, Context, Design, Designed,
};

/// One of the library's optimisation methods ([`OptimisationMethod`]).
pub struct Gap(pub OptimisationMethod);

impl Design for Gap {
    /// A controller within the zone; a given load needs a floating body, a given displacement
    /// and the linear programme's pin none or one; a roller starts straight.
    fn check(&self, c: &Check) -> Result<()> {
        check_controller(c)?;
        let name = c.case.method;
        match (&self.0, c.floating) {
            (OptimisationMethod::GivenLoad(s), true) => s.check()?,
            (OptimisationMethod::GivenDisplacement(s), false) => s.check()?,
            (OptimisationMethod::LoadSplit(s), true) => s.check()?,
            (OptimisationMethod::LinearProgramme(s), _) => s.check()?,
            (OptimisationMethod::GivenLoad(_) | OptimisationMethod::LoadSplit(_), false) => {
                return Err(Error::invalid(
                    "method",
                    name,
                    "needs a given load on a floating body (contact.load = { force_n }, or a \
                     punch under a pressure); for a given displacement take \
                     \"given_displacement\"",
                ))
            }
            (OptimisationMethod::GivenDisplacement(_), true) => {
                return Err(Error::invalid(
                    "method",
                    "given_displacement",
                    "a body floats under a given load: take \"given_load\" (or \"load_split\")",
                ))
            }
        }
        straight_roller(c, name)
    }

    fn dense_copies(&self, points: usize, solver: &dyn contopt_contact::ContactSolver) -> u64 {
        match self.0 {
            OptimisationMethod::LinearProgramme(_) => {
                LinearProgrammeSettings::DENSE_COPIES.max(solver.dense_copies(points))
            }
            _ => solver.dense_copies(points),
        }
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        let started = std::time::Instant::now();
        let setup = setup(c)?;
        let optimisation = optimisation_of(c, &setup)?;
        let optimum = self.0.run(&optimisation, c.solver)?;
        report.time("optimise", started);
        let solver: Option<Method> = Some(c.solver.method_for(c.problem));
        let mut designed = Designed {
            method: Some(optimum.method),
            solver,
            termination: optimum.termination.clone(),
            bound_p_max: Some(optimum.p_max),
            // The paper's Δh_max is the last pass's (Table 2): the change that pass computed,
            // within √TOLH of the one the returned contact was solved with.
            dh_max: Some(optimum.passes.last().map_or(optimum.dh_max(), |p| p.dh_max)),
            omega_nv_excess: optimum.omega_nv_excess,
            passes: optimum.passes.clone(),
            pressure: optimum.pressure.clone(),
            gap: optimum.gap.clone(),
            rigid: optimum.rigid.clone(),
            gap_change: optimum.gap_change.clone(),
            crown: None,
            roller: None,
            shown_gap: None,
        };
        if c.case.roller.is_some() && optimum.termination.is_solved() {
            let own = contopt_core::ContactState {
                pressure: optimum.pressure,
                gap: optimum.gap,
                rigid: optimum.rigid,
                active: vec![],
                iterations: 0,
                iterp: 0,
                iterd: 0,
                residuals: Default::default(),
                method: optimum.method,
                termination: optimum.termination,
            };
            match envelope_contacts(c, &own, &optimum.gap_change, report)? {
                Ok(states) => {
                    let figures = contacts(c, &states);
                    designed.roller = roller_figures(c, &figures, &optimum.gap_change, None);
                }
                Err(why) => designed.termination = why,
            }
        }
        Ok(designed)
    }
}
