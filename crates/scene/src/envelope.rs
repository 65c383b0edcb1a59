//! A roller's envelope of load cases: the cases, their solves under one crown, and the two
//! crowns designed for all of them, the robust one (the envelope load split) and the tuned
//! Fujiwara–Kawase profile (a Nelder–Mead search over K1, K2, z_m).

use contopt_contact::{ContactSolver, InterfaceProblem};
use contopt_core::observe::{stopped_by_observer, Flow, Iteration, Observer};
use contopt_core::{ContactState, Error, Result};
use contopt_optimise::nelder_mead;
use contopt_roller::Crown;

use crate::report::{EnvelopeCaseReport, TunedProfile};
use crate::roller::{envelope_case, Info, EDGE_LOADING};
use crate::spec::EnvelopeSpec;

/// The tuned profile's search: the absolute spread of the simplex's worst-case p_max at which
/// it stops \[MPa\], and its budget of crowns.
const TUNE_TOLERANCE_MPA: f64 = 0.05;
const TUNE_EVALUATIONS: usize = 150;
/// A load factor this close to 1 and a tilt this close to the scene's \[arc-minutes\] are
/// the scene's own case, listed first already (round-off).
const SAME_CASE: f64 = 1e-12;

/// One load case: its load \[N\], tilt \[arc-minutes\] and contact problem.
pub(crate) struct LoadCase<'a> {
    pub load_n: f64,
    pub tilt_arcmin: f64,
    pub problem: InterfaceProblem<'a>,
}

impl LoadCase<'_> {
    fn key(&self) -> [f64; 2] {
        [self.load_n, self.tilt_arcmin]
    }
}

/// The cases of an envelope: the scene's own (`nominal`, under the roller of `info`) first,
/// then every other combination of a load factor and a tilt of `spec`.
pub(crate) fn load_cases<'a>(
    nominal: &InterfaceProblem<'a>,
    info: &Info,
    spec: Option<&EnvelopeSpec>,
) -> Result<Vec<LoadCase<'a>>> {
    let (load, tilt) = (info.roller.load, 60.0 * info.roller.tilt.to_degrees());
    let mut cases = vec![LoadCase {
        load_n: load,
        tilt_arcmin: tilt,
        problem: nominal.clone(),
    }];
    let Some(spec) = spec else {
        return Ok(cases);
    };
    check("envelope.load_factors", &spec.load_factors, |f| f > 0.0)?;
    check("envelope.tilts_arcmin", &spec.tilts_arcmin, |_| true)?;
    for &factor in &spec.load_factors {
        for &t in &spec.tilts_arcmin {
            if (factor - 1.0).abs() < SAME_CASE && (t - tilt).abs() < SAME_CASE {
                continue;
            }
            let mut modes = nominal.modes().to_vec();
            modes.iter_mut().for_each(|m| m.load *= factor);
            let slope = ((t - tilt) / 60.0).to_radians();
            let gap: Vec<f64> = nominal
                .initial_gap()
                .iter()
                .zip(&nominal.interface().points)
                .map(|(h, x)| h + slope * x[0])
                .collect();
            cases.push(LoadCase {
                load_n: factor * load,
                tilt_arcmin: t,
                problem: nominal.with_modes(modes)?.with_initial_gap(&gap)?,
            });
        }
    }
    Ok(cases)
}

/// The values of a list are finite and `ok`, and there is at least one.
fn check(field: &str, values: &[f64], ok: impl Fn(f64) -> bool) -> Result<()> {
    if values.is_empty() {
        return Err(Error::invalid(field, "[]", "needs at least one value"));
    }
    match values.iter().position(|&v| !(v.is_finite() && ok(v))) {
        Some(k) => Err(Error::invalid(
            format!("{field}[{k}]"),
            values[k],
            "must be finite (and a load factor positive)",
        )),
        None => Ok(()),
    }
}

