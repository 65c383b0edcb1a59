//! The constrained conjugate-gradient method of Polonsky & Keer (Wear 231, 1999) on an
//! interface problem applied as an operator: for large half-space grids whose influence
//! product is an FFT convolution, never a dense matrix.

// The iteration walks several parallel per-point arrays at once; index loops read best.
#![allow(clippy::needless_range_loop)]

use contopt_core::drive::Step;
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{check, ContactState, Error, Quantity, Residuals, Result, Stall, Termination};
use serde::{Deserialize, Serialize};

use crate::problem::Derived;
use crate::prolong::prolong;
use crate::watch::{self, Watch};
use crate::workspace::refill;
use crate::{problem, ContactSolver, InterfaceProblem, Workspace};

/// Relative size of a penetration outside the solved part that makes the part grow
/// (round-off).
const PENETRATION: f64 = 1e-12;
/// A cold start looks for contact within this fraction of the free gap's range above its
/// lowest point (a guess: the part grows until nothing outside it penetrates).
const SEED_FRACTION: f64 = 0.25;
/// A cold start on at least this many points starts from the solution of the coarser problem
/// (nested iteration), when the bodies offer one.
const NESTED_POINTS: usize = 256;
/// Relative spread of the free gap, over a cold start's seed, within which the seed is one
/// flat face (round-off of the gap's range): it then starts on its own grid.
const PLATEAU: f64 = 1e-12;
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
/// directions conjugated by Polak–Ribière. Each step costs one operator product, O(N log N) on
/// an FFT grid, and the preconditioner's; the gap residual moves with the step's product
/// (conjugate gradients' recursive residual) and costs a product of its own only after a step
/// in which a point left the contact set or entered it. When the problem can be restricted
/// ([`InterfaceProblem::restrict`]: a grid's bounding box), the solve runs where contact can
/// occur (where a warm start carries pressure, or within a quarter of the gap's range of its
/// lowest point) and is checked on the whole interface with one product; the part grows until
/// no point outside it penetrates.
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
    /// measure and `tolerance`. Solves in a workspace of its own
    /// ([`PolonskyKeer::solve_with`] keeps one across solves).
    fn solve_observed(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
    ) -> Result<ContactState> {
        let mut workspace = PolonskyKeerWorkspace::one_off();
        self.solve_with(problem, start, observer, &mut workspace)?;
        Ok(workspace.into_state())
    }

    /// [`PolonskyKeer::solve_with`] in the workspace's [`PolonskyKeerWorkspace`], the state
    /// copied out.
    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &mut Workspace,
    ) -> Result<ContactState> {
        let state = self.solve_with(problem, start, observer, &mut workspace.polonsky_keer)?;
        Ok(state.clone())
    }
}

/// The vectors of Polonsky–Keer solves, which a caller keeps across the solves of a design
/// loop (faer's explicit scratch): sized for a number of points ([`PolonskyKeerWorkspace::new`])
/// and grown when a problem is larger, they hold the conjugate-gradient buffers, the modes'
/// form, the iterate and the last solve's [`ContactState`]; and the problems a solve derives
/// from the one it solves (the parts of a grid it works on, [`InterfaceProblem::restrict`],
/// and the coarser grids of a cold start, [`InterfaceProblem::coarsen`]: bodies with their own
/// FFT plans and spectra), for the next solves of the same bodies, which refill only their
/// gaps. A solve in a workspace that has held a problem as large, and derived the same parts
/// and coarser problems from bodies of the same influence shapes and scales, allocates
/// nothing. What it keeps costs memory: the coarser grids of a problem hold about a third of
/// its grid's, and its parts up to three quarters each.
pub struct PolonskyKeerWorkspace {
    cg: Buffers,
    groups: Groups,
    /// The parts and coarser problems derived by earlier solves.
    derived: Derived,
    /// The iterate; on entry to a solve on a problem (or a part), its start when one is given.
    p: Vec<f64>,
    /// The pressure before the last step; also the spare vector of the steps that need one.
    previous: Vec<f64>,
    /// The points a solve on growing parts keeps.
    keep: Vec<bool>,
    /// The last part's points among the whole's, or a coarser problem's parent of each point.
    index: Vec<usize>,
    /// The last solve's state.
    state: ContactState,
}

impl Default for PolonskyKeerWorkspace {
    /// An empty workspace: its first solve sizes it.
    fn default() -> Self {
        Self::new(0)
    }
}

impl PolonskyKeerWorkspace {
    /// A workspace for problems of up to `points` points (it grows for larger ones).
    pub fn new(points: usize) -> Self {
        let state = ContactState {
            pressure: Vec::with_capacity(points),
            gap: Vec::with_capacity(points),
            rigid: vec![],
            active: Vec::with_capacity(points),
            iterations: 0,
            iterp: 0,
            iterd: 0,
            residuals: Residuals::new(0.0, &[], &[]),
            method: Method::PolonskyKeer,
            termination: Termination::Converged,
        };
        Self {
            cg: Buffers::new(points),
            groups: Groups::new(points),
            derived: Derived::keeping(),
            p: Vec::with_capacity(points),
            previous: Vec::with_capacity(points),
            keep: Vec::with_capacity(points),
            index: vec![],
            state,
        }
    }

