//! The restricted linear programme (3.5): its passes, each a programme restricted by a contact
//! set, and the seed of the first.

use contopt_contact::ContactSolver;
#[cfg(doc)]
use contopt_contact::InterfaceProblem;
use contopt_core::drive::Step;
use contopt_core::observe::{Method, Nested};
use contopt_core::{
    check, Constraint, Error, Infeasibility, Result, Stall, Termination, Unboundedness,
};
use faer::Mat;

use crate::passes::Passes;
use crate::programme::{self, Kind, RowSource, Rows, Solved};
use crate::{
    IterationSettings, LinearProgrammeSettings, LoadSplitSettings, Mode, Optimisation, Optimum,
    Pass, Reference, Region, ROUND_OFF, SOLVER_ACCURACY,
};

/// Programmes a pass solves under [`Reference::Least`] when no rigid translation takes up a
/// uniform gap change: each moves the pinned node to where the last one's Δh came out least,
/// which settles in one or two.
const PIN_MOVES: usize = 4;

/// The conflicting constraints an infeasible programme's reason names.
const NAMED_ROWS: usize = 3;

/// How a point enters a pass of the programme: the complementarity pᵀd = 0 of (3.5) as a
/// restriction, d = 0 or p = 0, with p ≥ 0 and d ≥ 0 as inequalities.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Restriction {
    /// In contact: d = 0, p ≥ 0 (always on Ω_v, where p = v·p_max).
    Closed,
    /// Open: p = 0, d ≥ 0.
    Open,
}

/// How a pass ended: its optimum; the points whose restriction its programme could not meet
/// (a closed point that would have to pull, an open one that would have to penetrate), with
/// the constraints that conflict; or why it has none.
enum PassEnd {
    Solved(Box<Optimum>),
    Flip(Vec<usize>, Infeasibility),
    Ended(Termination),
}

