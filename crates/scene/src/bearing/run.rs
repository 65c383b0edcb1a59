//! The run of a bearing case: the load distribution of every load case, the design of the
//! crown over the bearing's envelope (when the scene asks for one), every loaded roller's
//! contact on the solved raceway under the final crown, and the lives.
//!
//! A design is made for the rollers' loads and tilts under the scene's (straight) roller; the
//! designed crown then changes the rollers' stiffness and so the loads a little. The final
//! figures are all of one state: the distributions solved again with the designed crown, and
//! every contact solved at those loads under it.

use std::time::Instant;

use contopt_contact::InterfaceProblem;
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::stress::peak_index;
use contopt_core::{ContactState, Error, Result, Termination};

use contopt_results::{
    BearingLoadCase, BearingReport, BearingRoller, CaseReport, ModelLimit, TunedProfile,
    WorstContact,
};
use contopt_roller::{
    bearing_cases, end_ratio, hertz_slice_load, penalised_worst, robust_crown,
    slice_loads_from_pressure, slice_peaks_from_pressure, solve_cases, tolerance_band,
    tune_profile, tune_profile_coarse_to_fine, BearingSettings, CaseContact, Crown,
    CylindricalRollerBearing, Grid, LoadCase, LoadDistribution, Raceway, Roller, RollerCase,
    RollerEnds, SliceLoads, EDGE_LOADING,
};

mod crown_box;

use super::grids::{self, Grids, Solved};
use super::{duty_cycle_levels, BearingObjective, BearingPlan};
use crate::lives::{CaseSlices, LivesInput, LivesOutput};
use crate::methods::{roller_report, BearingCrown, Check, Context, Design, Designed};
use crate::report::{GROWTH, MIN_CELLS_ACROSS};

/// Two rollers whose loads agree to this fraction and whose tilts agree to this many
/// arc-minutes are one contact (a roller and its mirror across the load line: round-off).
const SAME_CONTACT: f64 = 1e-9;

/// The distinct contacts of a bearing's loaded rollers on the solved raceway over every load
/// case, and where each roller's is.
struct Envelope {
    /// The distinct contacts, in the order met (load case by load case, heaviest first).
    contacts: Vec<RollerCase>,
    /// Each contact's first load case and roller.
    origin: Vec<(usize, usize)>,
    /// Per load case, per roller: its contact, or `None` when unloaded.
    index: Vec<Vec<Option<usize>>>,
}

impl Envelope {
    fn new(distributions: &[LoadDistribution], raceway: Raceway) -> Self {
        let mut env = Envelope {
            contacts: vec![],
            origin: vec![],
            index: vec![],
        };
        for (i, d) in distributions.iter().enumerate() {
            let mut index = vec![None; d.rollers.len()];
            for case in d.roller_cases(raceway) {
                let same = env.contacts.iter().position(|c| {
                    (c.load_n - case.load_n).abs() <= SAME_CONTACT * case.load_n
                        && (c.tilt_arcmin - case.tilt_arcmin).abs() <= SAME_CONTACT
                });
                index[case.roller] = Some(same.unwrap_or_else(|| {
                    env.contacts.push(case);
                    env.origin.push((i, case.roller));
                    env.contacts.len() - 1
                }));
            }
            env.index.push(index);
        }
        env
    }

    /// The contacts as load cases of `nominal` (under `roller`), with the tolerance band's
    /// two further crowns when `tolerance` > 0: [`tolerance_band`]'s blocks.
    fn cases<'a>(
        &self,
        nominal: &InterfaceProblem<'a>,
        roller: &Roller,
        tolerance: f64,
    ) -> Result<Vec<LoadCase<'a>>> {
        let cases = bearing_cases(nominal, roller, &self.contacts)?;
        match tolerance > 0.0 {
            true => tolerance_band(&cases, roller.length, tolerance),
            false => Ok(cases),
        }
    }

    /// The band's crowns: 1, or 3 with a tolerance band.
    fn bands(&self, states: usize) -> usize {
        states / self.contacts.len().max(1)
    }
}

/// The solved raceway's figures of one state of the run.
struct Geometry<'p> {
    points: &'p [[f64; 3]],
    /// The grid's cell \[mm\].
    cell: [f64; 2],
    /// The effective length \[mm\].
    length: f64,
    /// The pair's radius across the contact and its modulus \[mm, MPa\] (Hertz's line load of
    /// a slice's peak).
    radius: f64,
    e_star: f64,
}

/// Each load case's distribution for `bearing`, its equilibrium's steps reported to
/// `observer`; an unmet equilibrium is its termination.
fn distributions(
    bearing: &CylindricalRollerBearing,
    plan: &BearingPlan,
    observer: &dyn Observer,
) -> Result<std::result::Result<Vec<LoadDistribution>, Termination>> {
    let settings = BearingSettings::default();
    let mut all = Vec::with_capacity(plan.loads.len());
    for (_, load, _) in &plan.loads {
        let d = bearing.solve_observed(load, &settings, observer)?;
        if !d.termination.is_solved() {
            return Ok(Err(d.termination));
        }
        all.push(d);
    }
    Ok(Ok(all))
}

