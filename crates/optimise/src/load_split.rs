//! The optimum of (3.5) without a dense matrix: the load carried by each design column.

use contopt_contact::{parallel, ContactSolver, FreeMode, InterfaceProblem, Workspace};
use contopt_core::drive::Step;
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{ContactState, Error, Result, Termination};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use crate::passes::{Bound, Passes};
use crate::{
    LoadSplitSettings, Optimisation, Optimum, Pass, Reference, Region, ROUND_OFF, SOLVER_ACCURACY,
};

/// The exponent α of p̄ ∝ F^α for a column whose contact spans several points: a Hertzian line
/// contact's p₀ grows as the square root of its load.
const LINE_EXPONENT: f64 = 0.5;
/// The exponent for a column whose contact is one point: its pressure is its load over its
/// weight.
const POINT_EXPONENT: f64 = 1.0;
/// A column whose contact spans at most this many points takes its exponent from its own
/// discrete contact ([`discrete_exponent`]) instead of the line contact's: at the roller's
/// ends, where rows enter one by one, the measured ∂ln p̄/∂ln F of contacts 3 to 7 points
/// across is 0.23 to 0.64 against the ½ of a line contact (800 × 417 cells), and with it the
/// 800 × 417 roller takes the updates of the 200 × 105 one (9 at L1 = 0 and 3 mm, 11 with
/// the line contact's exponent; 9–10 with any limit from 4 to 32 points, and 8 with every
/// column's own, which costs a factorisation 181 points square per column and update and
/// took 1.6–2.0 times as long). A wide contact keeps the line contact's ½, which is how p̄
/// follows a smooth change of every column's load: a column narrower than its contact is
/// stiffer on its own (0.76 in the roller's middle), and that coupling is Anderson mixing's
/// to learn.
const DISCRETE_POINTS: usize = 8;
/// The contact solves of an update stop at this fraction of the last update's miss (in the
/// solver's own measure, [`ContactSolver::loosened`]). With 10⁻² a solve whose error sits in a
/// few points at the roller's ends stopped after one step, and the split took up to 16
/// updates instead of 10; with 10⁻³ it took one update more or fewer than exact solves on
/// some grids (L1 = 5 mm: 9, 10, 11 on 200 × 105, 400 × 209, 800 × 417 against 10, 10, 10;
/// L1 = 0: 9 against 8 on 100 × 53); with 5·10⁻⁴ it takes exactly the updates of exact
/// solves on every grid from 50 × 27 to 800 × 417, L1 = 0, 3 and 5 mm (`roller_scaling
/// case`), for about a tenth more conjugate-gradient steps than 10⁻³ (L1 = 3 mm on
/// 800 × 417: 55 against 50; exact solves 92).
const FORCING: f64 = 5e-4;
/// The contact solver's tolerance in the first update, before any miss is known: that of
/// Polonsky–Keer's coarse starts.
const FIRST_FORCING: f64 = 1e-6;
/// An update whose contact solves stopped at this fraction of the split's tolerance or below
/// counts as exact: the error of its contact is two orders below the miss it is judged by.
/// On the 100 × 53 roller (L1 = 3 mm) the eighth update met the tolerance (8.5·10⁻⁹) with
/// solves at 6.9·10⁻¹¹, and a ninth, exact one only confirmed it.
const EXACT_ENOUGH: f64 = 1e-2;
/// How many past iterates Anderson mixing combines.
const ANDERSON_DEPTH: usize = 5;
/// Tikhonov term of Anderson mixing's normal equations, relative to their trace: keeps nearly
/// parallel residual differences from making them singular (round-off).
const ANDERSON_REGULARISATION: f64 = 1e-12;
/// Newton steps in ln P of the share update: it converges in a few.
const NEWTON_STEPS: usize = 50;
/// A Newton step in ln P below this ends the share update's solve (convergence).
const NEWTON_STEP: f64 = 1e-14;

/// The design columns of a gap shape whose rows each reach one node: the points of each node,
/// their rigid-mode displacement r (one value per column), and the column's Ω_v measure and mean
/// controller value.
pub(crate) struct Columns {
    points: Vec<Vec<usize>>,
    r: Vec<f64>,
    /// L_k = Σ wᵢ over the column's Ω_v points.
    measure: Vec<f64>,
    /// v̄_k, the L-weighted mean of v on the column's Ω_v points.
    v: Vec<f64>,
}

