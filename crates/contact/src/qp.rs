//! The complementary-energy QP (2.14) by the interior-point solver clarabel.

use clarabel::algebra::CscMatrix;
use clarabel::solver::{
    DefaultSettingsBuilder, DefaultSolver, IPSolver, SolverStatus, SupportedConeT,
};
use contopt_core::{ContactState, Error, Result, Status};

use crate::{kalker, ContactSolver, InterfaceProblem};

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
    /// Feasibility and duality-gap tolerance (clarabel's tol_feas, tol_gap_abs, tol_gap_rel).
    pub tolerance: f64,
}

impl Default for Qp {
    fn default() -> Self {
        Self { tolerance: 1e-10 }
    }
}

impl ContactSolver for Qp {
    fn name(&self) -> &str {
        "QP (clarabel)"
    }

    fn solve(&self, problem: &InterfaceProblem) -> Result<ContactState> {
        let n = problem.len();
        let m = problem.load().len();
        // The upper triangle as triplets and CSC (three n²/2 arrays) and the factor's fill.
        const QP_COPIES: u64 = 5;
        let (w, a, r) = (
            problem.weights(),
            problem.dense_influence(QP_COPIES)?,
            problem.rigid(),
        );
        let g = problem.free_gap();
        // Scale pressures so the Hessian's diagonal is of order one.
        let s = (0..n)
            .map(|i| w[i] * a[(i, i)] * w[i])
            .fold(0.0, f64::max)
            .sqrt();
        if !(s > 0.0) {
            return Err(Error::invalid(
                "influence",
                s,
                "the bodies have no compliance at the interface",
            ));
        }
        let (mut colptr, mut rowval, mut nzval) = (vec![0], vec![], vec![]);
        for j in 0..n {
            for i in 0..=j {
                rowval.push(i);
                nzval.push(w[i] * a[(i, j)] * w[j] / (s * s));
            }
            colptr.push(rowval.len());
        }
        let hess = CscMatrix::new(n, n, colptr, rowval, nzval);
        let lin: Vec<f64> = (0..n).map(|i| w[i] * g[i] / s).collect();
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
        let cons = CscMatrix::new_from_triplets(m + n, n, ii, jj, vv);
        let mut b = vec![0.0; m + n];
        for (k, q) in problem.load().iter().enumerate() {
            b[k] = -q;
        }
        let mut cones = vec![];
        if m > 0 {
            cones.push(SupportedConeT::ZeroConeT(m));
        }
        cones.push(SupportedConeT::NonnegativeConeT(n));
        let settings = DefaultSettingsBuilder::default()
            .verbose(false)
            .tol_feas(self.tolerance)
            .tol_gap_abs(self.tolerance)
            .tol_gap_rel(self.tolerance)
            .max_iter(200)
            .build()
            .map_err(|e| Error::invalid("solver.tolerance", self.tolerance, format!("{e:?}")))?;
        let mut solver =
            DefaultSolver::new(&hess, &lin, &cons, &b, &cones, settings).map_err(|e| {
                Error::invalid("QP data", format!("{e:?}"), "clarabel rejected the problem")
            })?;
        solver.solve();
        let sol = &solver.solution;
        match sol.status {
            SolverStatus::Solved | SolverStatus::AlmostSolved => {}
            SolverStatus::PrimalInfeasible | SolverStatus::AlmostPrimalInfeasible => {
                return Err(Error::invalid(
                    "loads",
                    format!("{:?}", problem.load()),
                    "cannot be equilibrated by compressive contact",
                ));
            }
            status => {
                // clarabel's last iterate, with its own rigid amplitudes and the status.
                let pressure = sol.x.iter().map(|&x| x.max(0.0) / s).collect::<Vec<_>>();
                let active = pressure.iter().map(|&p| p > 0.0).collect();
                let rigid = sol.z[..m].to_vec();
                let mut state =
                    problem.state(pressure, rigid, active, [sol.iterations as usize, 0, 0]);
                state.status = Status::Stopped(format!(
                    "clarabel status {status:?}, primal residual {:.3e}, dual residual {:.3e}",
                    sol.r_prim, sol.r_dual
                ));
                return Ok(state);
            }
        }
        // Polish on clarabel's contact set (see the type's documentation).
        let p_max = sol.x.iter().fold(0.0f64, |a, &b| a.max(b));
        let contact: Vec<bool> = sol.x.iter().map(|&x| x > 1e-6 * p_max).collect();
        let mut state = kalker::exact(problem, Some(&contact))?;
        // The polish must reproduce clarabel's own rigid-body approach.
        for (k, (&mine, &theirs)) in state.rigid.iter().zip(&sol.z[..m]).enumerate() {
            if (mine - theirs).abs() > 1e-6 * theirs.abs().max(1e-12) {
                state.status = Status::Stopped(format!("polished rigid amplitude {k} = {mine:e} disagrees with the interior point's {theirs:e}"));
            }
        }
        state.iterations = sol.iterations as usize;
        Ok(state)
    }
}
