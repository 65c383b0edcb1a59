//! The Kalker active-set iteration and the Uzawa loop shared by the penalty method, the
//! augmented Lagrangian and the active-set QP solver.

use contopt_core::{ContactState, Error, Result};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use crate::InterfaceProblem;

/// Solution of one subproblem on its final active set.
struct Inner {
    pressure: Vec<f64>,
    rigid: Vec<f64>,
    /// Gap d of the solution.
    gap: Vec<f64>,
    /// Round-off level of the gap: 10⁻¹³ of its largest terms.
    gap_floor: f64,
    iterp: usize,
    iterd: usize,
}

/// Solves the proximal subproblem
///
/// min ½ pᵀ (H + ρW) p + pᵀ W (g − ρ p̂)  over  p ≥ 0,  Rᵀ W p = −q,
///
/// whose solution is p = ⟨p̂ − c d⟩ with c = 1/ρ: eq. (2.19) with the gap d of the new
/// state, i.e. one augmented-Lagrangian step (2.18)–(2.20); with p̂ = 0 it is the penalty
/// method. Kalker's iteration: solve with the points of `active` in contact
/// (d + ρ(p − p̂) = 0 there, p = 0 elsewhere); drop the points whose pressure came out negative
/// (one `iterp`), else add the points that penetrate (one `iterd`); repeat until neither occurs.
fn solve_inner(
    problem: &InterfaceProblem,
    rho: f64,
    shift: &[f64],
    active: &mut [bool],
) -> Result<Inner> {
    let n = problem.len();
    let m = problem.load().len();
    let (w, a, r, q) = (
        problem.weights(),
        problem.influence(),
        problem.rigid(),
        problem.load(),
    );
    let g = problem.free_gap();
    let gap_scale = g.iter().fold(0.0f64, |s, v| s.max(v.abs())).max(1e-300);
    let (mut iterp, mut iterd) = (0, 0);
    let max_changes = 4 * n + 20;
    loop {
        if !active.iter().any(|&c| c) && m > 0 {
            // A floating body needs at least one contact point to be held.
            let closest = (0..n).min_by(|&i, &j| g[i].total_cmp(&g[j])).unwrap_or(0);
            active[closest] = true;
        }
        let idx: Vec<usize> = (0..n).filter(|&i| active[i]).collect();
        let k = idx.len();
        let mut pressure = vec![0.0; n];
        let mut rigid = vec![0.0; m];
        if k > 0 {
            let mat = Mat::from_fn(k, k, |a_, b_| {
                let (i, j) = (idx[a_], idx[b_]);
                w[i] * a[(i, j)] * w[j] + if a_ == b_ { rho * w[i] } else { 0.0 }
            });
            let llt = Llt::new(mat.as_ref(), Side::Lower).map_err(|_| Error::NotConverged {
                method: "Kalker active set".into(),
                iterations: iterp + iterd,
                detail: format!(
                    "the influence matrix is singular on the {k} contact points (penalty term rho = {rho:e}); \
                     use a finite penalty parameter or the augmented Lagrangian"
                ),
            })?;
            let b = Mat::from_fn(k, 1, |a_, _| {
                let i = idx[a_];
                w[i] * (-g[i] + rho * shift[i])
            });
            let y = llt.solve(&b);
            let mut p_c = y.clone();
            if m > 0 {
                let bm = Mat::from_fn(k, m, |a_, c| w[idx[a_]] * r[(idx[a_], c)]);
                let z = llt.solve(&bm);
                let s = bm.transpose() * &z;
                let rhs = Mat::from_fn(m, 1, |c, _| {
                    (0..k).map(|a_| bm[(a_, c)] * y[(a_, 0)]).sum::<f64>() + q[c]
                });
                let lambda = Llt::new(s.as_ref(), Side::Lower)
                    .map_err(|_| Error::NotConverged {
                        method: "Kalker active set".into(),
                        iterations: iterp + iterd,
                        detail: format!(
                            "the {k} contact points do not hold the rigid modes {:?}",
                            problem.mode_names()
                        ),
                    })?
                    .solve(&rhs);
                p_c = &y - &z * &lambda;
                for (c, l) in rigid.iter_mut().enumerate() {
                    *l = lambda[(c, 0)];
                }
            }
            for (a_, &i) in idx.iter().enumerate() {
                pressure[i] = p_c[(a_, 0)];
            }
        }
        let p_scale = pressure.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let negative: Vec<usize> = idx
            .iter()
            .copied()
            .filter(|&i| pressure[i] < -1e-12 * p_scale)
            .collect();
        if !negative.is_empty() {
            for i in negative {
                active[i] = false;
            }
            iterp += 1;
        } else {
            let d = problem.gap(&pressure, &rigid);
            let tol = 1e-11 * gap_scale.max(d.iter().fold(0.0f64, |s, v| s.max(v.abs())));
            let penetrating: Vec<usize> = (0..n)
                .filter(|&i| !active[i] && d[i] - rho * shift[i] < -tol)
                .collect();
            if penetrating.is_empty() {
                for p in pressure.iter_mut() {
                    *p = p.max(0.0);
                }
                // d = g + A W p + R λ, with the elastic term balancing the others on C.
                let motion = (0..n)
                    .map(|i| (0..m).map(|c| r[(i, c)] * rigid[c]).sum::<f64>().abs())
                    .fold(0.0f64, f64::max);
                let gap_floor = 1e-13 * (gap_scale + motion);
                return Ok(Inner {
                    pressure,
                    rigid,
                    gap: d,
                    gap_floor,
                    iterp,
                    iterd,
                });
            }
            for i in penetrating {
                active[i] = true;
            }
            iterd += 1;
        }
        if iterp + iterd > max_changes {
            return Err(Error::NotConverged {
                method: "Kalker active set".into(),
                iterations: iterp + iterd,
                detail: format!("the contact set kept changing ({iterp} for negative pressure, {iterd} for penetration)"),
            });
        }
    }
}

