//! Control of the contact pressure and optimisation of the initial gap (§3 of Páczelt 1994):
//! find the change of initial gap Δh ≥ 0 that minimises p_max subject to p(x) ≤ v(x)·p_max.
//!
//! One [`Optimisation`] serves every interface problem, whatever its region: the points of Ω_v
//! (d = 0 and χ = v·p_max − p = 0 prescribed), of Ω_nv (d ≥ 0 and χ ≥ 0 only) and outside Ω_opt
//! are tags ([`Region`]), and the gap change reaches the points through the map Q of a
//! [`GapShape`] (eq. 3.3: Δh_nv = f(Δh)). It solves
//! - by the iteration of §3.2, steps 1–7, with a contact solver inside
//!   ([`Optimisation::iterate`]), under a given load (p_max from equilibrium, the case of
//!   eq. 4.1 and Tables 1 and 3) or a given displacement (p_max from the contact pressure,
//!   Table 2), stopping on TOLH (4.2);
//! - as the restricted linear programme (3.5) on the dense influence matrix
//!   ([`Optimisation::linear_programme`]), for small problems and as a cross-check;
//! - or, for large problems, as the same optimum without a dense matrix: one strictly convex
//!   contact QP per update of the loads carried by the design columns
//!   ([`Optimisation::load_split`]), solved by any contact solver, matrix-free ones included;
//!   its generalisation to several load cases sharing one gap change, the robust optimum of
//!   max over the cases of p ≤ v·p_max ([`Optimisation::envelope_split`]).
//!
//! [`nelder_mead`] tunes the few parameters of a given profile family (a derivative-free
//! search), the published practice the optimised gaps are compared with.

// Input checks are written `!(x > 0.0)` on purpose: the negation also rejects NaN.
#![allow(clippy::neg_cmp_op_on_partial_ord)]

mod controller;
mod iteration;
mod load_split;
mod lp;
mod simplex;
#[cfg(test)]
mod tests;

pub use controller::{Constant, Controller, Product, Profile};
pub use iteration::{Iteration, Mode};
pub use load_split::EnvelopeOptimum;
pub use simplex::{nelder_mead, Minimum};

use contopt_contact::{ContactSolver, InterfaceProblem};
use contopt_core::observe::{self, stopped_by_observer, Flow, Observer, Silent};
use contopt_core::{ContactState, Error, GapShape, Result};

/// Relative round-off of a sum over points (a row of Q, a column's rigid displacement, the
/// equilibrium of v·p_max): values that agree to it are equal (round-off).
pub(crate) const ROUND_OFF: f64 = 1e-9;

/// Relative accuracy of the pressures, gaps and gap changes that come out of a contact solve
/// or an interior point: a value below it times its scale is noise (convergence).
pub(crate) const SOLVER_ACCURACY: f64 = 1e-6;

/// Role of an interface point in the optimisation (§3.2), one per point through
/// [`Optimisation::with_regions`]; without it every point is Ω_v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// In the proposed contact zone Ω but outside Ω_opt: only p ≥ 0, d ≥ 0, pd = 0.
    Contact,
    /// Ω_v: d = 0 and χ = v·p_max − p = 0 are prescribed.
    OmegaV,
    /// Ω_nv = Ω_opt − Ω_v: only d ≥ 0 and χ ≥ 0; the gap change follows Ω_v (eq. 3.3).
    OmegaNv,
}

/// The result of an optimisation.
#[derive(Clone, Debug)]
pub struct Optimum {
    /// The least largest pressure p_max \[MPa\].
    pub p_max: f64,
    /// Gap change at the design nodes of the [`GapShape`], Δh ≥ 0, zero at the reference
    /// node \[mm\].
    pub dh: Vec<f64>,
    /// Gap change at the interface points, QΔh \[mm\].
    pub gap_change: Vec<f64>,
    /// The pressure at the interface points \[MPa\]: v·p_max on Ω_v.
    pub pressure: Vec<f64>,
    /// Gap after deformation at the interface points \[mm\].
    pub gap: Vec<f64>,
    /// Rigid-mode amplitudes λ.
    pub rigid: Vec<f64>,
    /// The rows of the iteration of §3.2 (Table 2's columns); one row for the LP, its number
    /// of restrictions in `k`.
    pub iterations: Vec<Iteration>,
}

