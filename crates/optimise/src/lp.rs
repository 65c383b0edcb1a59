//! The restricted linear programme (3.5) by clarabel.

use contopt_contact::conic::{self, CscMatrix, Outcome};
use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::observe::{Flow, Method};
use contopt_core::{check, Error, Result, Termination};
use faer::Mat;

use crate::passes::Passes;
use crate::{
    LinearProgrammeSettings, Optimisation, Optimum, Pass, Reference, Region, ROUND_OFF,
    SOLVER_ACCURACY,
};

/// The n × n arrays of a pass held at once: A, its rows, the triplets and the CSC matrix, and
/// the interior point's factor.
const LP_COPIES: u64 = 10;

/// Relative pressure (of p_max) and gap (of the gap unit) above which a point of a pass's
/// solution carries pressure across an open gap: two orders above the interior point's
/// tolerance (convergence).
const COMPLEMENTARITY: f64 = 1e-8;

/// Programmes a pass solves under [`Reference::Least`] when no rigid translation takes up a
/// uniform gap change: each moves the pinned node to where the last one's Δh came out least,
/// which settles in one or two.
const PIN_MOVES: usize = 4;

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

/// How a pass's programme ended: its optimum and the number of points that carry pressure
/// across an open gap, or why it has none.
enum PassEnd {
    Solved(Box<Optimum>, usize),
    Ended(Termination),
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
    /// complementary (on a one-dimensional region, where Ω_v is everything, the first is), at
    /// most [`LinearProgrammeSettings::max_passes`] passes. The contact solves use
    /// `contact_solver`; each pass is reported to the observer
    /// ([`Optimisation::with_observer`]) with its number of such points. Dense: it needs the
    /// influence matrix ([`InterfaceProblem::dense_influence`]); large problems take
    /// [`Optimisation::load_split`].
    ///
    /// Under [`Reference::Least`] a node is pinned (Δh = 0) and Δh is free in sign: when a
    /// floating body translates every point alike, a uniform gap change is a rigid approach,
    /// and the optimum is shifted so that min Δh = 0 (its approach taking up the shift);
    /// otherwise (a given displacement, points kept outside Ω_opt) the pin moves to where Δh
    /// came out least and the programme is solved again, until Δh ≥ 0. Under
    /// [`Reference::Node`] the node is pinned and Δh ≥ 0 is a constraint, as (3.5) writes it.
    ///
    /// An infeasible or unbounded programme ends it with [`Termination::Infeasible`] or
    /// [`Termination::Unbounded`], holding the last pass's optimum (or, before the first, the
    /// contact solution without a gap change).
    pub fn linear_programme(
        &self,
        contact_solver: &dyn ContactSolver,
        settings: &LinearProgrammeSettings,
    ) -> Result<Optimum> {
        settings.check()?;
        let lp = Programme::new(self, settings.tolerance)?;
        let mut passes = Passes::new(self.observer, Method::LinearProgramme, 0.0);
        let mut restricted = match lp.first_restrictions(contact_solver)? {
            Ok(restricted) => restricted,
            Err(end) => return self.programme_ended(contact_solver, passes, None, end),
        };
        let mut tried = vec![restricted.clone()];
        let mut last: Option<Optimum> = None;
        for pass in 1..=settings.max_passes {
            let (optimum, violated) = match lp.solve_pass(&restricted)? {
                PassEnd::Solved(optimum, violated) => (*optimum, violated),
                PassEnd::Ended(end) => {
                    return self.programme_ended(contact_solver, passes, last, end)
                }
            };
            let row = Pass {
                k: pass,
                ..optimum.passes[0]
            };
            let flow = passes.push(row, violated as f64);
            if violated == 0 {
                self.check_sign(&optimum.dh)?;
                return Ok(passes.finish(optimum, Termination::Converged));
            }
            if flow == Flow::Stop {
                return Ok(passes.finish(optimum, Termination::Stopped { after: pass }));
            }
            restricted = match lp.restrict(contact_solver, &optimum.gap_change)? {
                Ok(restricted) => restricted,
                Err(end) => return Ok(passes.finish(optimum, end)),
            };
            if tried.contains(&restricted) {
                let reason = format!(
                    "the contact sets of its passes repeat; {violated} points carry pressure \
                     across an open gap"
                );
                return Ok(passes.finish(optimum, Termination::Stalled { reason }));
            }
            tried.push(restricted.clone());
            last = Some(optimum);
        }
        let end = passes.step_limit();
        let last = last.ok_or_else(|| Error::invalid("max_passes", 0, "at least one pass"))?;
        Ok(passes.finish(last, end))
    }

