//! The one iteration loop of the library (argmin's `Executor`, in our words): a [`Driver`]
//! counts a method's steps, checks its step limit, reports each step to an [`Observer`],
//! honours a stop and returns how the method ended as a typed [`Termination`]. A method
//! supplies its step only, as a closure that says what the step came to ([`Step`]).
//!
//! The optimisations of §3.2 and (3.5), the load split, the profile search and the bearing's
//! ring equilibrium run on it; a solver or a design of your own runs on it the same way.
//!
//! ```
//! use std::cell::Cell;
//! use contopt_core::drive::{Driver, Step};
//! use contopt_core::observe::{Event, Flow, Method};
//! use contopt_core::Termination;
//!
//! // Halve x until it is below 10⁻³, at most 20 steps, an observer counting the steps.
//! let seen = Cell::new(0);
//! let count = |e: &Event| {
//!     seen.set(seen.get() + 1);
//!     Flow::Continue
//! };
//! let mut driver = Driver::new(Method::Other("halving"), &count, 1e-3, 20);
//! let mut x = 1.0;
//! let end = driver.run(|_, _| {
//!     x *= 0.5;
//!     Ok::<_, ()>(Step::converged_below(x, 1e-3))
//! })?;
//! driver.announce(&end);
//! assert_eq!(end, Termination::Converged);
//! assert_eq!((driver.steps(), seen.get()), (10, 11)); // ten steps and the last event
//!
//! // The same with a limit of 5 steps ends at the limit, where x stood.
//! let mut driver = Driver::new(Method::Other("halving"), &count, 1e-3, 5);
//! let mut x = 1.0;
//! let end = driver.run(|_, _| {
//!     x *= 0.5;
//!     Ok::<_, ()>(Step::converged_below(x, 1e-3))
//! })?;
//! assert_eq!(end, Termination::StepLimit { steps: 5, measure: 0.03125, tolerance: 1e-3 });
//! # Ok::<(), ()>(())
//! ```

use crate::observe::{Event, Flow, Method, Observer};
use crate::Termination;

/// What one step of a method came to.
#[derive(Clone, Debug, PartialEq)]
pub enum Step {
    /// The step is done, with its convergence measure: it is reported, and the method goes
    /// on unless the observer stops it or the step limit is reached.
    Next(f64),
    /// The step is done, with its measure, and it is the method's last: it is reported, and
    /// the method ends as the termination says (an observer's stop asks for no more).
    Last(f64, Termination),
    /// The step could not be done (an inner method that ended short, a value that is not
    /// finite): the method ends as the termination says, the step unreported.
    Ended(Termination),
}

impl Step {
    /// A step whose `measure` converged when it is at most `tolerance`.
    pub fn converged_below(measure: f64, tolerance: f64) -> Self {
        match measure <= tolerance {
            true => Step::Last(measure, Termination::Converged),
            false => Step::Next(measure),
        }
    }
}

/// How the inner methods a driven method goes on from ended: the first answer of reduced
/// accuracy, which becomes the end of a method that converges.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Inner {
    reduced: Option<Termination>,
}

impl Inner {
    /// Notes how an inner method, `method`, ended: `termination`.
    pub fn note(&mut self, method: Method, termination: &Termination) {
        if self.reduced.is_none() && !termination.is_converged() && termination.is_solved() {
            self.reduced = Some(termination.clone().inside(method));
        }
    }
}

/// Reports `method`'s iteration `iteration` with its convergence `measure` and the
/// `tolerance` it must reach to `observer`: [`Termination::Stopped`] when the observer asks to
/// stop. The one report of a step, for a [`Driver`] and for a loop that numbers its own steps.
pub fn report(
    observer: &dyn Observer,
    method: Method,
    iteration: usize,
    measure: f64,
    tolerance: f64,
) -> Option<Termination> {
    let event = Event::step(method, iteration, measure, tolerance);
    (observer.observe(&event) == Flow::Stop).then_some(Termination::Stopped { after: iteration })
}

/// Runs the steps of one method: counts them, checks the step limit, reports each to the
/// observer as an [`Event`] of the method and honours its stop; keeps what the methods it
/// runs came to ([`Inner`]) to end with.
pub struct Driver<'o> {
    observer: &'o dyn Observer,
    method: Method,
    tolerance: f64,
    max_steps: usize,
    /// Steps of the same solve before this driver's, which its events number on from.
    before: usize,
    steps: usize,
    measure: f64,
    inner: Inner,
}

impl<'o> Driver<'o> {
    /// A driver of `method` reporting to `observer`, whose measure must reach `tolerance`,
    /// in at most `max_steps` steps.
    pub fn new(
        method: Method,
        observer: &'o dyn Observer,
        tolerance: f64,
        max_steps: usize,
    ) -> Self {
        Self {
            observer,
            method,
            tolerance,
            max_steps,
            before: 0,
            steps: 0,
            measure: f64::NAN,
            inner: Inner::default(),
        }
    }

    /// The same driver for a loop that follows `before` steps of the same solve (the parts of
    /// a solve on a growing part of the interface, a penalty solve's start and its main solve):
    /// its events, and the step an observer stops it after, number on from there; its own
    /// steps, and its step limit, count from 0.
    pub fn after(self, before: usize) -> Self {
        Self { before, ..self }
    }

    /// The method it drives.
    pub fn method(&self) -> Method {
        self.method
    }

    /// Steps reported so far.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Whether the steps so far reach the step limit, for a method whose steps
    /// [`Driver::report`]s.
    pub fn exhausted(&self) -> bool {
        self.steps >= self.max_steps
    }

