//! The rows of an optimisation loop and its reports to the observer: one event per pass at
//! level 0, and a last event with how the loop ended.

use contopt_core::observe::{Event, Flow, Method, Observer};
use contopt_core::Termination;

use crate::{Optimisation, Optimum, Pass, Region, SOLVER_ACCURACY};

/// How far above v·p_max \[relative to p_max\] a point of Ω_v may end: above what the fit of
/// nodal gap changes to Gauss points leaves of χ = 0 (measured: ≤ 2.4·10⁻³ of p_max on Tables
/// 1–3 and the rollers, 8 % at the Gauss point next to the rim in Table 2's L1 = 40 mm), well
/// below a point the design does not hold (the filleted punch's Ω_v edge node on a 0.1 mm
/// mesh carried 51 % of p_max where v = 0).
const OMEGA_V_HELD: f64 = 0.25;

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
    /// breaks χ ≥ 0 on Ω_nv, or passes v·p_max on Ω_v by more than [`OMEGA_V_HELD`], ends as
    /// [`Termination::Infeasible`], naming where.
    pub(crate) fn finish(self, optimum: Optimum, termination: Termination) -> Optimum {
        let excess = self.bound.excess(&optimum.pressure, optimum.p_max);
        let held = self.bound.omega_v_excess(&optimum.pressure, optimum.p_max);
        let termination = match (termination, excess, held) {
            (Termination::Converged, Some((value, i)), _)
                if value > SOLVER_ACCURACY * optimum.p_max =>
            {
                self.bound.broken(value, i)
            }
            (Termination::Converged, _, Some((value, i)))
                if value > OMEGA_V_HELD * optimum.p_max =>
            {
                self.bound.not_held(value, i)
            }
            (termination, _, _) => termination,
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

/// The largest p − v·p_max over `points` (index, v) of `pressure`, with its point.
fn largest_excess(points: &[(usize, f64)], pressure: &[f64], p_max: f64) -> Option<(f64, usize)> {
    points
        .iter()
        .filter(|(i, _)| *i < pressure.len())
        .map(|&(i, v)| (pressure[i] - v * p_max, i))
        .max_by(|a, b| a.0.total_cmp(&b.0))
}

/// The points of Ω_nv with their controller values, where χ = v·p_max − p ≥ 0 must hold, and
/// those of Ω_v, where χ = 0 is prescribed.
pub(crate) struct Bound<'o> {
    omega_nv: Vec<(usize, f64)>,
    omega_v: Vec<(usize, f64)>,
    points: &'o [[f64; 3]],
}

impl<'o> Bound<'o> {
    pub(crate) fn new(opt: &'o Optimisation<'_>) -> Self {
        let of = |region: Region| {
            (0..opt.v.len())
                .filter(|&i| opt.regions[i] == region)
                .map(|i| (i, opt.v[i]))
                .collect()
        };
        Self {
            omega_nv: of(Region::OmegaNv),
            omega_v: of(Region::OmegaV),
            points: opt.problem.interface().points(),
        }
    }

    /// The largest p − v·p_max over Ω_nv of `pressure` under `p_max` \[MPa\], with its point;
    /// `None` without Ω_nv.
    pub(crate) fn excess(&self, pressure: &[f64], p_max: f64) -> Option<(f64, usize)> {
        largest_excess(&self.omega_nv, pressure, p_max)
    }

    /// The largest p − v·p_max over Ω_v \[MPa\], with its point; `None` without Ω_v.
    pub(crate) fn omega_v_excess(&self, pressure: &[f64], p_max: f64) -> Option<(f64, usize)> {
        largest_excess(&self.omega_v, pressure, p_max)
    }

    /// The termination of an optimum whose pressure passes v·p_max by `value` at point `i`
    /// of Ω_v, where the design prescribes p = v·p_max.
    pub(crate) fn not_held(&self, value: f64, i: usize) -> Termination {
        Termination::Infeasible {
            reason: format!(
                "p passes v·p_max by {value:.4e} MPa at point {i} {:?} of Ω_v, where the design \
                 prescribes p = v·p_max: the gap change fitted there (step 6) cannot hold it, \
                 as where a face beyond Ω_v's edge touches; move Ω_v's edge or coarsen the \
                 faces there",
                self.points[i]
            ),
        }
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