impl Optimisation<'_> {
    /// The optimum of the restricted LP (3.5) for a given load, found as a sequence of strictly
    /// convex contact QPs instead of a dense programme: every design column j of the gap shape
    /// (a node of Q, reached by the rows of its points) becomes a rigid mode of its own, loaded
    /// by a prescribed share F_j of the total load,
    ///
    /// min ½ pᵀ W A W p + pᵀ W g  subject to  p ≥ 0,  Σᵢ∈j wᵢ rᵢ pᵢ = F_j,
    ///
    /// whose multipliers λ_j are the column approaches; the gap change is their spread,
    /// Δh_j = r (λ_j − λ_N), zero at the reference node N (under [`Reference::Least`] the
    /// column of least r·λ_j, so min Δh = 0; the body's approach is then λ_N, which keeps the
    /// optimum's gap that of the solve). An outer update of the shares drives each column's
    /// Ω_v pressure to v_j·p_max: F_j ← F_j (v_j p_max / p̄_j)^(1/α_j), with the exponent α_j
    /// of p̄ ∝ F^α read from the column's own contact (1 for one point, that of the discrete
    /// contact for a few points when the bodies give the influence among them, ½ at the peak
    /// of a Hertzian line contact, ½ (p₀/p̄)² ≤ 1 off its peak), and p_max the value at which
    /// the shares add up to the load, accelerated by Anderson mixing of the last updates, which
    /// learns how the columns couple through the body. At its fixed point the Ω_v points are
    /// closed at v·p_max, equilibrium holds and the rest of Ω is complementary: the
    /// conditions of (3.5), whose optimum it is (with d = 0 and χ = 0 prescribed on Ω_v, the
    /// programme's feasible set is that one point). A column whose Ω_v holds several points is
    /// driven by the largest p/v among them, so that none exceeds v·p_max.
    ///
    /// Every contact solve starts from the previous pressure, so a matrix-free `solver`
    /// ([`contopt_contact::PolonskyKeer`]) takes a few steps after the first; a dense one works
    /// too, for small problems. An iterative solver's tolerance is loosened
    /// ([`ContactSolver::loosened`]) to 5·10⁻⁴ of the last update's miss (10⁻⁶ in the first):
    /// an update far from the optimum needs no exact contact, and the roller's updates take
    /// about half the steps. The update expected to end the split is solved to the solver's
    /// own tolerance, as is the last update allowed, and the split ends only on an update
    /// solved to that or to 10⁻² of its own tolerance. Stops when every column's Ω_v pressure
    /// is within [`LoadSplitSettings::tolerance`]·p_max of v·p_max, after at most
    /// [`LoadSplitSettings::max_iterations`] solves; each solve is a pass of the result,
    /// reported to the observer ([`Optimisation::with_observer`]) with its miss. Needs a
    /// floating body with one rigid mode (the given load) and a gap shape whose rows each reach
    /// one node (pointwise, or extruded along an axis), every point in a column (no point
    /// kept outside Ω_opt by [`Optimisation::with_omega`]).
    pub fn load_split(
        &self,
        solver: &dyn ContactSolver,
        settings: &LoadSplitSettings,
    ) -> Result<Optimum> {
        Ok(self.envelope_split(&[], solver, settings)?.optimum)
    }

    /// The robust optimum over an envelope of load cases that share one gap change: the least
    /// p_max with max_c p_c ≤ v·p_max for every case c, the problem's own (the design case)
    /// and each of `cases` (the same interface with its own initial gap, say a tilt, and its
    /// own load), equality on Ω_v. It is the load split of the design case, whose column
    /// shares are driven by the envelope maxₖ p̄ of the cases' Ω_v pressures instead of its
    /// own; every case is solved again, from its last pressure, under the gap change of each
    /// update. Its passes are events of [`Method::EnvelopeSplit`] (of [`Method::LoadSplit`]
    /// without further cases).
    ///
    /// Why the closed envelope is the optimum: raising the gap of one column lowers that
    /// column's pressure and raises the others' in every case (the load is carried
    /// elsewhere), and a uniform gap change changes nothing, so the Jacobian J of the envelope
    /// in Δh has a non-positive diagonal, non-negative off-diagonal entries and zero row sums.
    /// Its transpose has a non-negative null vector μ (Perron–Frobenius), which are the
    /// multipliers of the minimax's stationarity μᵀJ = 0 with every column active. With one
    /// case it is the load split itself.
    pub fn envelope_split(
        &self,
        cases: &[InterfaceProblem],
        solver: &dyn ContactSolver,
        settings: &LoadSplitSettings,
    ) -> Result<EnvelopeOptimum> {
        let levels = vec![1.0; cases.len()];
        self.envelope_split_levels(cases, &levels, solver, settings)
    }

    /// The envelope split with a pressure level per case: the least p_max with
    /// p_c ≤ s_c·v·p_max for each of `cases` (`levels` = s_c, relative to the design case's
    /// own level 1), so that the envelope whose Ω_v pressure is driven to v·p_max is
    /// max(p, maxₖ p_c/s_c). A case with s_c > 1 may carry more than the design case, one with
    /// s_c < 1 less: the levels weigh the cases (a duty cycle's time fractions, say), and with
    /// every s_c = 1 it is [`Optimisation::envelope_split`]. Dividing a case's pressure by a
    /// positive constant keeps the signs of the envelope's Jacobian, so the argument for the
    /// closed envelope holds unchanged. Each case's Ω_nv is checked against s_c·v·p_max.
    pub fn envelope_split_levels(
        &self,
        cases: &[InterfaceProblem],
        levels: &[f64],
        solver: &dyn ContactSolver,
        settings: &LoadSplitSettings,
    ) -> Result<EnvelopeOptimum> {
        settings.check()?;
        self.check_cases(cases)?;
        check_levels(levels, cases.len())?;
        let columns = self.columns()?;
        let method = match cases.is_empty() {
            true => Method::LoadSplit,
            false => Method::EnvelopeSplit,
        };
        let split = Split {
            opt: self,
            cases,
            levels,
            columns: &columns,
        };
        let mut passes = Passes::new(self, method, settings.tolerance, settings.max_iterations);
        let mut update = ShareUpdate::new(&columns);
        let (mut last, mut failed): (Option<SplitIterate>, Option<Failed>) = (None, None);
        let mut forcing = Some(FIRST_FORCING);
        let end = passes.driver.run(|k, inner| {
            // The last update allowed is solved exactly: a split that stops there reports
            // how far an exact contact got.
            let loose = forcing
                .filter(|_| k < settings.max_iterations)
                .and_then(|t| solver.loosened(t));
            let exact =
                loose.is_none() || forcing.is_some_and(|t| t <= EXACT_ENOUGH * settings.tolerance);
            let solver_k = loose.as_deref().unwrap_or(solver);
            let iterate = match split.pass(solver_k, &update.share, last.as_ref())? {
                Ok(iterate) => iterate,
                Err(f) => return Ok(Step::Ended(failed.insert(f).end.clone())),
            };
            std::iter::once(&iterate.state)
                .chain(&iterate.cases)
                .for_each(|s| inner.note(s.method, &s.termination));
            passes.rows.push(iterate.row(k, last.as_ref()));
            let miss = iterate.miss;
            if miss <= settings.tolerance && exact {
                self.check_sign(&iterate.dh)?;
                last = Some(iterate);
                return Ok(Step::Last(miss, Termination::Converged));
            }
            forcing = iterate.forcing(last.as_ref(), settings.tolerance);
            update.next(
                &iterate.envelope,
                &iterate.exponent,
                &columns.v,
                iterate.p_max,
            );
            last = Some(iterate);
            Ok(Step::Next(miss))
        })?;
        match (failed, last) {
            (Some(failed), last) => Ok(split.held(passes, last, failed)),
            (None, Some(last)) => Ok(split.finish(passes, last, end)),
            (None, None) => Err(Error::invalid("max_iterations", 0, "at least one update")),
        }
    }

    /// The envelope's cases share the design case's interface.
    fn check_cases(&self, cases: &[InterfaceProblem]) -> Result<()> {
        for (c, case) in cases.iter().enumerate() {
            if case.len() != self.problem.len() || case.modes().len() != 1 {
                return Err(Error::invalid(
                    format!("cases[{c}]"),
                    format!("{} points, {} modes", case.len(), case.modes().len()),
                    format!(
                        "a case of the envelope shares the design case's {} points and floats \
                         under one load",
                        self.problem.len()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// The design columns, checked: one rigid mode, rows that each reach one node, and one
    /// displacement r per column.
    pub(crate) fn columns(&self) -> Result<Columns> {
        let problem = self.problem;
        let modes = problem.modes();
        if modes.len() != 1 {
            return Err(Error::invalid(
                "mode",
                format!("{} rigid modes", modes.len()),
                "the load split needs one floating body with one mode (the given load)",
            ));
        }
        if let Some(i) = self.kept.iter().position(|&k| k) {
            return Err(Error::invalid(
                format!("omega_opt[{i}]"),
                false,
                "the load split moves every point with a design column: points outside Ω_opt \
                 that keep their gap need the iteration or the linear programme",
            ));
        }
        let n = problem.len();
        let mut r = vec![0.0; n];
        for (&i, &v) in modes[0].points.iter().zip(&modes[0].displacement) {
            r[i] = v;
        }
        let nodes = self.shape.nodes().len();
        let mut points = vec![vec![]; nodes];
        for (i, &ri) in r.iter().enumerate() {
            match self.shape.row(i) {
                [(k, _)] => points[*k].push(i),
                row => {
                    return Err(Error::invalid(
                        format!("gap_shape.rows[{i}]"),
                        format!("{} nodes", row.len()),
                        "the load split needs one node per point (a pointwise or extruded shape)",
                    ))
                }
            }
            if ri == 0.0 {
                return Err(Error::invalid(
                    format!("rigid mode at point {i}"),
                    0.0,
                    "the floating body must move every point of the region",
                ));
            }
        }
        self.column_data(points, &r)
    }

    /// The columns of the nodes' `points`, each moved by its one value of `r`.
    fn column_data(&self, points: Vec<Vec<usize>>, r: &[f64]) -> Result<Columns> {
        let w = self.problem.weights();
        let nodes = points.len();
        let (mut measure, mut v, mut column_r) =
            (vec![0.0; nodes], vec![0.0; nodes], vec![0.0; nodes]);
        for (k, members) in points.iter().enumerate() {
            // check_rows ties every node a point reaches to Ω_v; a node no point reaches
            // has no column to load.
            let Some(&first) = members.first() else {
                return Err(Error::invalid(
                    format!("gap_shape.nodes[{k}]"),
                    format!("{:?}", self.shape.nodes()[k]),
                    "the load split needs every design node reached by a point",
                ));
            };
            column_r[k] = r[first];
            if let Some(&i) = members
                .iter()
                .find(|&&i| (r[i] - column_r[k]).abs() > ROUND_OFF * column_r[k].abs())
            {
                return Err(Error::invalid(
                    format!("rigid mode at point {i}"),
                    r[i],
                    format!(
                        "moves the column of node {k} unevenly ({} at its first point): a column \
                         must translate as a whole",
                        column_r[k]
                    ),
                ));
            }
            for &i in members
                .iter()
                .filter(|&&i| self.regions[i] == Region::OmegaV)
            {
                measure[k] += w[i];
                v[k] += w[i] * self.v[i];
            }
            v[k] /= measure[k];
        }
        Ok(Columns {
            points,
            r: column_r,
            measure,
            v,
        })
    }
}

/// One update of a load split: the design case's column solve, the crown from its approaches,
/// every case's contact under it, the envelope of their Ω_v pressures and its row.
struct SplitIterate {
    state: ContactState,
    cases: Vec<ContactState>,
    dh: Vec<f64>,
    envelope: Vec<f64>,
    /// Each column's exponent α in the solve that sets its envelope.
    exponent: Vec<f64>,
    p_max: f64,
    miss: f64,
}

impl SplitIterate {
    /// The contact solver's tolerance for the next update, after `last`: [`FORCING`] times
    /// this update's miss (an inexact solve, Dembo, Eisenstat & Steihaug's forcing term:
    /// its error far below the update's own), or `None`, the solver's own, once the miss
    /// shrinking at its last rate would meet `tolerance`, so that the update that ends the
    /// split is solved exactly.
    fn forcing(&self, last: Option<&SplitIterate>, tolerance: f64) -> Option<f64> {
        let rate = last.map_or(1.0, |l| (self.miss / l.miss).min(1.0));
        (self.miss * rate > tolerance).then_some(FORCING * self.miss)
    }

    /// Its row as update `k`, after `last`.
    fn row(&self, k: usize, last: Option<&SplitIterate>) -> Pass {
        let tolh = last.map_or(0.0, |l| {
            self.dh
                .iter()
                .zip(&l.dh)
                .map(|(a, b)| (a - b).powi(2))
                .sum()
        });
        let states = std::iter::once(&self.state).chain(&self.cases);
        Pass::new(k, self.p_max, &self.dh, tolh, states)
    }
}

/// A contact solve of an update that ended short: the update's column solve (the one that
/// failed, or the one before the case that did), whether the column solve failed, and how the
/// split ends (seen from outside).
struct Failed {
    column: ContactState,
    column_failed: bool,
    end: Termination,
}

/// What a load split works with.
struct Split<'s, 'a> {
    opt: &'s Optimisation<'a>,
    cases: &'s [InterfaceProblem<'s>],
    /// Each case's pressure level s_c, relative to the design case's.
    levels: &'s [f64],
    columns: &'s Columns,
}

impl Split<'_, '_> {
    /// An update with the column loads `share`, solved by `solver` (the split's own, or it
    /// loosened) from the pressures of `last`: the iterate, or the contact solve that did not
    /// converge.
    fn pass(
        &self,
        solver: &dyn ContactSolver,
        share: &[f64],
        last: Option<&SplitIterate>,
    ) -> Result<std::result::Result<SplitIterate, Failed>> {
        let (opt, columns) = (self.opt, self.columns);
        let warm = last.map(|l| l.state.pressure.as_slice());
        let state = self.column_solve(solver, share, warm)?;
        if !state.termination.is_solved() {
            return Ok(Err(Failed {
                end: state.termination.clone().inside(state.method),
                column: state,
                column_failed: true,
            }));
        }
        let (dh, _) = self.crown(&state.rigid);
        let mut envelope = columns.omega_v_pressure(opt, &state.pressure);
        let mut exponent = columns.exponents(opt, opt.problem, &state.pressure);
        let gap_change = opt.shape.apply(&dh);
        let mut cases = Vec::with_capacity(self.cases.len());
        let solved_cases = self.solve_cases(solver, &gap_change, last);
        for (c, solved) in solved_cases.into_iter().enumerate() {
            let solved = solved?;
            if !solved.termination.is_solved() {
                return Ok(Err(Failed {
                    end: solved.termination.inside(solved.method),
                    column: state,
                    column_failed: false,
                }));
            }
            let mean = columns.omega_v_pressure(opt, &solved.pressure);
            let case_exponent = columns.exponents(opt, &self.cases[c], &solved.pressure);
            let level = self.levels[c];
            for (j, m) in mean.into_iter().enumerate() {
                if m / level > envelope[j] {
                    envelope[j] = m / level;
                    exponent[j] = case_exponent[j];
                }
            }
            cases.push(solved);
        }
        let p_max = columns.fitted_p_max(&envelope);
        let miss = columns.miss(&envelope, p_max);
        Ok(Ok(SplitIterate {
            state,
            cases,
            dh,
            envelope,
            exponent,
            p_max,
            miss,
        }))
    }

    /// The cases under `gap_change`, each from its pressure in `last`, solved at once on the
    /// current rayon pool's threads ([`parallel::solve_each`]: results and events those of
    /// solving them in turn), up to the first that fails or does not converge.
    fn solve_cases(
        &self,
        solver: &dyn ContactSolver,
        gap_change: &[f64],
        last: Option<&SplitIterate>,
    ) -> Vec<Result<ContactState>> {
        let cases = self.cases;
        let solve = |c: usize, observer: &dyn Observer| {
            let start = last.map(|l| l.cases[c].pressure.as_slice());
            let workspace = &mut Workspace::one_off();
            crate::solve_gap_changed(solver, &cases[c], gap_change, start, observer, workspace)
        };
        let at_once = cases.first().map_or(1, |c| parallel::at_once(solver, c));
        let go_on = |r: &Result<ContactState>| r.as_ref().is_ok_and(|s| s.termination.is_solved());
        let observer = Nested(self.opt.observer);
        parallel::solve_each(cases.len(), at_once, &observer, solve, go_on)
    }

    /// The contact problem with each column a mode of its own loaded by `share` of the load.
    fn column_solve(
        &self,
        solver: &dyn ContactSolver,
        share: &[f64],
        warm: Option<&[f64]>,
    ) -> Result<ContactState> {
        let (opt, columns) = (self.opt, self.columns);
        let total = -opt.problem.modes()[0].load;
        let modes = columns
            .points
            .iter()
            .enumerate()
            .map(|(k, members)| FreeMode {
                name: format!("column {k}"),
                points: members.clone(),
                displacement: vec![columns.r[k]; members.len()],
                load: -share[k] * total,
            })
            .collect();
        let problem: InterfaceProblem = opt.problem.with_modes(modes)?;
        let zero = vec![0.0; problem.len()];
        opt.solve_with_gap_change(solver, &problem, &zero, warm)
    }

    /// Δh_j = r (λ_j − λ_N) from the column approaches, and the body's approach λ_N.
    fn crown(&self, lambda: &[f64]) -> (Vec<f64>, f64) {
        let r = &self.columns.r;
        let n = match self.opt.reference {
            Reference::Node(k) => k,
            Reference::Least => (0..lambda.len())
                .min_by(|&a, &b| (r[a] * lambda[a]).total_cmp(&(r[b] * lambda[b])))
                .unwrap_or(0),
        };
        let dh = lambda
            .iter()
            .zip(r)
            .map(|(l, r)| r * (l - lambda[n]))
            .collect();
        (dh, lambda[n])
    }

    /// The optimum of `iterate`, ended as `termination`: its largest p − v·p_max on Ω_nv is
    /// that of every case, and a converged split whose further case breaks χ ≥ 0 there ends
    /// as infeasible, naming it (its design case is checked as every optimum is).
    fn finish(
        self,
        passes: Passes,
        iterate: SplitIterate,
        termination: Termination,
    ) -> EnvelopeOptimum {
        let (_, approach) = self.crown(&iterate.state.rigid);
        let bound = Bound::new(self.opt);
        let worst = iterate
            .cases
            .iter()
            .enumerate()
            .filter_map(|(c, s)| {
                let level = self.levels[c] * iterate.p_max;
                Some((bound.excess(&s.pressure, level)?, c))
            })
            .max_by(|a, b| a.0 .0.total_cmp(&b.0 .0));
        let termination = match (termination, worst) {
            (end, Some(((value, i), c)))
                if end.is_solved() && value > SOLVER_ACCURACY * iterate.p_max =>
            {
                bound.broken(value, i, Some(c + 1))
            }
            (termination, _) => termination,
        };
        let optimum = Optimum {
            rigid: vec![approach],
            ..self
                .opt
                .optimum(iterate.state, iterate.dh, iterate.p_max, Method::LoadSplit)
        };
        let mut optimum = passes.finish(optimum, termination);
        if let (Some(own), Some(((value, _), _))) = (optimum.omega_nv_excess, worst) {
            optimum.omega_nv_excess = Some(own.max(value));
        }
        EnvelopeOptimum {
            optimum,
            cases: iterate.cases,
        }
    }

    /// The optimum when a contact solve ended short: the last update when there is one and
    /// the failed solve is a case's or not finite; else the update's column solve, with the
    /// crown of its approaches and no cases.
    fn held(self, passes: Passes, last: Option<SplitIterate>, failed: Failed) -> EnvelopeOptimum {
        let Failed {
            column,
            column_failed,
            end,
        } = failed;
        match last {
            Some(last) if !column_failed || column.non_finite().is_some() => {
                self.finish(passes, last, end)
            }
            _ => {
                let (dh, _) = self.crown(&column.rigid);
                let p_max = self.opt.p_max_on_omega_opt(&column.pressure);
                let iterate = SplitIterate {
                    state: column,
                    cases: vec![],
                    dh,
                    envelope: vec![],
                    exponent: vec![],
                    p_max,
                    miss: f64::NAN,
                };
                self.finish(passes, iterate, end)
            }
        }
    }
}

/// The robust optimum of [`Optimisation::envelope_split`].
#[derive(Clone, Debug)]
pub struct EnvelopeOptimum {
    /// The gap change, p_max and the design case's contact, and how the split ended.
    pub optimum: Optimum,
    /// The contact of each further case under the same gap change (none when the split ended
    /// before it solved them).
    pub cases: Vec<ContactState>,
}

impl Columns {
    /// p̄_k = v̄_k · max p/v over each column's Ω_v points (where v > 0): the pressure that
    /// meets v·p_max first, so that p ≤ v·p_max holds on every Ω_v point of the column when
    /// p̄_k = v̄_k·p_max. On a single Ω_v point it is that point's pressure; on the two ends of
    /// a symmetric column, the larger.
    fn omega_v_pressure(&self, opt: &Optimisation, pressure: &[f64]) -> Vec<f64> {
        self.points
            .iter()
            .zip(&self.v)
            .map(|(members, v)| {
                v * members
                    .iter()
                    .filter(|&&i| opt.regions[i] == Region::OmegaV && opt.v[i] > 0.0)
                    .map(|&i| pressure[i] / opt.v[i])
                    .fold(0.0, f64::max)
            })
            .collect()
    }

    /// The exponent α_j of p̄_j ∝ F_j^α of each column under `pressure`, a contact of
    /// `problem`, from [`Columns::exponents_with`] and the problem's [`discrete_exponent`].
    fn exponents(
        &self,
        opt: &Optimisation,
        problem: &InterfaceProblem,
        pressure: &[f64],
    ) -> Vec<f64> {
        let discrete = |set: &[usize], d: usize| discrete_exponent(problem, set, d, pressure);
        self.exponents_with(&opt.regions, &opt.v, pressure, discrete)
    }

    /// The exponent α_j of p̄_j ∝ F_j^α of each column under `pressure`: 1 where its contact
    /// is one Ω_v point (its pressure is its load over its weight); for a contact of at most
    /// [`DISCRETE_POINTS`] points, `discrete(set, d)` of its loaded points and driving point
    /// when it gives one; else that of a Hertzian line contact p = p₀√(1 − s²) at the Ω_v
    /// point that drives the column, whose p₀ and half-width grow as F^½:
    /// α = ½/(1 − s²) = ½ (p₀/p̄)², ½ at the peak and growing towards the contact's edge, at
    /// most 1 (a point just reached by the contact).
    fn exponents_with(
        &self,
        regions: &[Region],
        v: &[f64],
        pressure: &[f64],
        discrete: impl Fn(&[usize], usize) -> Option<f64>,
    ) -> Vec<f64> {
        let mut loaded = Vec::with_capacity(DISCRETE_POINTS + 1);
        self.points
            .iter()
            .map(|members| {
                loaded.clear();
                loaded.extend(
                    members
                        .iter()
                        .filter(|&&i| pressure[i] > 0.0)
                        .take(DISCRETE_POINTS + 1),
                );
                if let [i] = loaded[..] {
                    if regions[i] == Region::OmegaV {
                        return POINT_EXPONENT;
                    }
                }
                let driving = members
                    .iter()
                    .filter(|&&i| regions[i] == Region::OmegaV && v[i] > 0.0)
                    .max_by(|&&a, &&b| (pressure[a] / v[a]).total_cmp(&(pressure[b] / v[b])));
                let Some(&d) = driving.filter(|&&d| pressure[d] > 0.0) else {
                    return LINE_EXPONENT;
                };
                let discrete = (loaded.len() <= DISCRETE_POINTS)
                    .then(|| discrete(&loaded, d))
                    .flatten();
                discrete
                    .unwrap_or_else(|| {
                        let peak = members.iter().map(|&i| pressure[i]).fold(0.0, f64::max);
                        LINE_EXPONENT * (peak / pressure[d]).powi(2)
                    })
                    .min(POINT_EXPONENT)
            })
            .collect()
    }

    /// How far the Ω_v pressures `mean` miss v̄·`p_max`: the largest |p̄_k − v̄_k p_max|
    /// relative to p_max. When p_max is 0 (no column's Ω_v carries pressure: the load is
    /// carried off Ω_v) the largest miss is 0 too, and so is the measure, not 0/0: a split
    /// there has met its target v̄·0, and its check of Ω_nv against v·p_max
    /// (`check_envelope`) says that Ω_v holds no column's peak.
    fn miss(&self, mean: &[f64], p_max: f64) -> f64 {
        let worst = (0..mean.len())
            .map(|j| (mean[j] - self.v[j] * p_max).abs())
            .fold(0.0, f64::max);
        if p_max > 0.0 {
            worst / p_max
        } else {
            worst
        }
    }

    /// The p_max that fits p̄ = v̄ p_max best in the L-weighted least-squares sense.
    fn fitted_p_max(&self, mean: &[f64]) -> f64 {
        let (mut num, mut den) = (0.0, 0.0);
        for ((l, v), p) in self.measure.iter().zip(&self.v).zip(mean) {
            num += l * v * p;
            den += l * v * v;
        }
        num / den
    }
}

/// The cases' levels, checked: one per case, each positive and finite.
fn check_levels(levels: &[f64], cases: usize) -> Result<()> {
    if levels.len() != cases {
        return Err(Error::invalid(
            "levels",
            format!("{} levels", levels.len()),
            format!("one pressure level per case of the envelope ({cases})"),
        ));
    }
    contopt_core::check::all_finite("levels", levels)?;
    contopt_core::check::all_positive("levels", levels)
}

/// The exponent α = ∂ln p_d/∂ln F of a column whose contact is the few points `set`, at its
/// driving point d, with the set held: a unit approach of the column puts the forces
/// f = A_CC⁻¹·1 on it (A_CC the influence among the set's points,
/// [`InterfaceProblem::influence_block`]), so p_d grows by f_d/w_d while the load grows by
/// Σ f, and α = (f_d / w_d p_d) · (Σ wᵢpᵢ / Σ fᵢ): the column's own ∂ln p_d/∂ln F with its
/// neighbours' loads held, to the third digit of a finite difference on the roller. For a
/// plane line contact resolved by many points it tends to the Hertzian ½ at the peak (the
/// increment of a Hertzian pressure with its load, ∂p/∂F ∝ 1/√(1 − s²), is the flat punch's
/// A_CC⁻¹·1); on a few points it is the discrete contact's: where a row has just entered,
/// the load goes to that row and α falls well below ½; one point gives 1. `None` when the
/// bodies give no influence entries or the block is not positive definite.
fn discrete_exponent(
    problem: &InterfaceProblem,
    set: &[usize],
    driving: usize,
    pressure: &[f64],
) -> Option<f64> {
    let block = problem.influence_block(set)?;
    let forces = Llt::new(block.as_ref(), Side::Lower)
        .ok()?
        .solve(Mat::<f64>::from_fn(set.len(), 1, |_, _| 1.0));
    let w = problem.weights();
    let d = set.iter().position(|&i| i == driving)?;
    let carried: f64 = (0..set.len()).map(|a| forces[(a, 0)]).sum();
    let load: f64 = set.iter().map(|&i| w[i] * pressure[i]).sum();
    let alpha = forces[(d, 0)] / (w[driving] * pressure[driving]) * load / carried;
    (alpha.is_finite() && alpha > 0.0).then_some(alpha)
}

/// Scales `share` to sum to one.
fn normalise(share: &mut [f64]) {
    let sum: f64 = share.iter().sum();
    share.iter_mut().for_each(|s| *s /= sum);
}

/// The next shares F_k (v_k P / p̄_k)^(1/α_k), with P chosen (Newton in ln P) so that they add
/// up to one; a column whose Ω_v opened (p̄ = 0) doubles its share.
fn next_shares(share: &[f64], mean: &[f64], v: &[f64], exponent: &[f64], p_max: f64) -> Vec<f64> {
    let grown = |x: f64| -> Vec<f64> {
        (0..share.len())
            .map(|k| {
                if v[k] == 0.0 {
                    0.0
                } else if mean[k] > 0.0 {
                    share[k] * ((v[k] * x.exp() / mean[k]).ln() / exponent[k]).exp()
                } else {
                    2.0 * share[k]
                }
            })
            .collect()
    };
    let mut x = p_max.ln();
    for _ in 0..NEWTON_STEPS {
        let next = grown(x);
        let sum: f64 = next.iter().sum();
        let slope: f64 = next
            .iter()
            .zip(exponent)
            .zip(mean)
            .filter(|(_, m)| **m > 0.0)
            .map(|((s, a), _)| s / a)
            .sum();
        let step = (sum - 1.0) / slope.max(f64::MIN_POSITIVE);
        x -= step.clamp(-1.0, 1.0);
        if step.abs() < NEWTON_STEP {
            break;
        }
    }
    let mut next = grown(x);
    normalise(&mut next);
    next
}

/// The shares F_j / Q of the load split and how they are updated: the per-column power law,
/// accelerated by Anderson mixing.
struct ShareUpdate {
    share: Vec<f64>,
    anderson: Anderson,
}

impl ShareUpdate {
    /// First shares: a Hertzian column carries F ∝ p₀², so F_j ∝ L_j v_j².
    fn new(columns: &Columns) -> Self {
        let mut share: Vec<f64> = (0..columns.v.len())
            .map(|k| columns.measure[k] * columns.v[k].powi(2))
            .collect();
        normalise(&mut share);
        Self {
            share,
            anderson: Anderson::default(),
        }
    }

    /// The shares after a solve that gave the Ω_v pressures `mean` and `p_max`, with each
    /// column's `exponent` there.
    fn next(&mut self, mean: &[f64], exponent: &[f64], v: &[f64], p_max: f64) {
        let image = next_shares(&self.share, mean, v, exponent, p_max);
        self.share = if mean.iter().zip(v).all(|(p, v)| *p > 0.0 || *v == 0.0) {
            self.anderson.mix(&self.share, &image)
        } else {
            // An Ω_v point opened: its column's share doubles, outside the smooth map.
            self.anderson.reset();
            image
        };
    }
}

/// Anderson mixing (type II; Walker & Ni, SIAM J. Numer. Anal. 49, 2011) of the share update,
/// on the logarithms of the shares: the next iterate combines the last few iterates and their
/// images so that the columns' coupling through the half-space, which the per-column update
/// ignores, is learnt from the history. Columns without load (v = 0) stay at zero.
#[derive(Default)]
struct Anderson {
    /// The last iterates x and residuals f = G(x) − x, oldest first.
    history: Vec<(Vec<f64>, Vec<f64>)>,
}

impl Anderson {
    fn reset(&mut self) {
        self.history.clear();
    }

    /// The next shares from the current ones and their image under the update.
    fn mix(&mut self, share: &[f64], image: &[f64]) -> Vec<f64> {
        let log = |s: &[f64]| -> Vec<f64> {
            s.iter()
                .map(|&v| if v > 0.0 { v.ln() } else { 0.0 })
                .collect()
        };
        let (x, gx) = (log(share), log(image));
        let f: Vec<f64> = gx.iter().zip(&x).map(|(g, x)| g - x).collect();
        self.history.push((x, f.clone()));
        if self.history.len() > ANDERSON_DEPTH + 1 {
            self.history.remove(0);
        }
        let k = self.history.len() - 1;
        if k == 0 {
            return image.to_vec();
        }
        let diff =
            |a: &[f64], b: &[f64]| -> Vec<f64> { a.iter().zip(b).map(|(a, b)| a - b).collect() };
        let h = &self.history;
        let df: Vec<Vec<f64>> = (0..k).map(|i| diff(&h[i + 1].1, &h[i].1)).collect();
        let dx: Vec<Vec<f64>> = (0..k).map(|i| diff(&h[i + 1].0, &h[i].0)).collect();
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(a, b)| a * b).sum::<f64>();
        let trace: f64 = df.iter().map(|d| dot(d, d)).sum();
        let gram = Mat::from_fn(k, k, |a, b| {
            dot(&df[a], &df[b])
                + if a == b {
                    ANDERSON_REGULARISATION * trace
                } else {
                    0.0
                }
        });
        let rhs = Mat::from_fn(k, 1, |a, _| dot(&df[a], &f));
        let Ok(llt) = Llt::new(gram.as_ref(), Side::Lower) else {
            self.reset();
            return image.to_vec();
        };
        let gamma = llt.solve(&rhs);
        let mut next: Vec<f64> = (0..gx.len())
            .map(|j| {
                if image[j] == 0.0 {
                    return 0.0;
                }
                let correction: f64 = (0..k).map(|i| gamma[(i, 0)] * (dx[i][j] + df[i][j])).sum();
                (gx[j] - correction).exp()
            })
            .collect();
        normalise(&mut next);
        next
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The miss is relative to p_max, and 0 (not 0/0) when no column's Ω_v carries pressure.
    #[test]
    fn the_miss_is_finite_when_p_max_is_zero() {
        let columns = Columns {
            points: vec![vec![0], vec![1]],
            r: vec![1.0; 2],
            measure: vec![1.0; 2],
            v: vec![1.0, 0.5],
        };
        let p_max = columns.fitted_p_max(&[0.0, 0.0]);
        assert_eq!((p_max, columns.miss(&[0.0, 0.0], p_max)), (0.0, 0.0));
        let p_max = columns.fitted_p_max(&[2.0, 0.5]);
        let want = (2.0 - p_max).abs().max((0.5 - 0.5 * p_max).abs()) / p_max;
        assert_eq!(columns.miss(&[2.0, 0.5], p_max), want);
    }

    /// A column a few points wide takes its exponent from its own discrete contact: on one
    /// strip of cells under a rigid cylinder, with three points in contact (the outer two
    /// just reached), it is the slope ∂ln p_d/∂ln F of the contact solved at F(1 ± ε) to
    /// 10⁻⁶, and far below the line contact's ½ (the load goes to the rows that entered).
    #[test]
    fn a_few_point_columns_exponent_is_its_own_contacts() {
        use contopt_contact::{ActiveSet, ActiveSetSettings, ContactSolver};
        use contopt_core::{ElasticBody, Material, RigidBody};
        let (ny, dy, radius) = (15, 0.0022, 5.0);
        let material = Material::new(1.05e5, 0.3).unwrap();
        let origin = [0.0, -7.0 * dy];
        let body =
            contopt_greens::HalfSpace::grid("strip", material, 1, ny, 0.0125, dy, origin).unwrap();
        let iface = body.interface();
        let gap: Vec<f64> = iface
            .points()
            .iter()
            .map(|x| x[1] * x[1] / (2.0 * radius))
            .collect();
        let solver = ActiveSet::new(ActiveSetSettings::default()).unwrap();
        let roller = |force: f64| RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], force);
        let solve = |roller: &RigidBody| {
            let problem = InterfaceProblem::new(&body, roller, &gap).unwrap();
            solver.solve(&problem).unwrap().pressure
        };
        let (force, eps, d) = (8e-4, 1e-4, 7);
        let pressed = roller(force).unwrap();
        let problem = InterfaceProblem::new(&body, &pressed, &gap).unwrap();
        let pressure = solve(&pressed);
        let set: Vec<usize> = (0..ny).filter(|&i| pressure[i] > 0.0).collect();
        assert_eq!(set, vec![6, 7, 8], "{pressure:?}");
        assert!(pressure[6] < 0.2 * pressure[d], "{pressure:?}");
        let up = solve(&roller(force * (1.0 + eps)).unwrap());
        let down = solve(&roller(force * (1.0 - eps)).unwrap());
        let slope = (up[d].ln() - down[d].ln()) / ((1.0 + eps) / (1.0 - eps)).ln();
        let alpha = discrete_exponent(&problem, &set, d, &pressure).unwrap();
        eprintln!(
            "alpha {alpha}, slope {slope}, pressures {:?}",
            &pressure[5..10]
        );
        assert!((alpha - slope).abs() < 1e-6 * slope, "{alpha} {slope}");
        assert!(alpha < 0.4, "{alpha}");
    }

    /// A column's exponent is that of a Hertzian line contact p = p₀√(1 − y²/b²) with p₀ and
    /// b ∝ F^½ at its Ω_v point: d ln p / d ln F at fixed y, by a central difference of the
    /// closed form, ½ at the peak and 2/3 at y = b/2; 1 for a contact of one Ω_v point and for
    /// a point at the contact's edge.
    #[test]
    fn a_columns_exponent_is_the_hertzian_one_at_its_omega_v_point() {
        let hertz = |f: f64, y: f64| f.sqrt() * (1.0 - y * y / f).max(0.0).sqrt();
        let ys: Vec<f64> = (-8..=8).map(|k| k as f64 / 8.0).collect();
        let pressure: Vec<f64> = ys.iter().map(|&y| hertz(1.0, y)).collect();
        let columns = Columns {
            points: vec![(0..ys.len()).collect()],
            r: vec![1.0],
            measure: vec![1.0],
            v: vec![1.0],
        };
        let v = vec![1.0; ys.len()];
        for (at, want) in [(0.0, 0.5), (0.5, 2.0 / 3.0), (0.875, 1.0)] {
            let i = ys.iter().position(|&y| y == at).unwrap();
            let mut regions = vec![Region::OmegaNv; ys.len()];
            regions[i] = Region::OmegaV;
            let h = 1e-6;
            let slope = (hertz(1.0 + h, at).ln() - hertz(1.0 - h, at).ln()) / (2.0 * h);
            let alpha = columns.exponents_with(&regions, &v, &pressure, |_, _| None)[0];
            assert!((alpha - want).abs() < 1e-12, "y = {at}: {alpha}");
            assert!(
                (alpha - slope.min(1.0)).abs() < 1e-6,
                "y = {at}: {alpha} {slope}"
            );
        }
        let mut one = vec![0.0; ys.len()];
        one[8] = 3.0;
        let mut regions = vec![Region::OmegaNv; ys.len()];
        regions[8] = Region::OmegaV;
        assert_eq!(
            columns.exponents_with(&regions, &v, &one, |_, _| None),
            vec![1.0]
        );
    }
}
