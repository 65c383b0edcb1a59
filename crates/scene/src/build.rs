//! A case's bodies, built on its zone: the kinds that mesh or grid their own surface first,
//! then those that stand on a surface they are given (the zone's, or their partner's); two
//! imported bodies are paired and built together by their zone ([`crate::mesh_surface`]).

use std::time::{Duration, Instant};

use contopt_core::{ElasticBody, Interface};
use contopt_fem::{BuildStats, ContactPairing};

use crate::bodies::Side;
use crate::{Case, SceneError};

/// A case's two bodies, built once for every case of a scene that shares them.
pub struct Built {
    bodies: [Box<dyn ElasticBody>; 2],
    /// The time their build took.
    took: Duration,
    /// The pairing of two imported bodies, which measured the gap between them.
    pairing: Option<ContactPairing>,
    /// The sizes and times of the two imported bodies' builds, when paired.
    stats: Option<[BuildStats; 2]>,
}

impl Built {
    /// Two bodies paired by `pairing` (imported meshes), built in `took`.
    pub(crate) fn paired(
        bodies: [Box<dyn ElasticBody>; 2],
        pairing: ContactPairing,
        stats: [BuildStats; 2],
        took: Duration,
    ) -> Self {
        Self {
            bodies,
            took,
            pairing: Some(pairing),
            stats: Some(stats),
        }
    }

    /// The sizes and times of the two imported bodies' builds (assembly, factorisation,
    /// condensation), first body first, when they were paired and built together.
    pub fn stats(&self) -> Option<&[BuildStats; 2]> {
        self.stats.as_ref()
    }

    /// The pairing of two imported bodies meshed apart, which measured the gap between them.
    pub fn pairing(&self) -> Option<&ContactPairing> {
        self.pairing.as_ref()
    }

    /// The body below the zone (its outward normal is n¹).
    pub fn first(&self) -> &dyn ElasticBody {
        self.bodies[0].as_ref()
    }

    /// The body above the zone.
    pub fn second(&self) -> &dyn ElasticBody {
        self.bodies[1].as_ref()
    }

    /// The time the build took.
    pub fn took(&self) -> Duration {
        self.took
    }

    /// The two bodies, the first below the zone.
    pub fn into_bodies(self) -> [Box<dyn ElasticBody>; 2] {
        self.bodies
    }
}

impl Case {
    /// Builds the case's bodies: assembled, factorised and condensed, as its check planned.
    pub fn build(&self) -> Result<Built, SceneError> {
        if let Some(paired) = self.build_pair()? {
            return Ok(paired);
        }
        let start = Instant::now();
        let spec = &self.spec;
        let at = &self.locator;
        let mut built: [Option<Box<dyn ElasticBody>>; 2] = [None, None];
        // Owners first: a finite-element body meshes the faces its partner stands on.
        let order = [0, 1].map(|k| (!spec.body[k].owns_surface(), k));
        let mut order = order.to_vec();
        order.sort();
        for (_, k) in order {
            let place = crate::plan::placement(spec, &self.plan.layout, k, at, &self.meshes);
            let surface = self.surface(&built, k)?;
            let body = spec.body[k]
                .build(&place, surface.as_ref())
                .map_err(|e| at.library(&format!("body[{k}]"), e))?;
            built[k] = Some(body);
        }
        let [Some(first), Some(second)] = built else {
            return Err(at.at("body", "a body was not built"));
        };
        Ok(Built {
            bodies: [first, second],
            took: start.elapsed(),
            pairing: None,
            stats: None,
        })
    }

    /// The surface body `k` stands on, as the body below sees it: the zone's, or else the
    /// built partner's.
    fn surface(
        &self,
        built: &[Option<Box<dyn ElasticBody>>; 2],
        k: usize,
    ) -> Result<Option<Interface>, SceneError> {
        if let Some(surface) = self.plan.layout.surface() {
            return surface
                .map(Some)
                .map_err(|e| self.locator.library("contact.zone", e));
        }
        let partner = 1 - k;
        Ok(built[partner].as_ref().map(|body| {
            let own = body.interface();
            // The partner below sees the surface as it is; one above sees it mirrored.
            match side(partner) {
                Side::Below => own.clone(),
                Side::Above => own.mirrored(),
            }
        }))
    }
}

/// The side of body `k`.
fn side(k: usize) -> Side {
    if k == 0 {
        Side::Below
    } else {
        Side::Above
    }
}

