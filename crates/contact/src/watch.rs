//! How a method reports to its observer: each iteration as an [`Event`] of the method, numbered
//! on across the loops of one solve, and its last event with how it ended.

use contopt_core::drive::Driver;
use contopt_core::observe::{Event, Method, Observer};
use contopt_core::{ContactState, Termination};

/// Where a method reports its iterations: the observer, the method they carry and how many
/// came before in the same solve, so that the numbers run on across the loops of one solve (a
/// penalty solve's start at c_stiff and its main solve).
#[derive(Clone, Copy)]
pub(crate) struct Watch<'a> {
    observer: &'a dyn Observer,
    method: Method,
    before: usize,
}

impl<'a> Watch<'a> {
    pub(crate) fn new(observer: &'a dyn Observer, method: Method) -> Self {
        Self {
            observer,
            method,
            before: 0,
        }
    }

    /// Its observer.
    pub(crate) fn observer(&self) -> &'a dyn Observer {
        self.observer
    }

    /// The same watch for a loop that follows `before` iterations of the solve.
    pub(crate) fn after(self, before: usize) -> Self {
        Self { before, ..self }
    }

    /// The driver of a loop of the watched method that follows the iterations before it,
    /// whose measure must reach `tolerance` in at most `max_steps` steps.
    pub(crate) fn driver(&self, tolerance: f64, max_steps: usize) -> Driver<'a> {
        Driver::new(self.method, self.observer, tolerance, max_steps).after(self.before)
    }
}

/// Tells `observer` how the solve that gave `state` ended: its last event, with the number of
/// its iterations (`iterp` for the methods that count only Kalker's solves).
pub(crate) fn announce(observer: &dyn Observer, state: &ContactState) {
    let iteration = state.iterations.max(state.iterp);
    let event = Event::step(state.method, iteration, f64::NAN, f64::NAN).ending(&state.termination);
    let _ = observer.observe(&event);
}

/// Marks `state` as ended by `termination` unless it already says that a value is not finite
/// (which [`ContactState::stop_if_not_finite`] put there: it says more).
pub(crate) fn end(state: &mut ContactState, termination: Termination) {
    if !matches!(state.termination, Termination::NonFinite { .. }) {
        state.termination = termination;
    }
}
