//! Kalker's active-set iteration, the one loop behind every method that solves on a contact
//! set C: the penalty method and the active-set QP solver on the condensed interface, each
//! Uzawa step of the augmented Lagrangian, and the penalty method on the full finite-element
//! system (2.22, [`FullPenalty`](crate::FullPenalty)).

use contopt_core::observe::Method;
use contopt_core::{ContactState, Error, Result, Termination};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use crate::watch::{self, Watch};
use crate::InterfaceProblem;

/// The n × n matrices a Kalker solve holds at once: A, the contact-set matrix, its
/// eigenvectors and a product.
pub(crate) const DENSE_COPIES: u64 = 4;

/// An eigenvalue of the contact-set matrix below this fraction of its eigenvector's own
/// diagonal scale counts as null: the direction does not move the interface (round-off).
const NULL_EIGENVALUE: f64 = 1e-9;
/// A pressure in C below −`TENSION` times the largest |pᵢ| is tension (round-off).
const TENSION: f64 = 1e-12;
/// A gap outside C below −`PENETRATION` times the gap's largest term is a penetration
/// (round-off).
const PENETRATION: f64 = 1e-11;
/// The round-off level of a solved gap, relative to its largest terms (the free gap and the
/// rigid motion).
const GAP_ROUND_OFF: f64 = 1e-13;
/// c_stiff·maxᵢ(Aᵢᵢ wᵢ): the largest penalty parameter solved from scratch, whose proximal
/// term 1/c is 10⁻⁶ of the stiffest compliance (conditioning of the Cholesky solve).
const STIFF_RATIO: f64 = 1e6;
/// Kalker's iteration gives up after `SOLVES_PER_POINT`·n + [`SOLVES_EXTRA`] solves
/// (cycling: the pivot rule is finite, but a stuck iteration must still end).
const SOLVES_PER_POINT: usize = 4;
/// See [`SOLVES_PER_POINT`]: the allowance of a very small interface.
const SOLVES_EXTRA: usize = 20;

/// A system that Kalker's iteration solves on a contact set C: the condensed interface
/// problem ([`Subproblem`]) or the full finite-element system with penalty springs.
pub(crate) trait ContactSet {
    /// Number of contact points.
    fn points(&self) -> usize;
    /// The point put in contact when C is empty and a floating body would not be held (the
    /// point of least gap); `None` when nothing floats.
    fn anchor(&self) -> Option<usize>;
    /// Solves with the points of `active` in contact and zero pressure elsewhere; `Ok(Err)`
    /// with the reason when the system is singular on C (the iterate then holds no solve).
    fn solve_on(&mut self, active: &[bool]) -> Result<std::result::Result<(), String>>;
    /// The pressure of the last solve.
    fn pressure(&self) -> &[f64];
    /// The gap of point i after the last solve less the proximal shift, dᵢ − ρ p̂ᵢ: negative
    /// when the point, outside C, penetrates.
    fn clearance(&self, i: usize) -> f64;
    /// The largest term of the gap after the last solve, against which round-off is judged.
    fn gap_scale(&self) -> f64;
}

/// How Kalker's iteration ended; the system holds its last iterate.
pub(crate) struct Sweep {
    /// Solves, each followed by the sign check of p (the paper's `iterp`).
    pub iterp: usize,
    /// Penetration checks: the solves whose pressure had no negative value (`iterd`).
    pub iterd: usize,
    /// Why it stopped short; `None` when solved.
    pub halt: Option<Termination>,
}