/// The penalty method: one subproblem with ρ = 1/c and p̂ = 0, so p = c⟨−d⟩.
pub(crate) fn penalty(problem: &InterfaceProblem, c: f64) -> Result<ContactState> {
    let n = problem.len();
    let mut active = vec![true; n];
    let inner = solve_inner(problem, 1.0 / c, &vec![0.0; n], &mut active)?;
    Ok(problem.state(
        inner.pressure,
        inner.rigid,
        active,
        [1, inner.iterp, inner.iterd],
    ))
}

/// Uzawa's iteration p⁽ᵏ⁺¹⁾ = ⟨p⁽ᵏ⁾ − c d⁽ᵏ⁾⟩ (2.19)–(2.20), each step a Kalker subproblem,
/// from p = 0 and the contact set `start` (every point when `None`), until the pressure
/// changes by less than `tolerance`·p_max.
pub(crate) fn uzawa(
    problem: &InterfaceProblem,
    c: f64,
    tolerance: f64,
    max_steps: usize,
    start: Option<&[bool]>,
) -> Result<ContactState> {
    let n = problem.len();
    let mut shift = vec![0.0; n];
    let mut active = start.map_or_else(|| vec![true; n], <[bool]>::to_vec);
    let (mut iterp, mut iterd) = (0, 0);
    let mut change = f64::INFINITY;
    let mut rigid = vec![0.0; problem.load().len()];
    for step in 1..=max_steps {
        let inner = solve_inner(problem, 1.0 / c, &shift, &mut active)?;
        iterp += inner.iterp;
        iterd += inner.iterd;
        let p_max = inner.pressure.iter().fold(0.0f64, |s, v| s.max(*v));
        change = inner
            .pressure
            .iter()
            .zip(&shift)
            .fold(0.0f64, |s, (a, b)| s.max((a - b).abs()));
        shift = inner.pressure;
        rigid = inner.rigid;
        // Converged when the pressure settles, or when the gap on the contact set is at
        // round-off: with a large c, c·(round-off) would otherwise keep p drifting along the
        // directions that do not move the interface.
        let open_on_contact = (0..n)
            .filter(|&i| active[i])
            .fold(0.0f64, |s, i| s.max(inner.gap[i].abs()));
        if change <= tolerance * p_max.max(f64::MIN_POSITIVE) || open_on_contact <= inner.gap_floor
        {
            return Ok(problem.state(shift, rigid, active, [step, iterp, iterd]));
        }
    }
    let state = problem.state(shift, rigid, active, [max_steps, iterp, iterd]);
    Err(Error::NotConverged {
        method: "augmented Lagrangian (Uzawa)".into(),
        iterations: max_steps,
        detail: format!(
            "last pressure change {change:.3e} MPa, p_max {:.6} MPa, penetration {:.3e} mm; raise the penalty parameter c = {c:e} or the step limit",
            state.p_max(),
            state.residuals.penetration
        ),
    })
}

/// A penalty parameter that makes each proximal step nearly exact: c = 10⁶ / maxᵢ(Aᵢᵢ wᵢ).
pub(crate) fn stiff_penalty(problem: &InterfaceProblem) -> Result<f64> {
    let a = problem.influence();
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
