//! No design: the contact of the given bodies and gap, solved once.

use std::cell::RefCell;

use contopt_core::observe::{Event, Flow, Observer};
use contopt_core::Result;
use contopt_results::{CaseReport, MethodSteps, SolveSteps};

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
        let counted = Counted::new(c.observer);
        let state = c.solver.solve_observed(c.problem, None, &counted)?;
        report.time("solve", started);
        let mut steps = counted.steps.into_inner();
        steps.sort_by_key(|s| s.level);
        report.solve = Some(SolveSteps {
            steps,
            iterp: state.iterp,
            iterd: state.iterd,
        });
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

/// An observer that counts a solve's steps by method and level and passes every event on.
struct Counted<'a> {
    inner: &'a dyn Observer,
    steps: RefCell<Vec<MethodSteps>>,
}

impl<'a> Counted<'a> {
    fn new(inner: &'a dyn Observer) -> Self {
        Self {
            inner,
            steps: RefCell::new(vec![]),
        }
    }
}

impl Observer for Counted<'_> {
    /// A step is an event that does not end its method (the last event repeats the last
    /// step with how it ended).
    fn observe(&self, e: &Event) -> Flow {
        if e.end.is_none() {
            let mut steps = self.steps.borrow_mut();
            match steps
                .iter_mut()
                .find(|s| s.method == e.method && s.level == e.level)
            {
                Some(s) => s.steps += 1,
                None => steps.push(MethodSteps {
                    method: e.method,
                    level: e.level,
                    steps: 1,
                }),
            }
        }
        self.inner.observe(e)
    }
}