/// Kalker's iteration: solve with the points of `active` in contact (one `iterp`); drop the
/// points whose pressure came out negative, else check the gap (one `iterd`) and add the
/// points that penetrate; repeat until neither occurs. Changes follow [`PivotRule`], so the
/// iteration cannot cycle. Each solve is reported to `watch` with the number of points that
/// break a sign condition as the measure (tolerance 0).
pub(crate) fn iterate(
    system: &mut impl ContactSet,
    active: &mut [bool],
    watch: Watch,
) -> Result<Sweep> {
    let max_solves = SOLVES_PER_POINT * system.points() + SOLVES_EXTRA;
    let mut pivot = PivotRule::new();
    let (mut negative, mut penetrating) = (Vec::new(), Vec::new());
    let mut sweep = Sweep {
        iterp: 0,
        iterd: 0,
        halt: None,
    };
    loop {
        if !active.contains(&true) {
            if let Some(i) = system.anchor() {
                active[i] = true;
            }
        }
        if let Err(reason) = system.solve_on(active)? {
            sweep.halt = Some(Termination::Stalled { reason });
            return Ok(sweep);
        }
        sweep.iterp += 1;
        infeasible(system, active, &mut negative, &mut penetrating);
        if negative.is_empty() {
            sweep.iterd += 1;
        }
        let infeasible = negative.len() + penetrating.len();
        let stop = watch.report(sweep.iterp, infeasible as f64, 0.0);
        if infeasible == 0 {
            return Ok(sweep);
        }
        if stop.is_some() {
            sweep.halt = stop;
            return Ok(sweep);
        }
        if sweep.iterp >= max_solves {
            // The contact set kept changing: the measure is the points that still break a
            // sign condition (negative pressure or penetration).
            sweep.halt = Some(Termination::StepLimit {
                steps: sweep.iterp,
                measure: infeasible as f64,
                tolerance: 0.0,
            });
            return Ok(sweep);
        }
        match pivot.next(&negative, &penetrating) {
            Pivot::Drop(points) => points.into_iter().for_each(|i| active[i] = false),
            Pivot::Add(points) => points.into_iter().for_each(|i| active[i] = true),
        }
    }
}

/// The points of C in tension and the points outside C that penetrate, after the last solve.
fn infeasible(
    system: &impl ContactSet,
    active: &[bool],
    negative: &mut Vec<usize>,
    penetrating: &mut Vec<usize>,
) {
    let p = system.pressure();
    let p_scale = p.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    negative.clear();
    negative.extend((0..p.len()).filter(|&i| active[i] && p[i] < -TENSION * p_scale));
    let tol = PENETRATION * system.gap_scale();
    penetrating.clear();
    penetrating.extend((0..p.len()).filter(|&i| !active[i] && system.clearance(i) < -tol));
}

/// A pressure and rigid-mode amplitudes: an iterate, or the reference a solve starts from.
#[derive(Clone, Debug)]
pub(crate) struct Iterate {
    pub(crate) pressure: Vec<f64>,
    pub(crate) rigid: Vec<f64>,
}

impl Iterate {
    fn zero(n: usize, m: usize) -> Self {
        Self {
            pressure: vec![0.0; n],
            rigid: vec![0.0; m],
        }
    }
}

/// The contact-set matrix M = W_C A_CC W_C + ρ W_C, factorised.
enum ContactMatrix {
    Cholesky(Llt<f64>),
    /// With T = W^½ A W^½ = U Λ Uᵀ on the contact set, M⁺ = W^-½ U (Λ + ρ)⁺ Uᵀ W^-½, where an
    /// eigenvector u counts as null when its eigenvalue is below [`NULL_EIGENVALUE`] of its own
    /// diagonal scale Σᵢ uᵢ² Tᵢᵢ (scale-invariant: points of small weight near an axis are not null):
    /// no correction is made along the directions that do not move the interface, so
    /// c·(round-off) never enters.
    Spectral {
        u: Mat<f64>,
        inverse: Vec<f64>,
        root_w: Vec<f64>,
    },
}

