//! The constrained conjugate-gradient method of Polonsky & Keer (Wear 231, 1999) on an
//! interface problem applied as an operator: for large half-space grids whose influence
//! product is an FFT convolution, never a dense matrix.

// The iteration walks several parallel per-point arrays at once; index loops read best.
#![allow(clippy::needless_range_loop)]

use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{check, ContactState, Error, Quantity, Result, Stall, Termination};
use serde::{Deserialize, Serialize};

use crate::watch::{self, Watch};
use crate::{problem, ContactSolver, InterfaceProblem};

/// Relative size of a penetration outside the solved part that makes the part grow
/// (round-off).
const PENETRATION: f64 = 1e-12;
/// A cold start looks for contact within this fraction of the free gap's range above its
/// lowest point (a guess: the part grows until nothing outside it penetrates).
const SEED_FRACTION: f64 = 0.25;
/// A cold start on at least this many points starts from the solution of the coarser problem
/// (nested iteration), when the bodies offer one.
const NESTED_POINTS: usize = 256;
/// The tolerance of a coarser problem's solve (unless the solver's own is looser): its
/// solution is a start, whose distance from the finer one is the discretisation's, far above
/// this.
const NESTED_TOLERANCE: f64 = 1e-6;

/// Polonsky–Keer: conjugate gradients on the pressure restricted to the contact set, with
/// the set updated every step (points that leave get p = 0, penetrating points re-enter and
/// the conjugation restarts), and each loaded rigid mode's pressure rescaled to its load.
///
/// It solves the QP (2.14) of any [`InterfaceProblem`] through its influence operator: a rigid
/// indenter or two elastic grids on a half-space, under a given force (a floating body: the
/// approach is its mode's amplitude) or a given approach (in the initial gap, nothing floats).
/// The free rigid modes must move disjoint sets of points, each one way (a translation; or one
/// translation per design column, as the optimiser's load split gives). The directions are
/// projected, in the W inner product, onto the pressures that leave every mode's load
/// unchanged: for a translation, the weighted mean on the contact set is removed (eq. 2.10).
///
/// When the problem offers an approximate inverse ([`InterfaceProblem::precondition`]: a
/// half-space grid's circulant kernel inverse) the residual is preconditioned with it and the
/// directions conjugated by Polak–Ribière. Each step costs two operator products: O(N log N) on
/// an FFT grid. When the problem can be restricted ([`InterfaceProblem::restrict`]: a grid's
/// bounding box), the solve runs where contact can occur (where a warm start carries pressure,
/// or within a quarter of the gap's range of its lowest point) and is checked on the whole
/// interface with one product; the part grows until no point outside it penetrates.
#[derive(Clone, Copy, Debug)]
pub struct PolonskyKeer {
    settings: PolonskyKeerSettings,
}

/// The settings of [`PolonskyKeer`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct PolonskyKeerSettings {
    /// Stop when Σ wᵢ |Δpᵢ| falls below `tolerance` times the load (or the carried force).
    pub tolerance: f64,
    /// Largest number of steps.
    pub max_steps: usize,
}

impl PolonskyKeerSettings {
    /// The default tolerance on the relative pressure change of a step (convergence: near
    /// round-off, the steps are cheap).
    pub const TOLERANCE: f64 = 1e-12;
    /// The default limit on steps: conjugate gradients take tens to hundreds.
    pub const MAX_STEPS: usize = 10_000;
}

impl Default for PolonskyKeerSettings {
    fn default() -> Self {
        Self {
            tolerance: Self::TOLERANCE,
            max_steps: Self::MAX_STEPS,
        }
    }
}

impl PolonskyKeer {
    /// The solver with `settings`, checked: the tolerance in (0, 1), at least one step.
    pub fn new(settings: PolonskyKeerSettings) -> Result<Self> {
        check::between("tolerance", settings.tolerance, 0.0, 1.0)?;
        check::count("max_steps", settings.max_steps, 1, usize::MAX)?;
        Ok(Self { settings })
    }

    /// Its settings.
    pub fn settings(&self) -> &PolonskyKeerSettings {
        &self.settings
    }

