//! The restricted linear programme (3.5) by clarabel.

use contopt_contact::conic::{self, CscMatrix, Outcome};
use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::observe::Flow;
use contopt_core::{Error, Result};
use faer::Mat;

use crate::{Iteration, Optimisation, Optimum, Region, SOLVER_ACCURACY};

/// The n × n arrays of a pass held at once: A, its rows, the triplets and the CSC matrix, and
/// the interior point's factor.
const LP_COPIES: u64 = 10;

/// Relative pressure (of p_max) and gap (of the gap unit) above which a point of a pass's
/// solution carries pressure across an open gap: two orders above the interior point's
/// tolerance (convergence).
const COMPLEMENTARITY: f64 = 1e-8;

/// The programme's name in messages.
const LINEAR_PROGRAMME: &str = "linear programme (3.5)";

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
    /// contact solves use `contact_solver`; each pass is reported to the observer
    /// ([`Optimisation::with_observer`]) with its number of such points. Dense: it needs the
    /// influence matrix ([`InterfaceProblem::dense_influence`]); large problems take
    /// [`Optimisation::load_split`].
    /// Without a floating body the displacement is given, and N fixes the shape: Δh = 0 there.
    pub fn linear_programme(&self, contact_solver: &dyn ContactSolver) -> Result<Optimum> {
        let lp = Programme::new(self)?;
        let mut restricted: Vec<Restriction> = (0..lp.n)
            .map(|i| {
                if self.regions[i] == Region::OmegaV {
                    Restriction::Closed
                } else {
                    Restriction::Free
                }
            })
            .collect();
        let mut tried = vec![restricted.clone()];
        let mut pass = 0;
        loop {
            pass += 1;
            let (optimum, violated) = lp.solve(&restricted, pass)?;
            let flow = self.report(pass, violated as f64, 0.0);
            if violated == 0 {
                return Ok(optimum);
            }
            let detail = format!(
                "{violated} points carry pressure across an open gap (p_max {:.6} MPa)",
                optimum.p_max
            );
            if flow == Flow::Stop {
                return Err(Self::stopped(LINEAR_PROGRAMME, pass, detail));
            }
            restricted = lp.restrict(contact_solver, &optimum.gap_change)?;
            if tried.contains(&restricted) {
                return Err(Error::NotConverged {
                    method: LINEAR_PROGRAMME.into(),
                    iterations: pass,
                    detail: format!("the contact sets of its passes repeat; {detail}"),
                });
            }
            tried.push(restricted.clone());
        }
    }
}

/// The data of (3.5) in units that make its columns of order one: P for pressures, G =
/// P·max(A W 1) for gaps, each rigid mode by its largest displacement. The variables are
/// p (n) | p_max (at `i_max`) | Δh on the free design nodes (from `ih`) | λ (r, from `il`).
struct Programme<'o, 'a> {
    opt: &'o Optimisation<'a>,
    n: usize,
    /// The influence matrix A \[mm/N\].
    a: &'o Mat<f64>,
    /// The rigid modes R.
    rigid: Mat<f64>,
    /// The free gap g \[mm\].
    g: Vec<f64>,
    /// The design nodes other than the reference.
    free: Vec<usize>,
    /// The variable of each design node's Δh (`usize::MAX` at the reference).
    column_of: Vec<usize>,
    area: f64,
    unit_p: f64,
    unit_g: f64,
    rigid_scale: Vec<f64>,
    i_max: usize,
    ih: usize,
    il: usize,
}