impl ContactMatrix {
    fn new(a: &Mat<f64>, w: &[f64], idx: &[usize], rho: f64, spectral: bool) -> Option<Self> {
        let k = idx.len();
        if !spectral {
            let m = Mat::from_fn(k, k, |x, y| {
                let (i, j) = (idx[x], idx[y]);
                w[i] * a[(i, j)] * w[j] + if x == y { rho * w[i] } else { 0.0 }
            });
            return Llt::new(m.as_ref(), Side::Lower)
                .ok()
                .map(ContactMatrix::Cholesky);
        }
        let root_w: Vec<f64> = idx.iter().map(|&i| w[i].sqrt()).collect();
        let t = Mat::from_fn(k, k, |x, y| root_w[x] * a[(idx[x], idx[y])] * root_w[y]);
        let eig = t.self_adjoint_eigen(Side::Lower).ok()?;
        let u = eig.U();
        let inverse = (0..k)
            .map(|x| {
                let l = eig.S()[x];
                let scale: f64 = (0..k).map(|i| u[(i, x)] * u[(i, x)] * t[(i, i)]).sum();
                if l > NULL_EIGENVALUE * scale {
                    1.0 / (l + rho)
                } else {
                    0.0
                }
            })
            .collect();
        Some(ContactMatrix::Spectral {
            u: eig.U().to_owned(),
            inverse,
            root_w,
        })
    }

    fn solve(&self, b: &Mat<f64>) -> Mat<f64> {
        match self {
            ContactMatrix::Cholesky(llt) => llt.solve(b),
            ContactMatrix::Spectral { u, inverse, root_w } => {
                let scaled = Mat::from_fn(b.nrows(), b.ncols(), |i, j| b[(i, j)] / root_w[i]);
                let mut coef = u.transpose() * &scaled;
                for (i, inv) in inverse.iter().enumerate() {
                    for j in 0..coef.ncols() {
                        coef[(i, j)] *= inv;
                    }
                }
                let x = u * &coef;
                Mat::from_fn(x.nrows(), x.ncols(), |i, j| x[(i, j)] / root_w[i])
            }
        }
    }
}

/// Solution of one subproblem on its final active set.
pub(crate) struct Inner {
    pub(crate) solution: Iterate,
    /// Gap d of the solution.
    pub(crate) gap: Vec<f64>,
    /// Round-off level of the gap ([`GAP_ROUND_OFF`] of its largest terms); 0 when stopped.
    pub(crate) gap_floor: f64,
    /// Solves, each followed by the sign check of p (the paper's `iterp`).
    pub(crate) iterp: usize,
    /// Penetration checks: the solves whose pressure had no negative value (the paper's
    /// `iterd`).
    pub(crate) iterd: usize,
    /// Why the iteration stopped short, with `solution` its last iterate; `None` when solved.
    pub(crate) stopped: Option<Termination>,
}

impl Inner {
    /// The contact set it started from was already the answer.
    pub(crate) fn unchanged(&self) -> bool {
        self.iterp == 1
    }
}

/// The proximal subproblem
///
/// min ½ pᵀ (H + ρW) p + pᵀ W (g − ρ p̂)  over  p ≥ 0,  Rᵀ W p = −q,
///
/// whose solution is p = ⟨p̂ − c d⟩ with c = 1/ρ: eq. (2.19) with the gap d of the new
/// state, i.e. one augmented-Lagrangian step (2.18)–(2.20); with p̂ = 0 it is the penalty
/// method.
///
/// Each solve on C is in residual form: the correction to `reference` (restricted to C) is
/// driven by the reference's own residual −W(d + ρ(p − p̂)). Round-off in the data along the
/// directions that do not move the interface (a semi-definite H) is amplified by c; in this
/// form it multiplies the reference's residual instead of the whole gap, so a reference close
/// to the answer keeps large c accurate.
pub(crate) struct Subproblem<'a> {
    problem: &'a InterfaceProblem<'a>,
    rho: f64,
    shift: &'a [f64],
    /// Solve spectrally (for ρ below the stiff level; see [`ContactMatrix`]).
    spectral: bool,
    reference: &'a Iterate,
    /// The dense influence matrix A, the rigid modes R and their loads q.
    a: &'a Mat<f64>,
    r: Mat<f64>,
    q: Vec<f64>,
    /// The free gap g and its largest |gᵢ|.
    free_gap: Vec<f64>,
    free_scale: f64,
    /// The last solve's iterate and its gap d.
    current: Iterate,
    gap: Vec<f64>,
}

