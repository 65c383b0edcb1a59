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
//!   ([`Optimisation::linear_programme`]), restricted by the contact set of the load split's or
//!   the iteration's optimum, its equalities eliminated by a rank-revealing QR: wherever the
//!   dense matrices fit, and as a cross-check;
//! - or, for large problems, as the same optimum without a dense matrix: one strictly convex
//!   contact QP per update of the loads carried by the design columns
//!   ([`Optimisation::load_split`]), solved by any contact solver, matrix-free ones included;
//!   its generalisation to several load cases sharing one gap change, the robust optimum of
//!   max over the cases of p ≤ v·p_max ([`Optimisation::envelope_split`]).
//!
//! [`nelder_mead`] tunes the few parameters of a given profile family (a derivative-free
//! search), the published practice the optimised gaps are compared with.

//!
//! Every method ends with a [`Termination`] in its [`Optimum`], which always holds the last
//! iterate: a step limit, an observer's stop, an infeasible programme or a contact solve that
//! did not converge are outcomes, not errors. Every optimum states the largest p − v·p_max over
//! Ω_nv ([`Optimum::omega_nv_excess`]); one that breaks χ ≥ 0 there, or passes v·p_max on Ω_v
//! by more than a quarter of p_max (a point the design does not hold, beyond what fitting
//! nodal gap changes to Gauss points leaves), ends as [`Termination::Infeasible`], never as
//! converged. Errors are for bad input and for work refused
//! before it starts. Settings carry the library's defaults ([`IterationSettings`],
//! [`LoadSplitSettings`], [`LinearProgrammeSettings`], [`OptimisationMethod`]); controllers
//! are built from [`ControllerSettings`] too.

mod controller;
mod iteration;
mod load_split;
mod lp;
mod passes;
mod programme;
mod settings;
mod simplex;
/// Solves `problem` with its initial gap changed by `gap_change` (from the pressure `start`
/// when given) in `workspace`, reporting to `observer`.
pub(crate) fn solve_gap_changed(
    solver: &dyn ContactSolver,
    problem: &InterfaceProblem,
    gap_change: &[f64],
    start: Option<&[f64]>,
    observer: &dyn Observer,
    workspace: &mut Workspace,
) -> Result<ContactState> {
    let gap: Vec<f64> = problem
        .initial_gap()
        .iter()
        .zip(gap_change)
        .map(|(h, d)| h + d)
        .collect();
    let problem = problem.with_initial_gap(&gap)?;
    solver.solve_in(&problem, start, observer, workspace)
}

#[cfg(test)]
mod tests;

pub use controller::{Constant, Controller, ControllerSettings, Product, Profile};
pub use iteration::{Mode, Pass};
pub use load_split::EnvelopeOptimum;
pub use settings::{
    IterationSettings, LinearProgrammeSettings, LoadSplitSettings, OptimisationMethod,
};
pub use simplex::{nelder_mead, nelder_mead_observed, Minimum, SearchSettings};

use std::borrow::Cow;
use std::sync::Mutex;

use contopt_contact::{ContactSolver, InterfaceProblem, Workspace};
use contopt_core::observe::{Method, Nested, Observer, Silent};
use contopt_core::{ContactState, Error, GapShape, Result, Termination};

/// Relative round-off of a sum over points (a row of Q, a column's rigid displacement, the
/// equilibrium of v·p_max): values that agree to it are equal (round-off).
pub(crate) const ROUND_OFF: f64 = 1e-9;

/// Relative accuracy of the pressures, gaps and gap changes that come out of a contact solve
/// or an interior point: a value below it times its scale is noise (convergence).
pub(crate) const SOLVER_ACCURACY: f64 = 1e-6;

/// Role of an interface point in the optimisation (§3.2), one per point through
/// [`Optimisation::with_regions`] or [`Optimisation::with_omega`]; without them every point is
/// Ω_v.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// In the proposed contact zone Ω but outside Ω_opt: only p ≥ 0, d ≥ 0, pd = 0.
    Contact,
    /// Ω_v: d = 0 and χ = v·p_max − p = 0 are prescribed.
    OmegaV,
    /// Ω_nv = Ω_opt − Ω_v: only d ≥ 0 and χ ≥ 0; the gap change follows Ω_v (eq. 3.3).
    OmegaNv,
}