/// Where a raceway's contacts lie: each on its grid, or all on one.
enum OnGrid<'r, 'a> {
    Each(&'r Grids<'a>),
    One(&'r [[f64; 3]], [f64; 2]),
}

impl OnGrid<'_, '_> {
    /// Contact k's points and cell.
    fn at(&self, k: usize) -> (&[[f64; 3]], [f64; 2]) {
        match self {
            OnGrid::Each(grids) => (grids.of(k).points(), grids.of(k).cell),
            OnGrid::One(points, cell) => (points, *cell),
        }
    }
}

/// A raceway's contacts as the slices take them: their envelope, pressures (band after
/// band), grids, and Hertz's radius and modulus of the pair.
struct RingPressures<'r, 'a> {
    raceway: Raceway,
    env: &'r Envelope,
    pressures: Vec<&'r [f64]>,
    grid: OnGrid<'r, 'a>,
    radius: f64,
    e_star: f64,
}

impl<'a> Ring<'a> {
    fn pressures(&self) -> RingPressures<'_, 'a> {
        RingPressures {
            raceway: self.raceway,
            env: &self.env,
            pressures: (self.solved.states.iter())
                .map(|s| s.pressure.as_slice())
                .collect(),
            grid: OnGrid::Each(&self.grids),
            radius: self.radius,
            e_star: self.e_star,
        }
    }
}

/// Every load case's slice loads for the lives stage ([`crate::lives`]): the slice model's,
/// and per crown of the band each of `rings`' raceways replaced by its half-space contacts'
/// (contact k on its grid) and by the Hertzian loads of their slices' peaks.
fn slices(
    plan: &BearingPlan,
    distributions: &[LoadDistribution],
    rings: &[RingPressures],
    length: f64,
) -> Result<Vec<CaseSlices>> {
    let bands = (rings.iter())
        .map(|r| r.env.bands(r.pressures.len()))
        .min()
        .unwrap_or(1);
    let mut all = Vec::with_capacity(distributions.len());
    for (i, d) in distributions.iter().enumerate() {
        let base = SliceLoads::from_distribution(d)?;
        let mut per_band = vec![];
        for band in 0..bands {
            let (mut loads, mut raised) = (base.clone(), base.clone());
            for ring in rings {
                ring_slices(plan, ring, i, band, length, [&mut loads, &mut raised])?;
            }
            per_band.push([loads, raised]);
        }
        let (_, load, fraction) = &plan.loads[i];
        all.push(CaseSlices {
            radial_n: load.radial_n,
            fraction: *fraction,
            slice_model: base,
            bands: per_band,
        });
    }
    Ok(all)
}

/// Load case `i`'s rollers on `ring` in crown `band` of the tolerance: their slices in
/// `loads` from the half-space pressures, in `raised` from their slices' peaks too.
fn ring_slices(
    plan: &BearingPlan,
    ring: &RingPressures,
    i: usize,
    band: usize,
    length: f64,
    [loads, raised]: [&mut SliceLoads; 2],
) -> Result<()> {
    let slices = plan.bearing.slices;
    let width = length / slices as f64;
    let n = ring.env.contacts.len();
    for (j, contact) in ring.env.index[i].iter().enumerate() {
        let Some(k) = contact else { continue };
        let p = ring.pressures[band * n + k];
        let (points, cell) = ring.grid.at(*k);
        let q = slice_loads_from_pressure(points, p, cell, length, slices)?;
        let peaks = slice_peaks_from_pressure(points, p, cell, length, slices)?;
        let hertz: Vec<f64> = q
            .iter()
            .zip(&peaks)
            .map(|(q, p)| q.max(hertz_slice_load(*p, width, ring.radius, ring.e_star)))
            .collect();
        loads.set(ring.raceway, j, &q)?;
        raised.set(ring.raceway, j, &hertz)?;
    }
    Ok(())
}

/// The lives stage's input for `cases` under `plan`.
fn lives_input<'a>(plan: &'a BearingPlan, cases: &'a [CaseSlices]) -> LivesInput<'a> {
    LivesInput {
        rating: plan.rating,
        ratings: &plan.ratings,
        rotating: plan.rotating,
        cases,
        speed_rpm: plan.speed_rpm,
        lubrication: plan.lubrication.map(|l| l.figures),
    }
}

/// What a design of the crown found: the gap change per point \[mm\] and its account.
struct Crowned {
    change: Vec<f64>,
    method: Method,
    termination: Termination,
    bound_p_max: Option<f64>,
    tuned: Option<TunedProfile>,
    /// The robust crown's pressure level per load case, for the life.
    levels: Option<Vec<f64>>,
    /// The robust crown's largest p − v·p̂ over Ω_nv \[MPa\].
    omega_nv_excess: Option<f64>,
}

/// The life as a search's objective: −1000·ln L, so that the search's tolerance (absolute, in
/// the objective's units) is in thousandths of the life's logarithm, whatever its size.
const LOG_SCALE: f64 = 1000.0;

/// The envelope a bearing's crown is designed over: the distributions under the scene's
/// roller (`first`), their distinct contacts, those as load cases, and the grid's figures.
struct Over<'e, 'a> {
    first: &'e [LoadDistribution],
    env: &'e Envelope,
    cases: &'e [LoadCase<'a>],
    at: &'e Geometry<'e>,
}