impl<'a> Subproblem<'a> {
    pub(crate) fn new(
        problem: &'a InterfaceProblem<'a>,
        rho: f64,
        shift: &'a [f64],
        spectral: bool,
        reference: &'a Iterate,
    ) -> Result<Self> {
        let free_gap = problem.free_gap();
        Ok(Self {
            a: problem.dense_influence(DENSE_COPIES)?,
            r: problem.rigid(),
            q: problem.load(),
            free_scale: free_gap.iter().fold(0.0f64, |s, v| s.max(v.abs())),
            free_gap,
            current: reference.clone(),
            gap: vec![0.0; problem.len()],
            problem,
            rho,
            shift,
            spectral,
            reference,
        })
    }

    /// Kalker's iteration ([`iterate`]) from the contact set `active`, which it updates.
    pub(crate) fn solve(mut self, active: &mut [bool], watch: Watch) -> Result<Inner> {
        let sweep = iterate(&mut self, active, watch)?;
        let gap_floor = if sweep.halt.is_none() {
            for v in self.current.pressure.iter_mut() {
                *v = v.max(0.0);
            }
            // d = g + A W p + R λ, with the elastic term balancing the others on C.
            GAP_ROUND_OFF * (self.free_scale + self.rigid_motion())
        } else {
            0.0
        };
        Ok(Inner {
            solution: self.current,
            gap: self.gap,
            gap_floor,
            iterp: sweep.iterp,
            iterd: sweep.iterd,
            stopped: sweep.halt,
        })
    }

    /// The largest rigid motion |(R λ)ᵢ| of the current iterate.
    fn rigid_motion(&self) -> f64 {
        let lambda = &self.current.rigid;
        (0..self.problem.len())
            .map(|i| {
                (0..lambda.len())
                    .map(|c| self.r[(i, c)] * lambda[c])
                    .sum::<f64>()
                    .abs()
            })
            .fold(0.0f64, f64::max)
    }

    /// Corrects the current iterate (the reference restricted to C, whose points are `idx`)
    /// by the solve on C.
    fn correct(&mut self, idx: &[usize]) -> std::result::Result<(), String> {
        let (problem, rho, shift) = (self.problem, self.rho, self.shift);
        let w = problem.weights();
        let k = idx.len();
        let Some(llt) = ContactMatrix::new(self.a, w, idx, rho, self.spectral) else {
            return Err(format!(
                "the influence matrix is singular on the {k} contact points (penalty term rho = \
                 {rho:e}); use a finite penalty parameter or the augmented Lagrangian"
            ));
        };
        let p = &self.current.pressure;
        let d_ref = problem.gap(p, &self.current.rigid);
        let b = Mat::from_fn(k, 1, |a, _| {
            let i = idx[a];
            -w[i] * (d_ref[i] + rho * (p[i] - shift[i]))
        });
        let y = llt.solve(&b);
        let delta = if self.q.is_empty() {
            y
        } else {
            self.balance(&llt, idx, y)?
        };
        for (a, &i) in idx.iter().enumerate() {
            self.current.pressure[i] += delta[(a, 0)];
        }
        Ok(())
    }

