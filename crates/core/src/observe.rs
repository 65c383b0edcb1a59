//! Observers of iterative methods, as argmin has them: a contact solver, the optimisation loop
//! or a profile search reports each of its iterations to an [`Observer`] as an [`Event`], which
//! may log it, draw a progress bar or stop the method early.
//!
//! Methods nest: an optimisation runs contact solves, a crown search runs optimisations. An
//! outer method hands its inner ones [`Nested`], so that every event says how deep it was
//! raised ([`Event::level`]: 0 for the outermost method of a run).
//!
//! ```
//! use std::cell::Cell;
//! use contopt_core::observe::{Event, Flow, Method, Nested, Observer};
//!
//! // Stop any method after 3 iterations, counting what it reported.
//! let seen = Cell::new(0);
//! let stop_at_three = |e: &Event| {
//!     seen.set(seen.get() + 1);
//!     if e.iteration >= 3 { Flow::Stop } else { Flow::Continue }
//! };
//! let observer: &dyn Observer = &stop_at_three;
//! let event = Event::step(Method::PolonskyKeer, 3, 1.0, 0.1);
//! assert_eq!(observer.observe(&event), Flow::Stop);
//! // The same event raised inside an optimisation arrives one level deeper.
//! let deeper = |e: &Event| { assert_eq!(e.level, 1); Flow::Continue };
//! assert_eq!(Nested(&deeper).observe(&event), Flow::Continue);
//! assert_eq!(seen.get(), 1);
//! ```

use serde::{Deserialize, Serialize};

use crate::Termination;

/// The methods that report to observers. A solver of your own reports as
/// [`Method::Other`] with its name. Written to files as its [`Method::id`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Method {
    /// The complementary-energy QP (2.14) by an interior point.
    Qp,
    /// Kalker's active set with exact dense solves.
    ActiveSet,
    /// The penalty method (2.18 without the multiplier).
    Penalty,
    /// Uzawa's steps of the augmented Lagrangian (2.19–2.20).
    AugmentedLagrangian,
    /// Kalker's iteration inside another method (an Uzawa step's solves).
    Kalker,
    /// Polonsky–Keer's constrained conjugate gradients.
    PolonskyKeer,
    /// The penalty method on the uncondensed system (2.22).
    FullPenalty,
    /// The iteration of §3.2 (steps 1–7, TOLH of 4.2).
    GapIteration,
    /// The restricted linear programme (3.5).
    LinearProgramme,
    /// The optimum of (3.5) from the loads carried by the design columns.
    LoadSplit,
    /// The load split over an envelope of load cases (a robust crown).
    EnvelopeSplit,
    /// A derivative-free search over a profile's parameters (Nelder–Mead).
    ProfileSearch,
    /// Newton's steps to a bearing's ring equilibrium.
    RingEquilibrium,
    /// A method of your own.
    Other(&'static str),
}

/// The methods of the library, as [`Method::id`] names them.
const LIBRARY_METHODS: [Method; 13] = [
    Method::Qp,
    Method::ActiveSet,
    Method::Penalty,
    Method::AugmentedLagrangian,
    Method::Kalker,
    Method::PolonskyKeer,
    Method::FullPenalty,
    Method::GapIteration,
    Method::LinearProgramme,
    Method::LoadSplit,
    Method::EnvelopeSplit,
    Method::ProfileSearch,
    Method::RingEquilibrium,
];

impl Method {
    /// Its name in files (`"polonsky_keer"`, `"gap_iteration"`, …; a method of your own by
    /// the name it gave).
    pub fn id(&self) -> &'static str {
        match self {
            Method::Qp => "qp",
            Method::ActiveSet => "active_set",
            Method::Penalty => "penalty",
            Method::AugmentedLagrangian => "augmented_lagrangian",
            Method::Kalker => "kalker",
            Method::PolonskyKeer => "polonsky_keer",
            Method::FullPenalty => "full_penalty",
            Method::GapIteration => "gap_iteration",
            Method::LinearProgramme => "linear_programme",
            Method::LoadSplit => "load_split",
            Method::EnvelopeSplit => "envelope_split",
            Method::ProfileSearch => "profile_search",
            Method::RingEquilibrium => "ring_equilibrium",
            Method::Other(name) => name,
        }
    }
}