    /// The optimum of a programme that ended short: the last pass's, or the contact solution
    /// without a gap change when no pass gave one.
    fn programme_ended(
        &self,
        contact_solver: &dyn ContactSolver,
        passes: Passes,
        last: Option<Optimum>,
        end: Termination,
    ) -> Result<Optimum> {
        let held = match last {
            Some(optimum) => optimum,
            None => self.unoptimised(contact_solver, Method::LinearProgramme, end.clone())?,
        };
        let end = match &held.termination {
            Termination::Converged => end,
            inner => inner.clone(),
        };
        Ok(passes.finish(held, end))
    }

    /// The rigid mode that translates every point alike, with its displacement, when no point
    /// keeps its gap: a uniform gap change is then a rigid approach.
    fn uniform_mode(&self) -> Option<(usize, f64)> {
        if self.kept.iter().any(|&k| k) {
            return None;
        }
        let n = self.problem.len();
        self.problem
            .modes()
            .iter()
            .enumerate()
            .find_map(|(m, mode)| {
                let r = *mode.displacement.first()?;
                let uniform = mode.points.len() == n
                    && mode
                        .displacement
                        .iter()
                        .all(|d| (d - r).abs() <= ROUND_OFF * r.abs());
                (uniform && r != 0.0).then_some((m, r))
            })
    }
}

/// The variables of the gap change in one programme: the design nodes other than the pinned
/// one and the unused ones, and where each sits.
struct Layout {
    pin: usize,
    /// Whether Δh ≥ 0 is a constraint (a given reference node).
    signed: bool,
    free: Vec<usize>,
    /// The variable of each design node's Δh (`usize::MAX` for the pin and unused nodes).
    column_of: Vec<usize>,
    ih: usize,
    il: usize,
}

/// The data of (3.5) in units that make its columns of order one: P for pressures, G =
/// P·max(A W 1) for gaps, each rigid mode by its largest displacement. The variables are
/// p (n) | p_max (at `i_max`) | Δh on the free design nodes (from `ih`, see [`Layout`]) |
/// λ (r, from `il`).
struct Programme<'o, 'a> {
    opt: &'o Optimisation<'a>,
    n: usize,
    /// The influence matrix A \[mm/N\].
    a: &'o Mat<f64>,
    /// The rigid modes R.
    rigid: Mat<f64>,
    /// The free gap g \[mm\].
    g: Vec<f64>,
    area: f64,
    unit_p: f64,
    unit_g: f64,
    rigid_scale: Vec<f64>,
    i_max: usize,
    /// The interior point's tolerance.
    tolerance: f64,
}

impl<'o, 'a> Programme<'o, 'a> {
    fn new(opt: &'o Optimisation<'a>, tolerance: f64) -> Result<Self> {
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
        check::positive("loads", unit_p).map_err(|_| {
            Error::invalid(
                "loads",
                unit_p,
                "neither a load nor an overlap presses the bodies together",
            )
        })?;
        let rigid_scale = (0..q.len())
            .map(|m| (0..n).map(|i| rigid[(i, m)].abs()).fold(0.0, f64::max))
            .collect();
        Ok(Self {
            opt,
            n,
            a,
            rigid,
            g,
            area,
            unit_p,
            unit_g: unit_p * compliance,
            rigid_scale,
            i_max: n,
            tolerance,
        })
    }

    /// The number of rigid modes.
    fn modes(&self) -> usize {
        self.rigid_scale.len()
    }

    /// The variables of a programme with the design node `pin` held at Δh = 0.
    fn layout(&self, pin: usize, signed: bool) -> Layout {
        let used = self.opt.used_nodes();
        let free: Vec<usize> = (0..used.len()).filter(|&k| used[k] && k != pin).collect();
        let ih = self.n + 1;
        let mut column_of = vec![usize::MAX; used.len()];
        for (c, &k) in free.iter().enumerate() {
            column_of[k] = ih + c;
        }
        Layout {
            pin,
            signed,
            il: ih + free.len(),
            free,
            column_of,
            ih,
        }
    }

