//! A derivative-free minimiser for a few parameters: the simplex method of Nelder and Mead.
//!
//! It serves the published way of designing a logarithmic crown, tuning its three parameters
//! against a pressure computed for each guess (Fujiwara & Kawase 2007 used Rosenbrock's
//! method), as a baseline for the optimised crowns. Written here rather than taken from a
//! crate: it is a page, and argmin would bring a random-number stack for it.

use std::ops::ControlFlow;

use contopt_core::drive::{Driver, Inner};
use contopt_core::observe::{Method, Observer, Silent};
use contopt_core::{check, Error, Result, Termination};
use serde::{Deserialize, Serialize};

/// Reflection, expansion, contraction and shrink coefficients (the standard 1, 2, ½, ½).
const REFLECT: f64 = 1.0;
const EXPAND: f64 = 2.0;
const CONTRACT: f64 = 0.5;
const SHRINK: f64 = 0.5;

/// When a simplex search stops.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SearchSettings {
    /// Stop when the objective's values at the simplex's vertices differ by no more than
    /// this (absolute, in the objective's units: MPa for a crown's worst p_max).
    pub tolerance: f64,
    /// The budget of evaluations of the objective.
    pub max_evaluations: usize,
}

impl SearchSettings {
    /// The default spread: 0.05 MPa on a worst-case p_max of 10³ MPa, below what a grid
    /// resolves (convergence).
    pub const TOLERANCE: f64 = 0.05;
    /// The default budget: a three-parameter crown settles in about a hundred evaluations.
    pub const MAX_EVALUATIONS: usize = 150;

    /// The settings, checked: a tolerance ≥ 0 and finite, at least one evaluation.
    pub fn check(&self) -> Result<()> {
        check::non_negative("tolerance", self.tolerance)?;
        check::count("max_evaluations", self.max_evaluations, 1, usize::MAX)?;
        Ok(())
    }
}

impl Default for SearchSettings {
    fn default() -> Self {
        Self {
            tolerance: Self::TOLERANCE,
            max_evaluations: Self::MAX_EVALUATIONS,
        }
    }
}

/// The best point a simplex search found, and how it ended.
#[derive(Clone, Debug, PartialEq)]
pub struct Minimum {
    /// The parameters (the start when no evaluation finished).
    pub x: Vec<f64>,
    /// The objective there (infinite when no evaluation finished).
    pub value: f64,
    /// How many times the objective was evaluated.
    pub evaluations: usize,
    /// The last simplex's extent along each parameter (its largest less its smallest
    /// coordinate; empty when no simplex was made): how finely the search placed the minimum,
    /// the steps of a search that goes on from it.
    pub extent: Vec<f64>,
    /// [`Termination::Converged`] when the spread fell to the tolerance (or the first reduced
    /// accuracy the objective noted, [`Inner`]), [`Termination::StepLimit`] when the budget
    /// ran out (its steps are evaluations, its measure the last spread), the observer's
    /// [`Termination::Stopped`], or the termination the objective stopped it with.
    pub termination: Termination,
}

/// The simplex and the objective's bookkeeping.
struct Search<'o, F> {
    objective: F,
    /// Counts the evaluations, each one step of the search, and reports them.
    driver: Driver<'o>,
    evaluations: usize,
    /// Vertices with their values, best first after [`Search::sort`].
    simplex: Vec<(Vec<f64>, f64)>,
    /// The termination an evaluation stopped the search with.
    stop: Option<Termination>,
}

impl<'o, F: FnMut(&[f64], &mut Inner) -> Result<ControlFlow<Termination, f64>>> Search<'o, F> {
    /// The objective at `x` (NaN counts as +∞), reported as a step with its value as the
    /// measure; `None` when the objective or the observer stopped the search.
    fn eval(&mut self, x: &[f64]) -> Result<Option<f64>> {
        self.evaluations += 1;
        let f = match (self.objective)(x, self.driver.inner())? {
            ControlFlow::Continue(f) => f,
            ControlFlow::Break(end) => {
                self.stop = Some(end);
                return Ok(None);
            }
        };
        if let Some(stopped) = self.driver.report(f) {
            self.stop = Some(stopped);
            return Ok(None);
        }
        Ok(Some(if f.is_nan() { f64::INFINITY } else { f }))
    }

    fn sort(&mut self) {
        self.simplex.sort_by(|a, b| a.1.total_cmp(&b.1));
    }

    /// The spread of the values at the vertices.
    fn spread(&self) -> f64 {
        self.simplex[self.simplex.len() - 1].1 - self.simplex[0].1
    }

