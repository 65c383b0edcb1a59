//! The iteration of §3.2, steps 1–7, with a contact solver inside.

use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::{Error, Region, Result};
use faer::linalg::solvers::{ColPivQr, SolveLstsq};
use faer::Mat;

use crate::{Optimisation, Optimum};

/// What is given on the bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The load on a floating body (Tables 1 and 3): p_max follows from its equilibrium,
    /// p_max·Rᵀ W v = −q − Rᵀ W p (over the points outside Ω_v).
    GivenLoad,
    /// A displacement (Table 2): p_max is the largest contact pressure on Ω_opt (step 4).
    GivenDisplacement,
}

/// One row of the iteration (the columns of Table 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Iteration {
    /// Iteration number k.
    pub k: usize,
    /// p_max of step 4 \[MPa\].
    pub p_max: f64,
    /// Largest gap change Δh⁽ᵏ⁾ \[mm\].
    pub dh_max: f64,
    /// TOLH = Σⱼ (Δhⱼ⁽ᵏ⁾ − Δhⱼ⁽ᵏ⁻¹⁾)² over the design nodes \[mm²\] (4.2).
    pub tolh: f64,
    /// Kalker's primal (contact-set) iterations of the contact solve.
    pub iterp: usize,
    /// Kalker's dual (Uzawa) iterations of the contact solve.
    pub iterd: usize,
}

impl Optimisation<'_> {
    /// The iteration of §3.2: solve the contact problem with the gap h₀ + QΔh⁽ᵏ⁻¹⁾ (step 3),
    /// take p_max (step 4: under a given displacement, the largest pressure on Ω_opt read as a
    /// field, [`InterfaceProblem::recovered_pressure`], so that a sawtooth of Gauss-point values
    /// that moves nothing cannot set it), prescribe p = v·p_max on Ω_v (step 5), and choose Δh⁽ᵏ⁾ so that the
    /// gap closes on Ω_v under that pressure up to a uniform shift, Δh = 0 at the reference
    /// node N: Δh = −(m − m_N) (step 6, through a least-squares fit of Q, exact when Q
    /// interpolates like the displacements); stop
    /// when TOLH (4.2) ≤ `tolh` \[mm²\] (the paper: 0.5·10⁻⁶), at most `max_iterations`.
    ///
    /// Under [`Mode::GivenLoad`] the loop closes in two passes when Ω_v is the whole region:
    /// the second contact solve, on the optimised gap, reproduces v·p_max and changes nothing.
    pub fn iterate(
        &self,
        mode: Mode,
        solver: &dyn ContactSolver,
        tolh: f64,
        max_iterations: usize,
    ) -> Result<Optimum> {
        if !(tolh > 0.0) {
            return Err(Error::invalid("tolh", tolh, "must be positive"));
        }
        let problem = self.problem;
        let (n, r) = (problem.len(), problem.load().len());
        match (mode, r) {
            (Mode::GivenLoad, 0) => {
                return Err(Error::invalid(
                    "mode",
                    "given load",
                    "no body floats, so no load is given: use the given displacement",
                ))
            }
            (Mode::GivenDisplacement, r) if r > 0 => {
                return Err(Error::invalid(
                    "mode",
                    "given displacement",
                    format!("{r} rigid mode(s) float: support the bodies or give the load"),
                ))
            }
            _ => {}
        }
        let omega_v = self.omega_v();
        let fit = StepSix::new(self, &omega_v)?;
        let h0 = problem.initial_gap();
        let in_opt = |i: usize| self.regions[i] != Region::Contact;
        let mut dh = vec![0.0; self.shape.nodes().len()];
        let mut rows: Vec<Iteration> = vec![];
        let mut warm: Option<Vec<f64>> = None;
        for k in 1..=max_iterations {
            // Steps 3–4, each contact solve starting from the previous pressure.
            let change = self.shape.apply(&dh);
            let h: Vec<f64> = h0.iter().zip(&change).map(|(a, b)| a + b).collect();
            let trial = problem.with_initial_gap(&h)?;
            let state = match &warm {
                Some(p) => solver.solve_from(&trial, p)?,
                None => solver.solve(&trial)?,
            }
            .solved(solver.name())?;
            warm = Some(state.pressure.clone());
            let p_max = match mode {
                Mode::GivenDisplacement => {
                    let field = problem.recovered_pressure(&state.pressure)?;
                    (0..n)
                        .filter(|&i| in_opt(i))
                        .map(|i| field[i])
                        .fold(0.0, f64::max)
                }
                Mode::GivenLoad => self.equilibrium_p_max(&state.pressure)?,
            };
            // Step 5.
            let mut p = state.pressure.clone();
            for &i in &omega_v {
                p[i] = self.v[i] * p_max;
            }
            // Step 6: the residual gap on Ω_v with the original initial gap h₀.
            let m = problem.gap(&p, &state.rigid);
            let fitted = fit.solve(&omega_v.iter().map(|&i| -m[i]).collect::<Vec<_>>());
            // Q's rows sum to one, so subtracting Δh_N from every node moves the gap by −m_N
            // everywhere: the uniform part of the residual (the approach, a rigid translation)
            // is left to the contact solver and the gap does not change at N.
            let at_n = fitted[self.reference];
            let next: Vec<f64> = fitted.iter().map(|v| v - at_n).collect();
            let tolh_k: f64 = next.iter().zip(&dh).map(|(a, b)| (a - b).powi(2)).sum();
            dh = next;
            rows.push(Iteration {
                k,
                p_max,
                dh_max: dh.iter().fold(0.0, |a: f64, b| a.max(*b)),
                tolh: tolh_k,
                iterp: state.iterp,
                iterd: state.iterd,
            });
            // Step 7.
            if tolh_k <= tolh {
                self.check_sign(&dh)?;
                let gap_change = self.shape.apply(&dh);
                return Ok(Optimum {
                    p_max,
                    dh,
                    gap_change,
                    pressure: state.pressure,
                    gap: state.gap,
                    rigid: state.rigid,
                    iterations: rows,
                });
            }
        }
        let last = rows.last().map_or(f64::NAN, |r| r.tolh);
        Err(Error::NotConverged {
            method: "gap iteration (§3.2)".into(),
            iterations: max_iterations,
            detail: format!("TOLH = {last:.3e} mm² (tolerance {tolh:.1e})"),
        })
    }

    /// p_max of a given load: the least-squares solution over the rigid modes of
    /// p_max·(Rᵀ W v)_Ω_v + (Rᵀ W p)_rest = −q; fails when the loads cannot be carried by
    /// v·p_max (a moment against a symmetric controller, say) or would need p_max ≤ 0.
    pub(crate) fn equilibrium_p_max(&self, pressure: &[f64]) -> Result<f64> {
        let problem = self.problem;
        let (w, q) = (problem.weights(), problem.load());
        let (mut a, mut b) = (vec![0.0; q.len()], vec![0.0; q.len()]);
        for (m, mode) in problem.modes().iter().enumerate() {
            for (&i, &r) in mode.points.iter().zip(&mode.displacement) {
                if self.regions[i] == Region::OmegaV {
                    a[m] += r * w[i] * self.v[i];
                } else {
                    b[m] += r * w[i] * pressure[i];
                }
            }
        }
        let aa: f64 = a.iter().map(|x| x * x).sum();
        let p_max = -(0..q.len()).map(|m| a[m] * (b[m] + q[m])).sum::<f64>() / aa;
        for m in 0..q.len() {
            let residual = p_max * a[m] + b[m] + q[m];
            if residual.abs() > 1e-9 * q[m].abs().max(aa.sqrt() * p_max.abs()) {
                return Err(Error::invalid(
                    format!("load on {}", problem.mode_names()[m]),
                    q[m],
                    format!("cannot be carried by v·p_max (unbalanced by {residual:.3e} N)"),
                ));
            }
        }
        if !(p_max > 0.0) {
            return Err(Error::invalid(
                "p_max",
                p_max,
                "the given load needs a positive pressure",
            ));
        }
        Ok(p_max)
    }
}

