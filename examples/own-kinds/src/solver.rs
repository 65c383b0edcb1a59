//! A contact solver of one's own: projected Gauss–Seidel on the dense influence matrix
//! (`solver = { kind = "projected_gauss_seidel" }`), on the library's iteration driver.

use contopt_contact::{ContactSolver, InterfaceProblem, Workspace};
use contopt_core::drive::{Driver, Step};
use contopt_core::observe::{Method, Observer};
use contopt_core::{check, ContactState, Error, Result};
use contopt_scene::SolverKind;
use serde::{Deserialize, Serialize};

/// The solver's id in events and in `result.json`.
const METHOD: Method = Method::Other("projected_gauss_seidel");

/// The first half-width of the bracket of a floating body's amplitude \[mm\], doubled until
/// it holds the balance, up to [`BRACKET_END_MM`].
const BRACKET_START_MM: f64 = 1e-6;
const BRACKET_END_MM: f64 = 1e3;

// ANCHOR: solver
/// Projected Gauss–Seidel for the contact conditions p ≥ 0, d ≥ 0, p·d = 0 with
/// d = h + A W p + R λ (eq. 2.7): each sweep sets every point's pressure to the one that closes
/// its own gap, or to zero. A floating body's amplitude λ is found by bisection on its
/// equilibrium Σ wᵢ Rᵢ pᵢ + q = 0 (eq. 2.10), one driver step a bisection.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ProjectedGaussSeidel {
    /// A sweep converges when no pressure moves by more than this times the largest.
    pub tolerance: f64,
    /// The equilibrium holds when Σ wᵢ Rᵢ pᵢ + q is at most this times |q|.
    pub equilibrium: f64,
    /// Sweeps a solve may take for one λ.
    pub max_sweeps: usize,
    /// Bisections of λ.
    pub max_steps: usize,
}

impl Default for ProjectedGaussSeidel {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            equilibrium: 1e-10,
            max_sweeps: 10_000,
            max_steps: 200,
        }
    }
}

impl SolverKind for ProjectedGaussSeidel {
    fn build(&self) -> Result<Box<dyn ContactSolver>> {
        check::positive("tolerance", self.tolerance)?;
        check::positive("equilibrium", self.equilibrium)?;
        check::count("max_sweeps", self.max_sweeps, 1, usize::MAX)?;
        check::count("max_steps", self.max_steps, 1, usize::MAX)?;
        Ok(Box::new(*self))
    }
}

impl ContactSolver for ProjectedGaussSeidel {
    fn method(&self) -> Method {
        METHOD
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        1
    }

    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
        _workspace: &mut Workspace,
    ) -> Result<ContactState> {
        let sweeps = Sweeps::new(problem, self)?;
        let mut driver = Driver::new(METHOD, observer, self.equilibrium, self.max_steps);
        let (pressure, lambda, end) = match problem.modes() {
            [] => {
                let (p, end) = sweeps.solve(0.0)?;
                driver.report(0.0);
                (p, vec![], end)
            }
            [_] => {
                let (p, lambda, end) = sweeps.balance(&mut driver)?;
                (p, vec![lambda], end)
            }
            more => {
                return Err(Error::invalid(
                    "modes",
                    more.len(),
                    "projected Gauss–Seidel holds at most one floating mode",
                ))
            }
        };
        let active = pressure.iter().map(|&p| p > 0.0).collect();
        let mut state = problem.state(METHOD, pressure, lambda, active, [driver.steps(), 0, 0]);
        if state.termination.is_converged() {
            state.termination = end;
        }
        driver.announce(&state.termination);
        Ok(state)
    }
}
// ANCHOR_END: solver

/// The sweeps of one problem: its matrix, weights, initial gap and the floating mode.
struct Sweeps<'p> {
    a: &'p faer::Mat<f64>,
    w: &'p [f64],
    h: &'p [f64],
    /// The floating mode's displacement per point and load, or zeros.
    r: Vec<f64>,
    q: f64,
    settings: &'p ProjectedGaussSeidel,
}

