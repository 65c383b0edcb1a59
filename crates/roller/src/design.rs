//! Crowns designed for an envelope of load cases: the cases ([`load_cases`]), their contact
//! under one crown ([`solve_cases`]), the robust crown of the envelope load split
//! ([`robust_crown`], Páczelt 1994 §3.2 with the control of eq. 3.1 over every case) and the
//! Fujiwara–Kawase profile tuned by a Nelder–Mead search ([`tune_fujiwara_kawase`]).

use std::ops::ControlFlow;

use contopt_contact::{parallel, ContactSolver, InterfaceProblem};
use contopt_core::observe::{Method, Nested, Observer};
use contopt_core::{check, ContactState, Error, GapShape, Result, Termination};
use contopt_optimise::{
    nelder_mead_observed, Controller, LoadSplitSettings, Minimum, Optimisation, Region,
    SearchSettings,
};
use serde::{Deserialize, Serialize};

use crate::{end_ratio, Crown, Roller, RollerCase, EDGE_LOADING};

/// A load factor this close to 1 and a tilt this close to the scene's \[arc-minutes\] are the
/// scene's own case, listed first already (round-off).
const SAME_CASE: f64 = 1e-12;

/// The envelope of load cases a crown serves: every combination of a load factor (times the
/// roller's load) and a tilt.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Envelope {
    /// Factors on the roller's load, each positive.
    pub load_factors: Vec<f64>,
    /// Tilts γ \[arc-minutes\].
    pub tilts_arcmin: Vec<f64>,
}

impl Envelope {
    /// The envelope, checked: at least one value of each, finite, the load factors positive.
    pub fn check(&self) -> Result<()> {
        for (field, values) in [
            ("load_factors", &self.load_factors),
            ("tilts_arcmin", &self.tilts_arcmin),
        ] {
            check::count(
                &format!("{field} (its length)"),
                values.len(),
                1,
                usize::MAX,
            )?;
            check::all_finite(field, values)?;
        }
        check::all_positive("load_factors", &self.load_factors)?;
        Ok(())
    }
}

/// One load case: its load \[N\], tilt \[arc-minutes\] and contact problem.
#[derive(Clone, Debug)]
pub struct LoadCase<'a> {
    /// The load Q \[N\].
    pub load_n: f64,
    /// The tilt γ \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// The contact problem under that load and tilt.
    pub problem: InterfaceProblem<'a>,
}

/// The cases of an envelope: the roller's own (`nominal`, under `roller`'s load and tilt)
/// first, then every other combination of a load factor and a tilt of `envelope`, each the
/// nominal problem with its load scaled and the gap tilted by the difference of tilts.
pub fn load_cases<'a>(
    nominal: &InterfaceProblem<'a>,
    roller: &Roller,
    envelope: Option<&Envelope>,
) -> Result<Vec<LoadCase<'a>>> {
    let pairs: Vec<(f64, f64)> = match envelope {
        None => vec![],
        Some(envelope) => {
            envelope.check()?;
            envelope
                .load_factors
                .iter()
                .flat_map(|&f| {
                    envelope
                        .tilts_arcmin
                        .iter()
                        .map(move |&t| (f * roller.load, t))
                })
                .collect()
        }
    };
    cases_of(nominal, roller, &pairs)
}

/// The cases of a bearing's rollers on one raceway ([`crate::LoadDistribution::roller_cases`]):
/// each roller's load and tilt, in their order, the nominal problem (under `roller`'s load and
/// tilt) with its load scaled and its gap tilted by the difference of tilts. The nominal
/// problem is not a case of its own.
pub fn bearing_cases<'a>(
    nominal: &InterfaceProblem<'a>,
    roller: &Roller,
    rollers: &[RollerCase],
) -> Result<Vec<LoadCase<'a>>> {
    rollers
        .iter()
        .enumerate()
        .map(|(j, r)| {
            check::positive(&format!("rollers[{j}].load_n"), r.load_n)?;
            check::finite(&format!("rollers[{j}].tilt_arcmin"), r.tilt_arcmin)?;
            scaled_case(nominal, roller, r.load_n, r.tilt_arcmin)
        })
        .collect()
}