/// The index of the robust crown's design case, whose column loads carry the crown: the
/// heaviest case at the largest tilt, whose loaded end needs the deepest crown.
pub(crate) fn design_case(cases: &[LoadCase]) -> usize {
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

/// Every case solved with its initial gap changed by `gap_change`, each from its pressure in
/// `start` when given, reporting its iterations to `observer`.
pub(crate) fn solve_cases(
    cases: &[LoadCase],
    gap_change: &[f64],
    solver: &dyn ContactSolver,
    start: Option<&[ContactState]>,
    observer: &dyn Observer,
) -> Result<Vec<ContactState>> {
    cases
        .iter()
        .enumerate()
        .map(|(k, case)| {
            let gap: Vec<f64> = case
                .problem
                .initial_gap()
                .iter()
                .zip(gap_change)
                .map(|(h, d)| h + d)
                .collect();
            let problem = case.problem.with_initial_gap(&gap)?;
            let start = start.map(|s| s[k].pressure.as_slice());
            solver
                .solve_observed(&problem, start, observer)?
                .solved(solver.name())
        })
        .collect()
}

/// The reports of solved cases: `pressures` and approaches \[mm\] in the cases' order.
pub(crate) fn reports(
    cases: &[LoadCase],
    pressures: &[&[f64]],
    approaches: &[f64],
    dy: f64,
) -> Vec<EnvelopeCaseReport> {
    let points = &cases[0].problem.interface().points;
    cases
        .iter()
        .zip(pressures)
        .zip(approaches)
        .map(|((case, p), a)| envelope_case(case.key(), points, p, *a, dy))
        .collect()
}

/// The reports of cases solved by a contact solver.
pub(crate) fn state_reports(
    cases: &[LoadCase],
    states: &[ContactState],
    dy: f64,
) -> Vec<EnvelopeCaseReport> {
    let pressures: Vec<&[f64]> = states.iter().map(|s| s.pressure.as_slice()).collect();
    let approaches: Vec<f64> = states.iter().map(|s| -s.rigid[0]).collect();
    reports(cases, &pressures, &approaches, dy)
}

/// The search's objective: the worst case's p_max, raised by how far its worst end ratio
/// passes [`EDGE_LOADING`] (so that an edge-loaded crown never wins).
fn penalised_worst(points: &[[f64; 3]], states: &[ContactState]) -> f64 {
    states
        .iter()
        .map(|s| {
            let ratio = crate::roller::end_ratio(points, &s.pressure);
            s.p_max() * (ratio / EDGE_LOADING).max(1.0)
        })
        .fold(0.0, f64::max)
}

/// Reports the search's `crowns`-th crown, whose worst case is `worst` \[MPa\], to `observer`
/// (method [`TUNE_METHOD`]); a stop ends the search with an error.
fn report_crown(observer: &dyn Observer, crowns: usize, worst: f64) -> Result<()> {
    let iteration = Iteration {
        method: TUNE_METHOD,
        iteration: crowns,
        measure: worst,
        tolerance: TUNE_TOLERANCE_MPA,
    };
    match observer.observe(&iteration) {
        Flow::Continue => Ok(()),
        Flow::Stop => Err(Error::NotConverged {
            method: TUNE_METHOD.into(),
            iterations: crowns,
            detail: format!("{}; worst case {worst:.1} MPa", stopped_by_observer(crowns)),
        }),
    }
}

/// The name the Fujiwara–Kawase search reports its crowns under.
pub const TUNE_METHOD: &str = "Fujiwara-Kawase search";

/// The Fujiwara–Kawase profile tuned for `cases`: the parameters, the crown's drop at each
/// point \[mm\] and the cases' contact under it.
pub(crate) fn tune_fujiwara_kawase(
    cases: &[LoadCase],
    info: &Info,
    solver: &dyn ContactSolver,
    observer: &dyn Observer,
) -> Result<(TunedProfile, Vec<f64>, Vec<ContactState>)> {
    let roller = &info.roller;
    let (load, length, e_star) = (roller.load, roller.length, roller.e_star());
    let scale = load / (std::f64::consts::PI * length * e_star);
    let points = &cases[0].problem.interface().points;
    // K1 = e^u₀ > 0, K2 = 1/(1 + e^−u₁) in (0, 1), z_m = scale·e^u₂ > 0: an unconstrained
    // search.
    let parameters = |u: &[f64]| (u[0].exp(), 1.0 / (1.0 + (-u[1]).exp()), scale * u[2].exp());
    let drops = |u: &[f64]| -> Result<Vec<f64>> {
        let (k1, k2, z_m) = parameters(u);
        let crown = Crown::fujiwara_kawase(k1, k2, z_m, load, length, e_star)?;
        points.iter().map(|x| crown.drop(x[0], length)).collect()
    };
    let mut warm: Option<Vec<ContactState>> = None;
    let mut crowns = 0;
    let minimum = nelder_mead(
        |u| {
            let states = solve_cases(cases, &drops(u)?, solver, warm.as_deref(), observer)?;
            let value = penalised_worst(points, &states);
            warm = Some(states);
            crowns += 1;
            report_crown(observer, crowns, value)?;
            Ok(value)
        },
        &[0.0, 0.0, 5f64.ln()],
        &[0.5, 1.0, 0.5],
        TUNE_TOLERANCE_MPA,
        TUNE_EVALUATIONS,
    )?;
    let drop = drops(&minimum.x)?;
    let states = solve_cases(cases, &drop, solver, warm.as_deref(), observer)?;
    let (k1, k2, z_m_mm) = parameters(&minimum.x);
    let tuned = TunedProfile {
        k1,
        k2,
        z_m_mm,
        evaluations: minimum.evaluations,
    };
    Ok((tuned, drop, states))
}