    /// A workspace for one solve, which keeps no derived problem: each is dropped once used,
    /// as the solve's peak memory asks.
    pub(crate) fn one_off() -> Self {
        Self {
            derived: Derived::default(),
            ..Self::new(0)
        }
    }

    /// The state of the last solve (before any, an empty one).
    pub fn state(&self) -> &ContactState {
        &self.state
    }

    /// The state of the last solve (before any, an empty one), the workspace given up.
    pub fn into_state(self) -> ContactState {
        self.state
    }
}

impl PolonskyKeer {
    /// [`ContactSolver::solve_observed`] in the caller's `workspace`, which holds the returned
    /// state until its next solve: kept across the solves of a design loop, a solve of a
    /// problem no larger than an earlier one, on bodies of the same shapes, allocates nothing
    /// (see [`PolonskyKeerWorkspace`]; on a free grid, once an earlier solve derived the same
    /// parts and coarser grids).
    pub fn solve_with<'w>(
        &self,
        problem: &InterfaceProblem,
        start: Option<&[f64]>,
        observer: &dyn Observer,
        workspace: &'w mut PolonskyKeerWorkspace,
    ) -> Result<&'w ContactState> {
        if let Some(start) = start {
            if start.len() != problem.len() {
                return Err(Error::invalid(
                    "start",
                    format!("{} values", start.len()),
                    format!("one pressure per interface point ({})", problem.len()),
                ));
            }
            check::all_finite("start", start)?;
            workspace.p.clear();
            workspace.p.extend_from_slice(start);
        }
        let watch = Watch::new(observer, self.method());
        self.solve_nested(problem, start.is_some(), watch, workspace)?;
        watch::announce(observer, &workspace.state);
        Ok(&workspace.state)
    }

    /// Solves from the start in `ws.p` when `warm`; a cold start (or a start without pressure)
    /// on a problem with a coarser version ([`InterfaceProblem::coarsen`]), unless its seed is
    /// one flat face ([`flat_seed`]), starts from the coarse solution (itself found so, to
    /// [`NESTED_TOLERANCE`]), carried to each point by
    /// [`prolong`]: on a cell grid, interpolated between the coarse cells about it (one fine
    /// step fewer than each point taking its coarse point's pressure, for Hertz and the flat
    /// punch at 1024² cells). Its steps count with the solve's, and number the fine ones on; they are
    /// reported one level deeper (a solve that this one runs), so that an observer tells the
    /// fine grid's steps, the costly ones, from the coarser grids' (a quarter of the cost each
    /// level down).
    fn solve_nested(
        &self,
        problem: &InterfaceProblem,
        warm: bool,
        watch: Watch,
        ws: &mut PolonskyKeerWorkspace,
    ) -> Result<()> {
        let cold = !warm || ws.p.iter().all(|&v| v <= 0.0);
        if !cold || problem.len() < NESTED_POINTS || flat_seed(problem) {
            return self.solve_cropped(problem, warm, watch, ws);
        }
        let Some(coarse) = ws.derived.coarse(problem) else {
            return self.solve_cropped(problem, warm, watch, ws);
        };
        let nested = PolonskyKeer {
            settings: PolonskyKeerSettings {
                tolerance: self.settings.tolerance.max(NESTED_TOLERANCE),
                ..self.settings
            },
        };
        let deeper = Nested(watch.observer());
        let coarse_watch = Watch::new(&deeper, self.method());
        let solved = nested.solve_nested(coarse.problem(), false, coarse_watch, ws);
        let grids = problem.cell_grid().zip(coarse.problem().cell_grid());
        ws.derived.give_back(coarse, &mut ws.index);
        if solved.is_err() || !ws.state.is_converged() {
            ws.derived.done_with(&mut ws.index);
            // A start without pressure starts as zero pressure does.
            if warm {
                refill(&mut ws.p, problem.len(), 0.0);
            }
            return self.solve_cropped(problem, warm, watch, ws);
        }
        prolong(&ws.state.pressure, &ws.index, grids, &mut ws.p);
        // Unless the workspace keeps them, neither the coarse problem nor its parent index (a
        // usize per point) is held through the fine solve: at 2048² cells the index is 32 MiB
        // of its peak.
        ws.derived.done_with(&mut ws.index);
        let coarse_steps = ws.state.iterations;
        self.solve_cropped(problem, true, watch.after(coarse_steps), ws)?;
        ws.state.iterations += coarse_steps;
        Ok(())
    }

    /// Solves on a growing part of the interface when the problem can be restricted, from
    /// the start in `ws.p` when `warm`; each larger part starts from the pressure of the last.
    fn solve_cropped(
        &self,
        problem: &InterfaceProblem,
        mut warm: bool,
        watch: Watch,
        ws: &mut PolonskyKeerWorkspace,
    ) -> Result<()> {
        let n = problem.len();
        seed(problem, warm, ws);
        let mut steps = 0;
        while let Some(part) = ws.derived.part(problem, &ws.keep) {
            if warm {
                ws.previous.clear();
                ws.previous.extend(part.map().iter().map(|&k| ws.p[k]));
                std::mem::swap(&mut ws.p, &mut ws.previous);
            }
            let (part_steps, part_end) =
                self.solve_whole(part.problem(), warm, watch.after(steps), ws)?;
            // The part is dropped (or kept) before the whole problem's products.
            ws.derived.give_back(part, &mut ws.index);
            steps += part_steps;
            refill(&mut ws.previous, n, 0.0);
            for (a, &k) in ws.index.iter().enumerate() {
                ws.previous[k] = ws.p[a];
            }
            std::mem::swap(&mut ws.p, &mut ws.previous);
            ws.groups.prepare(problem)?;
            settle(problem, steps, ws);
            let grown = penetrating(problem, ws);
            ws.derived.done_with(&mut ws.index);
            if !grown || !part_end.is_converged() {
                watch::end(&mut ws.state, part_end);
                return Ok(());
            }
            warm = true;
        }
        let (whole_steps, end) = self.solve_whole(problem, warm, watch.after(steps), ws)?;
        settle(problem, steps + whole_steps, ws);
        if !end.is_converged() {
            watch::end(&mut ws.state, end);
        }
        Ok(())
    }

    /// The iteration on the whole of `problem` from the start in `ws.p` when `warm`, each
    /// step reported to `watch`; leaves the pressure in `ws.p` and returns the steps and how
    /// they ended. The caller settles the state ([`settle`]) on the problem it answers: a
    /// part's pressure is settled on the whole grid only, not on the part first (a product
    /// of the part's saved).
    fn solve_whole(
        &self,
        problem: &InterfaceProblem,
        warm: bool,
        watch: Watch,
        ws: &mut PolonskyKeerWorkspace,
    ) -> Result<(usize, Termination)> {
        let mut cg = Descent::new(problem, warm, ws)?;
        let tolerance = self.settings.tolerance;
        let mut driver = watch.driver(tolerance, self.settings.max_steps);
        let end = driver.run(|_, _| {
            let entered = match cg.step(problem) {
                Ok(entered) => entered,
                Err(cause) => {
                    return Ok::<_, Error>(Step::Last(f64::NAN, Termination::Stalled { cause }))
                }
            };
            let change = cg.change(problem);
            Ok(if !change.is_finite() {
                // The last finite iterate is kept; the step that overflowed is undone.
                cg.undo();
                let quantity = Quantity::Pressure;
                Step::Last(change, Termination::NonFinite { quantity })
            } else if change < tolerance && !entered {
                Step::Last(change, Termination::Converged)
            } else {
                Step::Next(change)
            })
        })?;
        Ok((driver.steps(), end))
    }
}