/// The nominal case, then one per (load \[N\], tilt \[arc-minutes\]) of `pairs` other than it.
fn cases_of<'a>(
    nominal: &InterfaceProblem<'a>,
    roller: &Roller,
    pairs: &[(f64, f64)],
) -> Result<Vec<LoadCase<'a>>> {
    let (load, tilt) = (roller.load, roller.tilt_arcmin());
    let mut cases = vec![LoadCase {
        load_n: load,
        tilt_arcmin: tilt,
        problem: nominal.clone(),
    }];
    for &(case_load, t) in pairs {
        let factor = case_load / load;
        if (factor - 1.0).abs() < SAME_CASE && (t - tilt).abs() < SAME_CASE {
            continue;
        }
        cases.push(scaled_case(nominal, roller, case_load, t)?);
    }
    Ok(cases)
}

/// The nominal problem (under `roller`'s load and tilt) under `load` \[N\] and `tilt`
/// \[arc-minutes\]: its modes' loads scaled, its gap tilted by the difference.
fn scaled_case<'a>(
    nominal: &InterfaceProblem<'a>,
    roller: &Roller,
    load: f64,
    tilt: f64,
) -> Result<LoadCase<'a>> {
    let factor = load / roller.load;
    let mut modes = nominal.modes().to_vec();
    modes.iter_mut().for_each(|m| m.load *= factor);
    let slope = ((tilt - roller.tilt_arcmin()) / 60.0).to_radians();
    let gap: Vec<f64> = nominal
        .initial_gap()
        .iter()
        .zip(nominal.interface().points())
        .map(|(h, x)| h + slope * x[0])
        .collect();
    Ok(LoadCase {
        load_n: load,
        tilt_arcmin: tilt,
        problem: nominal.with_modes(modes)?.with_initial_gap(&gap)?,
    })
}

/// The crown's tolerance band: every case of `cases` with the crown's drop off by +t·(2x/l)²
/// and by −t·(2x/l)² (`tolerance` = t \[mm\], `length` = l): the ends' drop off by ±t, the
/// centre true: the drop a crown's drawing tolerances, varying smoothly. (H. Fujiwara and
/// K. Yamauchi design logarithmic profiles for a tolerance band, *Tolerance design of
/// logarithmic roller profiles in cylindrical roller bearings*, J. Adv. Mech. Des. Syst.
/// Manuf. 4 (2010); their paper could not be read here, and this band is this crate's.)
/// Returned in three blocks of `cases.len()`: the cases as they are, the band's top, its
/// bottom.
///
/// Which deviations it covers: the drop off by c·t·(2x/l)² for every |c| ≤ 1, one parabolic
/// deviation scaled (an error in the crown's depth, the centre held), seen at c = ±1 only.
/// Why its ends are the worst: under a held load, adding c·(2x/l)² (≥ 0, largest at the ends)
/// to the gap lowers the pressure at the ends and raises it in the middle as c grows, so a
/// contact whose peak stays at an end (an edge-loaded or tilted case) has its largest p_max
/// at c = −1 and one whose peak stays in the middle at c = +1: over the band the worst is at
/// one of its ends. A contact whose peak moves between the middle and an end
/// within the band may peak at an interior c, which three crowns do not see; and deviations
/// of other shapes (a crown that starts elsewhere, an asymmetric or local error, a taper)
/// are not covered at all.
pub fn tolerance_band<'a>(
    cases: &[LoadCase<'a>],
    length: f64,
    tolerance: f64,
) -> Result<Vec<LoadCase<'a>>> {
    check::positive("length", length)?;
    check::non_negative("tolerance", tolerance)?;
    let mut band = cases.to_vec();
    for sign in [1.0, -1.0] {
        for case in cases {
            let gap: Vec<f64> = case
                .problem
                .initial_gap()
                .iter()
                .zip(case.problem.interface().points())
                .map(|(h, x)| h + sign * tolerance * (2.0 * x[0] / length).powi(2))
                .collect();
            band.push(LoadCase {
                problem: case.problem.with_initial_gap(&gap)?,
                ..case.clone()
            });
        }
    }
    Ok(band)
}