impl Serialize for Method {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.id())
    }
}

#[cfg(feature = "schema")]
impl schemars::JsonSchema for Method {
    fn schema_name() -> std::borrow::Cow<'static, str> {
        "Method".into()
    }

    /// A library method's id, or the name of a method of one's own.
    fn json_schema(_: &mut schemars::SchemaGenerator) -> schemars::Schema {
        let ids: Vec<&str> = LIBRARY_METHODS.iter().map(Method::id).collect();
        schemars::json_schema!({
            "description": format!(
                "The method, by its id ({}) or, for a method of one's own, its name.",
                ids.join(", ")
            ),
            "type": "string"
        })
    }
}

/// Reads a method by its [`Method::id`]: a library method's, or any other name as a method of
/// one's own ([`Method::Other`]), so that the result files of a user's solver or design read
/// back. An empty name is refused.
impl<'de> Deserialize<'de> for Method {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let id = String::deserialize(deserializer)?;
        if id.is_empty() {
            return Err(serde::de::Error::custom("a method's id is empty"));
        }
        Ok(LIBRARY_METHODS
            .into_iter()
            .find(|m| m.id() == id)
            .unwrap_or_else(|| Method::Other(interned(id))))
    }
}

/// The longest name of a method of one's own that is read back \[bytes\]; longer ones are cut.
const MAX_OTHER_NAME_BYTES: usize = 64;

/// The most distinct names of one's own methods kept for the process: past it, further names
/// read back as one shared name.
const MAX_OTHER_NAMES: usize = 1024;

/// The name of a method of one's own as a `'static` string: each distinct name is kept once
/// for the life of the process (they are few: a user's solvers and designs), at most
/// [`MAX_OTHER_NAMES`] of at most [`MAX_OTHER_NAME_BYTES`] bytes, so that a hostile file cannot
/// grow the memory without bound.
fn interned(mut id: String) -> &'static str {
    use std::collections::BTreeSet;
    use std::sync::{Mutex, PoisonError};
    static NAMES: Mutex<BTreeSet<&'static str>> = Mutex::new(BTreeSet::new());
    if id.len() > MAX_OTHER_NAME_BYTES {
        let mut end = MAX_OTHER_NAME_BYTES;
        while !id.is_char_boundary(end) {
            end -= 1;
        }
        id.truncate(end);
    }
    let mut names = NAMES.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(&name) = names.get(id.as_str()) {
        return name;
    }
    if names.len() >= MAX_OTHER_NAMES {
        return "other";
    }
    let name: &'static str = Box::leak(id.into_boxed_str());
    names.insert(name);
    name
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Method::Qp => "QP",
            Method::ActiveSet => "active-set solve",
            Method::Penalty => "penalty solve",
            Method::AugmentedLagrangian => "augmented Lagrangian",
            Method::Kalker => "Kalker iteration",
            Method::PolonskyKeer => "Polonsky–Keer solve",
            Method::FullPenalty => "penalty solve of the full system",
            Method::GapIteration => "gap iteration (§3.2)",
            Method::LinearProgramme => "linear programme (3.5)",
            Method::LoadSplit => "load split (3.5)",
            Method::EnvelopeSplit => "envelope load split (3.5)",
            Method::ProfileSearch => "profile search",
            Method::RingEquilibrium => "ring equilibrium",
            Method::Other(name) => name,
        })
    }
}

/// One iteration of a method, as it reports it; the last one also says how it ended.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Event<'a> {
    /// The method.
    pub method: Method,
    /// How deep the method runs: 0 for the outermost of a run, one more for each method that
    /// runs it (see [`Nested`]).
    pub level: usize,
    /// The iteration's number, from 1, counted by that method.
    pub iteration: usize,
    /// The method's convergence measure after this iteration (a relative residual, a change
    /// of the pressure, TOLH of eq. 4.2); NaN when the method has none.
    pub measure: f64,
    /// The value `measure` must reach for the method to stop converged.
    pub tolerance: f64,
    /// How the method ended, on its last event; `None` while it goes on.
    pub end: Option<&'a Termination>,
}

