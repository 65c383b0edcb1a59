//! The rows of an optimisation loop and its reports to the observer: one event per pass at
//! level 0, and a last event with how the loop ended.

use contopt_core::observe::{Event, Flow, Method, Observer};
use contopt_core::Termination;

use crate::{Optimisation, Optimum, Pass, Region, SOLVER_ACCURACY};

/// A loop's passes so far and where it reports them.
pub(crate) struct Passes<'o> {
    observer: &'o dyn Observer,
    method: Method,
    tolerance: f64,
    rows: Vec<Pass>,
    /// The passes reported, with a row or without.
    steps: usize,
    /// The measure of the last pass (NaN before the first).
    measure: f64,
    /// The bound χ ≥ 0 every optimum is checked against.
    bound: Bound<'o>,
}

impl<'o> Passes<'o> {
    /// No passes yet of `method` on `opt`, whose measure must reach `tolerance`.
    pub(crate) fn new(opt: &'o Optimisation<'_>, method: Method, tolerance: f64) -> Self {
        Self {
            observer: opt.observer,
            method,
            tolerance,
            rows: vec![],
            steps: 0,
            measure: f64::NAN,
            bound: Bound::new(opt),
        }
    }

    /// Records `row` with its convergence `measure` and reports it; what the observer asks.
    pub(crate) fn push(&mut self, row: Pass, measure: f64) -> Flow {
        self.rows.push(row);
        self.report(row.k, measure)
    }

    /// Reports pass `k` (a pass that gave no row, or one whose row was recorded) with its
    /// convergence `measure`; what the observer asks.
    pub(crate) fn report(&mut self, k: usize, measure: f64) -> Flow {
        self.steps += 1;
        self.measure = measure;
        let event = Event::step(self.method, k, measure, self.tolerance);
        self.observer.observe(&event)
    }

    /// The step limit after the passes so far.
    pub(crate) fn step_limit(&self) -> Termination {
        Termination::StepLimit {
            steps: self.steps,
            measure: self.measure,
            tolerance: self.tolerance,
        }
    }

    /// `optimum` with these rows and its largest p − v·p_max on Ω_nv, ended as
    /// `termination`, after the last event says so. An optimum that met its tolerance but
    /// breaks χ ≥ 0 on Ω_nv ends as [`Termination::Infeasible`], naming where.
    pub(crate) fn finish(self, optimum: Optimum, termination: Termination) -> Optimum {
        let excess = self.bound.excess(&optimum.pressure, optimum.p_max);
        let termination = match (termination, excess) {
            (Termination::Converged, Some((value, i)))
                if value > SOLVER_ACCURACY * optimum.p_max =>
            {
                self.bound.broken(value, i)
            }
            (termination, _) => termination,
        };
        let event =
            Event::step(self.method, self.steps, self.measure, self.tolerance).ending(&termination);
        let _ = self.observer.observe(&event);
        Optimum {
            passes: self.rows,
            method: self.method,
            termination,
            omega_nv_excess: excess.map(|(value, _)| value),
            ..optimum
        }
    }
}

/// The points of Ω_nv with their controller values, where χ = v·p_max − p ≥ 0 must hold.
pub(crate) struct Bound<'o> {
    omega_nv: Vec<(usize, f64)>,
    points: &'o [[f64; 3]],
}

impl<'o> Bound<'o> {
    pub(crate) fn new(opt: &'o Optimisation<'_>) -> Self {
        Self {
            omega_nv: (0..opt.v.len())
                .filter(|&i| opt.regions[i] == Region::OmegaNv)
                .map(|i| (i, opt.v[i]))
                .collect(),
            points: opt.problem.interface().points(),
        }
    }

    /// The largest p − v·p_max over Ω_nv of `pressure` under `p_max` \[MPa\], with its point;
    /// `None` without Ω_nv.
    pub(crate) fn excess(&self, pressure: &[f64], p_max: f64) -> Option<(f64, usize)> {
        self.omega_nv
            .iter()
            .filter(|(i, _)| *i < pressure.len())
            .map(|&(i, v)| (pressure[i] - v * p_max, i))
            .max_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// The termination of an optimum whose pressure passes v·p_max by `value` at point `i`
    /// of Ω_nv.
    pub(crate) fn broken(&self, value: f64, i: usize) -> Termination {
        Termination::Infeasible {
            reason: format!(
                "p passes v·p_max by {value:.4e} MPa at point {i} {:?} of Ω_nv (χ ≥ 0 of 3.4): \
                 the gap change there follows its design column, which Ω_v closes at v·p_max, \
                 so no gap change keeps it; the linear programme (3.5) finds the same. Put Ω_v \
                 where each column's pressure peaks",
                self.points[i]
            ),
        }
    }
}
