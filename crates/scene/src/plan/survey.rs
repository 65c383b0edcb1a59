//! The survey of a zone of imported meshes before anything is built ([`MeshSurface`]), and
//! the pairing's settings and errors that the build of the pair shares.

use std::collections::HashMap;

use contopt_core::{check, Error, Result};
use contopt_fem::{ContactPairing, Face, FaceSample, PairingSettings};

use crate::bodies::BodyKind;
use crate::chosen::Chosen;
use crate::error::Locator;
use crate::mesh_surface::{MeshPart, MeshSurface};
use crate::meshes::MeshFiles;
use crate::zone::{MeshZone, ZoneKind};
use crate::SceneError;

/// The mesh zone of `spec`, surveyed from its bodies' meshes (`None` for other zones);
/// errors placed at the body or the zone's key.
pub(crate) fn survey(
    bodies: &[Chosen<dyn BodyKind>],
    zone: &Chosen<dyn ZoneKind>,
    meshes: &MeshFiles,
    at: &Locator,
) -> Result<Option<MeshSurface>, SceneError> {
    let Some(zone) = zone.downcast::<MeshZone>() else {
        return Ok(None);
    };
    let settings = settings(zone).map_err(|e| at.library("contact.zone", e))?;
    let parts = parts(bodies, zone, meshes, at)?;
    let floats = parts
        .iter()
        .flatten()
        .map(MeshPart::floats)
        .collect::<Result<Vec<bool>>>()
        .map_err(|e| at.library("body", e))?;
    if floats == [true, true] {
        return Err(at.at(
            "body[1].supports",
            "both imported bodies float along the contact normal, each pressed only by the \
             other: hold one of them (a support that stops its motion along the normal), as \
             the run would refuse two free motions that move the contact alike",
        ));
    }
    let floating = floats.contains(&true);
    let nodes = [0, 1].map(|k| parts[k].as_ref().map(|p| p.model.mesh().nodes().len()));
    let (owner, paired) = match &parts {
        [Some(a), Some(b)] => {
            let survey =
                ContactPairing::survey((&a.model, &a.contact), (&b.model, &b.contact), &settings)
                    .map_err(|e| pairing_error(e, at))?;
            (a, Some(survey))
        }
        [Some(a), None] | [None, Some(a)] => (a, None),
        [None, None] => {
            return Err(at.at(
                "contact.zone.kind",
                "a zone of kind \"mesh\" is the contact faces of an imported body: give one \
                 body (or both) of kind \"fe_mesh\"",
            ))
        }
    };
    let index: HashMap<Face, usize> = owner
        .contact
        .iter()
        .enumerate()
        .map(|(k, &f)| (f, k))
        .collect();
    let (points, faces_of, samples): (Vec<[f64; 2]>, Vec<Vec<usize>>, usize) = match &paired {
        Some(survey) => (
            survey.nodes.clone(),
            (survey.node_faces.iter())
                .map(|faces| faces.iter().map(|f| index[f]).collect())
                .collect(),
            survey.first.len(),
        ),
        None => {
            let gauss: Vec<FaceSample> = (owner.contact.iter())
                .flat_map(|&f| FaceSample::gauss(&owner.model, f))
                .collect();
            (
                gauss.iter().map(|s| s.point).collect(),
                gauss.iter().map(|s| vec![index[&s.face]]).collect(),
                gauss.len(),
            )
        }
    };
    let face_lengths: Vec<f64> = owner.contact.iter().map(|&f| owner.chord(f)).collect();
    let half_extent = points.iter().fold([0.0f64; 2], |m, p| {
        [m[0].max(p[0].abs()), m[1].max(p[1].abs())]
    });
    let mut ends = vec![];
    for part in parts.iter().flatten() {
        ends.extend(part.ends());
    }
    Ok(Some(MeshSurface {
        analysis: zone.analysis,
        samples,
        cell: face_lengths.iter().fold(0.0, |m: f64, &l| m.max(l)),
        points,
        faces_of,
        face_lengths,
        paired: paired.is_some(),
        nodes,
        half_extent,
        ends,
        floating,
    }))
}

/// The pairing's settings of a zone: its search distance, positive and finite when given.
pub(crate) fn settings(zone: &MeshZone) -> Result<PairingSettings> {
    if let Some(d) = zone.search_mm {
        check::positive("search_mm", d)?;
    }
    Ok(PairingSettings {
        search_distance: zone.search_mm,
    })
}

/// The parts the bodies offer, each error at its body.
pub(crate) fn parts(
    bodies: &[Chosen<dyn BodyKind>],
    zone: &MeshZone,
    meshes: &MeshFiles,
    at: &Locator,
) -> Result<[Option<MeshPart>; 2], SceneError> {
    let part = |k: usize| {
        bodies[k]
            .part(meshes, zone.analysis)
            .transpose()
            .map_err(|e| at.library(&format!("body[{k}]"), e))
    };
    Ok([part(0)?, part(1)?])
}

/// A pairing's error at the key it concerns: a chain that breaks at its body's `contact`,
/// faces that do not pair at the zone.
pub(crate) fn pairing_error(e: Error, at: &Locator) -> SceneError {
    let Error::InvalidInput {
        field,
        value,
        reason,
    } = e
    else {
        return at.library("contact.zone", e);
    };
    let key = match field.as_str() {
        f if f.starts_with("pairing.first") => "body[0].contact",
        f if f.starts_with("pairing.second") => "body[1].contact",
        _ => "contact.zone",
    };
    at.at(
        key,
        format!("the contact faces ({value}) do not pair: {reason}"),
    )
}
