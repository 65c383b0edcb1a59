//! A case's figures from what its design found, in the results' units: the method's passes,
//! the interface's pressure, gap and gap change, the penetration and its warning, a roller's
//! figures.

use contopt_contact::InterfaceProblem;
use contopt_core::observe::Method;
use contopt_results::{CaseReport, CaseStatus, Pass, Point};

use crate::methods::Designed;
use crate::zone::Layout;
use crate::Case;

/// The penetration, as a fraction of the largest elastic displacement, above which a solution
/// carries a warning: the paper's c = E·10⁴ penetrates by about 10⁻⁶ of it.
pub const PENETRATION_WARNING: f64 = 1e-3;

/// Micrometres per millimetre: displacements, gaps and gap changes are reported in µm.
const UM: f64 = 1e3;

/// Fills `report` from the design's outcome on the contact `problem` it shows, the pressure
/// as [`shown_pressure`] reads it.
pub(crate) fn fill(report: &mut CaseReport, case: &Case, problem: &InterfaceProblem, d: Designed) {
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
    let points = problem.interface().points();
    let change = |i: usize| d.gap_change.get(i).copied().unwrap_or(0.0);
    let shown = |i: usize| {
        d.crown
            .as_ref()
            .and_then(|c| c.get(i))
            .copied()
            .unwrap_or(change(i))
    };
    let initial = problem.initial_gap();
    let pressure = shown_pressure(case, problem, &d.pressure);
    report.interface = (0..points.len().min(pressure.len()))
        .map(|i| Point {
            x_mm: points[i],
            p_mpa: pressure[i],
            d_um: UM * d.gap[i],
            dh_um: UM * shown(i),
            h_um: UM * initial.get(i).copied().unwrap_or(0.0),
        })
        .collect();
    let elastic_gap: Vec<f64> = (0..d.gap.len()).map(|i| d.gap[i] - change(i)).collect();
    penetration(report, problem, &elastic_gap, &d.rigid);
    report.roller = d.roller;
}

/// The pressure at the points as the report shows it. On a zone of element faces the three
/// Gauss points of each quadratic face outnumber its nodes; when neither body adds compliance
/// of its own at the points (the faces' bodies, a rigid body), the part of the pressure that
/// moves no node is free, and the exact solution of the points closed one by one can carry a
/// sawtooth through the whole contact: every third point open by a gap growing eightfold per
/// face (10⁻⁶ to 10⁻³ µm), its load on the other two, near twice the field there (a rigid
/// cylinder on a plane-stress block: p_max 1303 MPa against Hertz's 731, as converged). There
/// the pressure is read as the faces' field ([`InterfaceProblem::recovered_pressure`]: the
/// same nodal forces, the least Σ wᵢpᵢ² of them, the paper's C⁰ field of eq. 2.9), as it is:
/// at a contact's edge it may dip a little below zero (clipped, it would no longer carry the
/// nodal forces, by 1 % of p_max on Table 2). Otherwise, as the design left it.
fn shown_pressure(case: &Case, problem: &InterfaceProblem, pressure: &[f64]) -> Vec<f64> {
    let zone = &case.spec.contact.zone;
    let free = matches!(case.plan.layout, Layout::Faces(_))
        && (case.spec.body.iter()).all(|b| b.owns_surface() || b.compliance(zone) == Some(0.0));
    match free.then(|| problem.recovered_pressure(pressure)) {
        Some(Ok(field)) => field,
        _ => pressure.to_vec(),
    }
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use contopt_results::{CaseReport, Point};

    use super::{penetration, PENETRATION_WARNING, UM};
    use crate::{Format, Registry};

    /// A sphere on a bed on 10 rings: its contact problem (the gap zero at the centre).
    fn problem() -> contopt_contact::InterfaceProblem<'static> {
        let text = "name = \"bed\"\n[contact]\nzone = { kind = \"rings\", rings = 10, \
                    radius_mm = 5.0 }\ngap = { kind = \"sphere\", radius_mm = 20.0 }\nload = { \
                    force_n = 1000.0 }\n[[body]]\nkind = \"winkler\"\nmodulus_mpa_per_mm = \
                    50.0\n[[body]]\nkind = \"rigid\"\n";
        let scene = Registry::standard()
            .parse(text, Format::Toml, Path::new("bed.toml"))
            .unwrap();
        scene.cases()[0].problem().unwrap()
    }

    /// A report whose interface has the gaps `d` \[mm\].
    fn report(d: &[f64]) -> CaseReport {
        let mut report = CaseReport::new("bed", &Default::default(), serde_json::Value::Null);
        report.interface = d
            .iter()
            .map(|&d| Point {
                x_mm: [0.0; 3],
                p_mpa: 0.0,
                d_um: UM * d,
                dh_um: 0.0,
                h_um: 0.0,
            })
            .collect();
        report
    }

    /// The largest penetration is reported; past its share of the largest elastic
    /// displacement it carries a warning, below it none.
    #[test]
    fn a_penetration_is_judged_against_the_elastic_displacement() {
        let problem = problem();
        let n = problem.len();
        // The rigid body sinks by 0.1 mm: the elastic displacement is about that.
        let sink = [-0.1];
        let gap_of = |d: f64| {
            let mut gap = vec![0.0; n];
            gap[0] = d;
            gap
        };
        let elastic = problem.elastic_displacement(&gap_of(0.0), &sink);
        assert!(elastic > 0.0);
        let slight = -0.1 * PENETRATION_WARNING * elastic;
        let mut r = report(&gap_of(slight));
        penetration(&mut r, &problem, &gap_of(slight), &sink);
        assert!((r.penetration_um.unwrap() - UM * -slight).abs() < 1e-9);
        assert!(r.warnings.is_empty(), "{:?}", r.warnings);
        let deep = -10.0 * PENETRATION_WARNING * elastic;
        let mut r = report(&gap_of(deep));
        penetration(&mut r, &problem, &gap_of(deep), &sink);
        assert!(r.warnings[0].contains("penetrates"), "{:?}", r.warnings);
    }
}