    /// The first pin: the given reference node, or under [`Reference::Least`] the used node
    /// nearest the origin (the axis or the plane of symmetry), where a body pressed at its
    /// middle deflects most.
    fn first_layout(&self) -> Layout {
        let opt = self.opt;
        match opt.reference {
            Reference::Node(k) => self.layout(k, true),
            Reference::Least => {
                let used = opt.used_nodes();
                let nodes = opt.shape.nodes();
                let r = |k: usize| nodes[k].iter().map(|c| c * c).sum::<f64>();
                let pin = (0..nodes.len())
                    .filter(|&k| used[k])
                    .min_by(|&a, &b| r(a).total_cmp(&r(b)))
                    .unwrap_or(0);
                self.layout(pin, false)
            }
        }
    }

    /// Solves a pass under `restricted`, moving the pin under [`Reference::Least`] until
    /// Δh ≥ 0 (or shifting Δh when a rigid translation takes a uniform change up).
    fn solve_pass(&self, restricted: &[Restriction]) -> Result<PassEnd> {
        let mut layout = self.first_layout();
        let uniform = self.opt.uniform_mode();
        for _ in 0..PIN_MOVES {
            let (mut optimum, violated) = match self.solve(restricted, &layout)? {
                PassEnd::Solved(optimum, violated) => (optimum, violated),
                ended => return Ok(ended),
            };
            let least = self.opt.reference_node(&optimum.dh);
            let top = optimum.dh.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if layout.signed || optimum.dh[least] >= -SOLVER_ACCURACY * top {
                return Ok(PassEnd::Solved(optimum, violated));
            }
            if let Some((m, r)) = uniform {
                let least = optimum.dh[least];
                shift(&mut optimum, &self.opt.used_nodes(), least, m, r);
                return Ok(PassEnd::Solved(optimum, violated));
            }
            layout = self.layout(least, false);
        }
        Ok(PassEnd::Ended(Termination::Stalled {
            reason: format!(
                "the node of least gap change moved {PIN_MOVES} times between programmes"
            ),
        }))
    }

    /// The rows of a pass: equalities (a·x = b) and inequalities (written b − a·x ≥ 0).
    fn rows(&self, restricted: &[Restriction], layout: &Layout) -> (Vec<Row>, Vec<Row>) {
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
            let (row, c) = self.gap_row(i, layout);
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
        // Δh ≥ 0, where the reference node is given.
        if layout.signed {
            for c in 0..layout.free.len() {
                nonneg.push((vec![(layout.ih + c, -1.0)], 0.0));
            }
        }
        (zero, nonneg)
    }

    /// The gap at point `i` in gap units, d_i / G = g_i/G + Σ A_ij w_j P/G p̃_j + Σ R_im λ̃_m
    /// + Σ Q_ik Δh̃_k, as its coefficients and its constant g_i/G.
    fn gap_row(&self, i: usize, layout: &Layout) -> Row {
        let (opt, n) = (self.opt, self.n);
        let w = opt.problem.weights();
        let mut row: Vec<(usize, f64)> = (0..n)
            .map(|j| (j, self.a[(i, j)] * w[j] * self.unit_p / self.unit_g))
            .collect();
        for m in 0..self.modes() {
            row.push((layout.il + m, self.rigid[(i, m)] / self.rigid_scale[m]));
        }
        for &(k, wt) in opt.shape.row(i) {
            if layout.column_of[k] != usize::MAX {
                row.push((layout.column_of[k], wt));
            }
        }
        (row, self.g[i] / self.unit_g)
    }

