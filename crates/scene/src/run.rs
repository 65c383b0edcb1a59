//! The run of a scene's cases, which builds each distinct pair of bodies once, and the run of
//! one case on its bodies.

use std::time::{Duration, Instant};

use contopt_contact::InterfaceProblem;
use contopt_core::observe::{Observer, Silent};
use contopt_results::CaseReport;
use contopt_roller::LoadCase;

use crate::build::Built;
use crate::methods::Context;
use crate::plan::BuildKey;
use crate::report::Found;
use crate::{Case, Scene, SceneError};

/// The initial gap of a point where the gap is open for good (beyond a flat punch's rim), in
/// sizes of the interface: out of reach, since the solvers refuse an elastic displacement
/// larger than one size ([`contopt_contact::SMALL_STRAIN`]).
const OPEN_SIZES: f64 = 4.0;

/// A scene's cases run in order ([`Scene::run`]): an iterator of their reports.
///
/// Cases that differ only outside their bodies (a sweep over the controller, the gap, the
/// solver or the method's settings) share them: each distinct pair (by its zone, kinds and
/// load) is built — assembled, factorised, condensed — once, before its first case, and
/// dropped after its last.
pub struct Run<'s, 'o> {
    cases: &'s [Case],
    /// Each distinct key with the index of its last case.
    last: Vec<(&'s BuildKey, usize)>,
    /// The bodies of pairs whose last case is still to come.
    built: Vec<(&'s BuildKey, Built)>,
    next: usize,
    /// How many pairs were built so far.
    builds: usize,
    observer: &'o dyn Observer,
}

impl Scene {
    /// Runs every case in order: see [`Run`].
    pub fn run(&self) -> Run<'_, 'static> {
        self.run_observed(&Silent)
    }

    /// [`Scene::run`], reporting each iteration of the contact solves and of the designs to
    /// `observer` (see [`Case::run_observed`]).
    pub fn run_observed<'o>(&self, observer: &'o dyn Observer) -> Run<'_, 'o> {
        self.run_cases(0..self.cases.len(), observer)
    }

    /// [`Scene::run_observed`] over the cases `range` only (a job array's shard, see
    /// [`contopt_results::shard`]): their reports are those of the same cases in a run of the
    /// whole scene. A range past the cases is cut to them.
    pub fn run_cases<'o>(
        &self,
        range: std::ops::Range<usize>,
        observer: &'o dyn Observer,
    ) -> Run<'_, 'o> {
        let all = self.cases();
        let cases = &all[range.start.min(all.len())..range.end.min(all.len())];
        let mut last: Vec<(&BuildKey, usize)> = vec![];
        for (k, case) in cases.iter().enumerate() {
            match last.iter_mut().find(|(key, _)| **key == case.plan.key) {
                Some(entry) => entry.1 = k,
                None => last.push((&case.plan.key, k)),
            }
        }
        Run {
            cases,
            last,
            built: vec![],
            next: 0,
            builds: 0,
            observer,
        }
    }
}

impl Run<'_, '_> {
    /// The cases, in the order their reports come.
    pub fn cases(&self) -> &[Case] {
        self.cases
    }

    /// How many distinct pairs of bodies the cases need: the builds of a whole run.
    pub fn distinct_bodies(&self) -> usize {
        self.last.len()
    }

    /// How many pairs the run has built so far.
    pub fn builds(&self) -> usize {
        self.builds
    }

    /// Runs case `k` on its bodies, building them if no earlier case did, and drops them after
    /// the last case that needs them.
    fn run_case(&mut self, k: usize) -> Result<CaseReport, SceneError> {
        let case = &self.cases[k];
        let key = &case.plan.key;
        let kept = self.built.iter().position(|(k, _)| *k == key);
        let (built, took) = match kept.map(|i| self.built.swap_remove(i).1) {
            Some(built) => (built, Duration::ZERO),
            None => {
                self.builds += 1;
                let built = case.build()?;
                let took = built.took();
                (built, took)
            }
        };
        let report = case.run_built(&built, took, self.observer);
        if self.last.iter().any(|(kk, last)| *kk == key && *last > k) {
            self.built.push((key, built));
        }
        report
    }
}

impl Iterator for Run<'_, '_> {
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

impl ExactSizeIterator for Run<'_, '_> {}

impl Case {
    /// Solves the case. A method that stops short gives a report that says why and how far
    /// it got; bad input is an error.
    pub fn run(&self) -> Result<CaseReport, SceneError> {
        self.run_observed(&Silent)
    }

    /// [`Case::run`], reporting each iteration of its methods to `observer` (the outermost at
    /// level 0), which may stop them early (the case then reports how it was stopped).
    pub fn run_observed(&self, observer: &dyn Observer) -> Result<CaseReport, SceneError> {
        self.run_on(&self.build()?, observer)
    }

    /// Runs the case on bodies built for it (by this case, or by an earlier case of the scene
    /// that shares them: its `build` time is then only the interface's).
    pub fn run_on(&self, built: &Built, observer: &dyn Observer) -> Result<CaseReport, SceneError> {
        self.run_built(built, built.took(), observer)
    }

