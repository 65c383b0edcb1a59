//! The worst roller crown over its manufacturing tolerances (`[bearing] crown_tolerance`):
//! the scene's parametric roller crown as made anywhere in the box of its drop, crowned
//! length and log constant ([`worst_in_box`]), each crown judged on the solved raceway's
//! contacts under the final load distributions, on the design grid, by the case's objective
//! (the worst p_max, or the duty cycle's life). The distributions stay the nominal crown's:
//! a tolerance of a few micrometres moves the rollers' loads far less than their peaks.

use contopt_core::observe::Nested;
use contopt_core::{ContactState, Result};
use contopt_optimise::SearchSettings;
use contopt_results::CrownToleranceReport;
use contopt_roller::{solve_cases, worst_in_box, Crown, LoadDistribution};

use super::{peak_life, search_objective, BearingPlan, Envelope, Geometry};
use crate::methods::Context;

/// The simplex's budget after the grid: each crown solves every contact of the raceway.
const SEARCH_EVALUATIONS: usize = 40;

/// The simplex's stop: 0.05 MPa of p_max (or 5·10⁻⁵ of the life's logarithm).
const SEARCH_TOLERANCE: f64 = 0.05;

/// The worst crown of `plan`'s tolerance box about its roller crown, on the contacts of
/// `dists` with the design's gap change `change` on the grid of `at`; `None` without a box,
/// and with a warning in `warnings` when the case's roller crown has none of the parameters
/// the box spans (a straight roller, or a crown the case designs: its drop band is
/// `tolerance_um`).
pub(super) fn worst_crown(
    plan: &BearingPlan,
    c: &Context,
    (dists, change): (&[LoadDistribution], &[f64]),
    at: &Geometry,
    warnings: &mut Vec<String>,
) -> Result<Option<CrownToleranceReport>> {
    let Some((tolerances, grid)) = plan.crown_tolerance else {
        return Ok(None);
    };
    if !tolerances
        .active(&plan.bearing.roller_crown)
        .contains(&true)
    {
        warnings.push(format!(
            "bearing.crown_tolerance: the roller crown of this case ({}) has no end drop, \
             crowned length or log constant the box's non-zero tolerances span; no crown of \
             the box was searched (a designed crown's drop band is bearing.tolerance_um)",
            match plan.crown {
                Some(_) => "designed by the case".to_string(),
                None => format!("{:?}", plan.bearing.roller_crown),
            }
        ));
        return Ok(None);
    }
    let roller = (c.case.roller)
        .ok_or_else(|| contopt_core::Error::invalid("bearing", "its roller", "was not composed"))?;
    let nominal = &plan.bearing.roller_crown;
    let env = Envelope::new(dists, plan.raceway);
    let cases = env.cases(c.problem, roller, 0.0)?;
    let solve = |crown: &Crown| -> Result<Vec<ContactState>> {
        let gap: Vec<f64> = (at.points.iter().zip(change))
            .map(|(x, d)| Ok(d + crown.drop(x[0], at.length)? - nominal.drop(x[0], at.length)?))
            .collect::<Result<_>>()?;
        solve_cases(&cases, &gap, c.solver, None, &Nested(c.observer))
    };
    let mut objective = search_objective(plan, dists, &env, at);
    let settings = SearchSettings {
        tolerance: SEARCH_TOLERANCE,
        max_evaluations: SEARCH_EVALUATIONS,
    };
    let worst = worst_in_box(&tolerances, nominal, at.length, grid, &settings, |crown| {
        objective(&solve(crown)?)
    })?;
    let figures = |crown: &Crown| -> Result<(f64, f64)> {
        let states = solve(crown)?;
        let p_max = states.iter().map(ContactState::p_max).fold(0.0, f64::max);
        Ok((p_max, peak_life(plan, dists, &env, at, &states)?))
    };
    let (p_max, life) = figures(&worst.crown)?;
    let (nominal_p_max, nominal_life) = figures(nominal)?;
    Ok(Some(CrownToleranceReport {
        tolerances: [
            1e3 * tolerances.drop,
            tolerances.crowned_length,
            tolerances.log_constant,
        ],
        active: tolerances.active(nominal),
        deviation: worst.deviation,
        p_max_mpa: p_max,
        life_mrev: life,
        nominal_p_max_mpa: nominal_p_max,
        nominal_life_mrev: nominal_life,
        worst_corner: worst.worst_corner,
        worst: worst.value,
        evaluations: worst.evaluations,
    }))
}
