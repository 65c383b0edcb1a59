//! Independent contact solves (an envelope's cases under one crown) on the threads of the
//! current rayon pool, with results and events the same to the bit as solving them in turn.
//!
//! Each solve reports to an observer of its own that records its events; the caller's
//! observer is then shown them case after case, from the calling thread, as a run in turn
//! would. An observer that stops a solve ([`Flow::Stop`]) has it solved again, in turn, its
//! events up to the stop held back (the observer saw them): a solve is deterministic, so it
//! stops where a run in turn would have stopped it, and the observer sees every event once.
//! With one thread (a pool of one, `contopt run --jobs 1`) the solves run in turn, live.

use std::cell::{Cell, RefCell};

use contopt_core::observe::{Event, Flow, Observer, Recorded};
use rayon::prelude::*;

use crate::{ContactSolver, InterfaceProblem};

/// Solves `count` independent problems, `solve(k, observer)` for k = 0, 1, …, on the threads
/// of the current rayon pool, at most `at_once` at a time ([`at_once`]: what memory holds),
/// and returns the results in order. The run ends after the first result that `go_on`
/// refuses (an error, a solve that did not converge): later results are dropped and their
/// events not shown, as a run in turn would not have solved them. Results and the events
/// `observer` sees are those of a run in turn (module notes).
pub fn solve_each<T: Send>(
    count: usize,
    at_once: usize,
    observer: &dyn Observer,
    solve: impl Fn(usize, &dyn Observer) -> T + Sync,
    go_on: impl Fn(&T) -> bool,
) -> Vec<T> {
    let mut results = Vec::with_capacity(count);
    if rayon::current_num_threads() <= 1 || count <= 1 {
        for k in 0..count {
            let result = solve(k, observer);
            let more = go_on(&result);
            results.push(result);
            if !more {
                break;
            }
        }
        return results;
    }
    let chunk = at_once.clamp(1, count);
    for first in (0..count).step_by(chunk) {
        let solved: Vec<(T, Vec<Recorded>)> = (first..count.min(first + chunk))
            .into_par_iter()
            .map(|k| {
                let recorder = Recorder::default();
                let result = solve(k, &recorder);
                (result, recorder.events.into_inner())
            })
            .collect();
        for (k, (result, events)) in (first..).zip(solved) {
            let result = match replay(&events, observer) {
                None => result,
                Some(seen) => solve(k, &Resume::new(observer, seen)),
            };
            let more = go_on(&result);
            results.push(result);
            if !more {
                return results;
            }
        }
    }
    results
}

/// How many of `points`-point contact solves by `solver` may run at once on `problem`'s
/// matrices: all when the solver holds no dense matrix; else as many as keep the matrices
/// they hold, with the shared influence matrix, within the problem's dense limit
/// ([`InterfaceProblem::with_dense_limit`]), at least one.
pub fn at_once(solver: &dyn ContactSolver, problem: &InterfaceProblem) -> usize {
    let n = problem.len() as u64;
    let own = solver.dense_copies(problem.len()).saturating_sub(1);
    let matrix = n.saturating_mul(n).saturating_mul(8);
    match own.saturating_mul(matrix) {
        0 => usize::MAX,
        each => (problem.dense_limit().saturating_sub(matrix) / each).max(1) as usize,
    }
}

/// The observer of a solve on another thread: records its events, never stops it.
#[derive(Default)]
struct Recorder {
    events: RefCell<Vec<Recorded>>,
}

impl Observer for Recorder {
    fn observe(&self, event: &Event) -> Flow {
        self.events.borrow_mut().push(Recorded::of(event));
        Flow::Continue
    }
}

/// Shows `events` to `observer` in order; `Some(count)` of the events shown when it asked to
/// stop at the last of them.
fn replay(events: &[Recorded], observer: &dyn Observer) -> Option<usize> {
    for (k, e) in events.iter().enumerate() {
        if observer.observe(&e.event()) == Flow::Stop {
            return Some(k + 1);
        }
    }
    None
}

/// The observer of a solve again, after `observer` saw its first `seen` events and asked to
/// stop at the last: holds them back, answering as it did, and passes on the rest.
struct Resume<'o> {
    observer: &'o dyn Observer,
    seen: usize,
    count: Cell<usize>,
}

impl<'o> Resume<'o> {
    fn new(observer: &'o dyn Observer, seen: usize) -> Self {
        Self {
            observer,
            seen,
            count: Cell::new(0),
        }
    }
}

impl Observer for Resume<'_> {
    fn observe(&self, event: &Event) -> Flow {
        let k = self.count.get() + 1;
        self.count.set(k);
        match k.cmp(&self.seen) {
            std::cmp::Ordering::Less => Flow::Continue,
            std::cmp::Ordering::Equal => Flow::Stop,
            std::cmp::Ordering::Greater => self.observer.observe(event),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::observe::Method;
    use contopt_core::Termination;

    /// A solve that reports `k + 2` iterations and stops when told: its result is the
    /// iteration it ended on.
    fn solve(k: usize, observer: &dyn Observer) -> usize {
        let end = Termination::Converged;
        for i in 1..=k + 2 {
            let event = Event::step(Method::PolonskyKeer, i, k as f64, 0.0);
            let last = i == k + 2;
            let event = if last { event.ending(&end) } else { event };
            if observer.observe(&event) == Flow::Stop && !last {
                return 100 * k + i;
            }
        }
        100 * k + k + 2
    }

    /// What an observer saw, and where it stops.
    fn watch(stop_at: (f64, usize)) -> impl Fn(&Event) -> Flow {
        move |e: &Event| match (e.measure, e.iteration) == stop_at {
            true => Flow::Stop,
            false => Flow::Continue,
        }
    }

    /// On two threads, results, events and a stop in the third case are those of a run in
    /// turn; a refused result ends the run.
    #[test]
    fn in_parallel_as_in_turn() {
        let run = |threads: usize, at_once: usize| {
            let seen = std::sync::Mutex::new(vec![]);
            let stop = watch((2.0, 3));
            let observer = |e: &Event| {
                let what = (e.measure, e.iteration, e.end.is_some());
                seen.lock().unwrap().push(what);
                stop(e)
            };
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let results = pool.install(|| solve_each(6, at_once, &observer, solve, |&r| r != 406));
            (results, seen.into_inner().unwrap())
        };
        let (results, seen) = run(1, usize::MAX);
        assert_eq!(results, [2, 103, 203, 305, 406]);
        assert_eq!(seen.len(), 2 + 3 + 3 + 5 + 6);
        assert_eq!(run(2, usize::MAX), (results.clone(), seen.clone()));
        assert_eq!(run(2, 2), (results, seen));
    }
}
