//! A Winkler bed (`kind = "winkler"`): the book's worked example of a body kind of one's own,
//! this file and one line of `bodies/mod.rs`.

use contopt_core::{ElasticBody, Interface, Result};
use contopt_greens::Winkler;
use serde::{Deserialize, Serialize};

use super::{own_surface, BodyKind, Placement, Takes};
use crate::chosen::Chosen;
use crate::zone::ZoneKind;

/// Memory per point of a bed \[bytes\]: its surface.
const POINT_BYTES: u64 = 64;

// ANCHOR: kind
/// A Winkler bed of modulus k under the zone, held by the ground.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WinklerBed {
    /// Its name in reports (default `bed`).
    #[serde(default)]
    pub name: Option<String>,
    /// Bed modulus k \[MPa/mm\]: the pressure that sinks the surface by 1 mm.
    pub modulus_mpa_per_mm: f64,
}

impl BodyKind for WinklerBed {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "bed".into())
    }

    /// Any zone, either side; the modulus positive and finite.
    fn check(&self, _at: &Placement) -> Result<()> {
        contopt_core::check::positive("modulus_mpa_per_mm", self.modulus_mpa_per_mm).map(|_| ())
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        at.layout
            .points()
            .and_then(|n| contopt_core::memory::bytes(&[n], POINT_BYTES))
    }

    /// It stands on the zone's surface (or its finite-element partner's).
    fn owns_surface(&self) -> bool {
        false
    }

    /// The ground holds it.
    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Nothing
    }

    fn build(&self, at: &Placement, surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let own = own_surface(at, surface)?;
        Ok(Box::new(Winkler::on(
            self.name(),
            own,
            self.modulus_mpa_per_mm,
        )?))
    }
}
// ANCHOR_END: kind