impl Optimum {
    /// The largest gap change Δh_max \[mm\].
    pub fn dh_max(&self) -> f64 {
        self.dh.iter().fold(0.0, |m: f64, v| m.max(*v))
    }
}

/// The data of an optimisation: the interface problem, the gap map Q, the controller's values
/// and the regions.
pub struct Optimisation<'a> {
    problem: &'a InterfaceProblem<'a>,
    shape: &'a GapShape,
    /// v(xᵢ) at every point (used on Ω_opt).
    v: Vec<f64>,
    regions: Vec<Region>,
    /// The design node N of §3.2 step 6 where the gap does not change.
    reference: usize,
    /// Receives each iteration of the loop and of the contact solves inside it.
    observer: &'a dyn Observer,
}

impl<'a> Optimisation<'a> {
    /// The optimisation of `problem` with gap changes described by `shape` and pressures
    /// controlled by `controller`. The whole interface is Ω_v (the one-dimensional case of
    /// §3.2) until [`Optimisation::with_regions`] says otherwise.
    /// The reference node N, where the gap does not change, is the design node nearest the
    /// origin (the axis or the plane of symmetry); see [`Optimisation::with_reference`].
    pub fn new(
        problem: &'a InterfaceProblem<'a>,
        shape: &'a GapShape,
        controller: &dyn Controller,
    ) -> Result<Self> {
        let iface = problem.interface();
        if shape.len() != iface.len() {
            return Err(Error::invalid(
                "gap_shape",
                format!("{} rows", shape.len()),
                format!("one row per interface point ({})", iface.len()),
            ));
        }
        let v: Vec<f64> = iface.points().iter().map(|&x| controller.value(x)).collect();
        let regions = vec![Region::OmegaV; iface.len()];
        let nearest = (0..shape.nodes().len())
            .min_by(|&a, &b| {
                let r = |k: usize| shape.nodes()[k].iter().map(|c| c * c).sum::<f64>();
                r(a).total_cmp(&r(b))
            })
            .unwrap_or(0);
        let opt = Self {
            problem,
            shape,
            v,
            regions,
            reference: nearest,
            observer: &Silent,
        };
        opt.check()?;
        Ok(opt)
    }

    /// Reports each iteration of the optimisation and of its contact solves to `observer`,
    /// which may stop the loop early. The loop reports as method `"optimisation"`, with the
    /// measure it compares with its tolerance: TOLH (4.2) in [`Optimisation::iterate`], the
    /// number of points that carry pressure across an open gap (tolerance 0) in
    /// [`Optimisation::linear_programme`], the miss of v·p_max on Ω_v in
    /// [`Optimisation::load_split`] and [`Optimisation::envelope_split`]. Stopped, the loop
    /// fails with [`Error::NotConverged`] saying that an observer stopped it.
    pub fn with_observer(mut self, observer: &'a dyn Observer) -> Self {
        self.observer = observer;
        self
    }

    /// Sets the regions explicitly, one per interface point.
    pub fn with_regions(mut self, regions: Vec<Region>) -> Result<Self> {
        if regions.len() != self.v.len() {
            return Err(Error::invalid(
                "regions",
                regions.len(),
                format!("one per interface point ({})", self.v.len()),
            ));
        }
        self.regions = regions;
        self.check()?;
        Ok(self)
    }

    /// Sets the reference node N (an index of the gap shape's nodes) where Δh = 0.
    pub fn with_reference(mut self, node: usize) -> Result<Self> {
        if node >= self.shape.nodes().len() {
            return Err(Error::invalid(
                "reference",
                node,
                format!("a design node below {}", self.shape.nodes().len()),
            ));
        }
        self.reference = node;
        self.check()?;
        Ok(self)
    }