/// Marks in `ws.keep` where a solve starts: where the start in `ws.p` carries pressure (when
/// `warm`), or (a cold start, or a start without pressure) within [`SEED_FRACTION`] of the
/// free gap's range above its lowest point.
fn seed(problem: &InterfaceProblem, warm: bool, ws: &mut PolonskyKeerWorkspace) {
    if warm && ws.p.iter().any(|&v| v > 0.0) {
        ws.keep.clear();
        ws.keep.extend(ws.p.iter().map(|&v| v > 0.0));
        return;
    }
    let g = &mut ws.previous;
    refill(g, problem.len(), 0.0);
    problem.add_free_gap(g);
    let top = seed_level(problem);
    ws.keep.clear();
    ws.keep.extend(g.iter().map(|&h| h <= top));
}

/// The greatest free gap of a cold start's seed: [`SEED_FRACTION`] of the gap's range above
/// its lowest point.
fn seed_level(problem: &InterfaceProblem) -> f64 {
    gap_levels(problem).0
}

/// The seed's greatest free gap ([`seed_level`]) and the flat face's (the lowest gap plus its
/// round-off, [`PLATEAU`] of the gap's range), from one pass over the gaps.
fn gap_levels(problem: &InterfaceProblem) -> (f64, f64) {
    let (lo, hi) = range(problem.free_gaps());
    (lo + SEED_FRACTION * (hi - lo), lo + PLATEAU * (hi - lo))
}

