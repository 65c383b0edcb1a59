//! The restricted linear programme (3.5): its passes, each a programme restricted by a contact
//! set, and the seed of the first.

use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::observe::{Flow, Method, Nested};
use contopt_core::{check, Error, Result, Termination};
use faer::Mat;

use crate::passes::Passes;
use crate::programme::{self, Kind, RowSource, Rows, Solved};
use crate::{
    IterationSettings, LinearProgrammeSettings, LoadSplitSettings, Mode, Optimisation, Optimum,
    Pass, Reference, Region, ROUND_OFF, SOLVER_ACCURACY,
};

/// Relative pressure (of p_max) and gap (of the gap unit) above which a point of a pass's
/// solution carries pressure across an open gap: two orders above the interior point's
/// tolerance (convergence).
const COMPLEMENTARITY: f64 = 1e-8;

/// Programmes a pass solves under [`Reference::Least`] when no rigid translation takes up a
/// uniform gap change: each moves the pinned node to where the last one's Δh came out least,
/// which settles in one or two.
const PIN_MOVES: usize = 4;

/// Times a pass frees the points whose restriction its programme cannot meet (a closed point
/// that would pull, an open one that would penetrate) before it reports the programme
/// infeasible: the points at the edge of a contact set settle in one or two.
const LOOSENINGS: usize = 4;

/// How a point enters a pass of the programme.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Restriction {
    /// p ≥ 0 and d ≥ 0, the programme chooses.
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

/// How one programme of a pass ended: as a pass ends, or infeasible at points whose
/// restriction is to blame (with the termination to report if freeing them does not help).
enum Attempt {
    Pass(PassEnd),
    Loosen(Vec<usize>, Termination),
}