/// The design node N of §3.2 step 6, where the gap does not change (Δh_N = 0).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Reference {
    /// The node where the gap change comes out least, so that min Δh = 0 and Δh ≥ 0 of (3.5)
    /// holds by construction, wherever the body deflects most.
    #[default]
    Least,
    /// A given design node (an index of the gap shape's nodes). A gap change that comes out
    /// negative elsewhere is refused as an invalid reference: (3.5) requires Δh ≥ 0.
    Node(usize),
}

/// The result of an optimisation: its last iterate and how the method ended.
///
/// The pressure, the gap and the rigid amplitudes are those of one contact solution on the
/// initial gap changed by `gap_change`, so they agree with each other; `passes` holds the
/// rows of the loop (Table 2's columns: row k's Δh_max is the change that pass k computed,
/// which the next pass would solve with).
#[derive(Clone, Debug)]
pub struct Optimum {
    /// The least largest pressure p_max \[MPa\] (of the last pass).
    pub p_max: f64,
    /// Gap change at the design nodes of the [`GapShape`], Δh ≥ 0, zero at the reference
    /// node \[mm\].
    pub dh: Vec<f64>,
    /// Gap change at the interface points, QΔh \[mm\].
    pub gap_change: Vec<f64>,
    /// The pressure at the interface points \[MPa\]: v·p_max on Ω_v once converged.
    pub pressure: Vec<f64>,
    /// Gap after deformation at the interface points, the gap change included \[mm\].
    pub gap: Vec<f64>,
    /// Rigid-mode amplitudes λ.
    pub rigid: Vec<f64>,
    /// The rows of the loop, one per pass (for the programme: the pass that solved, its k
    /// counting the passes before it whose contact set it corrected).
    pub passes: Vec<Pass>,
    /// The method that found it.
    pub method: Method,
    /// How the method ended: [`Termination::Converged`], or why it stopped short. An
    /// optimum that met its tolerance but leaves p above v·p_max on Ω_nv (χ ≥ 0 of 3.4)
    /// ends as [`Termination::Infeasible`], never as converged.
    pub termination: Termination,
    /// The largest p − v·p_max over Ω_nv \[MPa\] (−min χ there: at most round-off when χ ≥ 0
    /// holds, negative where Ω_nv carries less than its bound); `None` without Ω_nv.
    pub omega_nv_excess: Option<f64>,
}

impl Optimum {
    /// The largest gap change Δh_max \[mm\].
    pub fn dh_max(&self) -> f64 {
        self.dh.iter().fold(0.0, |m: f64, v| m.max(*v))
    }

    /// Whether the method met its tolerance.
    pub fn is_converged(&self) -> bool {
        self.termination.is_converged()
    }
}

/// The data of an optimisation: the interface problem, the gap map Q, the controller's values
/// and the regions.
pub struct Optimisation<'a> {
    problem: &'a InterfaceProblem<'a>,
    shape: Cow<'a, GapShape>,
    /// v(xᵢ) at every point (used on Ω_opt).
    v: Vec<f64>,
    regions: Vec<Region>,
    /// Points that keep their gap: outside Ω_opt, set by [`Optimisation::with_omega`].
    kept: Vec<bool>,
    /// The design node N of §3.2 step 6 where the gap does not change.
    reference: Reference,
    /// Receives each pass of the loop; the contact solves inside report one level deeper.
    observer: &'a dyn Observer,
    /// The contact solver's buffers, kept across the loop's solves; not the problems a solve
    /// derives ([`Workspace::one_off`]): on the 800 × 417 roller those would double the peak
    /// memory (162 → 343 MB when this was measured; the kept buffers cost about 10 MB of the
    /// 146 MB peak now) for no time gained.
    workspace: Mutex<Workspace>,
}