/// Whether a cold start's seed ([`seed`]: the points within [`SEED_FRACTION`] of the free
/// gap's range above its lowest point) is one flat face, every point of it at the lowest gap
/// to round-off ([`PLATEAU`]): a rigid flat punch's face, or a gap flat everywhere. Pressed by
/// a translation, such a face is the contact set, and the load spread uniformly over it
/// starts the steps nearer than a coarser grid's answer: that grid's gaps are the means over
/// its cells, so the cells astride the face's edge stand off (by up to the step's height) and
/// its contact set lies a cell inside the face, whose rim, where the pressure is singular,
/// then starts from zero. Measured on the peers' flat punch (`halfspace_peers --one-row punch
/// N`, book: performance chapter): from the uniform start on the face 12, 14, 16 steps at
/// 256², 1024², 2048² cells; the nested start took 15, 17, 18 fine steps after the coarser
/// grids' 34, 53, 62 (with the padded circulant inverse as the preconditioner). Reads
/// the free gap without a buffer: a whole-grid vector held through the coarser grids' solves
/// would add to the peak.
fn flat_seed(problem: &InterfaceProblem) -> bool {
    flat_face(problem).is_some()
}

/// The greatest gap of the flat face that is a cold start's seed ([`flat_seed`]), if it is
/// one: the lowest gap plus its round-off ([`PLATEAU`] of the gap's range).
fn flat_face(problem: &InterfaceProblem) -> Option<f64> {
    let (seed, flat) = gap_levels(problem);
    problem
        .free_gaps()
        .all(|h| h <= flat || h > seed)
        .then_some(flat)
}

/// The least and greatest of `values`.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), h| {
        (a.min(h), b.max(h))
    })
}

/// Marks in `ws.keep` the points of a solved part (`ws.index`) and those outside it that the
/// part's answer (the gap of `ws.state`) makes penetrate, beyond round-off of the gaps' size;
/// returns whether any penetrates.
fn penetrating(problem: &InterfaceProblem, ws: &mut PolonskyKeerWorkspace) -> bool {
    let gap = &ws.state.gap;
    let free = &mut ws.previous;
    refill(free, problem.len(), 0.0);
    problem.add_free_gap(free);
    let scale = free
        .iter()
        .zip(gap)
        .fold(0.0f64, |m, (h, d)| m.max(h.abs() + d.abs()));
    refill(&mut ws.keep, problem.len(), false);
    for &k in &ws.index {
        ws.keep[k] = true;
    }
    let mut any = false;
    for (k, &d) in gap.iter().enumerate() {
        if !ws.keep[k] && d < -PENETRATION * scale {
            ws.keep[k] = true;
            any = true;
        }
    }
    any
}

/// The state of Polonsky and Keer's iteration: the workspace's pressure, its previous value,
/// the modes and the conjugate-gradient buffers, with the step's scalars.
struct Descent<'w> {
    ws: &'w mut PolonskyKeerWorkspace,
    kappa: f64,
    gz_old: f64,
    conjugate: bool,
}

impl<'w> Descent<'w> {
    /// The first pressure: the start in `ws.p` clipped at zero (when `warm`), or seeded from
    /// the gap, with each loaded mode's pressure scaled to its load.
    fn new(
        problem: &InterfaceProblem,
        warm: bool,
        ws: &'w mut PolonskyKeerWorkspace,
    ) -> Result<Self> {
        ws.groups.prepare(problem)?;
        ws.cg.prepare(problem);
        let w = problem.weights();
        let kappa = ws.cg.self_compliance(problem)?;
        ws.cg.d.fill(0.0);
        problem.add_free_gap(&mut ws.cg.d);
        if warm {
            ws.p.iter_mut().for_each(|v| *v = v.max(0.0));
        } else {
            let over = flat_face(problem)
                .or_else(|| ws.cg.offers_inverse(problem).then(|| seed_level(problem)));
            ws.groups.initial(w, &ws.cg.d, over, kappa, &mut ws.p);
        }
        ws.groups.restore(w, &ws.cg.d, &mut ws.p);
        refill(&mut ws.previous, problem.len(), 0.0);
        Ok(Self {
            ws,
            kappa,
            gz_old: 1.0,
            conjugate: false,
        })
    }

    /// One step: the residual, the direction, the move along it and the points that enter;
    /// returns whether any entered.
    fn step(&mut self, problem: &InterfaceProblem) -> std::result::Result<bool, Stall> {
        let PolonskyKeerWorkspace {
            cg,
            groups,
            p,
            previous,
            ..
        } = &mut *self.ws;
        cg.residual(problem, groups, p);
        cg.direction(problem, groups, self.conjugate, &mut self.gz_old);
        let entered = cg.step(problem, groups, p, previous, self.kappa)?;
        self.conjugate = !entered;
        groups.rescale(problem.weights(), &cg.d, p);
        Ok(entered)
    }