impl Optimisation<'_> {
    /// The linear programme (3.5): minimise p_max over p, Δh and λ subject to equilibrium
    /// Rᵀ W p = −q, p ≥ 0, χ = v·p_max − p ≥ 0 on Ω_opt (= 0 on Ω_v),
    /// d = g + A W p + R λ + QΔh ≥ 0 (= 0 on Ω_v), Δh ≥ 0 and Δh = 0 at the reference node.
    ///
    /// The complementarity pᵀd = 0 is kept by restriction: each pass solves the programme with
    /// d = 0 on the points of a contact set and p = 0 on the others, p ≥ 0 and d ≥ 0 as
    /// inequalities. The first pass's contact set is that of an optimum found without the
    /// dense matrix: the load split's where it applies, else the iteration of §3.2's (else the
    /// contact without a gap change); where Ω_v is the whole region there is nothing to seed.
    /// A pass whose programme cannot meet its restriction (a closed point that would have to
    /// pull, an open one that would have to penetrate, as its infeasibility certificate names
    /// them) flips those points for the next, as Kalker's active set does, at most
    /// [`LinearProgrammeSettings::max_passes`] passes; a contact set that comes back ends it
    /// as stalled. A programme is solved by eliminating its equalities (a rank-revealing QR,
    /// which drops the redundant ones) and handing the few directions left to clarabel; on a
    /// bearing roller, whose Ω_v closes every design column, none are left and the pass is one
    /// dense solve. Each pass is reported to the observer ([`Optimisation::with_observer`])
    /// with the number of points it flipped (0 on the last), the seed's optimisation one level
    /// deeper; `contact_solver` serves the seed. Dense: it needs the influence matrix
    /// ([`InterfaceProblem::dense_influence`]), so large problems take
    /// [`Optimisation::load_split`].
    ///
    /// Under [`Reference::Least`] a node is pinned (Δh = 0) and Δh is free in sign: when a
    /// floating body translates every point alike, a uniform gap change is a rigid approach,
    /// and the optimum is shifted so that min Δh = 0 (its approach taking up the shift);
    /// otherwise (a given displacement, points kept outside Ω_opt) the pin moves to where Δh
    /// came out least and the programme is solved again, until Δh ≥ 0. Under
    /// [`Reference::Node`] the node is pinned and Δh ≥ 0 is a constraint, as (3.5) writes it.
    ///
    /// An infeasible or unbounded programme ends it with [`Termination::Infeasible`] (naming
    /// the constraints that conflict) or [`Termination::Unbounded`], holding the contact
    /// solution without a gap change.
    pub fn linear_programme(
        &self,
        contact_solver: &dyn ContactSolver,
        settings: &LinearProgrammeSettings,
    ) -> Result<Optimum> {
        settings.check()?;
        let lp = Programme::new(self, settings.tolerance)?;
        let mut passes = Passes::new(self, Method::LinearProgramme, 0.0, settings.max_passes);
        let mut restricted = match lp.seed(contact_solver)? {
            Ok(restricted) => restricted,
            Err(end) => return self.programme_ended(contact_solver, passes, end),
        };
        let (mut tried, mut solved) = (vec![], None);
        let end = passes.driver.run(|pass, _| {
            tried.push(restricted.clone());
            Ok(match lp.solve_pass(&restricted)? {
                PassEnd::Solved(optimum) => {
                    passes.rows.push(Pass {
                        k: pass,
                        ..optimum.passes[0]
                    });
                    self.check_sign(&optimum.dh)?;
                    let accuracy = optimum.termination.clone();
                    solved = Some(optimum);
                    Step::Last(0.0, accuracy)
                }
                PassEnd::Flip(points, conflict) => {
                    points
                        .iter()
                        .for_each(|&i| restricted[i] = restricted[i].flipped());
                    let flipped = points.len() as f64;
                    match tried.contains(&restricted) {
                        true => Step::Last(
                            flipped,
                            Termination::Stalled {
                                cause: Stall::CyclingContactSet {
                                    passes: pass,
                                    conflict,
                                },
                            },
                        ),
                        false => Step::Next(flipped),
                    }
                }
                PassEnd::Ended(end) => Step::Ended(end),
            })
        })?;
        match solved {
            Some(optimum) => Ok(passes.finish(*optimum, end)),
            None => self.programme_ended(contact_solver, passes, end),
        }
    }

    /// The optimum of a programme that ended short, `end`: the contact solution without a gap
    /// change (no pass gave an optimum).
    fn programme_ended(
        &self,
        contact_solver: &dyn ContactSolver,
        passes: Passes,
        end: Termination,
    ) -> Result<Optimum> {
        let held = self.unoptimised(contact_solver, Method::LinearProgramme, end.clone())?;
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
            workspace: std::sync::Mutex::new(contopt_contact::Workspace::one_off()),
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

    /// Solves a pass under `restricted`, moving the pin under [`Reference::Least`] until
    /// Δh ≥ 0 (or shifting Δh when a rigid translation takes a uniform change up).
    fn solve_pass(&self, restricted: &[Restriction]) -> Result<PassEnd> {
        let mut layout = self.first_layout();
        let uniform = self.opt.uniform_mode();
        for _ in 0..PIN_MOVES {
            let mut optimum = match self.solve(restricted, &layout)? {
                PassEnd::Solved(optimum) => optimum,
                ended => return Ok(ended),
            };
            let least = self.opt.reference_node(&optimum.dh);
            let top = optimum.dh.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if layout.signed || optimum.dh[least] >= -SOLVER_ACCURACY * top {
                return Ok(PassEnd::Solved(optimum));
            }
            if let Some((m, r)) = uniform {
                let least = optimum.dh[least];
                shift(&mut optimum, &self.opt.used_nodes(), least, m, r);
                return Ok(PassEnd::Solved(optimum));
            }
            layout = self.layout(least, false);
        }
        Ok(PassEnd::Ended(Termination::Stalled {
            cause: Stall::WanderingReference { moves: PIN_MOVES },
        }))
    }

    /// Solves the programme under `restricted` with `layout`: its optimum in physical units,
    /// or how it ended.
    fn solve(&self, restricted: &[Restriction], layout: &Layout) -> Result<PassEnd> {
        let programme = Restricted::new(self, restricted, layout);
        let rows = programme.rows();
        Ok(match programme::solve(&programme, &rows, self.tolerance)? {
            Solved::Optimal(x, iterations, accuracy) => {
                PassEnd::Solved(Box::new(programme.optimum(&x, iterations, accuracy)))
            }
            Solved::Infeasible(conflict) => {
                let (blamed, cause) = (
                    self.blamed(restricted, &conflict),
                    self.infeasibility(&conflict),
                );
                match blamed.is_empty() {
                    true => PassEnd::Ended(Termination::Infeasible { cause }),
                    false => PassEnd::Flip(blamed, cause),
                }
            }
            Solved::Unbounded => PassEnd::Ended(Termination::Unbounded {
                cause: Unboundedness::GapChange,
            }),
            Solved::Stopped(end) => PassEnd::Ended(end),
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

    /// The infeasibility of a programme whose rows `conflict`, naming the first few.
    fn infeasibility(&self, conflict: &[Kind]) -> Infeasibility {
        Infeasibility::Programme {
            conflict: conflict
                .iter()
                .take(NAMED_ROWS)
                .map(|&k| self.constraint(k))
                .collect(),
            more: conflict.len().saturating_sub(NAMED_ROWS),
        }
    }

    /// A row as the constraint it is, with its point or node.
    fn constraint(&self, kind: Kind) -> Constraint {
        let opt = self.opt;
        let at = |point: usize| (point, opt.problem.interface().points()[point]);
        match kind {
            Kind::Equilibrium(m) => Constraint::Equilibrium {
                mode: opt.problem.mode_names().swap_remove(m),
            },
            Kind::Gap(i) => {
                let (point, position_mm) = at(i);
                Constraint::Gap { point, position_mm }
            }
            Kind::Chi(i) => {
                let (point, position_mm) = at(i);
                Constraint::Chi { point, position_mm }
            }
            Kind::Pressure(i) => {
                let (point, position_mm) = at(i);
                Constraint::Pressure { point, position_mm }
            }
            Kind::Level => Constraint::Level,
            Kind::Change(node) => Constraint::Change {
                node,
                position_mm: opt.shape.nodes()[node],
            },
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
            _ => {
                let zero = vec![0.0; self.n];
                let opt = self.opt;
                let contact =
                    opt.solve_with_gap_change(contact_solver, opt.problem, &zero, None)?;
                if !contact.termination.is_solved() {
                    return Ok(Err(contact.termination.inside(contact.method)));
                }
                Ok(Ok(self.classify(&contact.pressure, &contact.gap)))
            }
        }
    }

    /// The contact set of a contact solution: Ω_v and the points that carry pressure, or whose
    /// gap is closed (within [`SOLVER_ACCURACY`] of the gap unit: the edge of contact, where p
    /// may fall to 0), closed; the others open.
    fn classify(&self, pressure: &[f64], gap: &[f64]) -> Vec<Restriction> {
        let p_max = pressure.iter().fold(0.0, |m: f64, p| m.max(*p));
        (0..self.n)
            .map(|i| {
                let open = gap[i] > SOLVER_ACCURACY * self.unit_g;
                let closed = self.opt.regions[i] == Region::OmegaV
                    || pressure[i] > SOLVER_ACCURACY * p_max
                    || !open;
                match closed {
                    true => Restriction::Closed,
                    false => Restriction::Open,
                }
            })
            .collect()
    }
}

impl Restriction {
    /// The other restriction: a closed point that would pull opens, an open point that would
    /// penetrate closes.
    fn flipped(self) -> Self {
        match self {
            Restriction::Closed => Restriction::Open,
            Restriction::Open => Restriction::Closed,
        }
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
                Restriction::Open => at_least.push(Kind::Gap(i)),
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
    /// point's `iterations`, ended as `accuracy` says the interior point ended.
    fn optimum(&self, x: &[f64], iterations: usize, accuracy: Termination) -> Optimum {
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
        let row = Pass {
            k: 1,
            p_max,
            dh_max: dh.iter().fold(0.0, |m: f64, v| m.max(*v)),
            tolh: 0.0,
            iterp: iterations,
            iterd: 0,
        };
        Optimum {
            p_max,
            dh,
            gap_change,
            pressure,
            gap,
            rigid: lambda,
            passes: vec![row],
            method: Method::LinearProgramme,
            termination: accuracy,
            omega_nv_excess: None,
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::{active_set, with_sphere, CONSTANT};
    use crate::Profile;
    use contopt_contact::InterfaceProblem;
    use contopt_core::{ElasticBody, GapShape, Material, RigidBody};
    use contopt_greens::HalfSpace;

    /// A seed that closes a point which must stay open (the first ring outside the sphere's
    /// Ω_opt, which keeps its gap): the first pass's programme is infeasible at that point's
    /// pressure, which would have to pull, and names it; the point opens, and the next pass
    /// ends at the optimum of the right contact set, p_max within 1e-9 of the programme's own.
    #[test]
    fn a_pass_opens_a_point_its_restriction_wrongs() {
        with_sphere(Reference::Least, |opt, _| {
            let points = opt.problem.interface().points();
            let inner: Vec<bool> = points.iter().map(|x| x[0] < 6.0).collect();
            let masked = Optimisation::new(opt.problem, opt.shape.as_ref(), &CONSTANT)
                .unwrap()
                .with_omega(&inner, &inner)
                .unwrap();
            let solver = active_set();
            let settings = LinearProgrammeSettings::default();
            let right = masked.linear_programme(&solver, &settings).unwrap();
            assert!(right.is_converged(), "{}", right.termination);
            let lp = Programme::new(&masked, settings.tolerance).unwrap();
            let mut restricted = lp.seed(&solver).unwrap().unwrap();
            let ring = (0..points.len()).find(|&i| !inner[i]).unwrap();
            assert_eq!(restricted[ring], Restriction::Open);
            restricted[ring] = Restriction::Closed;
            match lp.solve_pass(&restricted).unwrap() {
                PassEnd::Flip(flipped, conflict) => {
                    assert_eq!(flipped, vec![ring], "{conflict}");
                    let pressure = |c: &Constraint| matches!(c, Constraint::Pressure { point, .. } if *point == ring);
                    assert!(
                        matches!(&conflict, Infeasibility::Programme { conflict, .. } if conflict.iter().any(pressure)),
                        "{conflict}"
                    );
                }
                _ => panic!("the first pass did not name the ring"),
            }
            restricted[ring] = Restriction::Open;
            let PassEnd::Solved(optimum) = lp.solve_pass(&restricted).unwrap() else {
                panic!("the second pass did not solve");
            };
            assert_eq!(optimum.pressure[ring], 0.0);
            assert!((optimum.p_max / right.p_max - 1.0).abs() < 1e-9);
        });
    }

    /// From a poor contact set, the uncrowned roller's (R = 10 mm, 12 kN, 20 × 21 cells,
    /// the C¹ controller from L1 = 3 mm, Ω_v the centre row), the passes flip every point whose
    /// restriction their programme cannot meet, as Kalker's active set does, and reach the
    /// load split's optimum (p_max within 1e-9) in a few passes (measured 4) without repeating
    /// a contact set.
    #[test]
    fn passes_reach_the_optimum_from_the_uncrowned_contact() {
        let (dx, dy) = (0.5, 0.04);
        let material = Material::new(2e5, 0.3).unwrap();
        let body = HalfSpace::grid("hs", material, 20, 21, dx, dy, [-4.75, -0.4]).unwrap();
        let iface = body.interface();
        let gap: Vec<f64> = iface.points().iter().map(|x| x[1] * x[1] / 20.0).collect();
        let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], 12_000.0).unwrap();
        let problem = InterfaceProblem::new(&body, &roller, &gap).unwrap();
        let regions = iface
            .points()
            .iter()
            .map(|x| match x[1].abs() < 0.5 * dy {
                true => Region::OmegaV,
                false => Region::OmegaNv,
            })
            .collect();
        let shape = GapShape::extruded(iface, 0).unwrap();
        let v = Profile::cubic(3.0, 5.0).unwrap();
        let opt = Optimisation::new(&problem, &shape, &v)
            .unwrap()
            .with_regions(regions)
            .unwrap();
        let solver = active_set();
        let split = opt.load_split(&solver, &Default::default()).unwrap();
        let lp = Programme::new(&opt, LinearProgrammeSettings::TOLERANCE).unwrap();
        let uncrowned = solver.solve(&problem).unwrap();
        let mut restricted = lp.classify(&uncrowned.pressure, &uncrowned.gap);
        let mut tried = vec![];
        for _ in 0..LinearProgrammeSettings::MAX_PASSES {
            tried.push(restricted.clone());
            match lp.solve_pass(&restricted).unwrap() {
                PassEnd::Solved(optimum) => {
                    eprintln!("solved after {} passes", tried.len());
                    assert!((optimum.p_max / split.p_max - 1.0).abs() < 1e-9);
                    return;
                }
                PassEnd::Flip(points, _) => {
                    points
                        .iter()
                        .for_each(|&i| restricted[i] = restricted[i].flipped());
                    assert!(!tried.contains(&restricted), "a contact set came back");
                }
                PassEnd::Ended(end) => panic!("{end}"),
            }
        }
        panic!("no optimum in {} passes", tried.len());
    }
}