    /// The solver with `tolerance` when it is looser than its own and below 1
    /// ([`ContactSolver::loosened`]).
    pub(crate) fn looser(&self, tolerance: f64) -> Option<Self> {
        let settings = PolonskyKeerSettings {
            tolerance,
            ..self.settings
        };
        (tolerance > self.settings.tolerance && tolerance < 1.0).then_some(Self { settings })
    }
}

impl ContactSolver for PolonskyKeer {
    fn method(&self) -> Method {
        Method::PolonskyKeer
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        0
    }

    /// Stops when Σ wᵢ |Δpᵢ| falls below `tolerance` times the load instead.
    fn loosened(&self, tolerance: f64) -> Option<Box<dyn ContactSolver>> {
        self.looser(tolerance)
            .map(|solver| Box::new(solver) as Box<dyn ContactSolver>)
    }

    /// Reports each conjugate-gradient step (`iterations`, numbered on across the growing
    /// parts of the interface) with the relative pressure change Σ wᵢ |Δpᵢ| / load as the
    /// measure and `tolerance`.
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        if let Some(start) = start {
            if start.len() != problem.len() {
                return Err(Error::invalid(
                    "start",
                    format!("{} values", start.len()),
                    format!("one pressure per interface point ({})", problem.len()),
                ));
            }
            check::all_finite("start", start)?;
        }
        let state = self.solve_nested(problem, start, Watch::new(observer, self.method()))?;
        watch::announce(observer, &state);
        Ok(state)
    }
}

impl PolonskyKeer {
    /// Solves from `start`; a cold start on a problem with a coarser version
    /// ([`InterfaceProblem::coarsen`]) starts from the coarse solution (itself found so, to
    /// [`NESTED_TOLERANCE`]), each point given its coarse point's pressure. Its steps count
    /// with the solve's, and number the fine ones on; they are reported one level deeper
    /// (a solve that this one runs), so that an observer tells the fine grid's steps, the
    /// costly ones, from the coarser grids' (a quarter of the cost each level down).
    fn solve_nested(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        watch: Watch,
    ) -> Result<ContactState> {
        let cold = start.is_none_or(|p| p.iter().all(|&v| v <= 0.0));
        let given = || start.map(<[f64]>::to_vec);
        if !cold || problem.len() < NESTED_POINTS {
            return self.solve_cropped(problem, given(), watch);
        }
        let Some((coarse, parent)) = problem.coarsen() else {
            return self.solve_cropped(problem, given(), watch);
        };
        let nested = PolonskyKeer {
            settings: PolonskyKeerSettings {
                tolerance: self.settings.tolerance.max(NESTED_TOLERANCE),
                ..self.settings
            },
        };
        let deeper = Nested(watch.observer());
        let coarse_watch = Watch::new(&deeper, self.method());
        let solved = nested.solve_nested(&coarse, None, coarse_watch).ok();
        drop(coarse);
        let Some(solved) = solved.filter(ContactState::is_converged) else {
            return self.solve_cropped(problem, given(), watch);
        };
        let fine: Vec<f64> = parent.iter().map(|&c| solved.pressure[c]).collect();
        // The parent index (a usize per point) and the coarse pressure are not held through
        // the fine solve: at 2048² cells the index alone is 32 MiB of its peak.
        drop((parent, solved.pressure));
        let mut state = self.solve_cropped(problem, Some(fine), watch.after(solved.iterations))?;
        state.iterations += solved.iterations;
        Ok(state)
    }

    /// Solves on a growing part of the interface when the problem can be restricted; each
    /// larger part starts from the pressure of the last. The start is taken, not borrowed: it
    /// is freed once the first part has its own copy (a whole-interface vector fewer at the
    /// part's solve).
    fn solve_cropped(
        &self,
        problem: &InterfaceProblem,
        start: Option<Vec<f64>>,
        watch: Watch,
    ) -> Result<ContactState> {
        let n = problem.len();
        let mut keep = seed(problem, start.as_deref());
        let mut pressure = start;
        let mut steps = 0;
        while let Some((part, index)) = problem.restrict(&keep) {
            let part_start: Option<Vec<f64>> =
                pressure.map(|p| index.iter().map(|&k| p[k]).collect());
            let state = self.solve_whole(&part, part_start.as_deref(), watch.after(steps))?;
            drop(part);
            steps += state.iterations;
            let mut whole = vec![0.0; n];
            for (a, &k) in index.iter().enumerate() {
                whole[k] = state.pressure[a];
            }
            let mut groups = Groups::new(problem)?;
            let mut forces = vec![0.0; n];
            let (gap, rigid) = groups.final_gap(problem, &whole, &mut forces, &mut []);
            drop(forces);
            let penetrating = penetrating(problem, &gap, &index);
            if penetrating.is_empty() || !state.is_converged() {
                let mut whole = outcome(problem, whole, (gap, rigid), steps);
                watch::end(&mut whole, state.termination);
                return Ok(whole);
            }
            for k in index.into_iter().chain(penetrating) {
                keep[k] = true;
            }
            pressure = Some(whole);
        }
        let mut state = self.solve_whole(problem, pressure.as_deref(), watch.after(steps))?;
        state.iterations += steps;
        Ok(state)
    }