/// The design of the crown over the envelope `over` by `crown`, on the case's contact `c`.
fn design(plan: &BearingPlan, crown: BearingCrown, c: &Context, over: &Over) -> Result<Crowned> {
    let Over {
        first,
        env,
        cases,
        at,
    } = *over;
    let (problem, solver, observer) = (c.problem, c.solver, c.observer);
    let roller = (c.case.roller)
        .ok_or_else(|| Error::invalid("bearing", "its roller", "was not composed"))?;
    let family = match crown {
        BearingCrown::Envelope(settings) => {
            let controller = (c.case.controller)
                .ok_or_else(|| Error::invalid("controller", "missing", "the method needs one"))?;
            // For the life, each load case is held to its duty-cycle level.
            let levels = match plan.objective {
                BearingObjective::PMax => None,
                BearingObjective::Life => Some(contact_levels(plan, env, cases.len())?),
            };
            let crown = robust_crown(
                cases,
                levels.as_ref().map(|l| l.1.as_slice()),
                controller.build()?.as_ref(),
                at.cell[1],
                solver,
                &settings,
                observer,
            )?;
            return Ok(Crowned {
                change: crown.drop,
                method: Method::EnvelopeSplit,
                termination: crown.termination,
                bound_p_max: Some(crown.p_max),
                tuned: None,
                levels: levels.map(|l| l.0),
                omega_nv_excess: crown.omega_nv_excess,
            });
        }
        BearingCrown::Search(family, settings) => (family, settings),
    };
    let loose = crate::methods::search::search_solver(solver, problem);
    let solver = loose.as_deref().unwrap_or(solver);
    let mut objective = search_objective(plan, first, env, at);
    let fine = Grid {
        cases,
        objective: &mut objective,
    };
    let tuned = match coarse_grid(plan.cells, problem, at) {
        Some((nominal, cell)) => {
            let coarse = env.cases(&nominal, roller, plan.tolerance)?;
            let geometry = Geometry {
                points: nominal.interface().points(),
                cell,
                ..*at
            };
            let mut on_coarse = search_objective(plan, first, env, &geometry);
            let coarse = Grid {
                cases: &coarse,
                objective: &mut on_coarse,
            };
            let (f, s) = family;
            tune_profile_coarse_to_fine(coarse, fine, roller, f, solver, &s, observer)?
        }
        None => tune_profile(
            cases,
            roller,
            family.0,
            solver,
            &family.1,
            fine.objective,
            observer,
        )?,
    };
    Ok(Crowned {
        tuned: Some(crate::methods::search::tuned_profile(&tuned)),
        change: tuned.drop,
        method: Method::ProfileSearch,
        termination: tuned.termination,
        bound_p_max: None,
        levels: None,
        omega_nv_excess: None,
    })
}

/// The load cases' duty-cycle pressure levels ([`duty_cycle_levels`]) from their heaviest
/// rollers in `env`, and each of the `cases` contacts' (band after band): its load case's.
fn contact_levels(
    plan: &BearingPlan,
    env: &Envelope,
    cases: usize,
) -> Result<(Vec<f64>, Vec<f64>)> {
    let mut heaviest = vec![0.0; plan.loads.len()];
    for (contact, (i, _)) in env.contacts.iter().zip(&env.origin) {
        heaviest[*i] = f64::max(heaviest[*i], contact.load_n);
    }
    let fractions: Vec<f64> = plan.loads.iter().map(|l| l.2).collect();
    let levels = duty_cycle_levels(&heaviest, &fractions)?;
    let n = env.contacts.len().max(1);
    let per_contact = (0..cases).map(|k| levels[env.origin[k % n].0]).collect();
    Ok((levels, per_contact))
}

/// What a profile search minimises over the envelope's contacts on the grid of `at`: the
/// worst p_max ([`penalised_worst`]) or −1000·ln of the duty cycle's life
/// ([`LOG_SCALE`]).
fn search_objective<'o>(
    plan: &'o BearingPlan,
    first: &'o [LoadDistribution],
    env: &'o Envelope,
    at: &'o Geometry,
) -> impl FnMut(&[ContactState]) -> Result<f64> + 'o {
    move |states: &[ContactState]| -> Result<f64> {
        match plan.objective {
            BearingObjective::PMax => Ok(penalised_worst(at.points, states)),
            BearingObjective::Life => {
                Ok(-LOG_SCALE * peak_life(plan, first, env, at, states)?.ln())
            }
        }
    }
}

/// The duty cycle's life from the slice peaks of the solved raceway's contacts `states` (all
/// on the grid of `at`), the other ring's the slice model's \[10⁶ revolutions\].
fn peak_life(
    plan: &BearingPlan,
    first: &[LoadDistribution],
    env: &Envelope,
    at: &Geometry,
    states: &[ContactState],
) -> Result<f64> {
    let ring = RingPressures {
        raceway: plan.raceway,
        env,
        pressures: states.iter().map(|s| s.pressure.as_slice()).collect(),
        grid: OnGrid::One(at.points, at.cell),
        radius: at.radius,
        e_star: at.e_star,
    };
    let cases = slices(plan, first, &[ring], at.length)?;
    Ok(crate::lives::lives(&lives_input(plan, &cases))?
        .duty
        .peak_pressure_mrev)
}

/// A grid of at least this many points is searched coarse to fine
/// ([`tune_profile_coarse_to_fine`]); a smaller one on itself (its solves cost little).
const COARSE_POINTS: usize = 2000;

/// The scene's contact problem on a grid of half the cells each way
/// ([`InterfaceProblem::coarsen`]) with its cell \[mm\], for a coarse-to-fine search; `None`
/// when the grid is small ([`COARSE_POINTS`]) or its bodies offer no coarser grid.
fn coarse_grid<'a>(
    [nx, ny]: [usize; 2],
    problem: &InterfaceProblem<'a>,
    at: &Geometry,
) -> Option<(InterfaceProblem<'a>, [f64; 2])> {
    if problem.len() < COARSE_POINTS || nx < 2 || ny < 2 {
        return None;
    }
    let (coarse, _) = problem.coarsen()?;
    (coarse.len() == nx.div_ceil(2) * ny.div_ceil(2))
        .then_some((coarse, [2.0 * at.cell[0], 2.0 * at.cell[1]]))
}

