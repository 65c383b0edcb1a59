//! The complementary-energy QP (2.14) by the interior-point solver clarabel.

use contopt_core::observe::{Method, Observer};
use contopt_core::{check, ContactState, Error, Result, Stall, Termination};
use serde::{Deserialize, Serialize};

use crate::conic::{self, CscMatrix, Outcome, Solution};
use crate::watch;
use crate::{kalker, problem, ContactSolver, InterfaceProblem, Workspace};

/// The n × n arrays of a solve held at once: the upper triangle as triplets and CSC (three
/// n²/2 arrays) and the factor's fill.
const QP_COPIES: u64 = 5;

/// Relative accuracy of the interior point's pressures and approaches at its tolerance: a
/// pressure below it times p_max is out of contact, and the polish's approach must agree with
/// clarabel's to it (convergence).
const INTERIOR_POINT_ACCURACY: f64 = 1e-6;

/// An approach below this \[mm\] counts as zero when the polish is compared with it
/// (round-off).
const ZERO_APPROACH: f64 = 1e-12;

/// min ½ pᵀ H p − pᵀ t  subject to  p ≥ 0,  G_Rᵀ p = q  (2.14), with H = W A W, t = −W g,
/// G_R = W R, by clarabel. The reference solver: exact to its tolerance, but its cost grows
/// like n³ with a dense H (about 2 s at 1000 points).
///
/// With a semi-definite H (three Gauss points per quadratic finite-element face outnumber the
/// face's displacement unknowns) the QP's minimisers share d and λ but not p. An interior
/// point alone returns the centre of that set, whose pressure oscillates from point to point.
/// So the answer is polished: clarabel's contact set and λ are kept, and the pressure is
/// re-solved on that set by proximal active-set steps from p = 0, which give the minimiser of
/// least Σ wᵢ pᵢ² (the limit of the penalty method, and the pressure the other solvers
/// return) exactly, instead of to the interior point's tolerance.
#[derive(Clone, Copy, Debug)]
pub struct Qp {
    settings: QpSettings,
}

/// The settings of the [`Qp`] solver.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct QpSettings {
    /// Feasibility and duality-gap tolerance (clarabel's tol_feas, tol_gap_abs, tol_gap_rel).
    pub tolerance: f64,
}

impl Default for QpSettings {
    fn default() -> Self {
        Self {
            tolerance: conic::TOLERANCE,
        }
    }
}

impl Qp {
    /// The solver with `settings`, checked: the tolerance in (0, 1).
    pub fn new(settings: QpSettings) -> Result<Self> {
        check::between("tolerance", settings.tolerance, 0.0, 1.0)?;
        Ok(Self { settings })
    }

    /// Its settings.
    pub fn settings(&self) -> &QpSettings {
        &self.settings
    }
}

impl ContactSolver for Qp {
    fn method(&self) -> Method {
        Method::Qp
    }

    fn dense_copies(&self, _points: usize) -> u64 {
        QP_COPIES
    }

    /// clarabel reports nothing per iteration (its only hook, a termination callback, cannot
    /// hold a borrowed observer): the observer sees the solve's end alone. Solves from scratch.
    fn solve_in(
        &self,
        problem: &InterfaceProblem,
        _start: Option<&[f64]>,
        observer: &dyn Observer,
        _workspace: &mut Workspace,
    ) -> Result<ContactState> {
        let state = self.interior_point(problem)?;
        watch::announce(observer, &state);
        Ok(state)
    }
}

impl Qp {
    fn interior_point(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        let qp = ScaledQp::new(problem)?;
        let m = problem.load().len();
        let sol = conic::solve(
            &qp.hessian,
            &qp.linear,
            &qp.constraints,
            &qp.b,
            m,
            self.settings.tolerance,
            "QP data",
        )?;
        match &sol.outcome {
            Outcome::Solved => polish(problem, &sol, Termination::Converged),
            Outcome::ReducedAccuracy(reduced) => polish(problem, &sol, reduced.clone()),
            Outcome::Infeasible => Err(Error::invalid(
                "loads",
                format!("{:?}", problem.load()),
                "cannot be equilibrated by compressive contact",
            )),
            Outcome::Unbounded => Err(Error::invalid(
                "influence",
                "not positive definite",
                "the complementary energy is unbounded: a free rigid mode moves no point",
            )),
            Outcome::Stopped(why) => Ok(last_iterate(problem, &sol, qp.scale, why.clone())),
        }
    }
}