    /// The iteration on the whole problem, each step reported to `watch`.
    fn solve_whole(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        watch: Watch,
    ) -> Result<ContactState> {
        let mut cg = Descent::new(problem, start)?;
        let (tolerance, max_steps) = (self.settings.tolerance, self.settings.max_steps);
        let (mut steps, mut change, mut halt) = (0, f64::INFINITY, None);
        while steps < max_steps && halt.is_none() {
            steps += 1;
            let entered = match cg.step(problem) {
                Ok(entered) => entered,
                Err(cause) => {
                    halt = Some(Termination::Stalled { cause });
                    false
                }
            };
            change = if halt.is_none() {
                cg.change(problem)
            } else {
                f64::NAN
            };
            if halt.is_none() && !change.is_finite() {
                // The last finite iterate is kept; the step that overflowed is undone.
                cg.undo();
                halt = Some(Termination::NonFinite {
                    quantity: Quantity::Pressure,
                });
            }
            let stop = watch.report(steps, change, tolerance);
            if halt.is_none() && change < tolerance && !entered {
                break;
            }
            halt = halt.or(stop);
        }
        // A NaN change is not converged either.
        if halt.is_none() && (change.is_nan() || change >= tolerance) {
            halt = Some(Termination::StepLimit {
                steps,
                measure: change,
                tolerance,
            });
        }
        let Descent {
            mut groups,
            p,
            mut cg,
            ..
        } = cg;
        let gap_rigid = groups.final_gap(problem, &p, &mut cg.forces, &mut cg.spare);
        drop(cg);
        let mut state = outcome(problem, p, gap_rigid, steps);
        if let Some(halt) = halt {
            watch::end(&mut state, halt);
        }
        Ok(state)
    }
}

/// Where a solve starts: where the start carries pressure, or (a cold start, or a start without
/// pressure) within [`SEED_FRACTION`] of the free gap's range above its lowest point.
fn seed(problem: &InterfaceProblem, start: Option<&[f64]>) -> Vec<bool> {
    match start {
        Some(p) if p.iter().any(|&v| v > 0.0) => p.iter().map(|&v| v > 0.0).collect(),
        _ => {
            let g = problem.free_gap();
            let (lo, hi) = g
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| {
                    (a.min(h), b.max(h))
                });
            g.iter()
                .map(|&h| h <= lo + SEED_FRACTION * (hi - lo))
                .collect()
        }
    }
}

/// The points outside a solved part (`index`) that the part's answer makes penetrate, beyond
/// round-off of the gaps' size.
fn penetrating(problem: &InterfaceProblem, gap: &[f64], index: &[usize]) -> Vec<usize> {
    let n = problem.len();
    let mut scale = vec![0.0; n];
    problem.add_free_gap(&mut scale);
    let scale = scale
        .iter()
        .zip(gap)
        .fold(0.0f64, |m, (h, d)| m.max(h.abs() + d.abs()));
    let mut inside = vec![false; n];
    for &k in index {
        inside[k] = true;
    }
    (0..n)
        .filter(|&k| !inside[k] && gap[k] < -PENETRATION * scale)
        .collect()
}

/// The state of Polonsky and Keer's iteration: the pressure, its previous value, the modes
/// and the conjugate-gradient buffers.
struct Descent {
    groups: Groups,
    cg: Buffers,
    kappa: f64,
    p: Vec<f64>,
    previous: Vec<f64>,
    gz_old: f64,
    conjugate: bool,
}