    /// Solves the programme under `restricted` with `layout`: its optimum in physical units
    /// and the number of points that carry pressure across an open gap, or how it ended.
    fn solve(&self, restricted: &[Restriction], layout: &Layout) -> Result<PassEnd> {
        let (zero, nonneg) = self.rows(restricted, layout);
        let nvar = layout.il + self.modes();
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
            self.tolerance,
            "linear programme (3.5)",
        )?;
        Ok(match sol.outcome {
            Outcome::Solved => {
                let (optimum, violated) = self.optimum(&sol.x, sol.iterations, layout);
                PassEnd::Solved(Box::new(optimum), violated)
            }
            Outcome::Infeasible => PassEnd::Ended(Termination::Infeasible {
                reason: "no gap change closes Ω_v under v·p_max with these loads".into(),
            }),
            Outcome::Unbounded => PassEnd::Ended(Termination::Unbounded {
                reason: "p_max is not bounded below: nothing presses the bodies together".into(),
            }),
            Outcome::Stopped(end) => PassEnd::Ended(end),
        })
    }

    /// A programme's solution `x` in physical units, as an optimum whose one row counts the
    /// interior point's iterations, with the number of points that carry pressure across an
    /// open gap.
    fn optimum(&self, x: &[f64], iterations: usize, layout: &Layout) -> (Optimum, usize) {
        let (opt, n) = (self.opt, self.n);
        let pressure: Vec<f64> = x[..n].iter().map(|p| p.max(0.0) * self.unit_p).collect();
        let p_max = x[self.i_max] * self.unit_p;
        let mut dh = vec![0.0; opt.shape.nodes().len()];
        for (c, &k) in layout.free.iter().enumerate() {
            let value = x[layout.ih + c] * self.unit_g;
            dh[k] = if layout.signed { value.max(0.0) } else { value };
        }
        debug_assert_eq!(dh[layout.pin], 0.0);
        let lambda: Vec<f64> = (0..self.modes())
            .map(|m| x[layout.il + m] * self.unit_g / self.rigid_scale[m])
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
        let row = Pass {
            k: 1,
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
            passes: vec![row],
            method: Method::LinearProgramme,
            termination: Termination::Converged,
        };
        (optimum, violated)
    }

    /// The restrictions of the first pass: Ω_v closed, Ω_nv free (χ ≥ 0 bounds its
    /// pressure), and the points outside Ω_opt as the contact problem without a gap change
    /// has them: left free, they could carry the whole load across open gaps and leave
    /// p_max = 0, a degenerate programme the interior point stalls on.
    fn first_restrictions(
        &self,
        contact_solver: &dyn ContactSolver,
    ) -> Result<std::result::Result<Vec<Restriction>, Termination>> {
        let regions = &self.opt.regions;
        let mut restricted: Vec<Restriction> = regions
            .iter()
            .map(|r| match r {
                Region::OmegaV => Restriction::Closed,
                _ => Restriction::Free,
            })
            .collect();
        if regions.contains(&Region::Contact) {
            let zero = vec![0.0; self.n];
            let contact = match self.restrict(contact_solver, &zero)? {
                Ok(contact) => contact,
                Err(end) => return Ok(Err(end)),
            };
            for i in (0..self.n).filter(|&i| regions[i] == Region::Contact) {
                restricted[i] = contact[i];
            }
        }
        Ok(Ok(restricted))
    }

    /// The restrictions of the next pass: the contact set of the contact problem on the gap
    /// changed by `gap_change`, or how that solve ended when it did not converge. Points at
    /// the edge of contact, with both p and d within [`SOLVER_ACCURACY`] of p_max and the gap
    /// unit, stay free: forcing them closed or open leaves the programme no interior, and the
    /// interior point stalls (a 40 × 21 roller did).
    fn restrict(
        &self,
        contact_solver: &dyn ContactSolver,
        gap_change: &[f64],
    ) -> Result<std::result::Result<Vec<Restriction>, Termination>> {
        let opt = self.opt;
        let contact = opt.solve_with_gap_change(contact_solver, opt.problem, gap_change, None)?;
        if !contact.is_converged() {
            return Ok(Err(contact.termination.inside(contact.method)));
        }
        let p_max = contact.p_max();
        Ok(Ok((0..self.n)
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
            .collect()))
    }
}

/// Shifts the gap change of `optimum` by −`least` at every `used` node (min Δh = 0) and takes
/// the shift up in the amplitude of the uniform mode `m` (displacement `r` at every point), so
/// that its gap is unchanged (Q's rows sum to one).
fn shift(optimum: &mut Optimum, used: &[bool], least: f64, m: usize, r: f64) {
    for (v, _) in optimum.dh.iter_mut().zip(used).filter(|(_, u)| **u) {
        *v -= least;
    }
    optimum.gap_change.iter_mut().for_each(|v| *v -= least);
    optimum.rigid[m] += least / r;
    optimum.passes[0].dh_max -= least;
}