impl Case {
    /// The two imported bodies of a mesh zone, paired and built together (`None` unless both
    /// bodies are imported), with the pairing that measured the gap between them.
    pub(crate) fn build_pair(&self) -> Result<Option<Built>, SceneError> {
        let start = std::time::Instant::now();
        let (spec, at) = (&self.spec, &self.locator);
        let Some(zone) = spec.contact.zone.downcast::<crate::zone::MeshZone>() else {
            return Ok(None);
        };
        let [Some(first), Some(second)] =
            crate::plan::survey::parts(&spec.body, zone, &self.meshes, at)?
        else {
            return Ok(None);
        };
        let settings =
            crate::plan::survey::settings(zone).map_err(|e| at.library("contact.zone", e))?;
        let pairing = ContactPairing::new(
            (&first.model, &first.contact),
            (&second.model, &second.contact),
            &settings,
        )
        .map_err(|e| crate::plan::survey::pairing_error(e, at))?;
        let (a, b) = pairing
            .bodies((first.name, first.model), (second.name, second.model))
            .map_err(|e| at.library("body", e))?;
        let stats = [*a.stats(), *b.stats()];
        let bodies: [Box<dyn contopt_core::ElasticBody>; 2] = [Box::new(a), Box::new(b)];
        Ok(Some(Built::paired(bodies, pairing, stats, start.elapsed())))
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::{Format, Registry};

    /// A sphere on a bed, swept over `key` with `values`.
    fn sweep(key: &str, values: &str) -> crate::Scene {
        let text = format!(
            "name = \"sweep\"\n[sweep]\nkey = \"{key}\"\nvalues = {values}\n[contact]\nzone = \
             {{ kind = \"rings\", rings = 40, radius_mm = 5.0 }}\ngap = {{ kind = \"sphere\", \
             radius_mm = 20.0 }}\nload = {{ force_n = 1000.0 }}\n[[body]]\nkind = \"winkler\"\n\
             modulus_mpa_per_mm = 50.0\n[[body]]\nkind = \"rigid\"\n"
        );
        Registry::standard()
            .parse(&text, Format::Toml, Path::new("sweep.toml"))
            .unwrap()
    }

    /// Cases share a build when their zone, bodies and load are equal as values: a sweep over
    /// the gap shares one, a sweep over a body's setting or the zone does not.
    #[test]
    fn cases_share_bodies_by_their_key() {
        let distinct = |scene: &crate::Scene| scene.run().distinct_bodies();
        assert_eq!(distinct(&sweep("contact.gap.radius_mm", "[10.0, 20.0]")), 1);
        assert_eq!(
            distinct(&sweep("body.0.modulus_mpa_per_mm", "[10.0, 20.0, 10.0]")),
            2
        );
        assert_eq!(distinct(&sweep("contact.zone.rings", "[20, 40]")), 2);
        assert_eq!(
            distinct(&sweep("contact.load.force_n", "[500.0, 1000.0]")),
            2
        );
    }

    /// A grid without `cell_mm` spans each case's own Hertz radius, so a sweep over the
    /// sphere's radius builds each case on its own cells: the R = 40 mm case on R = 10 mm's
    /// cells (1.5 × 0.324 mm across, its a = 0.515 mm) reached the grid's edge and was
    /// refused. Each p_max within 1 % of Hertz's p₀ (4538 and 1801 MPa); wrong cells would
    /// miss the second by the contact cut at the edge.
    #[test]
    fn a_grid_from_the_gap_follows_each_case() {
        let text = "name = \"grid-sweep\"\n[sweep]\nkey = \"contact.gap.radius_mm\"\nvalues = \
                    [10.0, 40.0]\n[contact]\nzone = { kind = \"grid\", cells = [24, 24] }\ngap = \
                    { kind = \"sphere\", radius_mm = 10.0 }\nload = { force_n = 1000.0 }\n\
                    [[body]]\nkind = \"half_space\"\nmaterial = { e_mpa = 2.0e5, nu = 0.3 }\n\
                    [[body]]\nkind = \"rigid\"\n";
        let scene = Registry::standard()
            .parse(text, Format::Toml, Path::new("grid-sweep.toml"))
            .unwrap();
        let mut run = scene.run();
        for p0 in [4538.297, 1801.024] {
            let report = run.next().unwrap().unwrap();
            assert!(report.limit.is_none(), "{:?}", report.limit);
            let p_max = report.p_max_mpa.unwrap();
            assert!((p_max / p0 - 1.0).abs() < 0.01, "{p_max} against {p0}");
        }
        assert_eq!(run.builds(), 2);
    }

    /// The bodies are built on the zone's surface: the bed's points are the rings', and the
    /// rigid body above stands on them mirrored.
    #[test]
    fn bodies_stand_on_the_zone() {
        let scene = sweep("contact.gap.radius_mm", "[10.0]");
        let built = scene.cases()[0].build().unwrap();
        let (bed, rigid) = (built.first().interface(), built.second().interface());
        assert_eq!(bed.len(), 40);
        assert_eq!(bed.points(), rigid.points());
        let normal = bed.normals()[0];
        assert!(normal.iter().any(|&c| c != 0.0));
        assert_eq!(rigid.normals()[0], normal.map(|c| -c));
        assert!(built.pairing().is_none() && built.stats().is_none());
    }
}