/// The index of the robust crown's design case, whose column loads carry the crown: the
/// heaviest case at the largest tilt, whose loaded end needs the deepest crown.
pub fn design_case(cases: &[LoadCase]) -> usize {
    (0..cases.len())
        .max_by(|&a, &b| {
            let key = |c: &LoadCase| (c.load_n, c.tilt_arcmin.abs(), c.tilt_arcmin);
            let (ka, kb) = (key(&cases[a]), key(&cases[b]));
            ka.0.total_cmp(&kb.0)
                .then(ka.1.total_cmp(&kb.1))
                .then(ka.2.total_cmp(&kb.2))
        })
        .unwrap_or(0)
}

/// Every case solved with its initial gap changed by `gap_change` \[mm per point\], each from
/// its pressure in `start` when given, its iterations reported to `observer`. The cases are
/// solved at once on the current rayon pool's threads, as many as the dense limit holds
/// ([`parallel::solve_each`]): results and events are those of solving them in turn.
pub fn solve_cases(
    cases: &[LoadCase],
    gap_change: &[f64],
    solver: &dyn ContactSolver,
    start: Option<&[ContactState]>,
    observer: &dyn Observer,
) -> Result<Vec<ContactState>> {
    let at_once = cases
        .first()
        .map_or(1, |c| parallel::at_once(solver, &c.problem));
    let solve = |k: usize, observer: &dyn Observer| {
        let case = &cases[k];
        let gap: Vec<f64> = case
            .problem
            .initial_gap()
            .iter()
            .zip(gap_change)
            .map(|(h, d)| h + d)
            .collect();
        let problem = case.problem.with_initial_gap(&gap)?;
        let start = start.map(|s| s[k].pressure.as_slice());
        solver.solve_observed(&problem, start, observer)
    };
    parallel::solve_each(cases.len(), at_once, observer, solve, Result::is_ok)
        .into_iter()
        .collect()
}

/// One case's contact under a designed crown.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Contact {
    /// The pressure at the grid's points \[MPa\].
    pub pressure: Vec<f64>,
    /// The gap after deformation, the crown included \[mm\].
    pub gap: Vec<f64>,
    /// The roller's approach \[mm\].
    pub approach_mm: f64,
}

/// The robust crown of [`robust_crown`].
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RobustCrown {
    /// The crown's drop at each point \[mm\] (the gap change, symmetric about mid-length).
    pub drop: Vec<f64>,
    /// The level p_max of max over the cases of p ≤ v·p_max \[MPa\].
    pub p_max: f64,
    /// Each case's contact in the cases' order; shorter when the split ended before it
    /// solved them.
    pub cases: Vec<Contact>,
    /// How the envelope load split ended.
    pub termination: Termination,
    /// The largest p − v·p_max over the Ω_nv of every case \[MPa\]
    /// ([`contopt_optimise::Optimum::omega_nv_excess`]).
    pub omega_nv_excess: Option<f64>,
}

