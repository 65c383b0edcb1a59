//! The iteration of §3.2, steps 1–7, with a contact solver inside.

use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::observe::Flow;
use contopt_core::{ContactState, Error, Result};
use faer::linalg::solvers::{ColPivQr, SolveLstsq};
use faer::Mat;

use crate::{Optimisation, Optimum, Region, ROUND_OFF};

/// The loop's name in messages.
const GAP_ITERATION: &str = "gap iteration (§3.2)";

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
    /// field, [`InterfaceProblem::recovered_pressure`], so that a sawtooth of Gauss-point
    /// values that moves nothing cannot set it), prescribe p = v·p_max on Ω_v (step 5), and
    /// choose Δh⁽ᵏ⁾ so that the gap closes on Ω_v under that pressure up to a uniform shift,
    /// Δh = 0 at the reference node N: Δh = −(m − m_N) (step 6, through a least-squares fit of
    /// Q, exact when Q interpolates like the displacements); stop when TOLH (4.2) ≤ `tolh`
    /// \[mm²\] (the paper: 0.5·10⁻⁶), at most `max_iterations` (step 7). Each pass is reported
    /// to the observer ([`Optimisation::with_observer`]) with its TOLH.
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
        self.check_mode(mode)?;
        let omega_v = self.omega_v();
        let fit = StepSix::new(self, &omega_v)?;
        let mut dh = vec![0.0; self.shape.nodes().len()];
        let mut rows: Vec<Iteration> = vec![];
        let mut warm: Option<Vec<f64>> = None;
        for k in 1..=max_iterations {
            // Steps 3–4, each contact solve starting from the previous pressure.
            let change = self.shape.apply(&dh);
            let state =
                self.solve_with_gap_change(solver, self.problem, &change, warm.as_deref())?;
            let p_max = self.step_four(mode, &state.pressure)?;
            // Steps 5–6.
            let next = self.steps_five_and_six(&fit, &omega_v, &state, p_max);
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
            let flow = self.report(k, tolh_k, tolh);
            // Step 7.
            if tolh_k <= tolh {
                self.check_sign(&dh)?;
                return Ok(Optimum {
                    p_max,
                    gap_change: self.shape.apply(&dh),
                    dh,
                    pressure: state.pressure,
                    gap: state.gap,
                    rigid: state.rigid,
                    iterations: rows,
                });
            }
            if flow == Flow::Stop {
                let detail = format!("TOLH = {tolh_k:.3e} mm² (tolerance {tolh:.1e})");
                return Err(Self::stopped(GAP_ITERATION, k, detail));
            }
            warm = Some(state.pressure);
        }
        let last = rows.last().map_or(f64::NAN, |r| r.tolh);
        Err(Error::NotConverged {
            method: GAP_ITERATION.into(),
            iterations: max_iterations,
            detail: format!("TOLH = {last:.3e} mm² (tolerance {tolh:.1e})"),
        })
    }

    /// The mode fits the bodies: a given load needs a floating body, a given displacement
    /// none.
    fn check_mode(&self, mode: Mode) -> Result<()> {
        match (mode, self.problem.load().len()) {
            (Mode::GivenLoad, 0) => Err(Error::invalid(
                "mode",
                "given load",
                "no body floats, so no load is given: use the given displacement",
            )),
            (Mode::GivenDisplacement, r) if r > 0 => Err(Error::invalid(
                "mode",
                "given displacement",
                format!("{r} rigid mode(s) float: support the bodies or give the load"),
            )),
            _ => Ok(()),
        }
    }

    /// Step 4: p_max of the contact pressure. Under a given displacement, the largest
    /// pressure on Ω_opt read as a field ([`InterfaceProblem::recovered_pressure`]); under a
    /// given load, the value equilibrium asks of v·p_max
    /// ([`Optimisation::equilibrium_p_max`]).
    fn step_four(&self, mode: Mode, pressure: &[f64]) -> Result<f64> {
        match mode {
            Mode::GivenDisplacement => {
                let field = self.problem.recovered_pressure(pressure)?;
                Ok((0..field.len())
                    .filter(|&i| self.regions[i] != Region::Contact)
                    .map(|i| field[i])
                    .fold(0.0, f64::max))
            }
            Mode::GivenLoad => self.equilibrium_p_max(pressure),
        }
    }

    /// Steps 5–6: prescribe p = v·p_max on Ω_v, take the residual gap m on Ω_v with the
    /// original initial gap h₀ and fit Δh = −(m − m_N) through Q.
    fn steps_five_and_six(
        &self,
        fit: &StepSix,
        omega_v: &[usize],
        state: &ContactState,
        p_max: f64,
    ) -> Vec<f64> {
        let mut p = state.pressure.clone();
        for &i in omega_v {
            p[i] = self.v[i] * p_max;
        }
        let m = self.problem.gap(&p, &state.rigid);
        let fitted = fit.solve(&omega_v.iter().map(|&i| -m[i]).collect::<Vec<_>>());
        // Q's rows sum to one, so subtracting Δh_N from every node moves the gap by −m_N
        // everywhere: the uniform part of the residual (the approach, a rigid translation)
        // is left to the contact solver and the gap does not change at N.
        let at_n = fitted[self.reference];
        fitted.iter().map(|v| v - at_n).collect()
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
            if residual.abs() > ROUND_OFF * q[m].abs().max(aa.sqrt() * p_max.abs()) {
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
