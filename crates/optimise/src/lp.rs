//! The restricted linear programme (3.5) by clarabel.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::{Error, Region, Result};

use crate::{Iteration, Optimisation, Optimum};

/// The n × n arrays of a pass held at once: A, its rows, the triplets and the CSC matrix, and
/// the interior point's factor.
const LP_COPIES: u64 = 10;

/// Relative size of a pressure (of p_max) or a gap (of the gap unit) below which a point counts
/// as being at the edge of contact when the next pass is restricted.
const EDGE: f64 = 1e-6;

/// A constraint row: its (column, coefficient) entries and its right-hand side.
type Row = (Vec<(usize, f64)>, f64);

/// How a point enters a pass of the programme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Restriction {
    /// p ≥ 0 and d ≥ 0 (the relaxed first pass).
    Free,
    /// In contact: d = 0 (always on Ω_v).
    Closed,
    /// Open: p = 0.
    Open,
}

impl Optimisation<'_> {
    /// The linear programme (3.5): minimise p_max over p, Δh and λ subject to equilibrium
    /// Rᵀ W p = −q, p ≥ 0, χ = v·p_max − p ≥ 0 on Ω_opt (= 0 on Ω_v),
    /// d = g + A W p + R λ + QΔh ≥ 0 (= 0 on Ω_v), Δh ≥ 0 and Δh = 0 at the reference node.
    ///
    /// The complementarity pᵀd = 0 is kept by restriction: the programme is solved without
    /// it; while some point outside Ω_v carries pressure across an open gap, the contact
    /// problem is solved on the programme's gap and its contact set restricts
    /// the next pass, d = 0 on the points in contact and p = 0 on the others, until a pass is
    /// complementary (on a one-dimensional region, where Ω_v is everything, the first is). The
    /// contact solves use `contact_solver`. Dense: it needs the influence matrix
    /// ([`InterfaceProblem::dense_influence`]); large problems take
    /// [`Optimisation::load_split`].
    /// Without a floating body the displacement is given, and N fixes the shape: Δh = 0 there.
    pub fn linear_programme(&self, contact_solver: &dyn ContactSolver) -> Result<Optimum> {
        let problem = self.problem;
        let n = problem.len();
        let (w, a, rigid, q) = (
            problem.weights(),
            problem.dense_influence(LP_COPIES)?,
            problem.rigid(),
            problem.load(),
        );
        let r = q.len();
        let g = problem.free_gap();
        let free = self.free_nodes();
        let nf = free.len();
        // Units: P for pressures, G = P·max(A W 1) for gaps, so the columns are of order one.
        let compliance = (0..n)
            .map(|i| (0..n).map(|j| a[(i, j)] * w[j]).sum::<f64>().abs())
            .fold(0.0, f64::max);
        let area: f64 = w.iter().sum();
        let unit_p = if r > 0 {
            q.iter().map(|x| x.abs()).fold(0.0, f64::max) / area
        } else {
            g.iter().map(|x| x.abs()).fold(0.0, f64::max) / compliance
        };
        if !(unit_p > 0.0 && unit_p.is_finite()) {
            return Err(Error::invalid(
                "loads",
                unit_p,
                "neither a load nor an overlap presses the bodies together",
            ));
        }
        let unit_g = unit_p * compliance;
        let rigid_scale = (0..r)
            .map(|m| (0..n).map(|i| rigid[(i, m)].abs()).fold(0.0, f64::max))
            .collect::<Vec<_>>();
        // Variables: p (n) | p_max (at i_max) | Δh on the free nodes (nf, from ih) | λ (r, from il).
        let (i_max, ih, il) = (n, n + 1, n + 1 + nf);
        let nvar = il + r;
        let mut column_of = vec![usize::MAX; self.shape.nodes().len()];
        for (c, &k) in free.iter().enumerate() {
            column_of[k] = ih + c;
        }
        let omega_v = |i: usize| self.regions[i] == Region::OmegaV;
        let in_opt = |i: usize| self.regions[i] != Region::Contact;
        let mut restricted: Vec<Restriction> = (0..n)
            .map(|i| {
                if omega_v(i) {
                    Restriction::Closed
                } else {
                    Restriction::Free
                }
            })
            .collect();
        let mut tried = vec![restricted.clone()];
        let mut passes = 0;
        loop {
            passes += 1;
            // Rows as (coefficients, b); zero-cone rows first, then non-negative ones:
            // zero: a·x = b; non-negative: b − a·x ≥ 0.
            let (mut zero, mut nonneg): (Vec<Row>, Vec<Row>) = (vec![], vec![]);
            for m in 0..r {
                let row = (0..n)
                    .map(|i| (i, rigid[(i, m)] * w[i] / (area * rigid_scale[m])))
                    .collect();
                zero.push((row, -q[m] / (unit_p * area * rigid_scale[m])));
            }
            for i in 0..n {
                // d_i / G = g_i/G + Σ A_ij w_j P/G p̃_j + Σ R_im λ_m/G + Σ Q_ik Δh̃_k.
                let mut row: Vec<(usize, f64)> = (0..n)
                    .map(|j| (j, a[(i, j)] * w[j] * unit_p / unit_g))
                    .collect();
                for m in 0..r {
                    row.push((il + m, rigid[(i, m)] / rigid_scale[m]));
                }
                for &(k, wt) in self.shape.row(i) {
                    if column_of[k] != usize::MAX {
                        row.push((column_of[k], wt));
                    }
                }
                let c = g[i] / unit_g;
                if restricted[i] == Restriction::Closed {
                    zero.push((row, -c));
                } else {
                    let negated = row.into_iter().map(|(j, v)| (j, -v)).collect();
                    nonneg.push((negated, c));
                }
                if restricted[i] == Restriction::Open {
                    zero.push((vec![(i, 1.0)], 0.0));
                }
                if omega_v(i) {
                    zero.push((vec![(i, 1.0), (i_max, -self.v[i])], 0.0));
                } else if in_opt(i) {
                    nonneg.push((vec![(i, 1.0), (i_max, -self.v[i])], 0.0));
                }
                // p ≥ 0 where p is not fixed already: a bound that holds with equality leaves
                // the programme no interior, and the interior point stalls.
                if !omega_v(i) && restricted[i] != Restriction::Open {
                    nonneg.push((vec![(i, -1.0)], 0.0));
                }
            }
            for c in 0..nf {
                nonneg.push((vec![(ih + c, -1.0)], 0.0));
            }
            let (nz, nn) = (zero.len(), nonneg.len());
            let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
            for (row_index, (row, rhs)) in zero.into_iter().chain(nonneg).enumerate() {
                for (j, v) in row {
                    ii.push(row_index);
                    jj.push(j);
                    vv.push(v);
                }
                b.push(rhs);
            }
            let cons = CscMatrix::new_from_triplets(nz + nn, nvar, ii, jj, vv);
            let hess = CscMatrix::zeros((nvar, nvar));
            let mut objective = vec![0.0; nvar];
            objective[i_max] = 1.0;
            let cones = [
                SupportedConeT::ZeroConeT(nz),
                SupportedConeT::NonnegativeConeT(nn),
            ];
            let settings = DefaultSettingsBuilder::default()
                .verbose(false)
                .tol_feas(1e-10)
                .tol_gap_abs(1e-10)
                .tol_gap_rel(1e-10)
                .max_iter(200)
                .build()
                .map_err(|e| Error::invalid("linear programme", format!("{e:?}"), "settings"))?;
            let mut solver = DefaultSolver::new(&hess, &objective, &cons, &b, &cones, settings)
                .map_err(|e| {
                    Error::invalid("linear programme", format!("{e:?}"), "clarabel rejected it")
                })?;
            solver.solve();
            let sol = &solver.solution;
            match sol.status {
                SolverStatus::Solved | SolverStatus::AlmostSolved => {}
                SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                    return Err(Error::invalid(
                        "optimisation",
                        "(3.5)",
                        "is infeasible: no Δh ≥ 0 closes Ω_v under v·p_max with these loads",
                    ))
                }
                status => {
                    return Err(Error::NotConverged {
                        method: "linear programme (3.5)".into(),
                        iterations: sol.iterations as usize,
                        detail: format!(
                            "status {status:?}, primal residual {:.3e}, dual residual {:.3e}",
                            sol.r_prim, sol.r_dual
                        ),
                    })
                }
            }
            let pressure: Vec<f64> = sol.x[..n].iter().map(|p| p.max(0.0) * unit_p).collect();
            let p_max = sol.x[i_max] * unit_p;
            let mut dh = vec![0.0; self.shape.nodes().len()];
            for (c, &k) in free.iter().enumerate() {
                dh[k] = sol.x[ih + c].max(0.0) * unit_g;
            }
            let lambda: Vec<f64> = (0..r)
                .map(|m| sol.x[il + m] * unit_g / rigid_scale[m])
                .collect();
            let gap_change = self.shape.apply(&dh);
            let mut gap = problem.gap(&pressure, &lambda);
            for (d, c) in gap.iter_mut().zip(&gap_change) {
                *d += c;
            }
            let violated = (0..n)
                .filter(|&i| pressure[i] > 1e-8 * p_max && gap[i] > 1e-8 * unit_g)
                .count();
            if violated == 0 {
                return Ok(Optimum {
                    p_max,
                    iterations: vec![Iteration {
                        k: passes,
                        p_max,
                        dh_max: dh.iter().fold(0.0, |m: f64, v| m.max(*v)),
                        tolh: 0.0,
                        iterp: sol.iterations as usize,
                        iterd: 0,
                    }],
                    dh,
                    gap_change,
                    pressure,
                    gap,
                    rigid: lambda,
                });
            }
            // Restrict the next pass by the contact set of the programme's gap.
            let h: Vec<f64> = problem
                .initial_gap()
                .iter()
                .zip(&gap_change)
                .map(|(a, b)| a + b)
                .collect();
            let contact = contact_solver
                .solve(&problem.with_initial_gap(&h)?)?
                .solved(contact_solver.name())?;
            // Points at the edge of contact, with both p and d at round-off, stay free: forcing
            // them closed or open leaves the programme no interior, and the interior point
            // stalls (a 40 × 21 roller did).
            let contact_p_max = contact.p_max();
            for (i, r) in restricted.iter_mut().enumerate() {
                if !omega_v(i) {
                    *r = if contact.pressure[i] > EDGE * contact_p_max {
                        Restriction::Closed
                    } else if contact.gap[i] > EDGE * unit_g {
                        Restriction::Open
                    } else {
                        Restriction::Free
                    };
                }
            }
            if tried.contains(&restricted) {
                return Err(Error::NotConverged {
                    method: "linear programme (3.5)".into(),
                    iterations: passes,
                    detail: format!(
                        "the contact sets of its passes repeat; {violated} points carry pressure \
                         across an open gap (p_max {p_max:.6} MPa)"
                    ),
                });
            }
            tried.push(restricted.clone());
        }
    }
}