impl<'o, 'a> Programme<'o, 'a> {
    fn new(opt: &'o Optimisation<'a>) -> Result<Self> {
        let problem = opt.problem;
        let n = problem.len();
        let (w, a, rigid, q) = (
            problem.weights(),
            problem.dense_influence(LP_COPIES)?,
            problem.rigid(),
            problem.load(),
        );
        let g = problem.free_gap();
        let compliance = (0..n)
            .map(|i| (0..n).map(|j| a[(i, j)] * w[j]).sum::<f64>().abs())
            .fold(0.0, f64::max);
        let area: f64 = w.iter().sum();
        let unit_p = if q.is_empty() {
            g.iter().map(|x| x.abs()).fold(0.0, f64::max) / compliance
        } else {
            q.iter().map(|x| x.abs()).fold(0.0, f64::max) / area
        };
        if !(unit_p > 0.0 && unit_p.is_finite()) {
            return Err(Error::invalid(
                "loads",
                unit_p,
                "neither a load nor an overlap presses the bodies together",
            ));
        }
        let rigid_scale = (0..q.len())
            .map(|m| (0..n).map(|i| rigid[(i, m)].abs()).fold(0.0, f64::max))
            .collect();
        let free = opt.free_nodes();
        let (i_max, ih, il) = (n, n + 1, n + 1 + free.len());
        let mut column_of = vec![usize::MAX; opt.shape.nodes().len()];
        for (c, &k) in free.iter().enumerate() {
            column_of[k] = ih + c;
        }
        Ok(Self {
            opt,
            n,
            a,
            rigid,
            g,
            free,
            column_of,
            area,
            unit_p,
            unit_g: unit_p * compliance,
            rigid_scale,
            i_max,
            ih,
            il,
        })
    }

    /// The number of rigid modes.
    fn modes(&self) -> usize {
        self.rigid_scale.len()
    }

    /// The rows of a pass: equalities (a·x = b) and inequalities (written b − a·x ≥ 0).
    fn rows(&self, restricted: &[Restriction]) -> (Vec<Row>, Vec<Row>) {
        let (opt, n) = (self.opt, self.n);
        let (w, q) = (opt.problem.weights(), opt.problem.load());
        let (mut zero, mut nonneg): (Vec<Row>, Vec<Row>) = (vec![], vec![]);
        // Equilibrium, Rᵀ W p = −q.
        for (m, q) in q.iter().enumerate() {
            let scale = self.area * self.rigid_scale[m];
            let row = (0..n)
                .map(|i| (i, self.rigid[(i, m)] * w[i] / scale))
                .collect();
            zero.push((row, -q / (self.unit_p * scale)));
        }
        for (i, &restriction) in restricted.iter().enumerate() {
            let (row, c) = self.gap_row(i);
            match restriction {
                Restriction::Closed => zero.push((row, -c)),
                _ => {
                    let negated = row.into_iter().map(|(j, v)| (j, -v)).collect();
                    nonneg.push((negated, c));
                    if restriction == Restriction::Open {
                        zero.push((vec![(i, 1.0)], 0.0));
                    }
                }
            }
            // χ = v·p_max − p: zero on Ω_v, non-negative on Ω_nv.
            let chi = vec![(i, 1.0), (self.i_max, -opt.v[i])];
            match opt.regions[i] {
                Region::OmegaV => zero.push((chi, 0.0)),
                Region::OmegaNv => nonneg.push((chi, 0.0)),
                Region::Contact => {}
            }
            // p ≥ 0 where p is not fixed already: a bound that holds with equality leaves
            // the programme no interior, and the interior point stalls.
            if opt.regions[i] != Region::OmegaV && restriction != Restriction::Open {
                nonneg.push((vec![(i, -1.0)], 0.0));
            }
        }
        // Δh ≥ 0.
        for c in 0..self.free.len() {
            nonneg.push((vec![(self.ih + c, -1.0)], 0.0));
        }
        (zero, nonneg)
    }

    /// The gap at point `i` in gap units, d_i / G = g_i/G + Σ A_ij w_j P/G p̃_j + Σ R_im λ̃_m
    /// + Σ Q_ik Δh̃_k, as its coefficients and its constant g_i/G.
    fn gap_row(&self, i: usize) -> Row {
        let (opt, n) = (self.opt, self.n);
        let w = opt.problem.weights();
        let mut row: Vec<(usize, f64)> = (0..n)
            .map(|j| (j, self.a[(i, j)] * w[j] * self.unit_p / self.unit_g))
            .collect();
        for m in 0..self.modes() {
            row.push((self.il + m, self.rigid[(i, m)] / self.rigid_scale[m]));
        }
        for &(k, wt) in opt.shape.row(i) {
            if self.column_of[k] != usize::MAX {
                row.push((self.column_of[k], wt));
            }
        }
        (row, self.g[i] / self.unit_g)
    }

