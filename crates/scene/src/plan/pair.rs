//! The checks of a case's two bodies together: their kinds on the zone, and the contact's load
//! on them.

use contopt_core::{Error, Result};

use crate::bodies::{BodyKind, Takes};
use crate::contact::LoadSpec;
use crate::registry::Chosen;
use crate::zone::ZoneSpec;

/// The pair's checks: two bodies, not both rigid, and the finite-element faces meshed by a
/// finite-element body.
pub fn check_pair(bodies: &[Chosen<dyn BodyKind>], zone: &ZoneSpec) -> Result<()> {
    let [below, above] = bodies else {
        return Err(Error::invalid(
            "body",
            format!("{} bodies", bodies.len()),
            "give two: the first below the zone, the second above",
        ));
    };
    if [below, above].map(|b| b.compliance(zone)) == [Some(0.0); 2] {
        return Err(Error::invalid(
            "body[1].kind",
            above.name(),
            "two rigid bodies have no compliance to share a load",
        ));
    }
    if matches!(zone, ZoneSpec::Faces(_)) && !(below.owns_surface() || above.owns_surface()) {
        return Err(Error::invalid(
            "contact.zone.kind",
            "faces",
            "finite-element faces are meshed by a finite-element body (fe_base, fe_block or \
             fe_punch); give one, or a grid, rings or strips",
        ));
    }
    if matches!(zone, ZoneSpec::Mesh(_)) && !(below.imported() || above.imported()) {
        return Err(Error::invalid(
            "contact.zone.kind",
            "mesh",
            "a zone of imported meshes is the contact faces of a body of kind \"fe_mesh\": \
             give one (or two)",
        ));
    }
    Ok(())
}

/// The contact's load fits the body above; without one, a body carries its own load.
pub fn check_load(
    bodies: [&Chosen<dyn BodyKind>; 2],
    zone: &ZoneSpec,
    load: LoadSpec,
) -> Result<()> {
    let [below, above] = bodies;
    if load == LoadSpec::None && below.takes(zone) == Takes::OwnLoad {
        return Ok(());
    }
    match (load, above.takes(zone)) {
        (LoadSpec::ForceN(f), Takes::Force) => {
            contopt_core::check::positive("contact.load.force_n", f).map(|_| ())
        }
        (LoadSpec::ForceN(_), Takes::OwnLoad) => Err(Error::invalid(
            "contact.load.force_n",
            above.name(),
            "carries its own load (a punch's `load`, an imported body's `loads`): the contact \
             takes no force",
        )),
        (LoadSpec::ForceN(_), Takes::Nothing) => Err(Error::invalid(
            "contact.load.force_n",
            above.name(),
            "is held and cannot float under a force: press it by an approach, or put it below",
        )),
        (LoadSpec::ApproachMm(a), _) => {
            contopt_core::check::positive("contact.load.approach_mm", a).map(|_| ())
        }
        (LoadSpec::None, Takes::OwnLoad) => Ok(()),
        (LoadSpec::None, _) => Err(Error::invalid(
            "contact.load",
            "none",
            "nothing presses the bodies together: give { force_n } or { approach_mm }, or a \
             load of a finite-element body",
        )),
    }
}