impl<'p> Sweeps<'p> {
    fn new(problem: &'p InterfaceProblem, settings: &'p ProjectedGaussSeidel) -> Result<Self> {
        let a = problem.dense_influence(1)?;
        let mut r = vec![0.0; problem.len()];
        let mut q = 0.0;
        if let [mode] = problem.modes() {
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                r[i] = v;
            }
            q = mode.load;
        }
        Ok(Self {
            a,
            w: problem.weights(),
            h: problem.initial_gap(),
            r,
            q,
            settings,
        })
    }

    /// The pressure for the amplitude `lambda`, swept until it settles.
    fn solve(&self, lambda: f64) -> Result<(Vec<f64>, contopt_core::Termination)> {
        let n = self.w.len();
        let mut p = vec![0.0; n];
        for _ in 0..self.settings.max_sweeps {
            let mut moved: f64 = 0.0;
            for i in 0..n {
                let own = self.a[(i, i)] * self.w[i];
                let d: f64 = self.h[i]
                    + self.r[i] * lambda
                    + (0..n)
                        .map(|j| self.a[(i, j)] * self.w[j] * p[j])
                        .sum::<f64>();
                let next = if d.is_finite() && own > 0.0 {
                    (p[i] - d / own).max(0.0)
                } else {
                    0.0
                };
                moved = moved.max((next - p[i]).abs());
                p[i] = next;
            }
            let largest = p.iter().copied().fold(0.0, f64::max);
            if moved <= self.settings.tolerance * largest.max(f64::MIN_POSITIVE) {
                return Ok((p, contopt_core::Termination::Converged));
            }
        }
        Ok((
            p,
            contopt_core::Termination::StepLimit {
                steps: self.settings.max_sweeps,
                measure: f64::NAN,
                tolerance: self.settings.tolerance,
            },
        ))
    }

    /// Σ wᵢ Rᵢ pᵢ + q: the pressure's force on the mode and its load, which balance.
    fn imbalance(&self, p: &[f64]) -> f64 {
        (0..p.len())
            .map(|i| self.w[i] * self.r[i] * p[i])
            .sum::<f64>()
            + self.q
    }

    /// The floating mode's amplitude that balances its load, by bisection on a bracket grown
    /// from zero both ways: the pressure, λ and how it ended.
    fn balance(&self, driver: &mut Driver) -> Result<(Vec<f64>, f64, contopt_core::Termination)> {
        let scale = self.q.abs().max(f64::MIN_POSITIVE);
        let at = |lambda: f64| -> Result<f64> { Ok(self.imbalance(&self.solve(lambda)?.0)) };
        let f_zero = at(0.0)?;
        let (mut lo, mut hi, mut f_lo, mut f_hi) = (0.0, 0.0, f_zero, f_zero);
        let mut reach = BRACKET_START_MM;
        while f_lo.signum() == f_hi.signum() && reach <= BRACKET_END_MM {
            (lo, hi) = (-reach, reach);
            (f_lo, f_hi) = (at(lo)?, at(hi)?);
            if f_lo.signum() != f_zero.signum() {
                (hi, f_hi) = (0.0, f_zero);
            } else if f_hi.signum() != f_zero.signum() {
                (lo, f_lo) = (0.0, f_zero);
            }
            reach *= 2.0;
        }
        if f_lo.signum() == f_hi.signum() {
            return Err(Error::invalid(
                "load",
                self.q,
                format!(
                    "no amplitude of the floating body within ±{BRACKET_END_MM} mm balances it"
                ),
            ));
        }
        let rising = f_hi > f_lo;
        let mut best = (Vec::new(), 0.0, contopt_core::Termination::Converged);
        let end = driver.run(|_, _| -> Result<Step> {
            let mid = 0.5 * (lo + hi);
            let (p, inner) = self.solve(mid)?;
            let off = self.imbalance(&p);
            match (off > 0.0) == rising {
                true => hi = mid,
                false => lo = mid,
            }
            best = (p, mid, inner.clone());
            Ok(match inner.is_converged() {
                true => Step::converged_below(off.abs() / scale, self.settings.equilibrium),
                false => Step::Ended(inner),
            })
        })?;
        let (p, lambda, _) = best;
        Ok((p, lambda, end))
    }
}