/// The robust crown for `cases` ([`load_cases`]): the envelope load split
/// ([`Optimisation::envelope_split`]) of the design case ([`design_case`]) with the others,
/// a gap change symmetric about mid-length and extruded across ([`GapShape::symmetric`]
/// along x), Ω_v the centre row (|y| ≤ `dy`/2, the cell size across; eq. 3.3: the rest of
/// each column follows it) and the pressure controlled by `controller` (eq. 3.1). The split
/// reports to `observer` at level 0, its contact solves one level deeper.
///
/// With `levels` (one per case, in the cases' order) the cases' pressures are held to their
/// own levels, p_c ≤ s_c·v·p̂ ([`Optimisation::envelope_split_levels`], the levels taken
/// relative to the design case's): [`RobustCrown::p_max`] is then the design case's level.
/// Without, every case is held to the one level p̂.
pub fn robust_crown(
    cases: &[LoadCase],
    levels: Option<&[f64]>,
    controller: &dyn Controller,
    dy: f64,
    solver: &dyn ContactSolver,
    settings: &LoadSplitSettings,
    observer: &dyn Observer,
) -> Result<RobustCrown> {
    check::positive("dy", dy)?;
    let design = design_case(cases);
    let levels = match levels {
        Some(l) if l.len() == cases.len() => l.to_vec(),
        Some(l) => {
            return Err(Error::invalid(
                "levels",
                format!("{} levels", l.len()),
                format!("one pressure level per load case ({})", cases.len()),
            ))
        }
        None => vec![1.0; cases.len()],
    };
    check::all_finite("levels", &levels)?;
    check::all_positive("levels", &levels)?;
    let problem = &cases
        .get(design)
        .ok_or_else(|| Error::invalid("cases", "none", "at least one load case"))?
        .problem;
    let iface = problem.interface();
    let shape = GapShape::symmetric(iface, 0)?;
    let regions = iface
        .points()
        .iter()
        .map(|x| match x[1].abs() <= 0.5 * dy {
            true => Region::OmegaV,
            false => Region::OmegaNv,
        })
        .collect();
    let optimisation = Optimisation::new(problem, &shape, controller)?
        .with_regions(regions)?
        .with_observer(observer);
    let others: Vec<InterfaceProblem> = (0..cases.len())
        .filter(|&k| k != design)
        .map(|k| cases[k].problem.clone())
        .collect();
    let relative: Vec<f64> = (0..cases.len())
        .filter(|&k| k != design)
        .map(|k| levels[k] / levels[design])
        .collect();
    let found = optimisation.envelope_split_levels(&others, &relative, solver, settings)?;
    let optimum = found.optimum;
    let own = Contact {
        pressure: optimum.pressure,
        gap: optimum.gap,
        approach_mm: -optimum.rigid[0],
    };
    let mut rest = found.cases.into_iter().map(|s| Contact {
        approach_mm: s.approach().unwrap_or(0.0),
        pressure: s.pressure,
        gap: s.gap,
    });
    let mut contacts = Vec::with_capacity(cases.len());
    let mut own = Some(own);
    for k in 0..cases.len() {
        let next = if k == design { own.take() } else { rest.next() };
        match next {
            Some(c) => contacts.push(c),
            None => break,
        }
    }
    Ok(RobustCrown {
        drop: optimum.gap_change,
        p_max: optimum.p_max,
        cases: contacts,
        termination: optimum.termination,
        omega_nv_excess: optimum.omega_nv_excess,
    })
}

/// The search's objective: the worst case's p_max, raised by how far its worst end ratio
/// passes [`EDGE_LOADING`] (so that an edge-loaded crown never wins).
pub fn penalised_worst(points: &[[f64; 3]], states: &[ContactState]) -> f64 {
    states
        .iter()
        .map(|s| s.p_max() * (end_ratio(points, &s.pressure) / EDGE_LOADING).max(1.0))
        .fold(0.0, f64::max)
}

/// A family of crowns that [`tune_profile`] searches.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ProfileFamily {
    /// Fujiwara and Kawase's K1, K2 and z_m ([`Crown::FujiwaraKawase`]).
    FujiwaraKawase,
    /// A circular crown's crowned fraction K of each half-length and its end drop z_m
    /// ([`Crown::circular_with_drop`]).
    Circular,
}

/// A crown tuned by [`tune_profile`].
#[derive(Clone, Debug, PartialEq)]
pub struct TunedCrown {
    /// Its family.
    pub family: ProfileFamily,
    /// The crown.
    pub crown: Crown,
    /// Fujiwara–Kawase's load coefficient K1 (`None` for a circular crown).
    pub k1: Option<f64>,
    /// The crowned fraction of each half-length: Fujiwara–Kawase's K2, a circular crown's K.
    pub k2: f64,
    /// The drop z_m at the ends \[mm\].
    pub z_m_mm: f64,
    /// The crown's drop at each point \[mm\].
    pub drop: Vec<f64>,
    /// The objective there \[MPa for [`penalised_worst`]\].
    pub worst: f64,
    /// Each case's contact under it (empty when no crown was solved).
    pub states: Vec<ContactState>,
    /// The crowns evaluated (on the scene's grid, after a coarse search's).
    pub evaluations: usize,
    /// The crowns evaluated on a coarser grid first ([`tune_profile_coarse_to_fine`]; 0
    /// without).
    pub coarse_evaluations: usize,
    /// How the search ended: converged, its budget used ([`Termination::StepLimit`]), an
    /// observer's stop ([`Termination::Stopped`]) or a contact solve that did not converge
    /// ([`Termination::Inner`]).
    pub termination: Termination,
}

