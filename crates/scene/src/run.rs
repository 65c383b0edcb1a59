//! The run of a scene's cases, which builds each distinct set of bodies once.

use std::collections::HashMap;

use contopt_core::observe::Observer;

use crate::build::Built;
use crate::{Case, CaseReport, Scene, SceneError};

/// A scene's cases run in order ([`Scene::run`]): an iterator of their reports.
///
/// Cases that differ only outside the problem (a sweep over the controller, the solver or the
/// optimisation's settings) share its bodies: each distinct problem (by its canonical form) is
/// built — assembled, factorised, condensed — once, before its first case, and dropped after
/// its last, so that at most the problems whose cases interleave are held at once.
pub struct Run<'o> {
    cases: Vec<Case>,
    /// Each case's problem key.
    keys: Vec<String>,
    /// The index of each key's last case.
    last: HashMap<String, usize>,
    /// The bodies of problems whose last case is still to come.
    built: HashMap<String, Built>,
    next: usize,
    observer: &'o dyn Observer,
}

impl Scene {
    /// Runs every case in order: see [`Run`].
    pub fn run(&self) -> Result<Run<'static>, SceneError> {
        self.run_observed(&contopt_core::observe::Silent)
    }

    /// [`Scene::run`], reporting each iteration of the contact solves and optimisations to
    /// `observer` (see [`Case::run_observed`]).
    pub fn run_observed<'o>(&self, observer: &'o dyn Observer) -> Result<Run<'o>, SceneError> {
        let cases = self.cases()?;
        let keys: Vec<String> = cases.iter().map(Case::problem_key).collect();
        let last = keys
            .iter()
            .enumerate()
            .map(|(k, key)| (key.clone(), k))
            .collect();
        Ok(Run {
            cases,
            keys,
            last,
            built: HashMap::new(),
            next: 0,
            observer,
        })
    }
}

impl Run<'_> {
    /// The cases, in the order their reports come.
    pub fn cases(&self) -> &[Case] {
        &self.cases
    }

    /// How many distinct sets of bodies the cases need: the builds of a whole run.
    pub fn builds(&self) -> usize {
        self.last.len()
    }

    /// Runs case `k` on its problem's bodies, building them if no earlier case did, and drops
    /// them after the problem's last case.
    fn run_case(&mut self, k: usize) -> Result<CaseReport, SceneError> {
        let (case, key) = (&self.cases[k], &self.keys[k]);
        let built = match self.built.remove(key) {
            Some(built) => built.reused(),
            None => case.build()?,
        };
        let report = case.run_on(&built, self.observer);
        if self.last.get(key).is_some_and(|&last| last > k) {
            self.built.insert(key.clone(), built);
        }
        report
    }
}

impl Iterator for Run<'_> {
    type Item = Result<CaseReport, SceneError>;

    fn next(&mut self) -> Option<Self::Item> {
        let k = self.next;
        if k >= self.cases.len() {
            return None;
        }
        self.next += 1;
        Some(self.run_case(k))
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let left = self.cases.len() - self.next;
        (left, Some(left))
    }
}

impl ExactSizeIterator for Run<'_> {}