    /// The step's change of the pressure, Σ wᵢ |Δpᵢ| over the load (or the carried force).
    fn change(&self, problem: &InterfaceProblem) -> f64 {
        let (w, p) = (problem.weights(), &self.ws.p);
        let (carried, moved) = p
            .iter()
            .zip(&self.ws.previous)
            .zip(w)
            .fold((0.0, 0.0), |(carried, moved), ((a, b), w)| {
                (carried + a * w, moved + w * (a - b).abs())
            });
        let scale = self
            .ws
            .groups
            .total_load()
            .max(carried)
            .max(f64::MIN_POSITIVE);
        moved / scale
    }

    /// Returns to the pressure before the last step.
    fn undo(&mut self) {
        self.ws.p.copy_from_slice(&self.ws.previous);
    }
}

/// The state of the final pressure `ws.p` after `steps` steps, in `ws.state`: its gap
/// d = g + A W p + R λ and the modes' amplitudes λ, fitted on its contact set, with the
/// residuals, checked ([`InterfaceProblem::verify`]). The modes' form must be prepared for
/// `problem`. Of the workspace's vectors it uses only `ws.previous` (the product's forces,
/// then the check's scratch) and the second body's spare: the iteration's buffers stay at the
/// size of the part last solved, so that a settle on the whole grid after a part's solve holds
/// no six vectors of the whole (at the punch's 2048² cells, 192 MiB of its peak).
fn settle(problem: &InterfaceProblem, steps: usize, ws: &mut PolonskyKeerWorkspace) {
    let PolonskyKeerWorkspace {
        cg,
        groups,
        p,
        previous: forces,
        state,
        ..
    } = ws;
    let w = problem.weights();
    forces.clear();
    forces.extend(p.iter().zip(w).map(|(p, w)| p * w));
    refill(&mut state.gap, p.len(), 0.0);
    cg.size_spare(problem);
    problem.apply_influence_with(forces, &mut state.gap, &mut cg.spare);
    problem.add_free_gap(&mut state.gap);
    state.active.clear();
    state.active.extend(p.iter().map(|&v| v > 0.0));
    groups.amplitudes(w, &state.gap, &state.active);
    problem.add_rigid_motion(&groups.lambda, &mut state.gap);
    state.rigid.clear();
    state.rigid.extend_from_slice(&groups.lambda);
    state.pressure.clear();
    state.pressure.extend_from_slice(p);
    state.residuals = problem.residuals(&state.pressure, &state.gap);
    (state.iterations, state.iterp, state.iterd) = (steps, 0, 0);
    state.method = Method::PolonskyKeer;
    state.termination = Termination::Converged;
    problem.verify_in(state, forces);
}

/// The vectors of the iteration, sized once per problem size.
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
    /// The last step's length τ along t, when it moved every point of the contact set by
    /// exactly −τ·tᵢ (none clipped at p = 0, none entered): the next residual is then the
    /// last one moved by −τ·A W t, already in `r`, without a product of its own.
    moved: Option<f64>,
}

impl Buffers {
    /// Empty buffers with room for `points` points.
    fn new(points: usize) -> Self {
        let room = || Vec::with_capacity(points);
        Self {
            forces: room(),
            spare: room(),
            d: room(),
            d_previous: room(),
            z: room(),
            t: room(),
            r: room(),
            contact: Vec::with_capacity(points),
            preconditioned: false,
            moved: None,
        }
    }

    /// Sizes the buffers for `problem` (`spare` only when its operator sums two products),
    /// zeroed.
    fn prepare(&mut self, problem: &InterfaceProblem) {
        let n = problem.len();
        for v in [
            &mut self.forces,
            &mut self.d,
            &mut self.d_previous,
            &mut self.z,
            &mut self.t,
            &mut self.r,
        ] {
            refill(v, n, 0.0);
        }
        self.size_spare(problem);
        refill(&mut self.contact, n, false);
        self.preconditioned = false;
        self.moved = None;
    }

    /// Sizes `spare` for `problem`: its points when its operator sums two products, else
    /// empty.
    fn size_spare(&mut self, problem: &InterfaceProblem) {
        let n = if problem.sums_two_products() {
            problem.len()
        } else {
            0
        };
        refill(&mut self.spare, n, 0.0);
    }