/// Fujiwara–Kawase's start: K1 = 1, K2 = ½ and z_m = 5·Q/(π l E*), in the unconstrained
/// parameters of [`Parameters`].
const FK_START: [f64; 3] = [0.0, 0.0, 1.609_437_912_434_100_3];
/// Its first simplex's steps in those parameters.
const FK_STEP: [f64; 3] = [0.5, 1.0, 0.5];
/// A circular crown's start: K = ½, z_m = 5·Q/(π l E*).
const CIRCULAR_START: [f64; 2] = [0.0, 1.609_437_912_434_100_3];
/// Its first simplex's steps.
const CIRCULAR_STEP: [f64; 2] = [1.0, 0.5];

/// The polish on the scene's grid after a coarse search starts with steps this fraction of
/// the coarse search's last simplex ([`contopt_optimise::Minimum::extent`]): the two grids'
/// optima differ by the discretisation, which the coarse simplex's size bounds from below.
const POLISH_STEP: f64 = 0.5;
/// The polish's smallest first step, as a fraction of a fresh search's (a coarse simplex
/// collapsed along a parameter still lets the polish move along it).
const POLISH_FLOOR: f64 = 0.1;
/// The polish's budget of crowns on the scene's grid: a few simplex steps about the coarse
/// optimum, the best kept.
const POLISH_EVALUATIONS: usize = 24;

/// A family's parameters, unconstrained for the search: K1 = e^u, a fraction K = 1/(1 +
/// e^−u) in (0, 1), z_m = scale·e^u > 0.
struct Parameters<'r> {
    family: ProfileFamily,
    roller: &'r Roller,
    scale: f64,
}

/// The crown of a search: its K1 (Fujiwara–Kawase), fraction K and end drop z_m \[mm\].
type Values = (Option<f64>, f64, f64);

impl<'r> Parameters<'r> {
    /// The family's parameters for `roller`: the end drop's scale Q/(π l E*).
    fn new(family: ProfileFamily, roller: &'r Roller) -> Self {
        let scale = roller.load / (std::f64::consts::PI * roller.length * roller.e_star());
        Parameters {
            family,
            roller,
            scale,
        }
    }

    fn start_and_step(&self) -> (&'static [f64], &'static [f64]) {
        match self.family {
            ProfileFamily::FujiwaraKawase => (&FK_START, &FK_STEP),
            ProfileFamily::Circular => (&CIRCULAR_START, &CIRCULAR_STEP),
        }
    }

    fn values(&self, u: &[f64]) -> Values {
        let fraction = |v: f64| 1.0 / (1.0 + (-v).exp());
        match self.family {
            ProfileFamily::FujiwaraKawase => {
                (Some(u[0].exp()), fraction(u[1]), self.scale * u[2].exp())
            }
            ProfileFamily::Circular => (None, fraction(u[0]), self.scale * u[1].exp()),
        }
    }

    fn crown(&self, u: &[f64]) -> Result<Crown> {
        let r = self.roller;
        let (k1, k, z_m) = self.values(u);
        match k1 {
            Some(k1) => Crown::fujiwara_kawase(k1, k, z_m, r.load, r.length, r.e_star()),
            None => {
                let half = 0.5 * r.length;
                Crown::circular_with_drop(z_m, (1.0 - k) * half, half)
            }
        }
    }

    /// The crown's drop at `points` for the parameters `u`.
    fn drops(&self, u: &[f64], points: &[[f64; 3]]) -> Result<Vec<f64>> {
        let crown = self.crown(u)?;
        points
            .iter()
            .map(|x| crown.drop(x[0], self.roller.length))
            .collect()
    }
}

