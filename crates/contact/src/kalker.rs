//! The Kalker active-set iteration and the Uzawa loop shared by the penalty method, the
//! augmented Lagrangian and the active-set QP solver.

use contopt_core::{ContactState, Error, Result, Status};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use crate::InterfaceProblem;

/// The n × n matrices a Kalker solve holds at once: A, the contact-set matrix, its
/// eigenvectors and a product.
pub(crate) const DENSE_COPIES: u64 = 4;

/// A pressure and rigid-mode amplitudes: an iterate, or the reference a solve starts from.
#[derive(Clone, Debug)]
struct Iterate {
    pressure: Vec<f64>,
    rigid: Vec<f64>,
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
    /// eigenvector u counts as null when its eigenvalue is below 10⁻⁹ of its own diagonal
    /// scale Σᵢ uᵢ² Tᵢᵢ (scale-invariant: points of small weight near an axis are not null):
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
                if l > 1e-9 * scale {
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
struct Inner {
    solution: Iterate,
    /// Gap d of the solution.
    gap: Vec<f64>,
    /// Round-off level of the gap: 10⁻¹³ of its largest terms.
    gap_floor: f64,
    /// Solves, each followed by the sign check of p (the paper's `iterp`).
    iterp: usize,
    /// Penetration checks: the solves whose pressure had no negative value (the paper's
    /// `iterd`).
    iterd: usize,
    /// Why the iteration stopped short, with `solution` its last iterate; `None` when solved.
    stopped: Option<String>,
}

impl Inner {
    /// The contact set it started from was already the answer.
    fn unchanged(&self) -> bool {
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
struct Subproblem<'a> {
    problem: &'a InterfaceProblem<'a>,
    rho: f64,
    shift: &'a [f64],
    /// Solve spectrally (for ρ below the stiff level; see [`ContactMatrix`]).
    spectral: bool,
}

impl Subproblem<'_> {
    /// Kalker's iteration: solve with the points of `active` in contact (d + ρ(p − p̂) = 0
    /// there, p = 0 elsewhere; one `iterp`); drop the points whose pressure came out negative,
    /// else check the gap (one `iterd`) and add the points that penetrate; repeat until neither
    /// occurs. Changes follow [`PivotRule`], so the iteration cannot cycle.
    ///
    /// Each solve is in residual form: the correction to `reference` (restricted to the
    /// contact set) is driven by the reference's own residual −W(d + ρ(p − p̂)). Round-off in
    /// the data along the directions that do not move the interface (a semi-definite H) is
    /// amplified by c; in this form it multiplies the reference's residual instead of the whole
    /// gap, so a reference close to the answer keeps large c accurate.
    fn solve(&self, reference: &Iterate, active: &mut [bool]) -> Result<Inner> {
        let problem = self.problem;
        let (rho, shift) = (self.rho, self.shift);
        let n = problem.len();
        let m = problem.load().len();
        let (w, a, r, q) = (
            problem.weights(),
            problem.dense_influence(DENSE_COPIES)?,
            problem.rigid(),
            problem.load(),
        );
        let g = problem.free_gap();
        let gap_scale = g.iter().fold(0.0f64, |s, v| s.max(v.abs())).max(1e-300);
        let (mut iterp, mut iterd) = (0, 0);
        let max_solves = 4 * n + 20;
        let mut pivot = PivotRule::new();
        loop {
            if !active.iter().any(|&c| c) && m > 0 {
                // A floating body needs at least one contact point to be held.
                let closest = (0..n).min_by(|&i, &j| g[i].total_cmp(&g[j])).unwrap_or(0);
                active[closest] = true;
            }
            let idx: Vec<usize> = (0..n).filter(|&i| active[i]).collect();
            let k = idx.len();
            let mut solution = Iterate {
                pressure: vec![0.0; n],
                rigid: reference.rigid.clone(),
            };
            for &i in &idx {
                solution.pressure[i] = reference.pressure[i];
            }
            if k > 0 {
                let stop = |detail: String, solution: Iterate| {
                    let gap = problem.gap(&solution.pressure, &solution.rigid);
                    Ok(Inner {
                        solution,
                        gap,
                        gap_floor: 0.0,
                        iterp,
                        iterd,
                        stopped: Some(detail),
                    })
                };
                let Some(llt) = ContactMatrix::new(a, w, &idx, rho, self.spectral) else {
                    return stop(format!(
                        "the influence matrix is singular on the {k} contact points (penalty term rho = {rho:e}); \
                         use a finite penalty parameter or the augmented Lagrangian"
                    ), solution);
                };
                let d_ref = problem.gap(&solution.pressure, &solution.rigid);
                let b = Mat::from_fn(k, 1, |a_, _| {
                    let i = idx[a_];
                    -w[i] * (d_ref[i] + rho * (solution.pressure[i] - shift[i]))
                });
                let y = llt.solve(&b);
                let mut delta = y.clone();
                if m > 0 {
                    let bm = Mat::from_fn(k, m, |a_, c| w[idx[a_]] * r[(idx[a_], c)]);
                    let z = llt.solve(&bm);
                    let s = bm.transpose() * &z;
                    // Equilibrium of the correction: Rᵀ W δ = −q − Rᵀ W p_ref.
                    let rhs = Mat::from_fn(m, 1, |c, _| {
                        let held: f64 = (0..k)
                            .map(|a_| bm[(a_, c)] * solution.pressure[idx[a_]])
                            .sum();
                        (0..k).map(|a_| bm[(a_, c)] * y[(a_, 0)]).sum::<f64>() + q[c] + held
                    });
                    let Ok(gram) = Llt::new(s.as_ref(), Side::Lower) else {
                        return stop(
                            format!(
                                "the {k} contact points do not hold the rigid modes {:?}",
                                problem.mode_names()
                            ),
                            solution,
                        );
                    };
                    let lambda = gram.solve(&rhs);
                    delta = &y - &z * &lambda;
                    for (c, l) in solution.rigid.iter_mut().enumerate() {
                        *l += lambda[(c, 0)];
                    }
                }
                for (a_, &i) in idx.iter().enumerate() {
                    solution.pressure[i] += delta[(a_, 0)];
                }
            }
            let p = &solution.pressure;
            let p_scale = p.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let negative: Vec<usize> = idx
                .iter()
                .copied()
                .filter(|&i| p[i] < -1e-12 * p_scale)
                .collect();
            let d = problem.gap(p, &solution.rigid);
            let tol = 1e-11 * gap_scale.max(d.iter().fold(0.0f64, |s, v| s.max(v.abs())));
            let penetrating: Vec<usize> = (0..n)
                .filter(|&i| !active[i] && d[i] - rho * shift[i] < -tol)
                .collect();
            iterp += 1;
            if negative.is_empty() {
                iterd += 1;
            }
            if negative.is_empty() && penetrating.is_empty() {
                for v in solution.pressure.iter_mut() {
                    *v = v.max(0.0);
                }
                // d = g + A W p + R λ, with the elastic term balancing the others on C.
                let motion = (0..n)
                    .map(|i| {
                        (0..m)
                            .map(|c| r[(i, c)] * solution.rigid[c])
                            .sum::<f64>()
                            .abs()
                    })
                    .fold(0.0f64, f64::max);
                let gap_floor = 1e-13 * (gap_scale + motion);
                return Ok(Inner {
                    solution,
                    gap: d,
                    gap_floor,
                    iterp,
                    iterd,
                    stopped: None,
                });
            }
            match pivot.next(&negative, &penetrating) {
                Pivot::Drop(points) => points.into_iter().for_each(|i| active[i] = false),
                Pivot::Add(points) => points.into_iter().for_each(|i| active[i] = true),
            }
            if iterp >= max_solves {
                return Ok(Inner {
                    stopped: Some(format!(
                        "the contact set kept changing: {} points had negative pressure and {} penetrated \
                         at the last of {iterp} solves",
                        negative.len(),
                        penetrating.len()
                    )),
                    solution,
                    gap: d,
                    gap_floor: 0.0,
                    iterp,
                    iterd,
                });
            }
        }
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
fn finish(
    problem: &InterfaceProblem,
    inner: Inner,
    active: Vec<bool>,
    steps: usize,
    counts: [usize; 2],
) -> ContactState {
    let s = inner.solution;
    let mut state = problem.state(
        s.pressure,
        s.rigid,
        active,
        [steps, counts[0] + inner.iterp, counts[1] + inner.iterd],
    );
    if let Some(reason) = inner.stopped {
        state.status = Status::Stopped(format!("Kalker's active set: {reason}"));
    }
    state
}

/// The QP (2.14) on the contact set `active` (updated by Kalker's iteration), from
/// `reference`: ρ = 0 with the pseudo-inverse, so nothing changes along the directions that
/// do not move the interface.
fn solve_exact(
    problem: &InterfaceProblem,
    reference: &Iterate,
    active: &mut [bool],
) -> Result<Inner> {
    let zeros = vec![0.0; problem.len()];
    Subproblem {
        problem,
        rho: 0.0,
        shift: &zeros,
        spectral: true,
    }
    .solve(reference, active)
}

/// The largest penalty parameter at which a subproblem is solved from scratch:
/// c_stiff = 10⁶ / maxᵢ(Aᵢᵢ wᵢ), where the proximal term is 10⁻⁶ of the stiffest compliance.
/// Larger parameters start from a c_stiff solution (see [`Subproblem::solve`]).
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
    Ok(1e6 / scale)
}

/// A starting iterate for a subproblem with penalty `c`: zero, or for c above c_stiff the
/// penalty solution at c_stiff (whose small gap keeps the large-c solve accurate).
fn start(
    problem: &InterfaceProblem,
    c: f64,
    active: &mut [bool],
    counts: &mut [usize; 2],
) -> Result<std::result::Result<Iterate, Inner>> {
    let (n, m) = (problem.len(), problem.load().len());
    let c_stiff = stiff_penalty(problem)?;
    if c <= c_stiff {
        return Ok(Ok(Iterate::zero(n, m)));
    }
    let zeros = vec![0.0; n];
    let pre = Subproblem {
        problem,
        rho: 1.0 / c_stiff,
        shift: &zeros,
        spectral: false,
    }
    .solve(&Iterate::zero(n, m), active)?;
    if pre.stopped.is_some() {
        return Ok(Err(pre));
    }
    counts[0] += pre.iterp;
    counts[1] += pre.iterd;
    Ok(Ok(pre.solution))
}

/// The penalty method: one subproblem with ρ = 1/c and p̂ = 0, so p = c⟨−d⟩.
pub(crate) fn penalty(problem: &InterfaceProblem, c: f64) -> Result<ContactState> {
    let n = problem.len();
    let mut active = vec![true; n];
    let mut counts = [0, 0];
    let reference = match start(problem, c, &mut active, &mut counts)? {
        Ok(reference) => reference,
        Err(stopped) => return Ok(finish(problem, stopped, active, 1, counts)),
    };
    let zeros = vec![0.0; n];
    let inner = Subproblem {
        problem,
        rho: 1.0 / c,
        shift: &zeros,
        spectral: c > stiff_penalty(problem)?,
    }
    .solve(&reference, &mut active)?;
    Ok(finish(problem, inner, active, 1, counts))
}

/// Uzawa's iteration p⁽ᵏ⁺¹⁾ = ⟨p⁽ᵏ⁾ − c d⁽ᵏ⁾⟩ (2.19)–(2.20), each step a Kalker subproblem,
/// from p = 0 with every point in contact, until the pressure changes by less than
/// `tolerance`·p_max or the gap on the contact set is at round-off; with `accelerate`, until
/// a step leaves the contact set unchanged, when the iteration's limit is solved for directly.
pub(crate) fn uzawa(
    problem: &InterfaceProblem,
    c: f64,
    tolerance: f64,
    max_steps: usize,
    accelerate: bool,
) -> Result<ContactState> {
    let n = problem.len();
    let mut active = vec![true; n];
    let mut counts = [0, 0];
    let mut current = match start(problem, c, &mut active, &mut counts)? {
        Ok(reference) => reference,
        Err(stopped) => return Ok(finish(problem, stopped, active, 0, counts)),
    };
    let spectral = c > stiff_penalty(problem)?;
    let mut change = f64::INFINITY;
    for step in 1..=max_steps {
        let shift = current.pressure.clone();
        let inner = Subproblem {
            problem,
            rho: 1.0 / c,
            shift: &shift,
            spectral,
        }
        .solve(&current, &mut active)?;
        if inner.stopped.is_some() {
            return Ok(finish(problem, inner, active, step, counts));
        }
        counts[0] += inner.iterp;
        counts[1] += inner.iterd;
        let p_max = inner
            .solution
            .pressure
            .iter()
            .fold(0.0f64, |s, v| s.max(*v));
        change = inner
            .solution
            .pressure
            .iter()
            .zip(&shift)
            .fold(0.0f64, |s, (a, b)| s.max((a - b).abs()));
        let unchanged = inner.unchanged();
        current = inner.solution;
        if accelerate && unchanged {
            // The step left the contact set unchanged: the rest of Uzawa's iteration is linear,
            // and its fixed point is the exact solve on this set from the current iterate
            // (which keeps the iterate's components along directions that do not move the
            // interface, as the iteration would).
            let jump = solve_exact(problem, &current, &mut active)?;
            return Ok(finish(problem, jump, active, step, counts));
        }
        // Converged when the pressure settles, or when the gap on the contact set is at
        // round-off: with a large c, c·(round-off) would otherwise keep p drifting along the
        // directions that do not move the interface.
        let open_on_contact = (0..n)
            .filter(|&i| active[i])
            .fold(0.0f64, |s, i| s.max(inner.gap[i].abs()));
        if change <= tolerance * p_max.max(f64::MIN_POSITIVE) || open_on_contact <= inner.gap_floor
        {
            return Ok(problem.state(
                current.pressure,
                current.rigid,
                active,
                [step, counts[0], counts[1]],
            ));
        }
    }
    let mut state = problem.state(
        current.pressure,
        current.rigid,
        active,
        [max_steps, counts[0], counts[1]],
    );
    state.status = Status::Stopped(format!(
        "Uzawa's {max_steps} steps: last pressure change {change:.3e} MPa, p_max {:.6} MPa; raise the penalty parameter c = {c:e} or the step limit",
        state.p_max(),
    ));
    Ok(state)
}

/// The QP (2.14) itself: Kalker's iteration with ρ = 0, solving on each contact set with the
/// pseudo-inverse (eigenvalues below 10⁻⁹ of the largest count as null), which gives the
/// pressure of least Σ wᵢpᵢ² exactly, whatever the conditioning of H. Without `start_set`,
/// one penalty solve at c_stiff (by Cholesky) first finds the contact set and a reference
/// pressure, so that the spectral solves are few.
pub(crate) fn exact(
    problem: &InterfaceProblem,
    start_set: Option<&[bool]>,
) -> Result<ContactState> {
    let (n, m) = (problem.len(), problem.load().len());
    let zeros = vec![0.0; n];
    let mut counts = [0, 0];
    let (mut active, reference) = match start_set {
        Some(set) => (set.to_vec(), Iterate::zero(n, m)),
        None => {
            let mut active = vec![true; n];
            let rho = 1.0 / stiff_penalty(problem)?;
            let pre = Subproblem {
                problem,
                rho,
                shift: &zeros,
                spectral: false,
            }
            .solve(&Iterate::zero(n, m), &mut active)?;
            if pre.stopped.is_some() {
                return Ok(finish(problem, pre, active, 1, counts));
            }
            counts = [pre.iterp, pre.iterd];
            (active, pre.solution)
        }
    };
    let inner = solve_exact(problem, &reference, &mut active)?;
    Ok(finish(problem, inner, active, 1, counts))
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
