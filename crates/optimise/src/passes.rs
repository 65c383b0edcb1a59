//! The rows of an optimisation loop and its reports to the observer: one event per pass at
//! level 0, and a last event with how the loop ended.

use contopt_core::drive::Driver;
use contopt_core::observe::Method;
use contopt_core::{Infeasibility, Termination};

use crate::{Optimisation, Optimum, Pass, Region, SOLVER_ACCURACY};

/// How far above v·p_max \[relative to p_max\] a point of Ω_v may end: above what the fit of
/// nodal gap changes to Gauss points leaves of χ = 0 (measured: ≤ 2.4·10⁻³ of p_max on Tables
/// 1–3 and the rollers, 8 % at the Gauss point next to the rim in Table 2's L1 = 40 mm), well
/// below a point the design does not hold (the filleted punch's Ω_v edge node on a 0.1 mm
/// mesh carried 51 % of p_max where v = 0).
const OMEGA_V_HELD: f64 = 0.25;

/// A loop's passes so far, the driver that runs them ([`Driver`]: it counts them, reports
/// them to the observer and says how the loop ended) and the bound its optimum is checked
/// against.
pub(crate) struct Passes<'o> {
    pub(crate) driver: Driver<'o>,
    pub(crate) rows: Vec<Pass>,
    /// The bound χ ≥ 0 every optimum is checked against.
    bound: Bound<'o>,
}

impl<'o> Passes<'o> {
    /// No passes yet of `method` on `opt`, whose measure must reach `tolerance` in at most
    /// `max_passes`.
    pub(crate) fn new(
        opt: &'o Optimisation<'_>,
        method: Method,
        tolerance: f64,
        max_passes: usize,
    ) -> Self {
        Self {
            driver: Driver::new(method, opt.observer, tolerance, max_passes),
            rows: vec![],
            bound: Bound::new(opt),
        }
    }

    /// `optimum` with these rows and its largest p − v·p_max on Ω_nv, ended as
    /// `termination` (a convergence as the first reduced accuracy its driver noted, if any),
    /// after the last event says so. An optimum whose answer stands but breaks χ ≥ 0 on Ω_nv,
    /// or passes v·p_max on Ω_v by more than [`OMEGA_V_HELD`], ends as
    /// [`Termination::Infeasible`], naming where.
    pub(crate) fn finish(self, optimum: Optimum, termination: Termination) -> Optimum {
        let excess = self.bound.excess(&optimum.pressure, optimum.p_max);
        let held = self.bound.omega_v_excess(&optimum.pressure, optimum.p_max);
        let p_max = optimum.p_max;
        let termination = match (self.driver.end(termination), excess, held) {
            (end, Some((value, i)), _) if end.is_solved() && value > SOLVER_ACCURACY * p_max => {
                self.bound.broken(value, i, None)
            }
            (end, _, Some((value, i))) if end.is_solved() && value > OMEGA_V_HELD * p_max => {
                self.bound.not_held(value, i)
            }
            (termination, _, _) => termination,
        };
        self.driver.announce(&termination);
        Optimum {
            passes: self.rows,
            method: self.driver.method(),
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

    /// The termination of an optimum whose pressure passes v·p_max by `excess` at point
    /// `point` of Ω_v, where the design prescribes p = v·p_max.
    pub(crate) fn not_held(&self, excess: f64, point: usize) -> Termination {
        Termination::Infeasible {
            cause: Infeasibility::OmegaVNotHeld {
                point,
                position_mm: self.points[point],
                excess_mpa: excess,
            },
        }
    }

    /// The termination of an optimum (of load case `case`, from 1, of an envelope) whose
    /// pressure passes v·p_max by `excess` at point `point` of Ω_nv.
    pub(crate) fn broken(&self, excess: f64, point: usize, case: Option<usize>) -> Termination {
        Termination::Infeasible {
            cause: Infeasibility::OmegaNv {
                point,
                position_mm: self.points[point],
                excess_mpa: excess,
                case,
            },
        }
    }
}