impl Descent {
    /// The first pressure: `start` clipped at zero, or seeded from the gap, with each loaded
    /// mode's pressure scaled to its load.
    fn new(problem: &InterfaceProblem, start: Option<&[f64]>) -> Result<Self> {
        let mut groups = Groups::new(problem)?;
        let w = problem.weights();
        let n = w.len();
        let mut cg = Buffers::new(problem);
        let kappa = cg.self_compliance(problem)?;
        let mut p = match start {
            Some(s) => s.iter().map(|v| v.max(0.0)).collect(),
            None => {
                let mut g = vec![0.0; n];
                problem.add_free_gap(&mut g);
                groups.initial(w, &g, kappa)
            }
        };
        cg.d.fill(0.0);
        problem.add_free_gap(&mut cg.d);
        groups.restore(w, &cg.d, &mut p);
        Ok(Self {
            groups,
            cg,
            kappa,
            p,
            previous: vec![0.0; n],
            gz_old: 1.0,
            conjugate: false,
        })
    }

    /// One step: the residual, the direction, the move along it and the points that enter;
    /// returns whether any entered.
    fn step(&mut self, problem: &InterfaceProblem) -> std::result::Result<bool, Stall> {
        let (cg, groups) = (&mut self.cg, &mut self.groups);
        cg.residual(problem, groups, &self.p);
        cg.direction(problem, groups, self.conjugate, &mut self.gz_old);
        self.previous.copy_from_slice(&self.p);
        let entered = cg.step(problem, groups, &mut self.p, self.kappa)?;
        self.conjugate = !entered;
        groups.restore(problem.weights(), &cg.d, &mut self.p);
        Ok(entered)
    }

    /// The step's change of the pressure, Σ wᵢ |Δpᵢ| over the load (or the carried force).
    fn change(&self, problem: &InterfaceProblem) -> f64 {
        let (w, p) = (problem.weights(), &self.p);
        let scale = self
            .groups
            .total_load()
            .max(p.iter().zip(w).map(|(p, w)| p * w).sum::<f64>())
            .max(f64::MIN_POSITIVE);
        p.iter()
            .zip(&self.previous)
            .zip(w)
            .map(|((a, b), w)| w * (a - b).abs())
            .sum::<f64>()
            / scale
    }

    /// Returns to the pressure before the last step.
    fn undo(&mut self) {
        self.p.copy_from_slice(&self.previous);
    }
}

/// The state of a final pressure with its gap and rigid amplitudes.
fn outcome(
    problem: &InterfaceProblem,
    pressure: Vec<f64>,
    (gap, rigid): (Vec<f64>, Vec<f64>),
    steps: usize,
) -> ContactState {
    let mut state = ContactState {
        active: pressure.iter().map(|&p| p > 0.0).collect(),
        residuals: problem.residuals(&pressure, &gap),
        pressure,
        gap,
        rigid,
        iterations: steps,
        iterp: 0,
        iterd: 0,
        method: Method::PolonskyKeer,
        termination: Termination::Converged,
    };
    problem.verify(&mut state);
    state
}

/// The vectors of the iteration, allocated once per solve.
struct Buffers {
    /// Forces W·p or W·t, the operator's input; the masked residual, the preconditioner's.
    forces: Vec<f64>,
    /// The second body's product when the operator sums two (else empty).
    spare: Vec<f64>,
    /// The gap residual d = g + A W p + R λ.
    d: Vec<f64>,
    d_previous: Vec<f64>,
    z: Vec<f64>,
    /// The search direction.
    t: Vec<f64>,
    /// A W t.
    r: Vec<f64>,
    contact: Vec<bool>,
    /// Whether the last direction was preconditioned (t then holds pressures, not gaps).
    preconditioned: bool,
}

impl Buffers {
    fn new(problem: &InterfaceProblem) -> Self {
        let n = problem.len();
        let zero = || vec![0.0; n];
        Self {
            forces: zero(),
            spare: if problem.sums_two_products() {
                zero()
            } else {
                vec![]
            },
            d: zero(),
            d_previous: zero(),
            z: zero(),
            t: zero(),
            r: zero(),
            contact: vec![false; n],
            preconditioned: false,
        }
    }