/// The designed drop along the centre row as the roller's crown for the slice model: a table
/// of (|x|, drop) over the row's cells at x ≥ 0 (a design's crown is symmetric).
fn crown_table(points: &[[f64; 3]], drop: &[f64], dy: f64) -> Result<Crown> {
    let mut rows: Vec<(f64, f64)> = points
        .iter()
        .zip(drop)
        .filter(|(x, _)| x[1].abs() < 0.5 * dy && x[0] >= 0.0)
        .map(|(x, d)| (x[0], *d))
        .collect();
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    Crown::table(
        rows.iter().map(|r| r.0).collect(),
        rows.iter().map(|r| r.1).collect(),
    )
}

/// Runs a bearing case on its composed contact `problem` (the roller under the design load):
/// the distributions, the design, the final contacts and the lives into `report`. Returns the
/// design's account for the report, with the worst contact's pressure, and that contact's
/// problem (the one the report's checks take).
impl Design for BearingPlan {
    /// Its checks are the bearing's plan's ([`super::plan`]).
    fn check(&self, _c: &Check) -> Result<()> {
        Ok(())
    }

    fn run(&self, c: &Context, report: &mut CaseReport) -> Result<Designed> {
        run(self, c, report)
    }
}

fn run(plan: &BearingPlan, c: &Context, report: &mut CaseReport) -> Result<Designed> {
    let (problem, solver, observer) = (c.problem, c.solver, c.observer);
    let roller = (c.case.roller)
        .ok_or_else(|| Error::invalid("bearing", "its roller", "was not composed"))?;
    let at = Geometry {
        points: problem.interface().points(),
        cell: c.case.layout.edge_cell(),
        length: roller.length,
        radius: roller.radius()?,
        e_star: roller.e_star(),
    };
    let started = Instant::now();
    let first = match distributions(&plan.bearing, plan, observer)? {
        Ok(d) => d,
        Err(why) => return Ok(Designed::unsolved(why, solver.method())),
    };
    report.time("distribution", started);
    report.warnings.extend(lone_rollers(plan, &first));
    let designed = match crown(plan, c, &first, &at, report)? {
        Ok(designed) => designed,
        Err(stopped) => return Ok(*stopped),
    };
    // The final state: the distributions under the final crown, every contact at its loads.
    let dists = match &designed {
        Some(d) => match crowned_distributions(plan, &d.change, &at, observer)? {
            Ok(dists) => dists,
            Err(why) => return Ok(Designed::unsolved(why, solver.method())),
        },
        None => first,
    };
    let layout = grids::Layout {
        cells: plan.cells,
        reach: plan.reach,
        ends: plan.free_ends.map(|weight| RollerEnds {
            chamfer_mm: plan.bearing.chamfer,
            weight,
        }),
    };
    let started = Instant::now();
    let change = designed
        .as_ref()
        .map_or_else(|| vec![0.0; problem.len()], |d| d.change.clone());
    let solve = |cases: &[LoadCase], change: &[f64]| {
        solve_cases(cases, change, solver, None, &Nested(observer))
    };
    let shared = Shared {
        layout: &layout,
        change: &change,
        solve: &solve,
    };
    let solved = ring(
        plan,
        &dists,
        plan.raceway,
        (problem, roller, at.cell),
        &shared,
    )?;
    let other = other_raceway(plan.raceway);
    let built = grids::built(
        &raceway_roller(plan, roller, other),
        roller.load,
        &layout,
        problem.dense_limit(),
    )?;
    let nominal = (&built.problem, &built.roller, built.cell);
    let opposite = ring(plan, &dists, other, nominal, &shared)?;
    report.time("solve", started);
    if let Some((why, which)) = [&solved, &opposite]
        .into_iter()
        .find_map(|ring| unsolved(plan, ring))
    {
        report.warnings.push(which);
        return Ok(Designed::unsolved(why, solver.method()));
    }
    let rings = Rings {
        dists: &dists,
        solved: &solved,
        opposite: &opposite,
        at: &at,
        roller,
    };
    let out = finish(plan, c, report, designed, &rings)?;
    let started = Instant::now();
    let worst_crown =
        crown_box::worst_crown(plan, c, (&dists, &change), &at, &mut report.warnings)?;
    if let Some(b) = report.bearing.as_mut() {
        b.crown_tolerance = worst_crown;
    }
    report.time("tolerance box", started);
    Ok(out)
}

/// The final state's contacts on both raceways, under the final distributions `dists`: the
/// designed one (`solved`) and the other (`opposite`), on the design's geometry `at`.
struct Rings<'r, 'a> {
    dists: &'r [LoadDistribution],
    solved: &'r Ring<'a>,
    opposite: &'r Ring<'a>,
    at: &'r Geometry<'r>,
    roller: &'r Roller,
}