    /// Solves pass number `pass` under `restricted`: its optimum in physical units and the
    /// number of points that carry pressure across an open gap.
    fn solve(&self, restricted: &[Restriction], pass: usize) -> Result<(Optimum, usize)> {
        let (zero, nonneg) = self.rows(restricted);
        let nvar = self.il + self.modes();
        let nz = zero.len();
        let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
        for (row_index, (row, rhs)) in zero.into_iter().chain(nonneg).enumerate() {
            for (j, v) in row {
                ii.push(row_index);
                jj.push(j);
                vv.push(v);
            }
            b.push(rhs);
        }
        let constraints = CscMatrix::new_from_triplets(b.len(), nvar, ii, jj, vv);
        let mut objective = vec![0.0; nvar];
        objective[self.i_max] = 1.0;
        let sol = conic::solve(
            &CscMatrix::zeros((nvar, nvar)),
            &objective,
            &constraints,
            &b,
            nz,
            conic::TOLERANCE,
            LINEAR_PROGRAMME,
        )?;
        match sol.outcome {
            Outcome::Solved => Ok(self.optimum(&sol.x, sol.iterations, pass)),
            Outcome::Infeasible => Err(Error::invalid(
                "optimisation",
                "(3.5)",
                "is infeasible: no Δh ≥ 0 closes Ω_v under v·p_max with these loads",
            )),
            Outcome::Stopped(detail) => Err(Error::NotConverged {
                method: LINEAR_PROGRAMME.into(),
                iterations: sol.iterations,
                detail,
            }),
        }
    }

    /// A pass's solution `x` in physical units, as an optimum whose one row counts the
    /// passes, with the number of points that carry pressure across an open gap.
    fn optimum(&self, x: &[f64], iterations: usize, pass: usize) -> (Optimum, usize) {
        let (opt, n) = (self.opt, self.n);
        let pressure: Vec<f64> = x[..n].iter().map(|p| p.max(0.0) * self.unit_p).collect();
        let p_max = x[self.i_max] * self.unit_p;
        let mut dh = vec![0.0; opt.shape.nodes().len()];
        for (c, &k) in self.free.iter().enumerate() {
            dh[k] = x[self.ih + c].max(0.0) * self.unit_g;
        }
        let lambda: Vec<f64> = (0..self.modes())
            .map(|m| x[self.il + m] * self.unit_g / self.rigid_scale[m])
            .collect();
        let gap_change = opt.shape.apply(&dh);
        let mut gap = opt.problem.gap(&pressure, &lambda);
        for (d, c) in gap.iter_mut().zip(&gap_change) {
            *d += c;
        }
        let violated = (0..n)
            .filter(|&i| {
                pressure[i] > COMPLEMENTARITY * p_max && gap[i] > COMPLEMENTARITY * self.unit_g
            })
            .count();
        let row = Iteration {
            k: pass,
            p_max,
            dh_max: dh.iter().fold(0.0, |m: f64, v| m.max(*v)),
            tolh: 0.0,
            iterp: iterations,
            iterd: 0,
        };
        let optimum = Optimum {
            p_max,
            dh,
            gap_change,
            pressure,
            gap,
            rigid: lambda,
            iterations: vec![row],
        };
        (optimum, violated)
    }

    /// The restrictions of the next pass: the contact set of the contact problem on the gap
    /// changed by `gap_change`. Points at the edge of contact, with both p and d within
    /// [`SOLVER_ACCURACY`] of p_max and the gap unit, stay free: forcing them closed or open
    /// leaves the programme no interior, and the interior point stalls (a 40 × 21 roller did).
    fn restrict(
        &self,
        contact_solver: &dyn ContactSolver,
        gap_change: &[f64],
    ) -> Result<Vec<Restriction>> {
        let opt = self.opt;
        let contact = opt.solve_with_gap_change(contact_solver, opt.problem, gap_change, None)?;
        let p_max = contact.p_max();
        Ok((0..self.n)
            .map(|i| {
                if opt.regions[i] == Region::OmegaV || contact.pressure[i] > SOLVER_ACCURACY * p_max
                {
                    Restriction::Closed
                } else if contact.gap[i] > SOLVER_ACCURACY * self.unit_g {
                    Restriction::Open
                } else {
                    Restriction::Free
                }
            })
            .collect())
    }
}
