//! A case's bodies, built on its zone: the kinds that mesh or grid their own surface first,
//! then those that stand on a surface they are given (the zone's, or their partner's); two
//! imported bodies are paired and built together by their zone ([`crate::mesh_zone`]).

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
            let place = crate::prepare::placement(spec, &self.plan.layout, k, at, &self.meshes);
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