/// The QP (2.14) in clarabel's form, with the pressure scaled by `scale` so that the
/// Hessian's diagonal is of order one: x = s·p.
struct ScaledQp {
    /// The upper triangle of W A W / s².
    hessian: CscMatrix<f64>,
    /// W g / s.
    linear: Vec<f64>,
    /// The equilibrium rows (W R)ᵀ / s (zero cone) above −I (p ≥ 0).
    constraints: CscMatrix<f64>,
    /// −q, then zeros.
    b: Vec<f64>,
    /// s = maxᵢ wᵢ √Aᵢᵢ.
    scale: f64,
}

impl ScaledQp {
    fn new(problem: &InterfaceProblem) -> Result<Self> {
        let (n, m) = (problem.len(), problem.load().len());
        let (w, a, r) = (
            problem.weights(),
            problem.dense_influence(QP_COPIES)?,
            problem.rigid(),
        );
        let s = (0..n)
            .map(|i| w[i] * a[(i, i)] * w[i])
            .fold(0.0, f64::max)
            .sqrt();
        problem::compliance(s)?;
        let (mut colptr, mut rowval, mut nzval) = (vec![0], vec![], vec![]);
        for j in 0..n {
            for i in 0..=j {
                rowval.push(i);
                nzval.push(w[i] * a[(i, j)] * w[j] / (s * s));
            }
            colptr.push(rowval.len());
        }
        let g = problem.free_gap();
        let (mut ii, mut jj, mut vv) = (vec![], vec![], vec![]);
        for j in 0..n {
            for k in 0..m {
                ii.push(k);
                jj.push(j);
                vv.push(w[j] * r[(j, k)] / s);
            }
            ii.push(m + j);
            jj.push(j);
            vv.push(-1.0);
        }
        let mut b = vec![0.0; m + n];
        for (k, q) in problem.load().iter().enumerate() {
            b[k] = -q;
        }
        Ok(Self {
            hessian: CscMatrix::new(n, n, colptr, rowval, nzval),
            linear: (0..n).map(|i| w[i] * g[i] / s).collect(),
            constraints: CscMatrix::new_from_triplets(m + n, n, ii, jj, vv),
            b,
            scale: s,
        })
    }
}

/// The polish on clarabel's contact set (see [`Qp`]): the exact QP on the points whose
/// pressure exceeds [`INTERIOR_POINT_ACCURACY`]·p_max, checked against clarabel's own
/// rigid-body approach. A polish that agrees ends as `accuracy` says clarabel ended
/// ([`Termination::Converged`] or [`Termination::ReducedAccuracy`]).
fn polish(
    problem: &InterfaceProblem,
    sol: &Solution,
    accuracy: Termination,
) -> Result<ContactState> {
    let m = problem.load().len();
    let p_max = sol.x.iter().fold(0.0f64, |a, &b| a.max(b));
    let contact: Vec<bool> = sol
        .x
        .iter()
        .map(|&x| x > INTERIOR_POINT_ACCURACY * p_max)
        .collect();
    let mut state = kalker::exact(problem, Some(&contact))?;
    state.method = Method::Qp;
    let disagreement = state
        .rigid
        .iter()
        .zip(&sol.z[..m])
        .enumerate()
        .find(|(_, (mine, theirs))| {
            (*mine - *theirs).abs() > INTERIOR_POINT_ACCURACY * theirs.abs().max(ZERO_APPROACH)
        })
        .map(
            |(mode, (&polished, &interior_point))| Stall::PolishDisagrees {
                mode,
                polished,
                interior_point,
            },
        );
    if let Some(cause) = disagreement {
        watch::end(&mut state, Termination::Stalled { cause });
    } else if state.is_converged() {
        state.termination = accuracy;
    }
    state.iterations = sol.iterations;
    Ok(state)
}

/// clarabel's last iterate of a programme that stopped short, with its own rigid amplitudes
/// and why it stopped.
fn last_iterate(
    problem: &InterfaceProblem,
    sol: &Solution,
    scale: f64,
    why: Termination,
) -> ContactState {
    let m = problem.load().len();
    let pressure: Vec<f64> = sol.x.iter().map(|&x| x.max(0.0) / scale).collect();
    let active = pressure.iter().map(|&p| p > 0.0).collect();
    let rigid = sol.z[..m].to_vec();
    let mut state = problem.state(Method::Qp, pressure, rigid, active, [sol.iterations, 0, 0]);
    watch::end(&mut state, why);
    state
}