/// The best crown a search has seen: parameters, objective and the cases' states.
type Best = (Vec<f64>, f64, Vec<ContactState>);

/// What a search minimises over the cases' contacts under a crown: [`penalised_worst`], or a
/// caller's (the negative of a bearing's life, say).
pub type Objective<'o> = dyn FnMut(&[ContactState]) -> Result<f64> + 'o;

/// Tunes the Fujiwara–Kawase profile (NTN Technical Review 75, 2007: K1, K2, z_m) of
/// `roller` for every case of `cases` by a Nelder–Mead search ([`nelder_mead_observed`]) of the least
/// [`penalised_worst`], from K1 = 1, K2 = ½, z_m = 5·Q/(π l E*): [`tune_profile`] of
/// [`ProfileFamily::FujiwaraKawase`].
pub fn tune_fujiwara_kawase(
    cases: &[LoadCase],
    roller: &Roller,
    solver: &dyn ContactSolver,
    settings: &SearchSettings,
    observer: &dyn Observer,
) -> Result<TunedCrown> {
    let points = first_points(cases)?;
    let mut worst = |states: &[ContactState]| Ok(penalised_worst(points, states));
    let family = ProfileFamily::FujiwaraKawase;
    tune_profile(
        cases, roller, family, solver, settings, &mut worst, observer,
    )
}

/// The grid's points of the first case.
fn first_points<'c>(cases: &'c [LoadCase]) -> Result<&'c [[f64; 3]]> {
    Ok(cases
        .first()
        .ok_or_else(|| Error::invalid("cases", "none", "at least one load case"))?
        .problem
        .interface()
        .points())
}

/// Tunes a crown of `family` for `roller` over every case of `cases` by a Nelder–Mead search
/// ([`nelder_mead_observed`], as Fujiwara and Kawase tuned theirs by Rosenbrock's method) of the least
/// `objective`, from a crowned fraction of ½ and an end drop of 5·Q/(π l E*) (Fujiwara–Kawase
/// also K1 = 1). Each crown is reported to `observer` as an event of
/// [`Method::ProfileSearch`] at level 0 (its objective against the search's tolerance), the
/// contact solves one level deeper; a stop, a contact solve that does not converge and the
/// budget end the search with the best crown so far.
pub fn tune_profile(
    cases: &[LoadCase],
    roller: &Roller,
    family: ProfileFamily,
    solver: &dyn ContactSolver,
    settings: &SearchSettings,
    objective: &mut Objective,
    observer: &dyn Observer,
) -> Result<TunedCrown> {
    let run = Run::new(family, roller, solver, observer);
    let (start, step) = run.parameters.start_and_step();
    Ok(run.search(cases, start, step, settings, objective)?.0)
}

/// One grid of a coarse-to-fine search ([`tune_profile_coarse_to_fine`]): the load cases on
/// it and the objective over their contacts.
pub struct Grid<'g, 'a> {
    /// The cases, on this grid.
    pub cases: &'g [LoadCase<'a>],
    /// What the search minimises over their contacts.
    pub objective: &'g mut Objective<'g>,
}