    /// [`Case::run_on`], its build having taken `took` (zero for bodies another case built).
    pub(crate) fn run_built(
        &self,
        built: &Built,
        took: Duration,
        observer: &dyn Observer,
    ) -> Result<CaseReport, SceneError> {
        let at = &self.locator;
        let mut report = CaseReport::new(&self.label, &self.params, self.input());
        let start = Instant::now();
        let gap = self.initial_gap(built)?;
        let problem = InterfaceProblem::new(built.first(), built.second(), &gap)
            .map_err(|e| at.library("body", e))?
            .with_dense_limit(self.plan.dense_limit);
        let build_ms = 1e3 * (took + start.elapsed()).as_secs_f64();
        report.timings_ms.insert("build".into(), build_ms);
        let solver = self
            .spec
            .solver
            .build()
            .map_err(|e| at.library("solver", e))?;
        let cases = self
            .load_cases(&problem)
            .map_err(|e| at.library("envelope", e))?;
        let view = self.spec.view(&self.plan.layout, self.plan.roller.as_ref());
        let context = Context {
            case: view,
            problem: &problem,
            solver: solver.as_ref(),
            observer,
            cases: &cases,
        };
        let plan = &self.plan;
        let designed =
            (plan.design.run(&context, &mut report)).map_err(|e| at.library(plan.design_at, e))?;
        let found = Found {
            case: self,
            built,
            problem,
            designed,
        };
        crate::report::complete(&mut report, found)?;
        Ok(report)
    }

    /// A roller's load cases for `problem`, its own first; none for other gaps.
    fn load_cases<'a>(
        &self,
        problem: &InterfaceProblem<'a>,
    ) -> contopt_core::Result<Vec<LoadCase<'a>>> {
        match &self.plan.roller {
            Some(roller) => {
                contopt_roller::load_cases(problem, roller, self.spec.envelope.as_ref())
            }
            None => Ok(vec![]),
        }
    }

    /// The case's contact problem, its bodies built and owned: to solve with any solver or
    /// optimise from Rust.
    pub fn problem(&self) -> Result<InterfaceProblem<'static>, SceneError> {
        let built = self.build()?;
        let gap = self.initial_gap(&built)?;
        let [first, second] = built.into_bodies();
        InterfaceProblem::owned(first, second, &gap)
            .map(|p| p.with_dense_limit(self.plan.dense_limit))
            .map_err(|e| self.locator.library("body", e))
    }

    /// The initial gap at the first body's points \[mm\]: the gap's shape less the approach;
    /// where the gap is open for good (beyond a flat punch's rim), out of reach. Between two
    /// imported meshes, whose interface is the first body's face nodes, the measured gap or
    /// the gap's shape at the pairing's points, each weighted onto the nodes (∫ N¹ₖ h dS / w̃ₖ,
    /// [`contopt_fem::ContactPairing::project`]). A measured gap on a grid is the distance
    /// between the bodies' meshed faces, which the plan found
    /// ([`crate::bodies::BodyKind::face_shape`]).
    pub fn initial_gap(&self, built: &Built) -> Result<Vec<f64>, SceneError> {
        let at = &self.locator;
        let contact = &self.spec.contact;
        let approach = match contact.load {
            crate::contact::LoadSpec::ApproachMm(a) => a,
            _ => 0.0,
        };
        let open = OPEN_SIZES * built.first().interface().extent();
        let reach = |h: f64| if h.is_finite() { h } else { open };
        Ok(match built.pairing() {
            Some(pairing) if contact.gap.measured() => {
                pairing.initial_gap().iter().map(|h| h - approach).collect()
            }
            Some(pairing) => {
                let samples = pairing.first_samples().iter();
                let points: Vec<[f64; 3]> =
                    samples.map(|s| [s.point[0], s.point[1], 0.0]).collect();
                let shape: Vec<f64> = (self.gap_shape_at(&points)?.into_iter())
                    .map(reach)
                    .collect();
                let projected = pairing
                    .project(&shape)
                    .map_err(|e| at.library("contact.gap", e))?;
                projected.into_iter().map(|h| h - approach).collect()
            }
            None => match &self.plan.faces {
                Some(faces) if faces.len() == built.first().interface().len() => {
                    faces.iter().map(|h| h - approach).collect()
                }
                Some(faces) => {
                    return Err(at.at(
                        "contact.gap",
                        format!(
                            "the meshed faces were measured at {} points, the bodies have {}",
                            faces.len(),
                            built.first().interface().len()
                        ),
                    ))
                }
                None => (self.gap_shape(built)?.into_iter())
                    .map(|h| reach(h - approach))
                    .collect(),
            },
        })
    }

    /// The gap's shape h(x) at the first body's points \[mm\], infinite where it is open for
    /// good.
    fn gap_shape(&self, built: &Built) -> Result<Vec<f64>, SceneError> {
        self.gap_shape_at(built.first().interface().points())
    }

    /// The gap's shape h(x) at `points` \[mm\], infinite where it is open for good.
    fn gap_shape_at(&self, points: &[[f64; 3]]) -> Result<Vec<f64>, SceneError> {
        let at = &self.locator;
        let contact = &self.spec.contact;
        let gap = points
            .iter()
            .map(|&x| contact.gap.at(&contact.zone, x, self.plan.roller.as_ref()))
            .collect::<contopt_core::Result<Vec<f64>>>()
            .map_err(|e| at.library("contact.gap", e))?;
        crate::gap::covers(points, &gap, &self.plan.layout)
            .map_err(|e| at.library("contact.gap", e))?;
        Ok(gap)
    }
}