    /// The correction `y` on C made to balance the rigid modes, Rᵀ W δ = −q − Rᵀ W p_ref
    /// (eq. 2.10), with their amplitudes updated.
    fn balance(
        &mut self,
        llt: &ContactMatrix,
        idx: &[usize],
        y: Mat<f64>,
    ) -> std::result::Result<Mat<f64>, String> {
        let (k, m) = (idx.len(), self.q.len());
        let w = self.problem.weights();
        let bm = Mat::from_fn(k, m, |a, c| w[idx[a]] * self.r[(idx[a], c)]);
        let z = llt.solve(&bm);
        let s = bm.transpose() * &z;
        let p = &self.current.pressure;
        let rhs = Mat::from_fn(m, 1, |c, _| {
            let held: f64 = (0..k).map(|a| bm[(a, c)] * p[idx[a]]).sum();
            (0..k).map(|a| bm[(a, c)] * y[(a, 0)]).sum::<f64>() + self.q[c] + held
        });
        let Ok(gram) = Llt::new(s.as_ref(), Side::Lower) else {
            return Err(format!(
                "the {k} contact points do not hold the rigid modes {:?}",
                self.problem.mode_names()
            ));
        };
        let lambda = gram.solve(&rhs);
        for (c, l) in self.current.rigid.iter_mut().enumerate() {
            *l += lambda[(c, 0)];
        }
        Ok(&y - &z * &lambda)
    }
}

impl ContactSet for Subproblem<'_> {
    fn points(&self) -> usize {
        self.problem.len()
    }

    fn anchor(&self) -> Option<usize> {
        let g = &self.free_gap;
        (!self.q.is_empty()).then(|| (0..g.len()).min_by(|&i, &j| g[i].total_cmp(&g[j])))?
    }

    fn solve_on(&mut self, active: &[bool]) -> Result<std::result::Result<(), String>> {
        let idx: Vec<usize> = (0..active.len()).filter(|&i| active[i]).collect();
        self.current.pressure.fill(0.0);
        for &i in &idx {
            self.current.pressure[i] = self.reference.pressure[i];
        }
        self.current.rigid.clone_from(&self.reference.rigid);
        let outcome = if idx.is_empty() {
            Ok(())
        } else {
            self.correct(&idx)
        };
        self.gap = self
            .problem
            .gap(&self.current.pressure, &self.current.rigid);
        Ok(outcome)
    }

    fn pressure(&self) -> &[f64] {
        &self.current.pressure
    }

    fn clearance(&self, i: usize) -> f64 {
        self.gap[i] - self.rho * self.shift[i]
    }

    fn gap_scale(&self) -> f64 {
        self.gap.iter().fold(self.free_scale, |s, v| s.max(v.abs()))
    }
}

/// A change of the contact set.
#[derive(Debug, PartialEq)]
enum Pivot {
    /// Points that leave the set (their pressure came out negative).
    Drop(Vec<usize>),
    /// Points that join it (they penetrate).
    Add(Vec<usize>),
}

/// The choice of the next contact set, after Júdice and Pires' safeguard for block principal
/// pivoting: Kalker's block changes (every negative-pressure point leaves, else every
/// penetrating point joins) while the number of infeasible points keeps reaching new lows, with
/// a few passes of grace; otherwise one point at a time, the lowest-numbered infeasible one
/// (Murty's rule, finite for the positive-definite matrix of a subproblem). Block changes alone
/// can cycle when the matrix is nearly singular on the set, as it is for three Gauss points per
/// quadratic face, where many points have p ≈ d ≈ 0 (an optimised gap).
struct PivotRule {
    /// Fewest infeasible points seen so far.
    best: usize,
    /// Block passes left without a new low.
    grace: usize,
}

impl PivotRule {
    /// Block passes allowed without a new low in the number of infeasible points.
    const GRACE: usize = 3;

    fn new() -> Self {
        Self {
            best: usize::MAX,
            grace: Self::GRACE,
        }
    }