/// [`tune_profile`] coarse to fine: the search on `coarse` (the same cases on a grid of fewer
/// cells, [`InterfaceProblem::coarsen`]), then a polish on `fine` (the scene's grid): a
/// Nelder–Mead search from the coarse optimum with first steps half the coarse search's last
/// simplex ([`contopt_optimise::Minimum::extent`]; at least a tenth of a fresh search's), at
/// most 24 crowns (and the simplex step under way), to `settings`' tolerance; the best fine
/// crown is returned, ended as the coarse search ended (the polish's budget is its design). The
/// two grids' optima differ by the discretisation, so the polish is a short local search where
/// a restart from scratch on the fine grid would spend a search's budget again. The crowns
/// solved on the coarse grid are counted in [`TunedCrown::coarse_evaluations`]; a coarse search
/// that did not end converged or at its budget (a stop, a contact solve that failed) is
/// returned as it is.
pub fn tune_profile_coarse_to_fine(
    coarse: Grid,
    fine: Grid,
    roller: &Roller,
    family: ProfileFamily,
    solver: &dyn ContactSolver,
    settings: &SearchSettings,
    observer: &dyn Observer,
) -> Result<TunedCrown> {
    let run = Run::new(family, roller, solver, observer);
    let (start, step) = run.parameters.start_and_step();
    let (first, minimum) = run.search(coarse.cases, start, step, settings, coarse.objective)?;
    if !matches!(
        first.termination,
        Termination::Converged | Termination::StepLimit { .. }
    ) {
        return Ok(first);
    }
    let steps: Vec<f64> = step
        .iter()
        .zip(&minimum.extent)
        .map(|(fresh, extent)| (POLISH_STEP * extent).max(POLISH_FLOOR * fresh))
        .collect();
    let polish = SearchSettings {
        max_evaluations: POLISH_EVALUATIONS.min(settings.max_evaluations),
        ..*settings
    };
    let (tuned, _) = run.search(fine.cases, &minimum.x, &steps, &polish, fine.objective)?;
    // The polish's budget is its design: ended there (or converged) it ends as the coarse
    // search did; a stop or a failed contact solve is its own.
    let termination = match tuned.termination {
        Termination::Converged | Termination::StepLimit { .. } => first.termination,
        ref other => other.clone(),
    };
    Ok(TunedCrown {
        coarse_evaluations: first.evaluations,
        termination,
        ..tuned
    })
}

/// What every search of a family runs with: its parameters, contact solver and observer.
struct Run<'r> {
    parameters: Parameters<'r>,
    solver: &'r dyn ContactSolver,
    observer: &'r dyn Observer,
}

impl<'r> Run<'r> {
    /// The searches of `family` for `roller`, solving with `solver`, reported to `observer`.
    fn new(
        family: ProfileFamily,
        roller: &'r Roller,
        solver: &'r dyn ContactSolver,
        observer: &'r dyn Observer,
    ) -> Self {
        Self {
            parameters: Parameters::new(family, roller),
            solver,
            observer,
        }
    }

    /// A Nelder–Mead search of `objective` over `cases` from `start` with first steps `step`:
    /// the best crown, and the search's minimum (its last simplex's extent).
    fn search(
        &self,
        cases: &[LoadCase],
        start: &[f64],
        step: &[f64],
        settings: &SearchSettings,
        objective: &mut Objective,
    ) -> Result<(TunedCrown, Minimum)> {
        let Run {
            ref parameters,
            solver,
            observer,
        } = *self;
        let family = parameters.family;
        let points = first_points(cases)?;
        let mut best: Option<Best> = None;
        let mut warm: Option<Vec<ContactState>> = None;
        let (minimum, mut driver) = nelder_mead_observed(
            |u, inner| {
                let states = solve_cases(
                    cases,
                    &parameters.drops(u, points)?,
                    solver,
                    warm.as_deref(),
                    &Nested(observer),
                )?;
                if let Some(s) = states.iter().find(|s| !s.termination.is_solved()) {
                    return Ok(ControlFlow::Break(s.termination.clone().inside(s.method)));
                }
                states
                    .iter()
                    .for_each(|s| inner.note(s.method, &s.termination));
                let value = objective(&states)?;
                if best.as_ref().is_none_or(|b| value < b.1) {
                    best = Some((u.to_vec(), value, states.clone()));
                }
                warm = Some(states);
                Ok(ControlFlow::Continue(value))
            },
            start,
            step,
            settings,
            Method::ProfileSearch,
            observer,
        )?;
        let (u, worst, states) = best.unwrap_or_else(|| (start.to_vec(), f64::INFINITY, vec![]));
        let termination = minimum.termination.clone();
        driver.settle(worst);
        driver.announce(&termination);
        let (k1, k2, z_m_mm) = parameters.values(&u);
        let tuned = TunedCrown {
            family,
            crown: parameters.crown(&u)?,
            k1,
            k2,
            z_m_mm,
            drop: parameters.drops(&u, points)?,
            worst,
            states,
            evaluations: minimum.evaluations,
            coarse_evaluations: 0,
            termination,
        };
        Ok((tuned, minimum))
    }
}
