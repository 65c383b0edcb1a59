//! Observers of iterative methods, as argmin has them: a contact solver or the optimisation
//! loop reports each of its iterations to an [`Observer`], which may log it, draw a progress
//! bar or stop the method early.
//!
//! ```
//! use std::cell::Cell;
//! use contopt_core::observe::{Flow, Iteration, Observer};
//!
//! // Stop any method after 3 iterations, counting what it reported.
//! let seen = Cell::new(0);
//! let stop_at_three = |it: &Iteration| {
//!     seen.set(seen.get() + 1);
//!     if it.iteration >= 3 { Flow::Stop } else { Flow::Continue }
//! };
//! let observer: &dyn Observer = &stop_at_three;
//! let it = Iteration { method: "demo", iteration: 3, measure: 1.0, tolerance: 0.1 };
//! assert_eq!(observer.observe(&it), Flow::Stop);
//! assert_eq!(seen.get(), 1);
//! ```

/// One iteration of an iterative method, as it reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration<'a> {
    /// The method: a contact solver's name (`"Polonsky-Keer"`, `"augmented Lagrangian"`,
    /// `"active set"`, …) or `"optimisation"` for the loop of §3.2.
    pub method: &'a str,
    /// The iteration's number, from 1, counted by that method.
    pub iteration: usize,
    /// The method's convergence measure after this iteration (a relative residual, a change
    /// of the pressure, TOLH of eq. 4.2); NaN when the method has none.
    pub measure: f64,
    /// The value `measure` must reach for the method to stop converged.
    pub tolerance: f64,
}

/// What an observer asks of the method that reported to it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[must_use]
pub enum Flow {
    /// Go on iterating.
    #[default]
    Continue,
    /// Stop now: the method returns its last iterate as
    /// [`Status::Stopped`](crate::Status::Stopped), saying that an observer stopped it.
    Stop,
}

/// Receives the iterations of a method. Takes `&self` so that one observer can be shared by
/// nested methods (the optimisation loop and the contact solves inside it); keep its state in
/// a `Cell`, a `RefCell` or a lock. Any `Fn(&Iteration) -> Flow` closure is an observer.
pub trait Observer {
    /// Called after each iteration of a method.
    fn observe(&self, iteration: &Iteration) -> Flow;
}

/// The observer that sees nothing and never stops a method: the default.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Observer for Silent {
    fn observe(&self, _: &Iteration) -> Flow {
        Flow::Continue
    }
}

impl<F: Fn(&Iteration) -> Flow> Observer for F {
    fn observe(&self, iteration: &Iteration) -> Flow {
        self(iteration)
    }
}

/// The reason a method gives when an observer stopped it after `iterations` iterations.
pub fn stopped_by_observer(iterations: usize) -> String {
    format!("stopped by an observer after {iterations} iterations")
}
