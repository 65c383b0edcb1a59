//! The iteration of §3.2, steps 1–7, with a contact solver inside.

use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::drive::Step;
use contopt_core::observe::Method;
#[cfg(doc)]
use contopt_core::Termination;
use contopt_core::{check, ContactState, Error, Result};
use faer::linalg::solvers::{ColPivQr, SolveLstsq};
use faer::Mat;

use crate::passes::Passes;
use crate::{IterationSettings, Optimisation, Optimum, Region, ROUND_OFF, SOLVER_ACCURACY};

/// How far below v·p_max \[of p_max\] the pressure on Ω_v, read as a field, may end for the
/// iteration of §3.2 to stop: measured at the paper's Table 2 (TOLH met) 0.39, 1.36, 0.56,
/// 1.10 % and below; a flat punch held at 1 µm met TOLH with its rim at 0.58 of p_max, p_max
/// 4 to 15 % above the linear programme's.
const OMEGA_V_EVEN: f64 = 0.05;

/// What is given on the bodies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Mode {
    /// The load on a floating body (Tables 1 and 3): p_max follows from its equilibrium,
    /// p_max·Rᵀ W v = −q − Rᵀ W p (over the points outside Ω_v).
    GivenLoad,
    /// A displacement (Table 2): p_max is the largest contact pressure on Ω_opt (step 4).
    GivenDisplacement,
}

/// One pass of an optimisation loop (the columns of Table 2).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Pass {
    /// The pass number k, from 1.
    pub k: usize,
    /// p_max of step 4 \[MPa\].
    pub p_max: f64,
    /// Largest gap change Δh⁽ᵏ⁾ the pass computed \[mm\].
    pub dh_max: f64,
    /// TOLH = Σⱼ (Δhⱼ⁽ᵏ⁾ − Δhⱼ⁽ᵏ⁻¹⁾)² over the design nodes \[mm²\] (4.2); 0 for the linear
    /// programme.
    pub tolh: f64,
    /// The contact solver's steps in the pass, summed over its solves: Kalker's solves on a
    /// contact set (the paper's I_terp, [`ContactState::iterp`]), or a solver's own
    /// iterations when it has no such solves; for the linear programme, the interior point's
    /// iterations.
    pub iterp: usize,
    /// Kalker's penetration checks (the paper's I_terd, [`ContactState::iterd`]), summed over
    /// the pass's contact solves; 0 for a solver without them.
    pub iterd: usize,
}

impl Pass {
    /// The row of pass `k` with p_max, the gap change `dh` and TOLH, counting the solver
    /// steps of `states`.
    pub(crate) fn new<'s>(
        k: usize,
        p_max: f64,
        dh: &[f64],
        tolh: f64,
        states: impl IntoIterator<Item = &'s ContactState>,
    ) -> Self {
        let (mut iterp, mut iterd) = (0, 0);
        for s in states {
            iterp += s.iterp.max(s.iterations);
            iterd += s.iterd;
        }
        Self {
            k,
            p_max,
            dh_max: dh.iter().fold(0.0, |a: f64, b| a.max(*b)),
            tolh,
            iterp,
            iterd,
        }
    }
}

/// The last completed pass: its contact solution, the gap change it was solved with and its
/// p_max.
type Iterate = (ContactState, Vec<f64>, f64);