    /// The change for `negative` points in the set and `penetrating` points outside it (not
    /// both empty).
    fn next(&mut self, negative: &[usize], penetrating: &[usize]) -> Pivot {
        let infeasible = negative.len() + penetrating.len();
        let block = if infeasible < self.best {
            self.best = infeasible;
            self.grace = Self::GRACE;
            true
        } else if self.grace > 0 {
            self.grace -= 1;
            true
        } else {
            false
        };
        if block {
            if negative.is_empty() {
                Pivot::Add(penetrating.to_vec())
            } else {
                Pivot::Drop(negative.to_vec())
            }
        } else {
            let first = |s: &[usize]| s.iter().copied().min().unwrap_or(usize::MAX);
            let (drop, add) = (first(negative), first(penetrating));
            if drop < add {
                Pivot::Drop(vec![drop])
            } else {
                Pivot::Add(vec![add])
            }
        }
    }
}

/// The contact state of a subproblem's solution, after `steps` outer steps, with the set
/// changes counted before it.
pub(crate) fn finish(
    problem: &InterfaceProblem,
    method: Method,
    inner: Inner,
    active: Vec<bool>,
    steps: usize,
    counts: [usize; 2],
) -> ContactState {
    let s = inner.solution;
    let mut state = problem.state(
        method,
        s.pressure,
        s.rigid,
        active,
        [steps, counts[0] + inner.iterp, counts[1] + inner.iterd],
    );
    if let Some(halt) = inner.stopped {
        watch::end(&mut state, halt);
    }
    state
}

/// The QP (2.14) on the contact set `active` (updated by Kalker's iteration), from
/// `reference`: ρ = 0 with the pseudo-inverse, so nothing changes along the directions that
/// do not move the interface.
pub(crate) fn solve_exact(
    problem: &InterfaceProblem,
    reference: &Iterate,
    active: &mut [bool],
    watch: Watch,
) -> Result<Inner> {
    let zeros = vec![0.0; problem.len()];
    Subproblem::new(problem, 0.0, &zeros, true, reference)?.solve(active, watch)
}

/// The largest penalty parameter at which a subproblem is solved from scratch:
/// c_stiff = [`STIFF_RATIO`] / maxᵢ(Aᵢᵢ wᵢ). Larger parameters start from a c_stiff solution
/// (see [`Subproblem`]).
pub(crate) fn stiff_penalty(problem: &InterfaceProblem) -> Result<f64> {
    let a = problem.dense_influence(DENSE_COPIES)?;
    let scale = (0..problem.len())
        .map(|i| a[(i, i)] * problem.weights()[i])
        .fold(0.0, f64::max);
    if !(scale > 0.0) {
        return Err(Error::invalid(
            "influence",
            scale,
            "the bodies have no compliance at the interface (two rigid bodies?)",
        ));
    }
    Ok(STIFF_RATIO / scale)
}

/// A starting iterate for a subproblem with penalty `c`: zero, or for c above c_stiff the
/// penalty solution at c_stiff (whose small gap keeps the large-c solve accurate), its solves
/// added to `counts`; the stopped solve when it stopped short.
pub(crate) fn start(
    problem: &InterfaceProblem,
    c: f64,
    active: &mut [bool],
    counts: &mut [usize; 2],
    watch: Watch,
) -> Result<std::result::Result<Iterate, Inner>> {
    let (n, m) = (problem.len(), problem.load().len());
    let c_stiff = stiff_penalty(problem)?;
    let zero = Iterate::zero(n, m);
    if c <= c_stiff {
        return Ok(Ok(zero));
    }
    let zeros = vec![0.0; n];
    let pre = Subproblem::new(problem, 1.0 / c_stiff, &zeros, false, &zero)?
        .solve(active, watch.after(counts[0]))?;
    if pre.stopped.is_some() {
        return Ok(Err(pre));
    }
    counts[0] += pre.iterp;
    counts[1] += pre.iterd;
    Ok(Ok(pre.solution))
}