impl Optimisation<'_> {
    /// The linear programme (3.5): minimise p_max over p, Δh and λ subject to equilibrium
    /// Rᵀ W p = −q, p ≥ 0, χ = v·p_max − p ≥ 0 on Ω_opt (= 0 on Ω_v),
    /// d = g + A W p + R λ + QΔh ≥ 0 (= 0 on Ω_v), Δh ≥ 0 and Δh = 0 at the reference node.
    ///
    /// The complementarity pᵀd = 0 is kept by restriction: each pass solves the programme with
    /// d = 0 on the points of a contact set, p = 0 on the open points and both p ≥ 0 and d ≥ 0
    /// on the points at its edge; while some point carries pressure across an open gap, the
    /// contact problem is solved on the pass's gap and its contact set restricts the next
    /// pass, at most [`LinearProgrammeSettings::max_passes`] passes. The first pass's contact
    /// set is that of an optimum found without the dense matrix: the load split's where it
    /// applies, else the iteration of §3.2's (else the contact without a gap change); where
    /// Ω_v is the whole region there is nothing to seed. A programme is solved by eliminating
    /// its equalities (a rank-revealing QR, which drops the redundant ones) and handing the
    /// few directions left to clarabel; on a bearing roller, whose Ω_v closes every design
    /// column, none are left and the pass is one dense solve. The contact solves use
    /// `contact_solver`; each pass is reported to the observer
    /// ([`Optimisation::with_observer`]) with its number of points that carry pressure across
    /// an open gap, the seed's optimisation one level deeper. Dense: it needs the influence
    /// matrix ([`InterfaceProblem::dense_influence`]), so large problems take
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
    /// [`Termination::Unbounded`], naming the constraints that conflict, holding the last
    /// pass's optimum (or, before the first, the contact solution without a gap change).
    pub fn linear_programme(
        &self,
        contact_solver: &dyn ContactSolver,
        settings: &LinearProgrammeSettings,
    ) -> Result<Optimum> {
        settings.check()?;
        let lp = Programme::new(self, settings.tolerance)?;
        let mut passes = Passes::new(self, Method::LinearProgramme, 0.0);
        let mut restricted = match lp.seed(contact_solver)? {
            Ok(restricted) => restricted,
            Err(end) => return self.programme_ended(contact_solver, passes, None, end),
        };
        let mut tried = vec![restricted.clone()];
        let mut last: Option<Optimum> = None;
        for pass in 1..=settings.max_passes {
            let (optimum, violated) = match lp.solve_pass(&mut restricted)? {
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

    /// The optimum whose contact set seeds the programme: the load split's where its columns
    /// apply, else the iteration's (under the given load, or the given displacement when
    /// nothing floats), reported one level deeper; `None` when that method refuses the
    /// problem.
    fn seeding_optimum(&self, contact_solver: &dyn ContactSolver) -> Result<Option<Optimum>> {
        let nested = Nested(self.observer);
        let seeding = Optimisation {
            problem: self.problem,
            shape: std::borrow::Cow::Borrowed(self.shape.as_ref()),
            v: self.v.clone(),
            regions: self.regions.clone(),
            kept: self.kept.clone(),
            reference: self.reference,
            observer: &nested,
        };
        let found = match (seeding.columns(), self.problem.modes().is_empty()) {
            (Ok(_), _) => seeding.load_split(contact_solver, &LoadSplitSettings::default()),
            (Err(_), floating) => {
                let mode = match floating {
                    true => Mode::GivenDisplacement,
                    false => Mode::GivenLoad,
                };
                seeding.iterate(mode, contact_solver, &IterationSettings::default())
            }
        };
        match found {
            Ok(optimum) => Ok(Some(optimum)),
            // A refusal of the seeding method (its own limits) leaves the programme to the
            // contact without a gap change; bad data fails the programme's checks as well.
            Err(Error::InvalidInput { .. }) => Ok(None),
            Err(other) => Err(other),
        }
    }
}

/// The variables of the gap change in one programme: the design nodes other than the pinned
/// one and the unused ones.
struct Layout {
    pin: usize,
    /// Whether Δh ≥ 0 is a constraint (a given reference node).
    signed: bool,
    /// The free design nodes, in the order of their variables.
    free: Vec<usize>,
    /// The position of each design node among `free` (`usize::MAX` for the pin and unused
    /// nodes).
    slot: Vec<usize>,
}

/// The data of (3.5) in units that make its columns of order one: P for pressures, G =
/// P·max(A W 1) for gaps, each rigid mode by its largest displacement.
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
    /// The interior point's tolerance.
    tolerance: f64,
}

impl<'o, 'a> Programme<'o, 'a> {
    fn new(opt: &'o Optimisation<'a>, tolerance: f64) -> Result<Self> {
        let problem = opt.problem;
        let n = problem.len();
        let (w, a, rigid, q) = (
            problem.weights(),
            problem.dense_influence(LinearProgrammeSettings::DENSE_COPIES)?,
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
            tolerance,
        })
    }

    /// The variables of a programme with the design node `pin` held at Δh = 0.
    fn layout(&self, pin: usize, signed: bool) -> Layout {
        let used = self.opt.used_nodes();
        let free: Vec<usize> = (0..used.len()).filter(|&k| used[k] && k != pin).collect();
        let mut slot = vec![usize::MAX; used.len()];
        for (c, &k) in free.iter().enumerate() {
            slot[k] = c;
        }
        Layout {
            pin,
            signed,
            free,
            slot,
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

    /// Solves a pass under `restricted`, freeing the points whose restriction its programme
    /// cannot meet, and moving the pin under [`Reference::Least`] until Δh ≥ 0 (or shifting
    /// Δh when a rigid translation takes a uniform change up).
    fn solve_pass(&self, restricted: &mut [Restriction]) -> Result<PassEnd> {
        let mut layout = self.first_layout();
        let uniform = self.opt.uniform_mode();
        let (mut moves, mut loosenings) = (0, 0);
        loop {
            let (mut optimum, violated) = match self.solve(restricted, &layout)? {
                Attempt::Pass(PassEnd::Solved(optimum, violated)) => (optimum, violated),
                Attempt::Pass(ended) => return Ok(ended),
                Attempt::Loosen(_, end) if loosenings == LOOSENINGS => {
                    return Ok(PassEnd::Ended(end))
                }
                Attempt::Loosen(points, _) => {
                    points
                        .iter()
                        .for_each(|&i| restricted[i] = Restriction::Free);
                    loosenings += 1;
                    continue;
                }
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
            moves += 1;
            if moves == PIN_MOVES {
                return Ok(PassEnd::Ended(Termination::Stalled {
                    reason: format!(
                        "the node of least gap change moved {PIN_MOVES} times between \
                         programmes"
                    ),
                }));
            }
            layout = self.layout(least, false);
        }
    }

    /// Solves the programme under `restricted` with `layout`: its optimum in physical units
    /// and the number of points that carry pressure across an open gap, or how it ended.
    fn solve(&self, restricted: &[Restriction], layout: &Layout) -> Result<Attempt> {
        let programme = Restricted::new(self, restricted, layout);
        let rows = programme.rows();
        Ok(match programme::solve(&programme, &rows, self.tolerance)? {
            Solved::Optimal(x, iterations) => {
                let (optimum, violated) = programme.optimum(&x, iterations);
                Attempt::Pass(PassEnd::Solved(Box::new(optimum), violated))
            }
            Solved::Infeasible(conflict) => {
                let reason = format!(
                    "no gap change meets these together: {}",
                    conflict
                        .iter()
                        .map(|&k| self.describe(k))
                        .collect::<Vec<_>>()
                        .join("; ")
                );
                let end = Termination::Infeasible { reason };
                let blamed = self.blamed(restricted, &conflict);
                match blamed.is_empty() {
                    true => Attempt::Pass(PassEnd::Ended(end)),
                    false => Attempt::Loosen(blamed, end),
                }
            }
            Solved::Unbounded => Attempt::Pass(PassEnd::Ended(Termination::Unbounded {
                reason: "p_max falls without bound along a gap change that nothing in the \
                         programme limits"
                    .into(),
            })),
            Solved::Stopped(end) => Attempt::Pass(PassEnd::Ended(end)),
        })
    }

    /// The points of `conflict` whose restriction is to blame: a closed point whose pressure
    /// would have to pull, an open point whose gap would have to close past zero.
    fn blamed(&self, restricted: &[Restriction], conflict: &[Kind]) -> Vec<usize> {
        conflict
            .iter()
            .filter_map(|&k| match k {
                Kind::Pressure(i) if restricted[i] == Restriction::Closed => Some(i),
                Kind::Gap(i) if restricted[i] == Restriction::Open => Some(i),
                _ => None,
            })
            .collect()
    }

    /// A row in words, with its point or node.
    fn describe(&self, kind: Kind) -> String {
        let opt = self.opt;
        let at = |i: usize| format!("point {i} {:?}", opt.problem.interface().points()[i]);
        match kind {
            Kind::Equilibrium(m) => format!(
                "the equilibrium of {} under its load",
                opt.problem.mode_names()[m]
            ),
            Kind::Gap(i) => format!("d ≥ 0 at {}", at(i)),
            Kind::Chi(i) => format!("p ≤ v·p_max (χ ≥ 0) at {} of Ω_nv", at(i)),
            Kind::Pressure(i) => format!("p ≥ 0 at {}", at(i)),
            Kind::Level => "p_max ≥ 0".into(),
            Kind::Change(k) => format!("Δh ≥ 0 at design node {k} {:?}", opt.shape.nodes()[k]),
        }
    }

    /// The restrictions of the first pass: Ω_v closed, the other points as the contact set
    /// of the seeding optimum ([`Optimisation::seeding_optimum`]), or of the contact without
    /// a gap change when that method does not apply; how the seeding ended when an observer
    /// stopped it.
    fn seed(
        &self,
        contact_solver: &dyn ContactSolver,
    ) -> Result<std::result::Result<Vec<Restriction>, Termination>> {
        if self.opt.regions.iter().all(|&r| r == Region::OmegaV) {
            return Ok(Ok(vec![Restriction::Closed; self.n]));
        }
        match self.opt.seeding_optimum(contact_solver)? {
            Some(o) if o.termination.is_stopped() => Ok(Err(o.termination.inside(o.method))),
            Some(o) if o.pressure.iter().chain(&o.gap).all(|v| v.is_finite()) => {
                Ok(Ok(self.classify(&o.pressure, &o.gap)))
            }
            _ => self.restrict(contact_solver, &vec![0.0; self.n]),
        }
    }

    /// The restrictions of the next pass: the contact set of the contact problem on the gap
    /// changed by `gap_change`, or how that solve ended when it did not converge.
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
        Ok(Ok(self.classify(&contact.pressure, &contact.gap)))
    }

    /// The contact set of a contact solution: Ω_v and the points that carry pressure closed,
    /// those with an open gap open. Points at the edge of contact, with both p and d within
    /// [`SOLVER_ACCURACY`] of p_max and the gap unit, stay free: the programme decides them.
    fn classify(&self, pressure: &[f64], gap: &[f64]) -> Vec<Restriction> {
        let p_max = pressure.iter().fold(0.0, |m: f64, p| m.max(*p));
        (0..self.n)
            .map(|i| {
                if self.opt.regions[i] == Region::OmegaV || pressure[i] > SOLVER_ACCURACY * p_max {
                    Restriction::Closed
                } else if gap[i] > SOLVER_ACCURACY * self.unit_g {
                    Restriction::Open
                } else {
                    Restriction::Free
                }
            })
            .collect()
    }
}

/// One restricted programme in the units of its [`Programme`]. Its variables: the pressure p
/// of the points neither open nor of Ω_v (on Ω_v p = v·p_max, on open points p = 0) | p_max
/// | Δh on the free design nodes | λ.
struct Restricted<'r, 'o, 'a> {
    lp: &'r Programme<'o, 'a>,
    restricted: &'r [Restriction],
    layout: &'r Layout,
    /// The variable of each point's pressure (`usize::MAX` where p is not one).
    pressure: Vec<usize>,
    i_max: usize,
    ih: usize,
    il: usize,
}

impl<'r, 'o, 'a> Restricted<'r, 'o, 'a> {
    fn new(lp: &'r Programme<'o, 'a>, restricted: &'r [Restriction], layout: &'r Layout) -> Self {
        let regions = &lp.opt.regions;
        let mut pressure = vec![usize::MAX; lp.n];
        let mut count = 0;
        for i in 0..lp.n {
            if regions[i] != Region::OmegaV && restricted[i] != Restriction::Open {
                pressure[i] = count;
                count += 1;
            }
        }
        let ih = count + 1;
        Self {
            lp,
            restricted,
            layout,
            pressure,
            i_max: count,
            ih,
            il: ih + layout.free.len(),
        }
    }

    /// Equilibrium and the closed gaps as equalities; the other gaps, χ on Ω_nv, p ≥ 0, p_max
    /// ≥ 0 and, under a given reference node, Δh ≥ 0 as inequalities. χ = 0 on Ω_v is no row:
    /// its pressure is v·p_max.
    fn rows(&self) -> Rows {
        let opt = self.lp.opt;
        let mut equal: Vec<Kind> = (0..self.lp.rigid_scale.len())
            .map(Kind::Equilibrium)
            .collect();
        let mut at_least = vec![Kind::Level];
        for i in 0..self.lp.n {
            match self.restricted[i] {
                Restriction::Closed => equal.push(Kind::Gap(i)),
                Restriction::Open | Restriction::Free => at_least.push(Kind::Gap(i)),
            }
            if self.pressure[i] == usize::MAX {
                continue;
            }
            at_least.push(Kind::Pressure(i));
            if opt.regions[i] == Region::OmegaNv {
                at_least.push(Kind::Chi(i));
            }
        }
        if self.layout.signed {
            at_least.extend(self.layout.free.iter().map(|&k| Kind::Change(k)));
        }
        Rows { equal, at_least }
    }

    /// The pressures p̃ at the points weighted by `factor(j)` as entries: their variables,
    /// and v·p_max on Ω_v summed into one entry (open points carry nothing).
    fn add_pressures(&self, factor: impl Fn(usize) -> f64, entries: &mut Vec<(usize, f64)>) {
        let opt = self.lp.opt;
        let mut on_omega_v = 0.0;
        for j in 0..self.lp.n {
            if self.pressure[j] != usize::MAX {
                entries.push((self.pressure[j], factor(j)));
            } else if opt.regions[j] == Region::OmegaV {
                on_omega_v += factor(j) * opt.v[j];
            }
        }
        entries.push((self.i_max, on_omega_v));
    }

    /// The gap at point `i` in gap units, d_i / G = g_i/G + Σ A_ij w_j P/G p̃_j + Σ R_im λ̃_m
    /// + Σ Q_ik Δh̃_k.
    fn gap_row(&self, i: usize, entries: &mut Vec<(usize, f64)>) -> f64 {
        let lp = self.lp;
        let w = lp.opt.problem.weights();
        let ratio = lp.unit_p / lp.unit_g;
        self.add_pressures(|j| lp.a[(i, j)] * w[j] * ratio, entries);
        for (m, scale) in lp.rigid_scale.iter().enumerate() {
            entries.push((self.il + m, lp.rigid[(i, m)] / scale));
        }
        for &(k, wt) in lp.opt.shape.row(i) {
            if self.layout.slot[k] != usize::MAX {
                entries.push((self.ih + self.layout.slot[k], wt));
            }
        }
        lp.g[i] / lp.unit_g
    }

    /// The solution `x` in physical units, as an optimum whose one row counts the interior
    /// point's `iterations`, with the number of points that carry pressure across an open gap.
    fn optimum(&self, x: &[f64], iterations: usize) -> (Optimum, usize) {
        let (lp, layout) = (self.lp, self.layout);
        let opt = lp.opt;
        let p_max = x[self.i_max] * lp.unit_p;
        let pressure: Vec<f64> = (0..lp.n)
            .map(|i| match (self.pressure[i], opt.regions[i]) {
                (usize::MAX, Region::OmegaV) => opt.v[i] * p_max,
                (usize::MAX, _) => 0.0,
                (c, _) => x[c].max(0.0) * lp.unit_p,
            })
            .collect();
        let mut dh = vec![0.0; opt.shape.nodes().len()];
        for (c, &k) in layout.free.iter().enumerate() {
            let value = x[self.ih + c] * lp.unit_g;
            dh[k] = if layout.signed { value.max(0.0) } else { value };
        }
        debug_assert_eq!(dh[layout.pin], 0.0);
        let lambda: Vec<f64> = (0..lp.rigid_scale.len())
            .map(|m| x[self.il + m] * lp.unit_g / lp.rigid_scale[m])
            .collect();
        let gap_change = opt.shape.apply(&dh);
        let mut gap = opt.problem.gap(&pressure, &lambda);
        for (d, c) in gap.iter_mut().zip(&gap_change) {
            *d += c;
        }
        let violated = (0..lp.n)
            .filter(|&i| {
                pressure[i] > COMPLEMENTARITY * p_max && gap[i] > COMPLEMENTARITY * lp.unit_g
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
            omega_nv_excess: None,
        };
        (optimum, violated)
    }
}

impl RowSource for Restricted<'_, '_, '_> {
    fn variables(&self) -> usize {
        self.il + self.lp.rigid_scale.len()
    }

    fn objective(&self) -> usize {
        self.i_max
    }

    fn row(&self, kind: Kind, entries: &mut Vec<(usize, f64)>) -> f64 {
        entries.clear();
        let lp = self.lp;
        let opt = lp.opt;
        match kind {
            // Rᵀ W p + q = 0, per unit of the mode's largest load.
            Kind::Equilibrium(m) => {
                let w = opt.problem.weights();
                let scale = lp.area * lp.rigid_scale[m];
                self.add_pressures(|i| lp.rigid[(i, m)] * w[i] / scale, entries);
                opt.problem.load()[m] / (lp.unit_p * scale)
            }
            Kind::Gap(i) => self.gap_row(i, entries),
            // χ = v·p_max − p.
            Kind::Chi(i) => {
                entries.push((self.i_max, opt.v[i]));
                entries.push((self.pressure[i], -1.0));
                0.0
            }
            Kind::Pressure(i) => {
                entries.push((self.pressure[i], 1.0));
                0.0
            }
            Kind::Level => {
                entries.push((self.i_max, 1.0));
                0.0
            }
            Kind::Change(k) => {
                entries.push((self.ih + self.layout.slot[k], 1.0));
                0.0
            }
        }
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