    /// Whether `problem` offers an approximate inverse ([`InterfaceProblem::precondition`]),
    /// asked once of zero gaps on every point, in the buffers (prepared, which it leaves so).
    fn offers_inverse(&mut self, problem: &InterfaceProblem) -> bool {
        self.contact.fill(true);
        // t is zero until the first direction.
        let offers = problem.precondition(&self.t, &self.contact, &mut self.z);
        self.contact.fill(false);
        self.z.fill(0.0);
        offers
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
    /// same in any consistent units. When τ = 0, −dᵢ/κ. The pressure before the move is
    /// kept in `previous`. Returns whether any entered; fails when the operator is not
    /// positive on the contact set. The direction's forces W t are in `forces`
    /// ([`Buffers::direction`] put them there).
    fn step(
        &mut self,
        problem: &InterfaceProblem,
        groups: &mut Groups,
        p: &mut [f64],
        previous: &mut [f64],
        kappa: f64,
    ) -> std::result::Result<bool, Stall> {
        let w = problem.weights();
        problem.apply_influence_with(&self.forces, &mut self.r, &mut self.spare);
        let (mut curvature, mut along) = (0.0, 0.0);
        for i in 0..w.len() {
            if self.contact[i] {
                curvature += w[i] * self.r[i] * self.t[i];
                along += w[i] * self.d[i] * self.t[i];
            }
        }
        let tau = if along == 0.0 {
            0.0
        } else if curvature > 0.0 {
            along / curvature
        } else {
            return Err(Stall::NotPositive { curvature });
        };
        let enter = match (tau > 0.0, self.preconditioned) {
            (true, false) => tau,
            (true, true) => tau / kappa,
            (false, _) => 1.0 / kappa,
        };
        let (mut entered, mut clipped) = (false, false);
        groups.clear_sums();
        for i in 0..p.len() {
            previous[i] = p[i];
            if self.contact[i] {
                let moved = p[i] - tau * self.t[i];
                clipped |= moved < 0.0;
                p[i] = moved.max(0.0);
            } else if groups.may_enter(i) && self.d[i] < 0.0 {
                p[i] = -enter * self.d[i];
                entered = true;
            }
            if p[i] > 0.0 {
                groups.add(w, i, p[i]);
            }
        }
        self.moved = (!entered && !clipped).then_some(tau);
        Ok(entered)
    }

    /// The contact set of `p` and the gap residual d, with the modes' amplitudes fitted on it
    /// ([`Groups::amplitudes`]); and in `forces`, d masked to the contact set (the
    /// preconditioner's input). After a step that moved every point by −τ·tᵢ (`moved`), the
    /// gap g + A W p is the last one less τ·A W t (the step's product, in `r`: conjugate
    /// gradients' recursive residual) and costs no product; after any other, it is the product
    /// of W p. Each of its passes over the points does what it can at once.
    fn residual(&mut self, problem: &InterfaceProblem, groups: &mut Groups, p: &[f64]) {
        let w = problem.weights();
        if let Some(tau) = self.moved {
            groups.clear_sums();
            for i in 0..w.len() {
                self.d[i] -= groups.motion(i) + tau * self.r[i];
                self.contact[i] = p[i] > 0.0;
                if self.contact[i] {
                    groups.add(w, i, self.d[i]);
                }
            }
            groups.fit(&self.d);
        } else {
            for (((f, c), &p), w) in self.forces.iter_mut().zip(&mut self.contact).zip(p).zip(w) {
                *f = p * w;
                *c = p > 0.0;
            }
            problem.apply_influence_with(&self.forces, &mut self.d, &mut self.spare);
            problem.add_free_gap(&mut self.d);
            groups.amplitudes(w, &self.d, &self.contact);
        }
        for i in 0..w.len() {
            self.d[i] += groups.motion(i);
            self.forces[i] = if self.contact[i] { self.d[i] } else { 0.0 };
        }
    }

    /// The next search direction t: the residual on the contact set (in `forces`, from
    /// [`Buffers::residual`]), preconditioned when the problem offers an approximate inverse
    /// (forces turned into pressures), projected so that the modes' loads do not change
    /// ([`Groups::shift`]), and conjugated by Polak–Ribière unless restarted; its forces W t
    /// left in `forces` for the step's product. Four passes over the points: each projection's
    /// sums are gathered while its vector is written, and applied with the next pass's work.
    fn direction(
        &mut self,
        problem: &InterfaceProblem,
        groups: &mut Groups,
        conjugate: bool,
        gz_old: &mut f64,
    ) {
        let w = problem.weights();
        let n = w.len();
        self.preconditioned = problem.precondition(&self.forces, &self.contact, &mut self.z);
        groups.clear_sums();
        for i in 0..n {
            self.z[i] = match (self.contact[i], self.preconditioned) {
                (false, _) => 0.0,
                (true, true) => self.z[i] / w[i],
                (true, false) => self.forces[i],
            };
            if self.contact[i] {
                groups.add(w, i, self.z[i]);
            }
        }
        // The projected z, with gᵀz and Polak–Ribière's gᵀz of the last residual.
        let (mut gz, mut gz_last) = (0.0, 0.0);
        for i in 0..n {
            if self.contact[i] {
                self.z[i] -= groups.shift(i);
                gz += w[i] * self.d[i] * self.z[i];
                gz_last += w[i] * self.d_previous[i] * self.z[i];
            }
        }
        let beta = if conjugate && *gz_old != 0.0 {
            ((gz - gz_last) / *gz_old).max(0.0)
        } else {
            0.0
        };
        groups.clear_sums();
        for i in 0..n {
            self.t[i] = if self.contact[i] {
                self.z[i] + beta * self.t[i]
            } else {
                0.0
            };
            if self.contact[i] {
                groups.add(w, i, self.t[i]);
            }
        }
        for i in 0..n {
            if self.contact[i] {
                self.t[i] -= groups.shift(i);
            }
            self.forces[i] = self.t[i] * w[i];
            self.d_previous[i] = self.d[i];
        }
        *gz_old = gz;
    }
}

/// No mode moves the point.
const NONE: usize = usize::MAX;
/// Relative difference between a mode's carried force and its load within which the
/// pressure is not rescaled: round-off of the sums over the points (2–5·10⁻¹⁴ after the
/// flat punch's steps at 1024² cells), no larger than the steps' default tolerance.
const LOAD_ROUND_OFF: f64 = 1e-12;

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
    /// rᵢ when one mode moves every point alike (a rigid indenter pressed along its axis, the
    /// common case): the steps' passes then read neither `owner` nor `r`, two vectors of the
    /// points' size fewer to stream each pass.
    uniform: Option<f64>,
}