/// The report of a bearing case from both raceways' final contacts: the lives (their own
/// stage, [`crate::lives`]), the warnings of the contacts' cells and edges, the bearing's
/// figures; and the design's outcome, the worst contact on the design grid shown.
fn finish(
    plan: &BearingPlan,
    c: &Context,
    report: &mut CaseReport,
    designed: Option<Crowned>,
    rings: &Rings,
) -> Result<Designed> {
    let Rings {
        dists,
        solved,
        opposite,
        at,
        roller,
    } = *rings;
    let started = Instant::now();
    let cases = slices(
        plan,
        dists,
        &[solved.pressures(), opposite.pressures()],
        at.length,
    )?;
    let lives = crate::lives::lives(&lives_input(plan, &cases))?;
    report.time("lives", started);
    let (env, grids, states) = (&solved.env, &solved.grids, &solved.solved.states);
    let n = env.contacts.len();
    let worst = (0..states.len())
        .max_by(|&a, &b| states[a].p_max().total_cmp(&states[b].p_max()))
        .unwrap_or(0);
    // The report's fields lie on the design grid: they show its worst contact.
    let shown = (0..states.len())
        .filter(|&s| grids.of[s % n] == 0)
        .max_by(|&a, &b| states[a].p_max().total_cmp(&states[b].p_max()))
        .unwrap_or(worst);
    let mut reached = vec![];
    for r in [solved, opposite] {
        let designed = designed.is_some() && r.raceway == plan.raceway;
        (report.warnings).extend(resolution_warnings(plan, r, designed)?);
        reached.extend(edge_reached(plan, r));
    }
    report.limit = edge_limit(plan, &reached);
    if shown != worst {
        report.warnings.push(elsewhere(plan, env, worst % n));
    }
    let levels = designed.as_ref().and_then(|d| d.levels.clone());
    report.bearing = Some(bearing_report(
        plan,
        dists,
        [solved, opposite],
        worst,
        lives,
        levels,
    ));
    let last = Final {
        solved: &solved.solved,
        env,
        grids,
        shown,
    };
    outcome(designed, &last, at, roller, c.solver.method())
}

/// The crown the case designs over the first distributions `first` (none when it gives its
/// own), timed into `report`; a design that stopped short of a solution is the case's outcome
/// (`Err`).
fn crown(
    plan: &BearingPlan,
    c: &Context,
    first: &[LoadDistribution],
    at: &Geometry,
    report: &mut CaseReport,
) -> Result<std::result::Result<Option<Crowned>, Box<Designed>>> {
    let Some(crown) = plan.crown else {
        return Ok(Ok(None));
    };
    let roller = (c.case.roller)
        .ok_or_else(|| Error::invalid("bearing", "its roller", "was not composed"))?;
    let env = Envelope::new(first, plan.raceway);
    let started = Instant::now();
    let cases = env.cases(c.problem, roller, plan.tolerance)?;
    let envelope = Over {
        first,
        env: &env,
        cases: &cases,
        at,
    };
    let d = design(plan, crown, c, &envelope)?;
    report.time("optimise", started);
    if !d.termination.is_solved() && !matches!(d.termination, Termination::StepLimit { .. }) {
        let mut out = Designed::unsolved(d.termination.clone(), c.solver.method());
        out.method = Some(d.method);
        return Ok(Err(Box::new(out)));
    }
    Ok(Ok(Some(d)))
}

/// The raceway across the roller from `raceway`.
fn other_raceway(raceway: Raceway) -> Raceway {
    match raceway {
        Raceway::Inner => Raceway::Outer,
        Raceway::Outer => Raceway::Inner,
    }
}

/// The case's roller (`roller`, on the solved raceway) on `raceway`: that raceway's diameter
/// (negative for the outer ring, whose conformity the gap's 1/R = 2/D − 2/D_o holds) and
/// crown, the roller's own crown.
fn raceway_roller(plan: &BearingPlan, roller: &Roller, raceway: Raceway) -> Roller {
    let b = &plan.bearing;
    let (diameter, crown) = match raceway {
        Raceway::Inner => (b.pitch_diameter - b.roller_diameter, &b.inner_crown),
        Raceway::Outer => (-(b.pitch_diameter + b.roller_diameter), &b.outer_crown),
    };
    Roller {
        raceway_diameter: Some(diameter),
        crown: b.roller_crown.clone().plus(crown.clone()),
        ..roller.clone()
    }
}

/// The solve of load cases under a gap change (the case's solver, reporting to its
/// observer).
type SolveCases<'d> = dyn Fn(&[LoadCase], &[f64]) -> Result<Vec<ContactState>> + 'd;

/// What the final state's contacts share on either raceway: the grids' layout, the crown's
/// gap change, and the solve of a list of load cases.
struct Shared<'d> {
    layout: &'d grids::Layout,
    change: &'d [f64],
    solve: &'d SolveCases<'d>,
}

/// One raceway's contacts in the final state: the distinct contacts, their grids and
/// solutions, and Hertz's radius and modulus of its pair (for a slice's peak load).
struct Ring<'a> {
    raceway: Raceway,
    env: Envelope,
    grids: Grids<'a>,
    solved: Solved,
    radius: f64,
    e_star: f64,
}

/// Every contact of `raceway` under `dists` solved on its grid, `nominal` the problem of
/// `roller` (on that raceway) under the design load and its grid's cell \[mm\].
fn ring<'a>(
    plan: &BearingPlan,
    dists: &[LoadDistribution],
    raceway: Raceway,
    (nominal, roller, cell): (&InterfaceProblem<'a>, &Roller, [f64; 2]),
    shared: &Shared,
) -> Result<Ring<'a>> {
    let env = Envelope::new(dists, raceway);
    let grids = Grids::new(nominal, roller, cell, shared.layout, &env.contacts)?;
    let solved = grids.solve(&env.contacts, plan.tolerance, shared.change, shared.solve)?;
    Ok(Ring {
        raceway,
        env,
        grids,
        solved,
        radius: roller.radius()?,
        e_star: roller.e_star(),
    })
}