impl Optimisation<'_> {
    /// The iteration of §3.2: solve the contact problem with the gap h₀ + QΔh⁽ᵏ⁻¹⁾ (step 3),
    /// take p_max (step 4: under a given displacement, the largest pressure on Ω_opt read as a
    /// field, [`InterfaceProblem::recovered_pressure`], so that a sawtooth of Gauss-point
    /// values that moves nothing cannot set it), prescribe p = v·p_max on Ω_v (step 5), and
    /// choose Δh⁽ᵏ⁾ so that the gap closes on Ω_v under that pressure up to a uniform shift,
    /// Δh = 0 at the reference node N: Δh = −(m − m_N) (step 6, through a least-squares fit of
    /// Q, exact when Q interpolates like the displacements; under [`crate::Reference::Least`]
    /// N is where −m is least, so min Δh = 0); stop when TOLH (4.2) ≤
    /// [`IterationSettings::tolh_mm2`] (the paper: 0.5·10⁻⁶ mm²) and the pass's pressure on
    /// Ω_v falls short of v·p_max by at most 5 % of p_max (TOLH is absolute in mm², which gap
    /// changes of a fraction of a micrometre meet from their first passes) or Δh has stopped
    /// moving (its change within 10⁻⁹ of its size: the checks of the optimum then say why Ω_v
    /// is not held), after at most [`IterationSettings::max_iterations`] passes (step 7). Each
    /// pass is reported to the observer ([`Optimisation::with_observer`]) with its TOLH.
    ///
    /// The optimum holds the last contact solution with the gap change it was solved with.
    /// A contact solve that does not converge ends the loop with [`Termination::Inner`],
    /// holding the last finite solution (the first solve's own state, without a gap change,
    /// when it is the first).
    ///
    /// Under [`Mode::GivenLoad`] the loop closes in two passes when Ω_v is the whole region:
    /// the second contact solve, on the optimised gap, reproduces v·p_max and changes nothing.
    ///
    /// On Ω_nv the paper's steps prescribe nothing, while (3.4) asks χ = v·p_max − p ≥ 0: a
    /// point of Ω_nv whose pressure a pass finds above v·p_max joins Ω_v in steps 5–6 (χ = 0
    /// and d = 0 prescribed there from then on) when step 6's fit reaches several nodes per
    /// row (a finite-element face). Where every row reaches one node (a roller's columns) its
    /// gap change is its column's, which Ω_v closes: an optimum with p above v·p_max there
    /// ends as [`Termination::Infeasible`], naming the point.
    pub fn iterate(
        &self,
        mode: Mode,
        solver: &dyn ContactSolver,
        settings: &IterationSettings,
    ) -> Result<Optimum> {
        settings.check()?;
        self.check_mode(mode)?;
        let mut prescribed = Prescribed::new(self)?;
        let tolh = settings.tolh_mm2;
        let mut passes = Passes::new(self, Method::GapIteration, tolh, settings.max_iterations);
        let mut dh = vec![0.0; self.shape.nodes().len()];
        let (mut last, mut held): (Option<Iterate>, Option<Optimum>) = (None, None);
        let end = passes.driver.run(|k, inner| {
            // Steps 3–4, each contact solve starting from the previous pressure.
            let warm = last.as_ref().map(|(s, _, _)| s.pressure.as_slice());
            let state =
                self.solve_with_gap_change(solver, self.problem, &self.shape.apply(&dh), warm)?;
            if !state.termination.is_solved() {
                let end = state.termination.clone().inside(state.method);
                held = Some(self.held(last.take(), state, dh.clone(), mode, &prescribed.mask));
                return Ok(Step::Ended(end));
            }
            inner.note(state.method, &state.termination);
            let mut p_max = self.step_four(mode, &state.pressure, &prescribed.mask)?;
            if prescribed.bind(self, &state.pressure, p_max)? {
                p_max = self.step_four(mode, &state.pressure, &prescribed.mask)?;
            }
            // Steps 5–6.
            let next = self.steps_five_and_six(&prescribed, &state, p_max);
            let tolh_k: f64 = next.iter().zip(&dh).map(|(a, b)| (a - b).powi(2)).sum();
            passes
                .rows
                .push(Pass::new(k, p_max, &next, tolh_k, [&state]));
            // Step 7, once Ω_v also carries v·p_max (TOLH is absolute: gap changes of a
            // fraction of a micrometre meet it long before) or the gap change has stopped
            // moving, when the optimum's own checks say why Ω_v is not held.
            let moving = tolh_k.sqrt() > ROUND_OFF * norm(&next);
            let step = match Step::converged_below(tolh_k, tolh) {
                Step::Last(..) if moving && !self.even_on_omega_v(&state.pressure, p_max)? => {
                    Step::Next(tolh_k)
                }
                step => step,
            };
            if matches!(step, Step::Last(..)) {
                self.check_sign(&dh)?;
            }
            last = Some((state, std::mem::replace(&mut dh, next), p_max));
            Ok(step)
        })?;
        let optimum = match (held, last) {
            (Some(held), _) => held,
            (None, Some((state, dh, p_max))) => {
                self.optimum(state, dh, p_max, Method::GapIteration)
            }
            (None, None) => {
                return Err(Error::invalid("max_iterations", 0, "at least one pass"));
            }
        };
        Ok(passes.finish(optimum, end))
    }

    /// The iterate a loop holds when a contact solve ends short: that solve's `state` (solved
    /// with `dh`) when it is finite or the first, else the last completed pass.
    fn held(
        &self,
        last: Option<Iterate>,
        state: ContactState,
        dh: Vec<f64>,
        mode: Mode,
        prescribed: &[bool],
    ) -> Optimum {
        let (state, dh) = match last {
            Some((s, d, p_max)) if state.non_finite().is_some() => {
                return self.optimum(s, d, p_max, Method::GapIteration)
            }
            _ => (state, dh),
        };
        let p_max = match mode {
            Mode::GivenLoad => self
                .equilibrium_p_max(&state.pressure, prescribed)
                .unwrap_or(f64::NAN),
            Mode::GivenDisplacement => self.p_max_on_omega_opt(&state.pressure),
        };
        self.optimum(state, dh, p_max, Method::GapIteration)
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

    /// Whether the pressure, read as a field ([`InterfaceProblem::recovered_pressure`]),
    /// falls short of v·p_max nowhere on Ω_v by more than [`OMEGA_V_EVEN`] of p_max.
    fn even_on_omega_v(&self, pressure: &[f64], p_max: f64) -> Result<bool> {
        let field = self.problem.recovered_pressure(pressure)?;
        Ok((0..field.len())
            .filter(|&i| self.regions[i] == Region::OmegaV)
            .all(|i| self.v[i] * p_max - field[i] <= OMEGA_V_EVEN * p_max))
    }

    /// Step 4: p_max of the contact pressure. Under a given displacement, the largest
    /// pressure on Ω_opt read as a field ([`InterfaceProblem::recovered_pressure`]); under a
    /// given load, the value equilibrium asks of v·p_max
    /// ([`Optimisation::equilibrium_p_max`]) with p = v·p_max on the `prescribed` points.
    fn step_four(&self, mode: Mode, pressure: &[f64], prescribed: &[bool]) -> Result<f64> {
        match mode {
            Mode::GivenDisplacement => {
                let field = self.problem.recovered_pressure(pressure)?;
                Ok((0..field.len())
                    .filter(|&i| self.regions[i] != Region::Contact)
                    .map(|i| field[i])
                    .fold(0.0, f64::max))
            }
            Mode::GivenLoad => self.equilibrium_p_max(pressure, prescribed),
        }
    }

    /// Steps 5–6: prescribe p = v·p_max on the `prescribed` points (Ω_v and where χ ≥ 0
    /// binds), take the residual gap m there with the original initial gap h₀ and fit
    /// Δh = −(m − m_N) through Q.
    fn steps_five_and_six(
        &self,
        prescribed: &Prescribed,
        state: &ContactState,
        p_max: f64,
    ) -> Vec<f64> {
        let mut p = state.pressure.clone();
        for &i in &prescribed.points {
            p[i] = self.v[i] * p_max;
        }
        let m = self.problem.gap(&p, &state.rigid);
        let rhs: Vec<f64> = prescribed.points.iter().map(|&i| -m[i]).collect();
        let fitted = prescribed.fit.solve(&rhs);
        // Q's rows sum to one, so subtracting Δh_N from every node moves the gap by −m_N
        // everywhere: the uniform part of the residual (the approach, a rigid translation)
        // is left to the contact solver and the gap does not change at N.
        self.anchored(&fitted)
    }

    /// p_max of a given load: the least-squares solution over the rigid modes of
    /// p_max·(Rᵀ W v)_prescribed + (Rᵀ W p)_rest = −q, with the `prescribed` points (Ω_v and
    /// where χ ≥ 0 binds) at v·p_max; fails when the loads cannot be carried by v·p_max (a
    /// moment against a symmetric controller, say) or would need p_max ≤ 0.
    pub(crate) fn equilibrium_p_max(&self, pressure: &[f64], prescribed: &[bool]) -> Result<f64> {
        let problem = self.problem;
        let (w, q) = (problem.weights(), problem.load());
        let (mut a, mut b) = (vec![0.0; q.len()], vec![0.0; q.len()]);
        for (m, mode) in problem.modes().iter().enumerate() {
            for (&i, &r) in mode.points.iter().zip(&mode.displacement) {
                if prescribed[i] {
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
        check::positive("p_max", p_max)
            .map_err(|_| Error::invalid("p_max", p_max, "the given load needs a positive pressure"))
    }
}

/// The points where step 5 prescribes p = v·p_max and step 6 closes the gap: Ω_v, joined by
/// each point of Ω_nv where a pass finds p above v·p_max, so that χ ≥ 0 (3.4) binds there
/// as an equality, as in an active set. A point joins only when the fit can close it
/// independently, i.e. when it is a least-squares fit over rows that reach several nodes (the
/// quadratic faces of a finite-element body); where every row reaches one node (a roller's
/// extruded columns) an Ω_nv point's gap change is that of its column, which Ω_v closes, and
/// the loop's end says so when χ ≥ 0 fails there ([`Termination::Infeasible`]).
struct Prescribed {
    points: Vec<usize>,
    mask: Vec<bool>,
    fit: StepSix,
}

impl Prescribed {
    /// Ω_v, with its fit.
    fn new(opt: &Optimisation) -> Result<Self> {
        let points = opt.omega_v();
        let mut mask = vec![false; opt.v.len()];
        points.iter().for_each(|&i| mask[i] = true);
        Ok(Self {
            fit: StepSix::new(opt, &points)?,
            points,
            mask,
        })
    }

    /// Joins the points of Ω_nv whose `pressure` passes v·`p_max` (beyond the contact solve's
    /// accuracy) when the fit can take them; whether any joined.
    fn bind(&mut self, opt: &Optimisation, pressure: &[f64], p_max: f64) -> Result<bool> {
        if matches!(self.fit, StepSix::Diagonal { .. }) {
            return Ok(false);
        }
        let over: Vec<usize> = (0..pressure.len())
            .filter(|&i| opt.regions[i] == Region::OmegaNv && !self.mask[i])
            .filter(|&i| pressure[i] > opt.v[i] * p_max + SOLVER_ACCURACY * p_max)
            .collect();
        if over.is_empty() {
            return Ok(false);
        }
        for &i in &over {
            self.mask[i] = true;
        }
        self.points = (0..self.mask.len()).filter(|&i| self.mask[i]).collect();
        self.fit = StepSix::new(opt, &self.points)?;
        Ok(true)
    }
}

/// Step 6's least-squares fit of Q on the rows of the prescribed points (Ω_v, and where χ ≥ 0
/// binds), min ‖Q_Ω_v Δh − b‖, from the structure of Q: when every such row reaches one node
/// (a pointwise or an extruded shape), the normal equations are diagonal and Δh_k is the
/// weighted mean of b over its rows; otherwise (the quadratic face rows of a finite-element
/// body, a short 1-D region) a dense pivoted QR.
enum StepSix {
    Diagonal {
        /// (node, weight) of each Ω_v row.
        rows: Vec<(usize, f64)>,
        /// Σ weight² per node.
        norms: Vec<f64>,
    },
    /// The QR factors of the columns of the used nodes ([`Optimisation::used_nodes`]), the
    /// node of each column, and the number of nodes.
    Qr(ColPivQr<f64>, Vec<usize>, usize),
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
        let used = opt.used_nodes();
        let columns: Vec<usize> = (0..nodes).filter(|&k| used[k]).collect();
        let mut column_of = vec![usize::MAX; nodes];
        columns
            .iter()
            .enumerate()
            .for_each(|(c, &k)| column_of[k] = c);
        if omega_v.len() < columns.len() {
            // The least-squares fit needs at least as many rows as columns (faer asserts it).
            return Err(Error::invalid(
                "omega_v",
                format!("{} points", omega_v.len()),
                format!(
                    "step 6 fits the gap change at {} design nodes to the Ω_v points, too few \
                     to determine it: enlarge Ω_v or refine the faces",
                    columns.len()
                ),
            ));
        }
        let bytes = (omega_v.len() as u64)
            .saturating_mul(columns.len() as u64)
            .saturating_mul(16);
        let limit = opt.problem.dense_limit();
        if bytes > limit {
            return Err(Error::TooLarge {
                what: format!(
                    "step 6's dense {} × {} fit of Q",
                    omega_v.len(),
                    columns.len()
                ),
                bytes,
                limit,
                advice: "give the gap shape one node per point row (pointwise or extruded)".into(),
            });
        }
        // Ω_v rows reach only used nodes (Optimisation::check_rows ties every used node to Ω_v).
        let mut fit = Mat::<f64>::zeros(omega_v.len(), columns.len());
        for (a, &i) in omega_v.iter().enumerate() {
            for &(k, wt) in opt.shape.row(i) {
                fit[(a, column_of[k])] += wt;
            }
        }
        Ok(StepSix::Qr(fit.col_piv_qr(), columns, nodes))
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
            StepSix::Qr(qr, columns, nodes) => {
                let mut rhs = Mat::<f64>::from_fn(b.len(), 1, |a, _| b[a]);
                qr.solve_lstsq_in_place(rhs.as_mut());
                let mut dh = vec![0.0; *nodes];
                columns
                    .iter()
                    .enumerate()
                    .for_each(|(c, &k)| dh[k] = rhs[(c, 0)]);
                dh
            }
        }
    }
}

/// The Euclidean norm of `v`.
fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}
