//! The rows of an optimisation loop and its reports to the observer: one event per pass at
//! level 0, and a last event with how the loop ended.

use contopt_core::observe::{Event, Flow, Method, Observer};
use contopt_core::Termination;

use crate::{Optimum, Pass};

/// A loop's passes so far and where it reports them.
pub(crate) struct Passes<'o> {
    observer: &'o dyn Observer,
    method: Method,
    tolerance: f64,
    rows: Vec<Pass>,
    /// The measure of the last pass (NaN before the first).
    measure: f64,
}

impl<'o> Passes<'o> {
    /// No passes yet of `method`, whose measure must reach `tolerance`.
    pub(crate) fn new(observer: &'o dyn Observer, method: Method, tolerance: f64) -> Self {
        Self {
            observer,
            method,
            tolerance,
            rows: vec![],
            measure: f64::NAN,
        }
    }

    /// Records `row` with its convergence `measure` and reports it; what the observer asks.
    pub(crate) fn push(&mut self, row: Pass, measure: f64) -> Flow {
        self.rows.push(row);
        self.measure = measure;
        let event = Event::step(self.method, row.k, measure, self.tolerance);
        self.observer.observe(&event)
    }

    /// The step limit after the passes so far.
    pub(crate) fn step_limit(&self) -> Termination {
        Termination::StepLimit {
            steps: self.rows.len(),
            measure: self.measure,
            tolerance: self.tolerance,
        }
    }

    /// `optimum` with these rows, ended as `termination`, after the last event says so.
    pub(crate) fn finish(self, optimum: Optimum, termination: Termination) -> Optimum {
        let event = Event::step(self.method, self.rows.len(), self.measure, self.tolerance)
            .ending(&termination);
        let _ = self.observer.observe(&event);
        Optimum {
            passes: self.rows,
            method: self.method,
            termination,
            ..optimum
        }
    }
}