    /// Runs `step` (given the step's number, from 1, and where to note how the inner methods
    /// it runs ended) until it ends the method, the observer stops it or the step limit is
    /// reached; how the method ended (a convergence as the first reduced accuracy noted, if
    /// any). An error of a step is returned as it is. The last event is left to
    /// [`Driver::announce`], after any check of the method's own.
    pub fn run<E>(
        &mut self,
        mut step: impl FnMut(usize, &mut Inner) -> Result<Step, E>,
    ) -> Result<Termination, E> {
        while self.steps < self.max_steps {
            let (measure, end) = match step(self.steps + 1, &mut self.inner)? {
                Step::Next(measure) => (measure, None),
                Step::Last(measure, end) => (measure, Some(end)),
                Step::Ended(end) => return Ok(self.end(end)),
            };
            match (end, self.report(measure)) {
                (Some(end), _) => return Ok(self.end(end)),
                (None, Some(stopped)) => return Ok(stopped),
                (None, None) => {}
            }
        }
        Ok(self.end(self.step_limit()))
    }

    /// Reports one more step with its convergence `measure`: [`Termination::Stopped`] when
    /// the observer asks to stop. For a method whose steps come from a loop it does not own
    /// (an objective evaluated by a search); [`Driver::run`] reports through it.
    pub fn report(&mut self, measure: f64) -> Option<Termination> {
        self.steps += 1;
        self.measure = measure;
        report(
            self.observer,
            self.method,
            self.before + self.steps,
            measure,
            self.tolerance,
        )
    }

    /// Sets the measure the last event carries, for a method whose answer is not its last
    /// step (a search's best point).
    pub fn settle(&mut self, measure: f64) {
        self.measure = measure;
    }

    /// The step limit after the steps so far, with the last measure.
    pub fn step_limit(&self) -> Termination {
        Termination::StepLimit {
            steps: self.steps,
            measure: self.measure,
            tolerance: self.tolerance,
        }
    }

    /// Where a method whose steps [`Driver::report`]s notes how the inner methods it runs
    /// ended, as [`Driver::run`] gives its steps.
    pub fn inner(&mut self) -> &mut Inner {
        &mut self.inner
    }

    /// Notes how an inner method the driven one goes on from ended, for a method whose steps
    /// [`Driver::report`]s ([`Inner::note`]).
    pub fn note(&mut self, method: Method, termination: &Termination) {
        self.inner.note(method, termination);
    }

    /// How a method that would end as `termination` ends, with the reduced accuracy noted
    /// ([`Termination::with_reduced`]).
    pub fn end(&self, termination: Termination) -> Termination {
        termination.with_reduced(self.inner.reduced.clone())
    }

    /// Reports the method's last event: the steps so far, the last measure and how it
    /// ended, `termination`.
    pub fn announce(&self, termination: &Termination) {
        let iteration = self.before + self.steps;
        let event = Event::step(self.method, iteration, self.measure, self.tolerance);
        let _ = self.observer.observe(&event.ending(termination));
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::RefCell;

    use crate::observe::Recorded;

    /// A stop ends a method that would go on, not one whose step was its last; an ended step
    /// goes unreported; a reduced accuracy noted turns the convergence.
    #[test]
    fn stops_ends_and_reduced_accuracy() {
        let stop = |_: &Event| Flow::Stop;
        let mut driver = Driver::new(Method::Other("t"), &stop, 0.0, 9);
        let end = driver.run(|_, _| Ok::<_, ()>(Step::Next(1.0)));
        assert_eq!(end, Ok(Termination::Stopped { after: 1 }));
        let mut driver = Driver::new(Method::Other("t"), &stop, 0.0, 9);
        let cycled = Termination::Stalled {
            cause: crate::Stall::WanderingReference { moves: 1 },
        };
        let end = driver.run(|_, _| Ok::<_, ()>(Step::Last(1.0, cycled.clone())));
        assert_eq!(end, Ok(cycled));
        let seen = RefCell::new(vec![]);
        let record = |e: &Event| {
            seen.borrow_mut().push(Recorded::of(e));
            Flow::Continue
        };
        let mut driver = Driver::new(Method::Other("t"), &record, 0.0, 9);
        let reduced = Termination::ReducedAccuracy {
            measure: 1e-6,
            tolerance: 1e-9,
        };
        let end = driver.run(|k, _| {
            Ok::<_, ()>(match k {
                1 => Step::Next(2.0),
                _ => Step::Ended(Termination::Stopped { after: 0 }),
            })
        });
        assert_eq!(end, Ok(Termination::Stopped { after: 0 }));
        assert_eq!(seen.borrow().len(), 1);
        driver.note(Method::Qp, &reduced);
        assert_eq!(
            driver.end(Termination::Converged),
            reduced.inside(Method::Qp)
        );
        // A driver after 7 steps of the same solve numbers its events and its stop on from
        // there; its own steps and step limit count from 0.
        let numbers = RefCell::new(vec![]);
        let stop_at_9 = |e: &Event| {
            numbers.borrow_mut().push(Recorded::of(e).iteration);
            if Recorded::of(e).iteration == 9 {
                Flow::Stop
            } else {
                Flow::Continue
            }
        };
        let mut driver = Driver::new(Method::Other("t"), &stop_at_9, 0.0, 5).after(7);
        let end = driver.run(|_, _| Ok::<_, ()>(Step::Next(1.0)));
        assert_eq!(end, Ok(Termination::Stopped { after: 9 }));
        assert_eq!((driver.steps(), numbers.borrow().clone()), (2, vec![8, 9]));
        let mut driver = Driver::new(Method::Other("t"), &record, 0.0, 2).after(7);
        let end = driver.run(|_, _| Ok::<_, ()>(Step::Next(1.0)));
        let limit = Termination::StepLimit {
            steps: 2,
            measure: 1.0,
            tolerance: 0.0,
        };
        assert_eq!(end, Ok(limit));
    }
}
