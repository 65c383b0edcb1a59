//! The report stage, the last of a case's four (plan → build → design → **report**): what its
//! design found ([`Designed`]), on the bodies it was built on, turned into its [`CaseReport`].
//!
//! Its input is [`Found`]; its output the case's report, which the build and design stages have
//! begun (the case's label and input, their timings). In order:
//! - [`figures`]: the method's passes, the interface's pressure, gap and gap change in the
//!   results' units, the penetration and its warning, a roller's figures;
//! - [`limits`]: the model's limits, judged on every converged case (a contact reaching its
//!   zone's edge, too few cells across it, a peak at a sharp edge, Hertz's nominal contact);
//! - [`subsurface`]: the stresses below the surface, when the scene asks for them;
//! - [`fields`]: the meshes' fields for a viewer, when the scene asks for them;
//! - the closed-form pressure beside a validation case ([`crate::reference`]).

mod edge;
mod fields;
mod figures;
mod limits;
mod subsurface;

use std::time::Instant;

use contopt_contact::InterfaceProblem;
use contopt_results::CaseReport;

pub use edge::sharp_edge_warning;
pub use figures::PENETRATION_WARNING;
pub(crate) use limits::GROWTH;
pub use limits::MIN_CELLS_ACROSS;

use crate::methods::Designed;
use crate::{Built, Case, SceneError};

/// What the report stage takes: the case, the bodies built for it, the contact problem its
/// design solved and what the design found there.
pub(crate) struct Found<'c, 'p> {
    /// The case, with its plan.
    pub case: &'c Case,
    /// Its bodies.
    pub built: &'c Built,
    /// The contact problem the design stage solved.
    pub problem: InterfaceProblem<'p>,
    /// The design's outcome.
    pub designed: Designed,
}

/// Completes `report` from what the design `found`. The contact the report shows is the
/// design's own, or the one it names ([`Designed::shown_gap`]: a bearing's worst roller), on
/// which the model's limits are judged; the fields are written for the design's own contact
/// only.
pub(crate) fn complete(report: &mut CaseReport, found: Found) -> Result<(), SceneError> {
    let Found {
        case,
        built,
        problem,
        designed,
    } = found;
    let at = &case.locator;
    let own_contact = designed.shown_gap.is_none();
    let problem = match &designed.shown_gap {
        Some(gap) => {
            (problem.with_initial_gap(gap)).map_err(|e| at.library(case.plan.design_at, e))?
        }
        None => problem,
    };
    let rigid = designed.rigid.clone();
    figures::fill(report, case, &problem, designed);
    limits::judge(report, case, &problem);
    limits::coarse_elements(report, [built.first(), built.second()]);
    below_surface(report, case, built).map_err(|e| at.library("output.subsurface", e))?;
    if own_contact {
        fields::compute(report, case, built, &problem, &rigid);
    }
    report.reference = crate::reference::curve(case, report);
    report.settle();
    Ok(())
}

/// The stresses below the surface of the case's bodies, when the scene asks for them and the
/// case converged.
fn below_surface(report: &mut CaseReport, case: &Case, built: &Built) -> contopt_core::Result<()> {
    let (Some(spec), true) = (&case.spec.output.subsurface, report.is_solved()) else {
        return Ok(());
    };
    let started = Instant::now();
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
    report.subsurface = subsurface::compute(
        spec,
        [built.first(), built.second()],
        shared,
        &pressure,
        roller,
    )?;
    if let Some(found) = &report.subsurface {
        report.warnings.extend(subsurface::shallow_peaks(found));
    }
    report.time("subsurface", started);
    Ok(())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use contopt_contact::{ActiveSet, ActiveSetSettings, ContactSolver};
    use contopt_results::{CaseReport, CaseStatus};

    use super::{complete, Found};
    use crate::methods::Designed;
    use crate::{Format, Registry, Scene};

    /// A sphere (R = 20 mm) on a Winkler bed of 40 rings over r < 5 mm under 1 kN.
    fn scene() -> Scene {
        let text = "name = \"bed\"\n[contact]\nzone = { kind = \"rings\", rings = 40, radius_mm = \
                    5.0 }\ngap = { kind = \"sphere\", radius_mm = 20.0 }\nload = { force_n = \
                    1000.0 }\n[[body]]\nkind = \"winkler\"\nmodulus_mpa_per_mm = 50.0\n[[body]]\n\
                    kind = \"rigid\"\n";
        Registry::standard()
            .parse(text, Format::Toml, Path::new("bed.toml"))
            .unwrap()
    }

    /// The stage reports the design's contact in the results' units, and judges the contact the
    /// design names to show in place of the case's own: its initial gap is the report's h.
    #[test]
    fn the_report_shows_the_contact_the_design_names() {
        let scene = scene();
        let case = &scene.cases()[0];
        let built = case.build().unwrap();
        let gap = case.initial_gap(&built).unwrap();
        let problem =
            contopt_contact::InterfaceProblem::new(built.first(), built.second(), &gap).unwrap();
        let solver = ActiveSet::new(ActiveSetSettings::default()).unwrap();
        let state = solver.solve(&problem).unwrap();
        let p_max = state.pressure.iter().fold(0.0f64, |m, &p| m.max(p));
        let run = |shown: Option<Vec<f64>>| {
            let mut report = CaseReport::new("bed", &Default::default(), serde_json::Value::Null);
            let designed = Designed {
                shown_gap: shown,
                ..Designed::contact(state.clone())
            };
            let problem = problem.with_initial_gap(&gap).unwrap();
            let found = Found {
                case,
                built: &built,
                problem,
                designed,
            };
            complete(&mut report, found).unwrap();
            report
        };
        let own = run(None);
        assert_eq!(own.status, CaseStatus::Solved);
        assert_eq!(own.interface.len(), gap.len());
        assert!((own.p_max_mpa.unwrap() - p_max).abs() < 1e-12 * p_max);
        for (q, h) in own.interface.iter().zip(&gap) {
            assert!((q.h_um - 1e3 * h).abs() < 1e-9, "{} against {h} mm", q.h_um);
        }
        let lifted: Vec<f64> = gap.iter().map(|h| h + 0.01).collect();
        let shown = run(Some(lifted.clone()));
        for (q, h) in shown.interface.iter().zip(&lifted) {
            assert!((q.h_um - 1e3 * h).abs() < 1e-9, "{} against {h} mm", q.h_um);
        }
    }
}