/// Step 6's least-squares fit of Q on the rows of Ω_v, min ‖Q_Ω_v Δh − b‖, from the structure
/// of Q: when every Ω_v row reaches one node (a pointwise or an extruded shape), the normal
/// equations are diagonal and Δh_k is the weighted mean of b over its rows; otherwise (the
/// quadratic face rows of a finite-element body, a short 1-D region) a dense pivoted QR.
enum StepSix {
    Diagonal {
        /// (node, weight) of each Ω_v row.
        rows: Vec<(usize, f64)>,
        /// Σ weight² per node.
        norms: Vec<f64>,
    },
    /// The QR factors and the number of nodes.
    Qr(ColPivQr<f64>, usize),
}

impl StepSix {
    fn new(opt: &Optimisation, omega_v: &[usize]) -> Result<Self> {
        let nodes = opt.shape.nodes().len();
        let single: Option<Vec<(usize, f64)>> = omega_v
            .iter()
            .map(|&i| match opt.shape.row(i) {
                [one] => Some(*one),
                _ => None,
            })
            .collect();
        if let Some(rows) = single {
            let mut norms = vec![0.0; nodes];
            for &(k, wt) in &rows {
                norms[k] += wt * wt;
            }
            return Ok(StepSix::Diagonal { rows, norms });
        }
        let bytes = (omega_v.len() as u64)
            .saturating_mul(nodes as u64)
            .saturating_mul(16);
        let limit = opt.problem.dense_limit();
        if bytes > limit {
            return Err(Error::TooLarge {
                what: format!("step 6's dense {} × {nodes} fit of Q", omega_v.len()),
                bytes,
                limit,
                advice: "give the gap shape one node per point row (pointwise or extruded)".into(),
            });
        }
        let mut fit = Mat::<f64>::zeros(omega_v.len(), nodes);
        for (a, &i) in omega_v.iter().enumerate() {
            for &(k, wt) in opt.shape.row(i) {
                fit[(a, k)] += wt;
            }
        }
        Ok(StepSix::Qr(fit.col_piv_qr(), nodes))
    }

    /// Δh at every node from the right-hand side b on the Ω_v rows.
    fn solve(&self, b: &[f64]) -> Vec<f64> {
        match self {
            StepSix::Diagonal { rows, norms } => {
                let mut dh = vec![0.0; norms.len()];
                for (&(k, wt), b) in rows.iter().zip(b) {
                    dh[k] += wt * b;
                }
                for (v, n) in dh.iter_mut().zip(norms) {
                    if *n > 0.0 {
                        *v /= n;
                    }
                }
                dh
            }
            StepSix::Qr(qr, nodes) => {
                let mut rhs = Mat::<f64>::from_fn(b.len(), 1, |a, _| b[a]);
                qr.solve_lstsq_in_place(rhs.as_mut());
                (0..*nodes).map(|k| rhs[(k, 0)]).collect()
            }
        }
    }
}