    /// κ: a point's displacement under unit pressure on itself, for seeding pressures from
    /// gaps (a uniform pressure would not do: it moves a periodic grid not at all).
    fn self_compliance(&mut self, problem: &InterfaceProblem) -> Result<f64> {
        let w = problem.weights();
        self.forces.fill(0.0);
        self.forces[0] = w[0];
        problem.apply_influence_with(&self.forces, &mut self.r, &mut self.spare);
        problem::compliance(self.r[0])
    }
    /// Moves `p` along the direction t by the residual's component over the curvature, clipped
    /// at p = 0, and lets the penetrating points outside the contact set re-enter with the
    /// pressure −τ·dᵢ of that step. τ converts a gap into a pressure only when t is a gap (no
    /// preconditioner); a preconditioned t is a pressure and τ a pure number, so the gap is
    /// turned into a pressure by the point's own stiffness 1/κ, −τ·dᵢ/κ, and the step is the
    /// same in any consistent units. When τ = 0, −dᵢ/κ. Returns whether any entered; fails
    /// when the operator is not positive on the contact set.
    fn step(
        &mut self,
        problem: &InterfaceProblem,
        groups: &Groups,
        p: &mut [f64],
        kappa: f64,
    ) -> std::result::Result<bool, Stall> {
        let w = problem.weights();
        for ((f, t), w) in self.forces.iter_mut().zip(&self.t).zip(w) {
            *f = t * w;
        }
        problem.apply_influence_with(&self.forces, &mut self.r, &mut self.spare);
        let curvature = self.dot(w, &self.r, &self.t);
        let along = self.dot(w, &self.d, &self.t);
        let tau = if along == 0.0 {
            0.0
        } else if curvature > 0.0 {
            along / curvature
        } else {
            return Err(Stall::NotPositive { curvature });
        };
        for i in 0..p.len() {
            if self.contact[i] {
                p[i] = (p[i] - tau * self.t[i]).max(0.0);
            }
        }
        let enter = match (tau > 0.0, self.preconditioned) {
            (true, false) => tau,
            (true, true) => tau / kappa,
            (false, _) => 1.0 / kappa,
        };
        let mut entered = false;
        for i in 0..p.len() {
            if !self.contact[i] && groups.may_enter(i) && self.d[i] < 0.0 {
                p[i] = -enter * self.d[i];
                entered = true;
            }
        }
        Ok(entered)
    }

    /// Σ over the contact set of wᵢ aᵢ bᵢ.
    fn dot(&self, w: &[f64], a: &[f64], b: &[f64]) -> f64 {
        (0..w.len())
            .filter(|&i| self.contact[i])
            .map(|i| w[i] * a[i] * b[i])
            .sum()
    }

    /// The contact set of `p` and the gap residual d, with the modes' amplitudes fitted on it.
    fn residual(&mut self, problem: &InterfaceProblem, groups: &mut Groups, p: &[f64]) {
        let w = problem.weights();
        for ((f, p), w) in self.forces.iter_mut().zip(p).zip(w) {
            *f = p * w;
        }
        problem.apply_influence_with(&self.forces, &mut self.d, &mut self.spare);
        problem.add_free_gap(&mut self.d);
        for (c, &p) in self.contact.iter_mut().zip(p) {
            *c = p > 0.0;
        }
        groups.fit(w, &mut self.d, &self.contact);
    }

    /// The next search direction t: the residual on the contact set, preconditioned when the
    /// problem offers an approximate inverse (forces turned into pressures), projected so that
    /// the modes' loads do not change, and conjugated by Polak–Ribière unless restarted.
    fn direction(
        &mut self,
        problem: &InterfaceProblem,
        groups: &mut Groups,
        conjugate: bool,
        gz_old: &mut f64,
    ) {
        let w = problem.weights();
        let n = w.len();
        // The masked residual, in the forces' buffer (free until the step).
        for i in 0..n {
            self.forces[i] = if self.contact[i] { self.d[i] } else { 0.0 };
        }
        self.preconditioned = problem.precondition(&self.forces, &self.contact, &mut self.z);
        if self.preconditioned {
            for i in 0..n {
                self.z[i] = if self.contact[i] {
                    self.z[i] / w[i]
                } else {
                    0.0
                };
            }
        } else {
            self.z.copy_from_slice(&self.forces);
        }
        groups.project(w, &mut self.z, &self.contact);
        let gz = self.dot(w, &self.d, &self.z);
        let beta = if conjugate && *gz_old != 0.0 {
            ((gz - self.dot(w, &self.d_previous, &self.z)) / *gz_old).max(0.0)
        } else {
            0.0
        };
        for i in 0..n {
            self.t[i] = if self.contact[i] {
                self.z[i] + beta * self.t[i]
            } else {
                0.0
            };
        }
        groups.project(w, &mut self.t, &self.contact);
        *gz_old = gz;
        self.d_previous.copy_from_slice(&self.d);
    }
}