/// The final state of a bearing's run: every contact's solution on its grid (the distinct
/// contacts first, then a tolerance band's), and the contact the report shows.
struct Final<'f, 'a> {
    solved: &'f Solved,
    env: &'f Envelope,
    grids: &'f Grids<'a>,
    shown: usize,
}

/// The design's outcome from the final state: the shown contact's pressure and gap (its
/// initial gap the one the report shows), the crown designed (or the scene's, shown as Δh),
/// and the roller's figures over every distinct contact, the shown one first.
fn outcome(
    designed: Option<Crowned>,
    last: &Final,
    at: &Geometry,
    roller: &Roller,
    solver: Method,
) -> Result<Designed> {
    let (states, shown) = (&last.solved.states, last.shown);
    let n = last.env.contacts.len();
    let drop: Vec<f64> = match &designed {
        Some(d) => d.change.clone(),
        None => at
            .points
            .iter()
            .map(|x| roller.crown.drop(x[0], roller.length))
            .collect::<Result<Vec<f64>>>()?,
    };
    // The shown state first (a band's when the band holds the worst), then every contact's
    // nominal state.
    let contacts: Vec<(usize, CaseContact)> = std::iter::once(shown)
        .chain((0..n).filter(|&s| s != shown))
        .map(|s| {
            let k = s % n;
            let contact = CaseContact {
                load_n: last.env.contacts[k].load_n,
                tilt_arcmin: last.env.contacts[k].tilt_arcmin,
                pressure: &states[s].pressure,
                approach_mm: states[s].approach().unwrap_or(0.0),
            };
            (k, contact)
        })
        .collect();
    let figures = last.grids.figures(&contacts, &drop);
    let state = &states[shown];
    let tuned = designed.as_ref().and_then(|d| d.tuned.clone());
    Ok(Designed {
        method: designed.as_ref().map(|d| d.method),
        solver: Some(solver),
        termination: designed
            .as_ref()
            .map_or(Termination::Converged, |d| d.termination.clone()),
        pressure: state.pressure.clone(),
        gap: state.gap.clone(),
        rigid: state.rigid.clone(),
        gap_change: designed
            .as_ref()
            .map_or_else(Vec::new, |d| d.change.clone()),
        crown: designed.is_none().then_some(drop),
        bound_p_max: designed.as_ref().and_then(|d| d.bound_p_max),
        dh_max: designed
            .as_ref()
            .map(|d| d.change.iter().fold(0.0, |m: f64, v| m.max(*v))),
        omega_nv_excess: designed.as_ref().and_then(|d| d.omega_nv_excess),
        passes: vec![],
        roller: roller_report(&figures, true, tuned),
        shown_gap: Some(last.solved.initial_gaps[shown].clone()),
    })
}

/// The warnings of load cases whose clearance leaves one roller alone loaded: the bearing
/// then carries its load on a single roller, whatever its rating assumes.
fn lone_rollers(plan: &BearingPlan, dists: &[LoadDistribution]) -> Vec<String> {
    let clearance = plan.bearing.clearance;
    (dists.iter().enumerate())
        .filter_map(|(i, d)| {
            let mut loaded = (0..d.rollers.len()).filter(|&j| d.rollers[j].load_n > 0.0);
            let j = loaded.next()?;
            loaded.next().is_none().then(|| {
                format!(
                    "load case {i} (\"{}\"): the diametral clearance {clearance} mm ({:.0} µm) \
                     leaves roller {j} alone loaded, carrying all of F_r = {} N; check \
                     bearing.clearance_mm (in millimetres)",
                    plan.loads[i].0,
                    1e3 * clearance,
                    plan.loads[i].1.radial_n
                )
            })
        })
        .collect()
}

/// A contact named as tables name it: its load case (label) and roller, and its load.
fn named(plan: &BearingPlan, env: &Envelope, k: usize) -> String {
    let (i, j) = env.origin[k];
    format!(
        "load case {i} (\"{}\") roller {j} (Q = {:.4e} N)",
        plan.loads[i].0, env.contacts[k].load_n
    )
}

/// The first contact of `ring` whose solve did not converge: how it ended, and a warning
/// naming it (load case, roller, load, raceway, and the tolerance band's crown it was
/// solved under), so a bearing of many contacts says which one failed.
fn unsolved(plan: &BearingPlan, ring: &Ring) -> Option<(Termination, String)> {
    // States are contact k of band j at j·n + k; one exists only when n > 0.
    let n = ring.env.contacts.len();
    let states = &ring.solved.states;
    let at = states.iter().position(|s| !s.termination.is_solved())?;
    let band = match at / n {
        0 => String::new(),
        b => {
            let sign = if b == 1 { '+' } else { '−' };
            format!(
                ", its crown's drop {sign}{} µm (the tolerance band)",
                1e3 * plan.tolerance
            )
        }
    };
    let why = states[at].termination.clone().inside(states[at].method);
    let which = format!(
        "the contact of {}{band} did not converge: {why}",
        named_on(plan, ring, at % n)
    );
    Some((why, which))
}

/// A contact of `ring` named, with its raceway when it is not the solved one's.
fn named_on(plan: &BearingPlan, ring: &Ring, k: usize) -> String {
    let name = named(plan, &ring.env, k);
    match ring.raceway == plan.raceway {
        true => name,
        false => format!("{name} on the {} raceway", raceway_name(ring.raceway)),
    }
}

