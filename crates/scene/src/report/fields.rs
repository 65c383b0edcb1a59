//! The fields over the meshes of a case's bodies (`[output] fields`, on request): each body
//! that has a mesh gives its nodes, cells, displacements and stresses under the case's final
//! solution, and the report writes them for a viewer.

use contopt_contact::InterfaceProblem;
use contopt_core::{ElasticBody, Result};
use contopt_results::{CaseReport, CaseStatus, MeshFields};

use crate::{Built, Case};

/// The fields of every body with a mesh under the case's solution (the pressure at the
/// interface points of `report`, the rigid-mode amplitudes `rigid` of `problem`'s free
/// modes), when the scene asks for them and the methods converged; a half-space or a rigid
/// body gives none. Fields that cannot be computed (a pressure that leaves a floating body
/// unbalanced beyond the recovery's tolerance) leave the case's answer standing: none are
/// written, and a warning says why.
pub(crate) fn compute(
    report: &mut CaseReport,
    case: &Case,
    built: &Built,
    problem: &InterfaceProblem,
    rigid: &[f64],
) {
    if !case.spec.output.fields || report.status == CaseStatus::NotConverged {
        return;
    }
    let started = std::time::Instant::now();
    match of_bodies(report, built, problem, rigid) {
        Ok(fields) => report.fields = fields,
        Err(e) => report
            .warnings
            .push(format!("the fields for ParaView are not written: {e}")),
    }
    report.time("fields", started);
}

/// Each body's fields that has a mesh, with its number.
fn of_bodies(
    report: &CaseReport,
    built: &Built,
    problem: &InterfaceProblem,
    rigid: &[f64],
) -> Result<Vec<MeshFields>> {
    let pressure: Vec<f64> = report.interface.iter().map(|q| q.p_mpa).collect();
    let own_rigid = problem.body_rigid(rigid)?;
    let bodies: [&dyn ElasticBody; 2] = [built.first(), built.second()];
    let mut found = vec![];
    for (k, body) in bodies.iter().enumerate() {
        let own = super::subsurface::own_order(bodies, k, &pressure)?;
        if let Some(fields) = body.fields(&own, &own_rigid[k])? {
            found.push(MeshFields {
                body: k + 1,
                name: body.name().to_string(),
                fields,
            });
        }
    }
    Ok(found)
}