impl<'a> Optimisation<'a> {
    /// The optimisation of `problem` with gap changes described by `shape` and pressures
    /// controlled by `controller`. The whole interface is Ω_v (the one-dimensional case of
    /// §3.2) until [`Optimisation::with_regions`] or [`Optimisation::with_omega`] say
    /// otherwise; the reference node is where the gap change is least ([`Reference::Least`]).
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
        let v: Vec<f64> = iface
            .points()
            .iter()
            .map(|&x| controller.value(x))
            .collect();
        let opt = Self {
            problem,
            shape: Cow::Borrowed(shape),
            regions: vec![Region::OmegaV; v.len()],
            kept: vec![false; v.len()],
            v,
            reference: Reference::Least,
            observer: &Silent,
            workspace: Mutex::new(Workspace::one_off()),
        };
        opt.check()?;
        Ok(opt)
    }

    /// Reports each pass of the optimisation to `observer` as an event of its method
    /// ([`Method::GapIteration`], [`Method::LinearProgramme`], [`Method::LoadSplit`],
    /// [`Method::EnvelopeSplit`]) at level 0, with the measure it compares with its tolerance:
    /// TOLH (4.2) in [`Optimisation::iterate`], the number of points whose restriction a pass
    /// could not meet (tolerance 0) in [`Optimisation::linear_programme`], the miss of
    /// v·p_max on Ω_v in the load splits; the last event says how it ended. The contact
    /// solves inside report to it through [`Nested`], one level deeper. A stop ends the loop
    /// with [`Termination::Stopped`].
    pub fn with_observer(mut self, observer: &'a dyn Observer) -> Self {
        self.observer = observer;
        self
    }

    /// Sets the regions explicitly, one per interface point; every point's gap follows its
    /// row of Q.
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

    /// Sets Ω_v and Ω_opt from masks (one flag per interface point, Ω_v ⊆ Ω_opt): Ω_nv =
    /// Ω_opt − Ω_v, and the points outside Ω_opt are only in contact (p ≥ 0, d ≥ 0, pd = 0)
    /// and keep their initial gap: no gap change reaches them, whatever the shape's rows. A
    /// design node reached only from outside Ω_opt stays at Δh = 0.
    pub fn with_omega(mut self, omega_v: &[bool], omega_opt: &[bool]) -> Result<Self> {
        let n = self.v.len();
        for (field, mask) in [("omega_v", omega_v), ("omega_opt", omega_opt)] {
            if mask.len() != n {
                return Err(Error::invalid(
                    field,
                    format!("{} flags", mask.len()),
                    format!("one per interface point ({n})"),
                ));
            }
        }
        if let Some(i) = (0..n).find(|&i| omega_v[i] && !omega_opt[i]) {
            return Err(Error::invalid(
                format!("omega_v[{i}]"),
                true,
                "Ω_v lies inside Ω_opt: the point is not in omega_opt",
            ));
        }
        self.regions = (0..n)
            .map(|i| match (omega_v[i], omega_opt[i]) {
                (true, _) => Region::OmegaV,
                (false, true) => Region::OmegaNv,
                (false, false) => Region::Contact,
            })
            .collect();
        let rows = (0..n)
            .map(|i| match omega_opt[i] {
                true => self.shape.row(i).to_vec(),
                false => vec![],
            })
            .collect();
        self.shape = Cow::Owned(GapShape::new(self.shape.nodes().to_vec(), rows)?);
        self.kept = omega_opt.iter().map(|o| !o).collect();
        self.check()?;
        Ok(self)
    }

    /// Sets the reference node N of §3.2 step 6, where Δh = 0.
    pub fn with_reference(mut self, reference: Reference) -> Result<Self> {
        if let Reference::Node(node) = reference {
            if node >= self.shape.nodes().len() || !self.used_nodes()[node] {
                return Err(Error::invalid(
                    "reference",
                    node,
                    format!(
                        "a design node below {} that a point of Ω_opt reaches",
                        self.shape.nodes().len()
                    ),
                ));
            }
        }
        self.reference = reference;
        Ok(self)
    }

    /// The controller's values, the regions and the design nodes are consistent.
    fn check(&self) -> Result<()> {
        let pts = self.problem.interface().points();
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
        self.check_rows()
    }

    /// Each row of Q sums to one (a uniform Δh is a uniform gap change) except where the gap
    /// is kept, and every node that a point reaches is tied to Ω_v.
    fn check_rows(&self) -> Result<()> {
        for i in (0..self.v.len()).filter(|&i| !self.kept[i]) {
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
        for i in self.omega_v() {
            for &(k, w) in self.shape.row(i) {
                tied[k] |= w != 0.0;
            }
        }
        let used = self.used_nodes();
        if let Some(k) = (0..tied.len()).find(|&k| used[k] && !tied[k]) {
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

    /// The design nodes that some point's row reaches with a non-zero weight; the others
    /// stay at Δh = 0.
    pub(crate) fn used_nodes(&self) -> Vec<bool> {
        let mut used = vec![false; self.shape.nodes().len()];
        for i in 0..self.shape.len() {
            for &(k, w) in self.shape.row(i) {
                used[k] |= w != 0.0;
            }
        }
        used
    }

    /// The reference node for the fitted gap change `dh`: the given node, or the used node
    /// where `dh` is least.
    pub(crate) fn reference_node(&self, dh: &[f64]) -> usize {
        match self.reference {
            Reference::Node(k) => k,
            Reference::Least => {
                let used = self.used_nodes();
                (0..dh.len())
                    .filter(|&k| used[k])
                    .min_by(|&a, &b| dh[a].total_cmp(&dh[b]))
                    .unwrap_or(0)
            }
        }
    }

    /// `dh` less its value at the reference node (unused nodes stay 0), so that Δh_N = 0.
    pub(crate) fn anchored(&self, dh: &[f64]) -> Vec<f64> {
        let at_n = dh[self.reference_node(dh)];
        let used = self.used_nodes();
        (0..dh.len())
            .map(|k| if used[k] { dh[k] - at_n } else { 0.0 })
            .collect()
    }

    /// Solves `problem` with its initial gap changed by `gap_change` (from the pressure
    /// `start` when given), the contact solver reporting one level below the loop, in the
    /// loop's workspace (in one of its own while another solve holds that one).
    fn solve_with_gap_change(
        &self,
        solver: &dyn ContactSolver,
        problem: &InterfaceProblem,
        gap_change: &[f64],
        start: Option<&[f64]>,
    ) -> Result<ContactState> {
        let observer = Nested(self.observer);
        let solve = |workspace: &mut Workspace| {
            solve_gap_changed(solver, problem, gap_change, start, &observer, workspace)
        };
        match self.workspace.try_lock() {
            Ok(mut kept) => solve(&mut kept),
            Err(_) => solve(&mut Workspace::one_off()),
        }
    }

    /// The largest pressure on Ω_opt of a contact solution (its p_max before any
    /// optimisation).
    fn p_max_on_omega_opt(&self, pressure: &[f64]) -> f64 {
        (0..pressure.len())
            .filter(|&i| self.regions[i] != Region::Contact)
            .map(|i| pressure[i])
            .fold(0.0, f64::max)
    }

    /// The optimum of the contact solution `state`, solved with the gap change of `dh`.
    fn optimum(&self, state: ContactState, dh: Vec<f64>, p_max: f64, method: Method) -> Optimum {
        Optimum {
            p_max,
            gap_change: self.shape.apply(&dh),
            dh,
            pressure: state.pressure,
            gap: state.gap,
            rigid: state.rigid,
            passes: vec![],
            method,
            termination: Termination::Converged,
            omega_nv_excess: None,
        }
    }

    /// The iterate of a method that stopped before its first pass gave one: the contact
    /// solution without a gap change, ended as the solve ended (when it did not converge) or
    /// as `termination`.
    fn unoptimised(
        &self,
        solver: &dyn ContactSolver,
        method: Method,
        termination: Termination,
    ) -> Result<Optimum> {
        let zero = vec![0.0; self.shape.nodes().len()];
        let state =
            self.solve_with_gap_change(solver, self.problem, &self.shape.apply(&zero), None)?;
        let end = match state.termination.is_solved() {
            true => termination,
            false => state.termination.clone().inside(state.method),
        };
        let p_max = self.p_max_on_omega_opt(&state.pressure);
        Ok(Optimum {
            termination: end,
            ..self.optimum(state, zero, p_max, method)
        })
    }

    /// Fails when Δh is negative beyond round-off at some node: the given reference node is
    /// not where the gap change is least, and (3.5) requires Δh ≥ 0.
    fn check_sign(&self, dh: &[f64]) -> Result<()> {
        let Reference::Node(reference) = self.reference else {
            return Ok(());
        };
        let top = dh.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if let Some(k) = dh.iter().position(|&v| v < -SOLVER_ACCURACY * top) {
            return Err(Error::invalid(
                "reference",
                format!("{:?}", self.shape.nodes()[reference]),
                format!(
                    "the gap change is negative ({:.4e} mm) at node {k} {:?}: take as reference \
                     the node where it is least (Reference::Least)",
                    dh[k],
                    self.shape.nodes()[k]
                ),
            ));
        }
        Ok(())
    }
}