impl<'a> Event<'a> {
    /// An iteration at level 0 that the method goes on from.
    pub fn step(method: Method, iteration: usize, measure: f64, tolerance: f64) -> Self {
        Self {
            method,
            level: 0,
            iteration,
            measure,
            tolerance,
            end: None,
        }
    }

    /// The same event, marked as the method's last with how it ended.
    pub fn ending(self, end: &'a Termination) -> Self {
        Self {
            end: Some(end),
            ..self
        }
    }
}

/// An [`Event`] kept past the call that reported it, its termination owned: what an observer
/// records to show again later (a solve on another thread, whose events are replayed in order)
/// or to check afterwards.
#[derive(Clone, Debug, PartialEq)]
pub struct Recorded {
    /// The method.
    pub method: Method,
    /// Its level ([`Event::level`]).
    pub level: usize,
    /// The iteration's number.
    pub iteration: usize,
    /// The convergence measure after it.
    pub measure: f64,
    /// The value the measure must reach.
    pub tolerance: f64,
    /// How the method ended, on its last event.
    pub end: Option<Termination>,
}

impl Recorded {
    /// `event`, kept.
    pub fn of(event: &Event) -> Self {
        Self {
            method: event.method,
            level: event.level,
            iteration: event.iteration,
            measure: event.measure,
            tolerance: event.tolerance,
            end: event.end.cloned(),
        }
    }

    /// The event again, as it was reported.
    pub fn event(&self) -> Event<'_> {
        Event {
            method: self.method,
            level: self.level,
            iteration: self.iteration,
            measure: self.measure,
            tolerance: self.tolerance,
            end: self.end.as_ref(),
        }
    }
}

/// What an observer asks of the method that reported to it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
#[must_use]
pub enum Flow {
    /// Go on iterating.
    #[default]
    Continue,
    /// Stop now: the method returns its last iterate with
    /// [`Termination::Stopped`]. Ignored on a method's last event.
    Stop,
}

/// Receives the events of a method. Takes `&self` so that one observer can be shared by
/// nested methods (the optimisation loop and the contact solves inside it); keep its state in
/// a `Cell`, a `RefCell` or a lock. Any `Fn(&Event) -> Flow` closure is an observer.
///
/// An observer need not be `Sync`: it is called from the thread that runs the method only.
/// Contact solves that run at once on other threads (an envelope's cases,
/// `contopt_contact::parallel`) record their events, and the observer is shown them from the
/// calling thread, case after case, as a run in turn shows them.
pub trait Observer {
    /// Called after each iteration of a method.
    fn observe(&self, event: &Event) -> Flow;
}

/// The observer that sees nothing and never stops a method: the default.
#[derive(Clone, Copy, Debug, Default)]
pub struct Silent;

impl Observer for Silent {
    fn observe(&self, _: &Event) -> Flow {
        Flow::Continue
    }
}

impl<F: Fn(&Event) -> Flow> Observer for F {
    fn observe(&self, event: &Event) -> Flow {
        self(event)
    }
}

/// The observer an outer method gives the methods it runs: it passes their events on one
/// level deeper.
#[derive(Clone, Copy)]
pub struct Nested<'a>(pub &'a dyn Observer);

impl Observer for Nested<'_> {
    fn observe(&self, event: &Event) -> Flow {
        self.0.observe(&Event {
            level: event.level + 1,
            ..*event
        })
    }
}

#[cfg(test)]
mod tests {
    use super::Method;

    #[test]
    fn methods_of_ones_own_read_back_by_name() {
        let read = |id: &str| serde_json::from_value::<Method>(serde_json::json!(id));
        assert_eq!(read("load_split").unwrap(), Method::LoadSplit);
        let own = read("relief").unwrap();
        assert_eq!(own, Method::Other("relief"));
        assert_eq!(serde_json::to_value(own).unwrap(), "relief");
        // The same name twice is kept once.
        let again = read("relief").unwrap();
        assert!(matches!((own, again), (Method::Other(a), Method::Other(b)) if std::ptr::eq(a, b)));
        assert!(read("").is_err());
        let long = "x".repeat(1000);
        assert!(matches!(read(&long).unwrap(), Method::Other(n) if n.len() == 64));
    }
}