    /// The controller's values, the regions and the design nodes are consistent.
    fn check(&self) -> Result<()> {
        let pts = &self.problem.interface().points();
        for (i, &v) in self.v.iter().enumerate() {
            if self.regions[i] != Region::Contact && !(0.0..=1.0).contains(&v) {
                return Err(Error::invalid(
                    format!("controller at point {i} {:?}", pts[i]),
                    v,
                    "must lie in [0, 1]",
                ));
            }
        }
        let omega_v = self.omega_v();
        if omega_v.is_empty() {
            return Err(Error::invalid(
                "regions",
                "no Ω_v point",
                "Ω_v must not be empty",
            ));
        }
        if omega_v.iter().all(|&i| self.v[i] == 0.0) {
            return Err(Error::invalid(
                "controller",
                0.0,
                "vanishes on all of Ω_v: no pressure is allowed",
            ));
        }
        for i in 0..self.v.len() {
            let sum: f64 = self.shape.row(i).iter().map(|(_, w)| w).sum();
            if (sum - 1.0).abs() > ROUND_OFF {
                return Err(Error::invalid(
                    format!("gap_shape.rows[{i}]"),
                    sum,
                    "the weights of a row must sum to 1 (a uniform Δh is a uniform gap change)",
                ));
            }
        }
        let mut tied = vec![false; self.shape.nodes().len()];
        for &i in &omega_v {
            for &(k, w) in self.shape.row(i) {
                tied[k] |= w != 0.0;
            }
        }
        if let Some(k) = tied.iter().position(|t| !t) {
            return Err(Error::invalid(
                format!("gap_shape.nodes[{k}]"),
                format!("{:?}", self.shape.nodes()[k]),
                "is not tied to any Ω_v point, so its gap change is undetermined",
            ));
        }
        Ok(())
    }

    /// Points of Ω_v.
    fn omega_v(&self) -> Vec<usize> {
        (0..self.v.len())
            .filter(|&i| self.regions[i] == Region::OmegaV)
            .collect()
    }

    /// The design nodes other than the reference.
    pub(crate) fn free_nodes(&self) -> Vec<usize> {
        (0..self.shape.nodes().len())
            .filter(|&k| k != self.reference)
            .collect()
    }

    /// Reports pass `k` of the loop to the observer (see [`Optimisation::with_observer`]).
    fn report(&self, k: usize, measure: f64, tolerance: f64) -> Flow {
        self.observer.observe(&observe::Iteration {
            method: "optimisation",
            iteration: k,
            measure,
            tolerance,
        })
    }

    /// The error of a loop (`method`) that an observer stopped after `k` passes, `detail`
    /// saying how far it got.
    fn stopped(method: &str, k: usize, detail: String) -> Error {
        Error::NotConverged {
            method: method.into(),
            iterations: k,
            detail: format!("{}; {detail}", stopped_by_observer(k)),
        }
    }

    /// Solves `problem` with its initial gap changed by `gap_change` (from the pressure
    /// `start` when given), the contact solver reporting to the observer.
    fn solve_with_gap_change(
        &self,
        solver: &dyn ContactSolver,
        problem: &InterfaceProblem,
        gap_change: &[f64],
        start: Option<&[f64]>,
    ) -> Result<ContactState> {
        let gap: Vec<f64> = problem
            .initial_gap()
            .iter()
            .zip(gap_change)
            .map(|(h, d)| h + d)
            .collect();
        solver
            .solve_observed(&problem.with_initial_gap(&gap)?, start, self.observer)?
            .solved(solver.name())
    }

    /// Fails when Δh is negative beyond round-off at some node: the reference node is not
    /// where the gap change is least, and (3.5) requires Δh ≥ 0.
    fn check_sign(&self, dh: &[f64]) -> Result<()> {
        let top = dh.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if let Some(k) = dh.iter().position(|&v| v < -SOLVER_ACCURACY * top) {
            return Err(Error::invalid(
                "reference",
                format!("{:?}", self.shape.nodes()[self.reference]),
                format!(
                    "the gap change is negative ({:.4e} mm) at node {k} {:?}: take as reference \
                     the node where it is least",
                    dh[k],
                    self.shape.nodes()[k]
                ),
            ));
        }
        Ok(())
    }
}