/// The penalty method: one subproblem with ρ = 1/c and p̂ = 0, so p = c⟨−d⟩.
pub(crate) fn penalty(problem: &InterfaceProblem, c: f64, watch: Watch) -> Result<ContactState> {
    let n = problem.len();
    let mut active = vec![true; n];
    let mut counts = [0, 0];
    let reference = match start(problem, c, &mut active, &mut counts, watch)? {
        Ok(reference) => reference,
        Err(stopped) => {
            return Ok(finish(problem, Method::Penalty, stopped, active, 1, counts));
        }
    };
    let zeros = vec![0.0; n];
    let spectral = c > stiff_penalty(problem)?;
    let inner = Subproblem::new(problem, 1.0 / c, &zeros, spectral, &reference)?
        .solve(&mut active, watch.after(counts[0]))?;
    Ok(finish(problem, Method::Penalty, inner, active, 1, counts))
}

/// The largest |dᵢ| over the contact set of a subproblem's solution.
pub(crate) fn open_on_contact(inner: &Inner, active: &[bool]) -> f64 {
    (0..active.len())
        .filter(|&i| active[i])
        .fold(0.0f64, |s, i| s.max(inner.gap[i].abs()))
}

/// The QP (2.14) itself: Kalker's iteration with ρ = 0, solving on each contact set with the
/// pseudo-inverse (see [`ContactMatrix`]), which gives the pressure of least Σ wᵢpᵢ² exactly,
/// whatever the conditioning of H. Without `start_set`, one penalty solve at c_stiff (by
/// Cholesky) first finds the contact set and a reference pressure, so that the spectral solves
/// are few.
pub(crate) fn exact(
    problem: &InterfaceProblem,
    start_set: Option<&[bool]>,
) -> Result<ContactState> {
    let silent = contopt_core::observe::Silent;
    exact_observed(problem, start_set, Watch::new(&silent, Method::ActiveSet))
}

/// [`exact`], reporting each of Kalker's solves to `watch`.
pub(crate) fn exact_observed(
    problem: &InterfaceProblem,
    start_set: Option<&[bool]>,
    watch: Watch,
) -> Result<ContactState> {
    let (n, m) = (problem.len(), problem.load().len());
    let zero = Iterate::zero(n, m);
    let mut counts = [0, 0];
    let method = Method::ActiveSet;
    let (mut active, pre) = match start_set {
        Some(set) => (set.to_vec(), None),
        None => {
            let mut active = vec![true; n];
            let zeros = vec![0.0; n];
            let rho = 1.0 / stiff_penalty(problem)?;
            let pre =
                Subproblem::new(problem, rho, &zeros, false, &zero)?.solve(&mut active, watch)?;
            if pre.stopped.is_some() {
                return Ok(finish(problem, method, pre, active, 1, counts));
            }
            counts = [pre.iterp, pre.iterd];
            (active, Some(pre.solution))
        }
    };
    let reference = pre.as_ref().unwrap_or(&zero);
    let inner = solve_exact(problem, reference, &mut active, watch.after(counts[0]))?;
    Ok(finish(problem, method, inner, active, 1, counts))
}

#[cfg(test)]
mod pivot_tests {
    use super::{Pivot, PivotRule};

    /// Block changes while the number of infeasible points reaches new lows, three more of
    /// grace, then one point at a time (the lowest index) until a new low.
    #[test]
    fn block_changes_fall_back_to_single_points() {
        let mut rule = PivotRule::new();
        assert_eq!(rule.next(&[4, 7], &[1]), Pivot::Drop(vec![4, 7]));
        assert_eq!(rule.next(&[], &[5, 2]), Pivot::Add(vec![5, 2]));
        for _ in 0..PivotRule::GRACE {
            assert_eq!(rule.next(&[9], &[3, 8]), Pivot::Drop(vec![9]));
        }
        assert_eq!(rule.next(&[9], &[3, 8]), Pivot::Add(vec![3]));
        assert_eq!(rule.next(&[6, 9], &[8]), Pivot::Drop(vec![6]));
        assert_eq!(rule.next(&[], &[8]), Pivot::Add(vec![8]));
    }
}