/// The warning of a worst contact solved off the design grid: the report's fields show the
/// design grid's worst instead.
fn elsewhere(plan: &BearingPlan, env: &Envelope, k: usize) -> String {
    format!(
        "the worst contact, {}, is solved on cells sized for its own load, not on the design \
         load's (bearing.design_load_n = {:.4e} N): its figures are in the bearing's report, \
         while the case's pressure field shows the worst contact on the design load's cells; \
         set bearing.design_load_n near its load to see its field",
        named(plan, env, k),
        plan.design_load
    )
}

/// The warnings of contacts whose half-width spans few cells: on their own grids, fewer
/// than half of [`MIN_CELLS_ACROSS`]; and, when the crown was designed (on the design grid,
/// for all contacts at once), the load cases whose heaviest roller the design saw on the
/// design load's cells though it is far lighter (the final figures are solved on its own
/// grid, not the design's; a light roller at the edge of a loaded zone, which carries little
/// of the life, is not named).
fn resolution_warnings(plan: &BearingPlan, ring: &Ring, designed: bool) -> Result<Vec<String>> {
    let (env, grids) = (&ring.env, &ring.grids);
    let mut coarse = vec![];
    for k in 0..env.contacts.len() {
        let cells = grids.of(k).cells_across(env.contacts[k].load_n)?;
        if cells < 0.5 * MIN_CELLS_ACROSS {
            coarse.push(format!("{} with {cells:.1} cells", named_on(plan, ring, k)));
        }
    }
    let mut off_design = vec![];
    for index in env.index.iter().filter(|_| designed) {
        let heaviest = index
            .iter()
            .flatten()
            .copied()
            .max_by(|&a, &b| env.contacts[a].load_n.total_cmp(&env.contacts[b].load_n));
        if let Some(k) = heaviest.filter(|&k| grids.of[k] != 0) {
            let on_design = grids.grids[0].cells_across(env.contacts[k].load_n)?;
            off_design.push(format!(
                "{} with {on_design:.1} cells",
                named_on(plan, ring, k)
            ));
        }
    }
    let mut warnings = vec![];
    if !coarse.is_empty() {
        warnings.push(format!(
            "{} of the bearing's {} contacts span fewer than {} cells across their own Hertz \
             half-width, so their peaks and lives are coarse: {}; add cells across \
             (bearing.cells[1]) or narrow the grid (bearing.reach_b)",
            coarse.len(),
            env.contacts.len(),
            0.5 * MIN_CELLS_ACROSS,
            listed(&coarse)
        ));
    }
    if !off_design.is_empty() {
        warnings.push(format!(
            "the crown was designed over every loaded roller on the design load's cells \
             (bearing.design_load_n = {:.4e} N), where the heaviest roller of a far lighter \
             load case spans fewer than half of its cells across its half-width: {}; the \
             final figures are solved on cells sized for each roller's own load, but the \
             crown was shaped on coarse ones: set bearing.design_load_n nearer their loads if \
             those load cases matter to the design",
            plan.design_load,
            listed(&off_design)
        ));
    }
    Ok(warnings)
}

/// A point carries pressure when it holds more than this fraction of its contact's p_max.
const CARRIES: f64 = 1e-6;

/// The contacts whose pressure reaches their grid's outer rows across, each named once with
/// the reach of its grid across \[mm\]: the grid ends inside them.
fn edge_reached(plan: &BearingPlan, ring: &Ring) -> Vec<(String, f64)> {
    let (env, grids, states) = (&ring.env, &ring.grids, &ring.solved.states);
    let n = env.contacts.len().max(1);
    let mut reached: Vec<(String, f64)> = vec![];
    for (s, state) in states.iter().enumerate() {
        let k = s % n;
        let grid = grids.of(k);
        let points = grid.points();
        let outer = points.iter().fold(0.0f64, |m, x| m.max(x[1].abs()));
        let limit = CARRIES * state.p_max();
        let edge = (points.iter().zip(&state.pressure))
            .any(|(x, p)| x[1].abs() > outer - 0.5 * grid.cell[1] && *p > limit);
        let name = named_on(plan, ring, k);
        if edge && !reached.iter().any(|(r, _)| *r == name) {
            reached.push((name, outer + 0.5 * grid.cell[1]));
        }
    }
    reached
}

/// The limit of a case whose contacts `reached` their grids' outer rows across (named, with
/// each grid's reach \[mm\]): the grid ends inside them, so their pressures and the lives
/// are wrong, and `bearing.reach_b` widens every grid. It puts the case outside the model, as
/// the shown contact's own edge does ([`crate::report`]'s limits, which keep it).
fn edge_limit(plan: &BearingPlan, reached: &[(String, f64)]) -> Option<ModelLimit> {
    let &(_, extent) = reached.first()?;
    let names: Vec<String> = reached.iter().map(|(name, _)| name.clone()).collect();
    let message = format!(
        "the pressure of {} reaches the outer rows of its grid across (±{} Hertz half-widths \
         of its grid's load): the grid ends inside the contact, so its pressure and the lives \
         are wrong; raise bearing.reach_b",
        listed(&names),
        plan.reach
    );
    Some(ModelLimit {
        edge: format!("y = ±{extent:.4} mm"),
        extent_mm: extent,
        needed_mm: GROWTH * extent,
        message,
    })
}

/// At most this many contacts are named in a warning; the rest are counted.
const NAMED: usize = 6;

/// `items` joined, the first [`NAMED`] of them and a count of the rest.
fn listed(items: &[String]) -> String {
    let mut text = items[..items.len().min(NAMED)].join("; ");
    if items.len() > NAMED {
        text.push_str(&format!("; and {} more", items.len() - NAMED));
    }
    text
}