    /// One Nelder–Mead step on the sorted simplex: reflect the worst vertex through the
    /// centroid of the others, expand, contract or shrink; false when the objective stopped
    /// the search.
    fn step(&mut self) -> Result<bool> {
        let n = self.simplex.len() - 1;
        let centroid: Vec<f64> = (0..n)
            .map(|k| self.simplex[..n].iter().map(|(x, _)| x[k]).sum::<f64>() / n as f64)
            .collect();
        let worst = self.simplex[n].clone();
        let reflected = along(&centroid, &worst.0, -REFLECT);
        let Some(fr) = self.eval(&reflected)? else {
            return Ok(false);
        };
        if fr < self.simplex[0].1 {
            let expanded = along(&centroid, &worst.0, -EXPAND);
            let fe = self.eval(&expanded)?;
            self.simplex[n] = match fe {
                Some(fe) if fe < fr => (expanded, fe),
                _ => (reflected, fr),
            };
            return Ok(fe.is_some());
        }
        if fr < self.simplex[n - 1].1 {
            self.simplex[n] = (reflected, fr);
            return Ok(true);
        }
        let towards = if fr < worst.1 { &reflected } else { &worst.0 };
        let contracted = along(&centroid, towards, CONTRACT);
        let Some(fc) = self.eval(&contracted)? else {
            return Ok(false);
        };
        if fc < worst.1.min(fr) {
            self.simplex[n] = (contracted, fc);
            return Ok(true);
        }
        self.shrink()
    }

    /// Shrinks every vertex halfway towards the best; false when the objective stopped the
    /// search.
    fn shrink(&mut self) -> Result<bool> {
        let best = self.simplex[0].0.clone();
        for v in 1..self.simplex.len() {
            let x = along(&best, &self.simplex[v].0, SHRINK);
            let Some(f) = self.eval(&x)? else {
                return Ok(false);
            };
            self.simplex[v] = (x, f);
        }
        Ok(true)
    }

    /// The best vertex, ended as `termination` (the start when there is no vertex), and the
    /// driver.
    fn minimum(mut self, start: &[f64], termination: Termination) -> (Minimum, Driver<'o>) {
        self.sort();
        let extent = (0..start.len())
            .map(|k| {
                let along = self.simplex.iter().map(|(x, _)| x[k]);
                along.clone().fold(f64::NEG_INFINITY, f64::max)
                    - along.fold(f64::INFINITY, f64::min)
            })
            .filter(|e| e.is_finite())
            .collect();
        let (x, value) = match self.simplex.into_iter().next() {
            Some(best) => best,
            None => (start.to_vec(), f64::INFINITY),
        };
        let minimum = Minimum {
            x,
            value,
            evaluations: self.evaluations,
            extent,
            termination: self.driver.end(termination),
        };
        (minimum, self.driver)
    }

    /// The best vertex of a search the objective or the observer stopped.
    fn stopped(mut self, start: &[f64]) -> (Minimum, Driver<'o>) {
        let end = self.stop.take().unwrap_or(Termination::Stopped {
            after: self.evaluations,
        });
        self.minimum(start, end)
    }
}

/// The point `from + t·(to − from)`.
fn along(from: &[f64], to: &[f64], t: f64) -> Vec<f64> {
    from.iter().zip(to).map(|(a, b)| a + t * (b - a)).collect()
}

/// Minimises `objective` from `start` with a first simplex of steps `step` along each
/// parameter, until the values at the simplex's vertices differ by no more than
/// [`SearchSettings::tolerance`] ([`Termination::Converged`]) or
/// [`SearchSettings::max_evaluations`] is used up ([`Termination::StepLimit`]): the best vertex
/// either way. The objective returns `ControlFlow::Continue(value)`, or
/// `ControlFlow::Break(termination)` to end the search there (an inner method that did not
/// converge); an error of the objective is returned as it is. Unobserved:
/// [`nelder_mead_observed`] reports each evaluation.
pub fn nelder_mead(
    mut objective: impl FnMut(&[f64]) -> Result<ControlFlow<Termination, f64>>,
    start: &[f64],
    step: &[f64],
    settings: &SearchSettings,
) -> Result<Minimum> {
    let objective = |x: &[f64], _: &mut Inner| objective(x);
    let (minimum, _) = nelder_mead_observed(
        objective,
        start,
        step,
        settings,
        Method::ProfileSearch,
        &Silent,
    )?;
    Ok(minimum)
}

