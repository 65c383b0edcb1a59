//! A case's report from what its design found: the figures in the results' units, the
//! penetration and its warning, a roller's figures, and the stresses below the surface.

use contopt_contact::InterfaceProblem;
use contopt_core::observe::Method;
use contopt_results::{CaseReport, CaseStatus, Pass, Point};

use crate::methods::{Context, Designed};
use crate::{Built, Case};

/// The penetration, as a fraction of the largest elastic displacement, above which a solution
/// carries a warning: the paper's c = E·10⁴ penetrates by about 10⁻⁶ of it.
pub const PENETRATION_WARNING: f64 = 1e-3;

/// Micrometres per millimetre: displacements, gaps and gap changes are reported in µm.
const UM: f64 = 1e3;

/// Fills `report` from the design's outcome.
pub(crate) fn fill(report: &mut CaseReport, c: &Context, d: Designed) {
    report.method = d.method;
    report.solver = d.solver;
    report.status = if d.termination.is_solved() {
        CaseStatus::Solved
    } else {
        CaseStatus::NotConverged
    };
    report.termination = d.termination;
    report.bound_p_max_mpa = d.bound_p_max;
    report.dh_max_um = d.dh_max.map(|v| UM * v);
    report.omega_nv_excess_mpa = d.omega_nv_excess;
    report.approach_um = d.rigid.first().map(|lambda| -UM * lambda);
    report.passes = d
        .passes
        .iter()
        .map(|r| Pass {
            k: r.k,
            bound_p_max_mpa: r.p_max,
            dh_max_um: UM * r.dh_max,
            tolh_mm2: r.tolh,
            iterp: r.iterp,
            iterd: r.iterd,
        })
        .collect();
    let points = c.problem.interface().points();
    let change = |i: usize| d.gap_change.get(i).copied().unwrap_or(0.0);
    let shown = |i: usize| {
        d.crown
            .as_ref()
            .and_then(|c| c.get(i))
            .copied()
            .unwrap_or(change(i))
    };
    let initial = c.problem.initial_gap();
    report.interface = (0..points.len().min(d.pressure.len()))
        .map(|i| Point {
            x_mm: points[i],
            p_mpa: d.pressure[i],
            d_um: UM * d.gap[i],
            dh_um: UM * shown(i),
            h_um: UM * initial.get(i).copied().unwrap_or(0.0),
        })
        .collect();
    let elastic_gap: Vec<f64> = (0..d.gap.len()).map(|i| d.gap[i] - change(i)).collect();
    penetration(report, c.problem, &elastic_gap, &d.rigid);
    report.roller = d.roller;
}

/// The report's largest penetration, and a warning when it exceeds [`PENETRATION_WARNING`] of
/// the largest elastic displacement.
fn penetration(report: &mut CaseReport, problem: &InterfaceProblem, gap: &[f64], rigid: &[f64]) {
    if report.interface.is_empty() || gap.len() != problem.len() {
        return;
    }
    let elastic = problem.elastic_displacement(gap, rigid);
    let largest = report
        .interface
        .iter()
        .fold(0.0f64, |m, q| m.max(-q.d_um / UM));
    report.penetration_um = Some(UM * largest);
    if largest > PENETRATION_WARNING * elastic {
        let share = if elastic > 0.0 {
            format!("{:.2} % of", 100.0 * largest / elastic)
        } else {
            "more than".to_string()
        };
        let remedy = match report.solver {
            Some(Method::Penalty | Method::FullPenalty) => {
                "raise the penalty parameter c_mpa_per_mm (the paper takes E·10⁴) or use an \
                 exact solver"
            }
            _ if !report.is_solved() => {
                "the solve stopped before its tolerance (see its \
                 termination)"
            }
            _ => "tighten the solver's tolerance",
        };
        report.warnings.push(format!(
            "the solution penetrates by {largest:.3e} mm, {share} its largest elastic \
             displacement ({elastic:.3e} mm): {remedy}"
        ));
    }
}

/// The stresses below the surface of the case's bodies, when the scene asks for them and the
/// case converged.
pub(crate) fn below_surface(
    report: &mut CaseReport,
    case: &Case,
    built: &Built,
) -> contopt_core::Result<()> {
    let (Some(spec), true) = (&case.spec.output.subsurface, report.is_solved()) else {
        return Ok(());
    };
    let started = std::time::Instant::now();
    let pressure: Vec<f64> = report.interface.iter().map(|q| q.p_mpa).collect();
    let roller = case.plan.roller.is_some();
    // A roller with free ends has its own field, not the raceway's.
    let free_ends = case.spec.body.iter().any(|b| b.free_ends());
    let shared = !free_ends
        && case
            .plan
            .roller
            .as_ref()
            .is_some_and(|r| r.roller.nu() == r.raceway.nu());
    report.subsurface = crate::subsurface::compute(
        spec,
        [built.first(), built.second()],
        shared,
        &pressure,
        roller,
    )?;
    report.time("subsurface", started);
    Ok(())
}