/// Each load case's distribution with the designed crown `change` (per point \[mm\]) on the
/// plan's roller, as [`distributions`] gives them.
fn crowned_distributions(
    plan: &BearingPlan,
    change: &[f64],
    at: &Geometry,
    observer: &dyn Observer,
) -> Result<std::result::Result<Vec<LoadDistribution>, Termination>> {
    let mut bearing = plan.bearing.clone();
    bearing.roller_crown =
        (bearing.roller_crown.clone()).plus(crown_table(at.points, change, at.cell[1])?);
    distributions(&bearing, plan, observer)
}

/// A ring's contact p_max per load case and roller (the band's worst); `None` unloaded.
fn ring_peaks(ring: &Ring) -> Vec<Vec<Option<f64>>> {
    let (env, states) = (&ring.env, &ring.solved.states);
    let n = env.contacts.len();
    let bands = env.bands(states.len());
    let p_max = |k: usize| {
        (0..bands)
            .map(|b| states[b * n + k].p_max())
            .fold(0.0, f64::max)
    };
    (env.index.iter())
        .map(|rollers| rollers.iter().map(|k| k.map(p_max)).collect())
        .collect()
}

/// The bearing's report from the final state: `rings` the solved raceway's contacts, then
/// the other's.
fn bearing_report(
    plan: &BearingPlan,
    dists: &[LoadDistribution],
    rings: [&Ring; 2],
    worst: usize,
    lives: LivesOutput,
    levels: Option<Vec<f64>>,
) -> BearingReport {
    let peaks = rings.map(ring_peaks);
    // Each ring's peaks as [inner, outer].
    let inner_first = usize::from(rings[0].raceway != Raceway::Inner);
    let of_ring = |i: usize, j: usize| [peaks[inner_first][i][j], peaks[1 - inner_first][i][j]];
    let arcmin = |rad: f64| 60.0 * rad.to_degrees();
    let largest = |v: &mut dyn Iterator<Item = Option<f64>>| v.flatten().fold(0.0, f64::max);
    let load_cases = dists
        .iter()
        .zip(lives.per_case.into_iter().zip(lives.per_case_hours))
        .enumerate()
        .map(|(i, (d, (lives, hours)))| {
            let rollers: Vec<BearingRoller> = (d.rollers.iter().enumerate())
                .map(|(j, r)| BearingRoller {
                    angle_deg: r.angle.to_degrees(),
                    load_n: r.load_n,
                    tilt_arcmin: [arcmin(r.tilt_inner), arcmin(r.tilt_outer)],
                    p_max_mpa: peaks[0][i][j],
                    p_max_rings_mpa: of_ring(i, j),
                })
                .collect();
            let (label, load, fraction) = &plan.loads[i];
            BearingLoadCase {
                label: label.clone(),
                fraction: *fraction,
                radial_n: load.radial_n,
                misalignment_arcmin: arcmin(d.tilt[0]),
                moment_nmm: d.moment_nmm[0],
                displacement_um: [1e3 * d.displacement_mm[0], 1e3 * d.displacement_mm[1]],
                loaded_zone_deg: d.load_zone().to_degrees(),
                load_factor: d.load_factor(),
                iterations: d.iterations,
                p_max_mpa: largest(&mut rollers.iter().map(|r| r.p_max_mpa)),
                p_max_rings_mpa: [0, 1]
                    .map(|g| largest(&mut rollers.iter().map(|r| r.p_max_rings_mpa[g]))),
                rollers,
                lives,
                hours,
            }
        })
        .collect();
    BearingReport {
        dynamic_load_rating_n: plan.rating,
        slice_ratings_n: [plan.ratings.inner, plan.ratings.outer],
        raceway: raceway_name(plan.raceway).into(),
        rotating: raceway_name(plan.rotating).into(),
        design_load_n: plan.design_load,
        free_ends_weight: plan.free_ends,
        tolerance_um: 1e3 * plan.tolerance,
        pressure_levels: levels,
        contacts_solved: rings.iter().map(|r| r.solved.states.len()).sum(),
        load_cases,
        duty_cycle: lives.duty,
        speed_rpm: plan.speed_rpm,
        duty_cycle_hours: lives.duty_hours,
        lubrication: plan.lubrication.map(|l| l.report),
        crown_tolerance: None,
        worst: worst_contact(plan, rings[0], worst),
    }
}

/// The solved raceway's worst contact, state `worst` of `ring`.
fn worst_contact(plan: &BearingPlan, ring: &Ring, worst: usize) -> WorstContact {
    let (env, states) = (&ring.env, &ring.solved.states);
    let n = env.contacts.len();
    let (k, band) = (worst % n, worst / n);
    let (i, j) = env.origin[k];
    let pressure = &states[worst].pressure;
    let top = peak_index(pressure).unwrap_or(0);
    let points = ring.grids.of(k).points();
    let deviation = [0.0, 1.0, -1.0][band.min(2)] * 1e3 * plan.tolerance;
    WorstContact {
        load_case: i,
        roller: j,
        load_n: env.contacts[k].load_n,
        tilt_arcmin: env.contacts[k].tilt_arcmin,
        deviation_um: deviation,
        p_max_mpa: states[worst].p_max(),
        p_max_at_mm: [points[top][0], points[top][1]],
        edge_loading: end_ratio(points, pressure) > EDGE_LOADING,
    }
}

/// A raceway's name in the report.
fn raceway_name(r: Raceway) -> &'static str {
    match r {
        Raceway::Inner => "inner",
        Raceway::Outer => "outer",
    }
}