/// [`nelder_mead`] on a [`Driver`] of `method` reporting to `observer`: each evaluation is a
/// step, reported with the objective's value as its measure, the budget its step limit; the
/// observer may stop the search ([`Termination::Stopped`]). The objective may note how the
/// inner methods it ran ended ([`Inner::note`]): a converged search ends with the first reduced
/// accuracy noted. Returns the driver with the minimum, for the search's last event
/// ([`Driver::announce`]) after any check of the caller's own.
pub fn nelder_mead_observed<'o>(
    objective: impl FnMut(&[f64], &mut Inner) -> Result<ControlFlow<Termination, f64>>,
    start: &[f64],
    step: &[f64],
    settings: &SearchSettings,
    method: Method,
    observer: &'o dyn Observer,
) -> Result<(Minimum, Driver<'o>)> {
    settings.check()?;
    if start.is_empty() || step.len() != start.len() {
        return Err(Error::invalid(
            "step",
            format!("{} steps for {} parameters", step.len(), start.len()),
            "one step per parameter, at least one parameter",
        ));
    }
    let driver = Driver::new(
        method,
        observer,
        settings.tolerance,
        settings.max_evaluations,
    );
    let mut search = Search {
        objective,
        driver,
        evaluations: 0,
        simplex: Vec::with_capacity(start.len() + 1),
        stop: None,
    };
    for k in 0..=start.len() {
        let mut x = start.to_vec();
        if k > 0 {
            x[k - 1] += step[k - 1];
        }
        match search.eval(&x)? {
            Some(f) => search.simplex.push((x, f)),
            None => return Ok(search.stopped(start)),
        }
    }
    loop {
        search.sort();
        let spread = search.spread();
        if spread <= settings.tolerance {
            return Ok(search.minimum(start, Termination::Converged));
        }
        if search.driver.exhausted() {
            search.driver.settle(spread);
            let end = search.driver.step_limit();
            return Ok(search.minimum(start, end));
        }
        if !search.step()? {
            return Ok(search.stopped(start));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn value(f: f64) -> Result<ControlFlow<Termination, f64>> {
        Ok(ControlFlow::Continue(f))
    }

    fn settings(tolerance: f64, max_evaluations: usize) -> SearchSettings {
        SearchSettings {
            tolerance,
            max_evaluations,
        }
    }

    /// Rosenbrock's valley from (−1.2, 1): the minimum (1, 1) to 1e-4, in a few hundred
    /// evaluations, converged.
    #[test]
    fn finds_the_minimum_of_rosenbrocks_valley() {
        let f = |x: &[f64]| value(100.0 * (x[1] - x[0] * x[0]).powi(2) + (1.0 - x[0]).powi(2));
        let m = nelder_mead(f, &[-1.2, 1.0], &[0.5, 0.5], &settings(1e-14, 2000)).unwrap();
        assert!(
            (m.x[0] - 1.0).abs() < 1e-4 && (m.x[1] - 1.0).abs() < 1e-4,
            "{m:?}"
        );
        assert!(m.evaluations < 600, "{}", m.evaluations);
        assert_eq!(m.termination, Termination::Converged);
        // The last simplex is small about the minimum, and not a point.
        assert!(
            m.extent.iter().all(|&e| e > 0.0 && e < 1e-3),
            "{:?}",
            m.extent
        );
    }

    /// The budget ends the search with a step limit, not an error; the objective's error is
    /// returned; its stop ends the search with its termination and the best vertex so far;
    /// bad steps and settings are named.
    #[test]
    fn budget_stops_errors_and_bad_input() {
        let f = |x: &[f64]| value(x[0] * x[0]);
        let m = nelder_mead(f, &[3.0], &[1.0], &settings(0.0, 10)).unwrap();
        assert!(m.evaluations <= 12 && m.value < 9.0, "{m:?}");
        assert!(
            matches!(m.termination, Termination::StepLimit { steps, .. } if steps == m.evaluations),
            "{m:?}"
        );
        let failing = |_: &[f64]| Err(Error::invalid("k", 1, "no"));
        assert!(nelder_mead(failing, &[0.0], &[1.0], &settings(0.0, 10)).is_err());
        let mut calls = 0;
        let stopping = |x: &[f64]| {
            calls += 1;
            match calls {
                4 => Ok(ControlFlow::Break(Termination::Stopped { after: 4 })),
                _ => value(x[0] * x[0]),
            }
        };
        let m = nelder_mead(stopping, &[3.0], &[1.0], &settings(0.0, 100)).unwrap();
        assert_eq!(m.termination, Termination::Stopped { after: 4 });
        assert_eq!(m.evaluations, 4);
        assert!(m.value <= 9.0, "{m:?}");
        let e = nelder_mead(f, &[0.0], &[], &settings(0.0, 10)).unwrap_err();
        assert!(e.to_string().contains("one step per parameter"), "{e}");
        let e = nelder_mead(f, &[0.0], &[1.0], &settings(0.0, 0)).unwrap_err();
        assert!(e.to_string().contains("max_evaluations"), "{e}");
    }
}