impl Groups {
    /// Empty buffers with room for `points` points.
    fn new(points: usize) -> Self {
        Self {
            owner: Vec::with_capacity(points),
            r: Vec::with_capacity(points),
            target: vec![],
            num: vec![],
            den: vec![],
            lambda: vec![],
            extreme: vec![],
            seed: vec![],
            uniform: None,
        }
    }

    /// The modes of `problem` in this form; fails on modes the iteration cannot hold. One mode
    /// moving every point alike (`uniform`) needs no per-point table: `owner` and `r` stay
    /// empty (two vectors of the points' size fewer at the solve's peak: 34 MiB of Hertz's
    /// 2048² part).
    fn prepare(&mut self, problem: &InterfaceProblem) -> Result<()> {
        let (n, modes) = (problem.len(), problem.modes());
        self.uniform = match modes {
            [mode] if mode.points.len() == n => {
                let r = mode.displacement.first().copied();
                r.filter(|&r| mode.displacement.iter().all(|&v| v == r))
            }
            _ => None,
        };
        let table = if self.uniform.is_some() { 0 } else { n };
        refill(&mut self.owner, table, NONE);
        refill(&mut self.r, table, 0.0);
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
            if self.uniform.is_some() {
                continue;
            }
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                if self.owner[i] != NONE {
                    return Err(unsupported(&mode.name, "shares points with another mode"));
                }
                self.owner[i] = k;
                self.r[i] = v;
            }
        }
        let m = modes.len();
        self.target.clear();
        self.target.extend(modes.iter().map(|m| -m.load));
        for v in [
            &mut self.num,
            &mut self.den,
            &mut self.lambda,
            &mut self.extreme,
        ] {
            refill(v, m, 0.0);
        }
        refill(&mut self.seed, m, NONE);
        Ok(())
    }

    /// The mode that moves point i and its rᵢ, if any.
    #[inline(always)]
    fn mode_of(&self, i: usize) -> Option<(usize, f64)> {
        match self.uniform {
            Some(r) => Some((0, r)),
            None => match self.owner[i] {
                NONE => None,
                k => Some((k, self.r[i])),
            },
        }
    }

    fn total_load(&self) -> f64 {
        self.target.iter().map(|c| c.abs()).sum()
    }

    /// Whether point i may carry pressure (not on an unloaded mode, which stays open).
    fn may_enter(&self, i: usize) -> bool {
        self.mode_of(i).is_none_or(|(k, _)| self.target[k] != 0.0)
    }

    /// A first pressure from the free gap `g`: each loaded mode's load spread uniformly over
    /// its points whose gap is at most `over` (all its points when `over` is `None` or none
    /// of them is that low); elsewhere the overlap −g over κ. The caller passes the flat face
    /// when the seed is one ([`flat_face`]): a flat punch's part is its face's bounding box,
    /// whose corners the load spread over the whole box loaded only for the first steps to
    /// clip (two fine steps more at every size from 256² to 2048², `halfspace_peers --one-row
    /// punch N`). Otherwise the seed ([`seed_level`]) when the problem is preconditioned: the
    /// Pasternak bed's exact inverse took 116 and 45 steps from the whole spread, 53 and 31
    /// from the seed; and all points when it is not, which the bare iteration needs (225
    /// steps from the whole spread, 819 from the seed).
    fn initial(&mut self, w: &[f64], g: &[f64], over: Option<f64>, kappa: f64, p: &mut Vec<f64>) {
        let low = |i: usize| over.is_none_or(|top| g[i] <= top);
        // num: Σ w r over a mode's points that low; den: over all its points.
        self.clear_sums();
        for i in 0..w.len() {
            if let Some((k, r)) = self.mode_of(i) {
                self.den[k] += w[i] * r;
                if low(i) {
                    self.num[k] += w[i] * r;
                }
            }
        }
        p.clear();
        p.extend((0..w.len()).map(|i| {
            match self.mode_of(i) {
                None => (-g[i]).max(0.0) / kappa,
                Some((k, _)) if self.num[k] != 0.0 && low(i) => self.target[k] / self.num[k],
                Some((k, _)) if self.num[k] == 0.0 && self.den[k] != 0.0 => {
                    self.target[k] / self.den[k]
                }
                _ => 0.0,
            }
            .max(0.0)
        }));
    }

    /// num\[k\] = Σ wᵢ rᵢ f(i), den\[k\] = Σ wᵢ rᵢ² over the points of mode k with `member(i)`.
    fn sums(&mut self, w: &[f64], f: impl Fn(usize) -> f64, member: impl Fn(usize) -> bool) {
        self.num.fill(0.0);
        self.den.fill(0.0);
        for i in 0..w.len() {
            if let Some((k, r)) = self.mode_of(i).filter(|_| member(i)) {
                self.num[k] += w[i] * r * f(i);
                self.den[k] += w[i] * r * r;
            }
        }
    }

    /// Starts the sums of a projection ([`Groups::shift`]) afresh.
    fn clear_sums(&mut self) {
        self.num.fill(0.0);
        self.den.fill(0.0);
    }

    /// Adds point i, of value `v` and on the contact set, to the sums of a projection:
    /// num\[k\] += wᵢ rᵢ v, den\[k\] += wᵢ rᵢ² for its mode k.
    #[inline(always)]
    fn add(&mut self, w: &[f64], i: usize, v: f64) {
        if let Some((k, r)) = self.mode_of(i) {
            self.num[k] += w[i] * r * v;
            self.den[k] += w[i] * r * r;
        }
    }

    /// What the W-projection on the modes over the contact set removes from point i's value,
    /// once every point's is in the sums ([`Groups::add`]): rᵢ Σ w r v / Σ w r², so that
    /// Σ wᵢ rᵢ vᵢ = 0 for every mode afterwards (eq. 2.10).
    #[inline(always)]
    fn shift(&self, i: usize) -> f64 {
        match self.mode_of(i) {
            Some((k, r)) if self.den[k] > 0.0 => r * self.num[k] / self.den[k],
            _ => 0.0,
        }
    }

    /// The modes' motion at point i, (R λ)ᵢ, with the amplitudes of [`Groups::amplitudes`].
    #[inline(always)]
    fn motion(&self, i: usize) -> f64 {
        self.mode_of(i).map_or(0.0, |(k, r)| r * self.lambda[k])
    }

    /// λ fitted by least squares to close the gap `d` on the contact set
    /// (λₖ = −Σ w r d / Σ w r²), or, for a mode without contact, the value at which its nearest
    /// point just touches (d + rλ ≥ 0: λ ≥ −d/r for r > 0, λ ≤ −d/r for r < 0).
    fn amplitudes(&mut self, w: &[f64], d: &[f64], contact: &[bool]) {
        self.sums(w, |i| d[i], |i| contact[i]);
        self.fit(d);
    }

    /// [`Groups::amplitudes`] once the sums over the contact set of the gap `d` are in
    /// (`num`, `den`: [`Groups::add`] of each contact point's dᵢ).
    fn fit(&mut self, d: &[f64]) {
        self.extreme.fill(f64::NAN);
        // Only a mode without contact needs the pass for its bound.
        if self.den.contains(&0.0) {
            for i in 0..d.len() {
                let Some((k, r)) = self.mode_of(i) else {
                    continue;
                };
                if self.den[k] == 0.0 {
                    let bound = -d[i] / r;
                    let e = self.extreme[k];
                    self.extreme[k] = if e.is_nan() {
                        bound
                    } else if r > 0.0 {
                        e.max(bound)
                    } else {
                        e.min(bound)
                    };
                }
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
        self.sums(w, |i| p[i], |_| true);
        self.rescale(w, d, p);
    }

    /// [`Groups::restore`] once each mode's carried force Σ wᵢ rᵢ pᵢ is in `num` (a step
    /// gathers it while it moves the pressure). Nothing to do when every mode is loaded and
    /// carries its load to [`LOAD_ROUND_OFF`]: a step along a direction that keeps every
    /// mode's load (eq. 2.10) leaves it so, and a pass over the points is saved.
    fn rescale(&mut self, w: &[f64], d: &[f64], p: &mut [f64]) {
        let kept =
            |(&carried, &c): (&f64, &f64)| c != 0.0 && ((carried - c) / c).abs() <= LOAD_ROUND_OFF;
        if self.num.iter().zip(&self.target).all(kept) {
            return;
        }
        self.seed.fill(NONE);
        for i in 0..w.len() {
            let Some((k, _)) = self.mode_of(i) else {
                continue;
            };
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
            if i == NONE {
                continue;
            }
            if let Some((_, r)) = self.mode_of(i) {
                p[i] = self.target[k] / (w[i] * r);
            }
        }
    }
}