/// No mode moves the point.
const NONE: usize = usize::MAX;

/// The free rigid modes in the form the iteration uses: the mode of each point, its rᵢ, and
/// each mode's target force c = −q = Σ wᵢ rᵢ pᵢ; with per-mode buffers reused every step.
struct Groups {
    owner: Vec<usize>,
    r: Vec<f64>,
    target: Vec<f64>,
    num: Vec<f64>,
    den: Vec<f64>,
    lambda: Vec<f64>,
    /// Per mode: the point of least gap (seeding) or the bound at which it touches.
    extreme: Vec<f64>,
    seed: Vec<usize>,
}

impl Groups {
    fn new(problem: &InterfaceProblem) -> Result<Self> {
        let n = problem.len();
        let modes = problem.modes();
        let (mut owner, mut r) = (vec![NONE; n], vec![0.0; n]);
        let unsupported = |name: &str, why: &str| {
            Error::invalid(
                format!("rigid mode `{name}`"),
                why,
                "Polonsky-Keer needs modes that move disjoint sets of points, each one way \
                 (translations): use a dense solver",
            )
        };
        for (k, mode) in modes.iter().enumerate() {
            let positive = mode.displacement.iter().all(|&v| v > 0.0);
            let negative = mode.displacement.iter().all(|&v| v < 0.0);
            if !(positive || negative) {
                return Err(unsupported(&mode.name, "moves points both ways"));
            }
            if (positive && mode.load > 0.0) || (negative && mode.load < 0.0) {
                return Err(Error::invalid(
                    format!("load on {}", mode.name),
                    mode.load,
                    "pulls the bodies apart: compressive contact cannot carry it",
                ));
            }
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                if owner[i] != NONE {
                    return Err(unsupported(&mode.name, "shares points with another mode"));
                }
                owner[i] = k;
                r[i] = v;
            }
        }
        let m = modes.len();
        Ok(Self {
            owner,
            r,
            target: modes.iter().map(|m| -m.load).collect(),
            num: vec![0.0; m],
            den: vec![0.0; m],
            lambda: vec![0.0; m],
            extreme: vec![0.0; m],
            seed: vec![NONE; m],
        })
    }

    fn total_load(&self) -> f64 {
        self.target.iter().map(|c| c.abs()).sum()
    }

    /// Whether point i may carry pressure (not on an unloaded mode, which stays open).
    fn may_enter(&self, i: usize) -> bool {
        self.owner[i] == NONE || self.target[self.owner[i]] != 0.0
    }

    /// A first pressure: each loaded mode's load spread uniformly over its points; elsewhere
    /// the overlap −g over κ.
    fn initial(&mut self, w: &[f64], g: &[f64], kappa: f64) -> Vec<f64> {
        self.sums(w, |_| 1.0, |_| true);
        (0..w.len())
            .map(|i| match self.owner[i] {
                NONE => (-g[i]).max(0.0) / kappa,
                k if self.num[k] != 0.0 => (self.target[k] / self.num[k]).max(0.0),
                _ => 0.0,
            })
            .collect()
    }

    /// num\[k\] = Σ wᵢ rᵢ f(i), den\[k\] = Σ wᵢ rᵢ² over the points of mode k with `member(i)`.
    fn sums(&mut self, w: &[f64], f: impl Fn(usize) -> f64, member: impl Fn(usize) -> bool) {
        self.num.fill(0.0);
        self.den.fill(0.0);
        for i in 0..w.len() {
            let k = self.owner[i];
            if k != NONE && member(i) {
                self.num[k] += w[i] * self.r[i] * f(i);
                self.den[k] += w[i] * self.r[i] * self.r[i];
            }
        }
    }

    /// Removes from `v` its W-projection on the modes over the contact set:
    /// vᵢ −= rᵢ Σ w r v / Σ w r², so that Σ wᵢ rᵢ vᵢ = 0 for every mode.
    fn project(&mut self, w: &[f64], v: &mut [f64], contact: &[bool]) {
        if self.target.is_empty() {
            return;
        }
        self.sums(w, |i| v[i], |i| contact[i]);
        for i in 0..w.len() {
            let k = self.owner[i];
            if k != NONE && contact[i] && self.den[k] > 0.0 {
                v[i] -= self.r[i] * self.num[k] / self.den[k];
            }
        }
    }

    /// Adds to `d` the modes' motion R λ with the amplitudes of [`Groups::amplitudes`].
    fn fit(&mut self, w: &[f64], d: &mut [f64], contact: &[bool]) {
        self.amplitudes(w, d, contact);
        for i in 0..d.len() {
            let k = self.owner[i];
            if k != NONE {
                d[i] += self.r[i] * self.lambda[k];
            }
        }
    }

    /// λ fitted by least squares to close the gap `d` on the contact set
    /// (λₖ = −Σ w r d / Σ w r²), or, for a mode without contact, the value at which its nearest
    /// point just touches (d + rλ ≥ 0: λ ≥ −d/r for r > 0, λ ≤ −d/r for r < 0).
    fn amplitudes(&mut self, w: &[f64], d: &[f64], contact: &[bool]) {
        self.sums(w, |i| d[i], |i| contact[i]);
        self.extreme.fill(f64::NAN);
        for i in 0..d.len() {
            let k = self.owner[i];
            if k != NONE && self.den[k] == 0.0 {
                let bound = -d[i] / self.r[i];
                let e = self.extreme[k];
                self.extreme[k] = if e.is_nan() {
                    bound
                } else if self.r[i] > 0.0 {
                    e.max(bound)
                } else {
                    e.min(bound)
                };
            }
        }
        for k in 0..self.target.len() {
            self.lambda[k] = if self.den[k] > 0.0 {
                -self.num[k] / self.den[k]
            } else if self.extreme[k].is_nan() {
                0.0
            } else {
                self.extreme[k]
            };
        }
    }

    /// Scales each loaded mode's pressure to its load; a mode that carries nothing is seeded at
    /// its point of least gap `d`.
    fn restore(&mut self, w: &[f64], d: &[f64], p: &mut [f64]) {
        if self.target.is_empty() {
            return;
        }
        self.sums(w, |i| p[i], |_| true);
        self.seed.fill(NONE);
        for i in 0..w.len() {
            let k = self.owner[i];
            if k == NONE {
                continue;
            }
            let (carried, c) = (self.num[k], self.target[k]);
            if c == 0.0 {
                p[i] = 0.0;
            } else if carried * c > 0.0 {
                p[i] *= c / carried;
            } else if self.seed[k] == NONE || d[i] < d[self.seed[k]] {
                self.seed[k] = i;
            }
        }
        for k in 0..self.seed.len() {
            let i = self.seed[k];
            if i != NONE {
                p[i] = self.target[k] / (w[i] * self.r[i]);
            }
        }
    }

    /// The gap d = g + A W p + R λ of a final pressure, and λ; `forces` and `spare` are the
    /// product's buffers (n values each; `spare` empty when the operator is one product).
    fn final_gap(
        &mut self,
        problem: &InterfaceProblem,
        p: &[f64],
        forces: &mut [f64],
        spare: &mut [f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let w = problem.weights();
        for ((f, p), w) in forces.iter_mut().zip(p).zip(w) {
            *f = p * w;
        }
        let mut d = vec![0.0; p.len()];
        let mut own;
        let spare = if spare.len() == p.len() || !problem.sums_two_products() {
            spare
        } else {
            own = vec![0.0; p.len()];
            &mut own[..]
        };
        problem.apply_influence_with(forces, &mut d, spare);
        problem.add_free_gap(&mut d);
        let contact: Vec<bool> = p.iter().map(|&v| v > 0.0).collect();
        self.amplitudes(w, &d, &contact);
        problem.add_rigid_motion(&self.lambda, &mut d);
        (d, self.lambda.clone())
    }
}
