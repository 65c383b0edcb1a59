//! The checks of a case's two bodies together: their kinds on the zone, and the contact's load
//! on them.

use contopt_core::{Error, Result};

use crate::bodies::{BodyKind, Takes};
use crate::chosen::Chosen;
use crate::load::LoadSpec;
use crate::zone::{FacesZone, MeshZone, ZoneKind};

/// The pair's checks: two bodies, not both rigid, and the finite-element faces meshed by a
/// finite-element body.
pub fn check_pair(bodies: &[Chosen<dyn BodyKind>], zone: &Chosen<dyn ZoneKind>) -> Result<()> {
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
    if zone.downcast::<FacesZone>().is_some() && !(below.owns_surface() || above.owns_surface()) {
        return Err(Error::invalid(
            "contact.zone.kind",
            "faces",
            "finite-element faces are meshed by a finite-element body (fe_base, fe_block or \
             fe_punch); give one, or a grid, rings or strips",
        ));
    }
    if zone.downcast::<MeshZone>().is_some() && !(below.imported() || above.imported()) {
        return Err(Error::invalid(
            "contact.zone.kind",
            "mesh",
            "a zone of imported meshes is the contact faces of a body of kind \"fe_mesh\": \
             give one (or two)",
        ));
    }
    Ok(())
}

/// The contact's load fits the body above; without one, a body carries its own load, or,
/// when the gap is `measured` between two held bodies, their interference presses them (a
/// shrink fit: the load is the interference, and an approach of 0 is the same).
pub fn check_load(
    bodies: [&Chosen<dyn BodyKind>; 2],
    zone: &Chosen<dyn ZoneKind>,
    load: LoadSpec,
    measured: bool,
) -> Result<()> {
    let [below, above] = bodies;
    if load == LoadSpec::None && below.takes(zone) == Takes::OwnLoad {
        return Ok(());
    }
    let held = [below, above].map(|b| b.takes(zone)) == [Takes::Nothing; 2];
    if measured && held {
        return match load {
            LoadSpec::ApproachMm(a) => {
                contopt_core::check::non_negative("contact.load.approach_mm", a).map(|_| ())
            }
            LoadSpec::ForceN(_) => Err(Error::invalid(
                "contact.load.force_n",
                above.name(),
                "is held and cannot float under a force: its interference with its partner \
                 (the measured gap) presses them, or an approach",
            )),
            LoadSpec::None => Ok(()),
        };
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
             load of a finite-element body (two imported bodies held by their supports are \
             pressed by their measured interference alone)",
        )),
    }
}

#[cfg(test)]
mod tests {
    use contopt_input::Node;

    use super::*;
    use crate::Registry;

    /// The bodies and zone of a scene's text.
    fn pair(bodies: &str, zone: &str) -> (Vec<Chosen<dyn BodyKind>>, Chosen<dyn ZoneKind>) {
        let text = format!("body = [{bodies}]\nzone = {zone}\n");
        let node = Node::parse_toml(&text).unwrap();
        let registry = Registry::standard();
        let Some(contopt_input::Value::Array(items)) = node.get("body").map(Node::value) else {
            panic!("no bodies in {text}");
        };
        let bodies = (items.iter().enumerate())
            .map(|(k, b)| registry.body(b, &format!("body[{k}]")).unwrap())
            .collect();
        let zone = registry.zone(node.get("zone").unwrap(), "contact.zone");
        (bodies, zone.unwrap())
    }

    const RINGS: &str = "{ kind = \"rings\", rings = 10, radius_mm = 5.0 }";
    const FACES: &str = "{ kind = \"faces\", analysis = \"axisymmetric\", radius_mm = 5.0, \
                         elements = 4 }";
    const BED: &str = "{ kind = \"winkler\", modulus_mpa_per_mm = 50.0 }";
    const MATERIAL: &str = "material = { e_mpa = 2e5, nu = 0.3 }";

    fn refusal(result: Result<()>) -> String {
        result.unwrap_err().to_string()
    }

    #[test]
    fn a_pair_is_two_bodies_not_both_rigid() {
        let (one, zone) = pair("\"rigid\"", RINGS);
        assert!(refusal(check_pair(&one, &zone)).contains("1 bodies"));
        let (rigid, zone) = pair("\"rigid\", \"rigid\"", RINGS);
        assert!(refusal(check_pair(&rigid, &zone)).contains("two rigid bodies"));
        let (bed, zone) = pair(&format!("{BED}, \"rigid\""), RINGS);
        assert!(check_pair(&bed, &zone).is_ok());
    }

    #[test]
    fn faces_are_meshed_by_a_finite_element_body() {
        let (bed, zone) = pair(&format!("{BED}, \"rigid\""), FACES);
        assert!(refusal(check_pair(&bed, &zone)).contains("meshed by a finite-element body"));
        let base = format!(
            "{{ kind = \"fe_base\", {MATERIAL}, radius_mm = 10.0, height_mm = 5.0, \
             supports = [\"clamped\"] }}"
        );
        let (fe, zone) = pair(&format!("{base}, \"rigid\""), FACES);
        assert!(check_pair(&fe, &zone).is_ok());
    }

    #[test]
    fn the_load_fits_the_body_above() {
        let (bodies, zone) = pair(&format!("{BED}, \"rigid\""), RINGS);
        let both = [&bodies[0], &bodies[1]];
        assert!(check_load(both, &zone, LoadSpec::ForceN(10.0), false).is_ok());
        assert!(
            refusal(check_load(both, &zone, LoadSpec::ForceN(-1.0), false)).contains("force_n")
        );
        assert!(refusal(check_load(both, &zone, LoadSpec::None, false)).contains("nothing presses"));
        assert!(check_load(both, &zone, LoadSpec::ApproachMm(0.1), false).is_ok());
        // A bed above is held by the ground: a force cannot press it.
        let (upside, zone) = pair(&format!("\"rigid\", {BED}"), RINGS);
        let held = refusal(check_load(
            [&upside[0], &upside[1]],
            &zone,
            LoadSpec::ForceN(1.0),
            false,
        ));
        assert!(held.contains("is held and cannot float"), "{held}");
        assert!(held.contains("winkler"), "{held}");
    }

    /// Two held bodies with a measured gap (a shrink fit) are pressed by their interference:
    /// no load, or an approach of 0, is accepted, a negative approach or a force is not;
    /// without a measured gap, nothing presses them.
    #[test]
    fn an_interference_presses_two_held_bodies() {
        let (beds, zone) = pair(&format!("{BED}, {BED}"), RINGS);
        let both = [&beds[0], &beds[1]];
        assert!(check_load(both, &zone, LoadSpec::None, true).is_ok());
        assert!(check_load(both, &zone, LoadSpec::ApproachMm(0.0), true).is_ok());
        let e = refusal(check_load(both, &zone, LoadSpec::ApproachMm(-1e-3), true));
        assert!(e.contains("approach_mm"), "{e}");
        let e = refusal(check_load(both, &zone, LoadSpec::ForceN(1.0), true));
        assert!(e.contains("interference"), "{e}");
        let e = refusal(check_load(both, &zone, LoadSpec::None, false));
        assert!(
            e.contains("nothing presses") && e.contains("interference"),
            "{e}"
        );
        let e = refusal(check_load(both, &zone, LoadSpec::ApproachMm(0.0), false));
        assert!(e.contains("approach_mm"), "{e}");
    }
}
