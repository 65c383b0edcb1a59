//! A rigid body (`kind = "rigid"`): no compliance; the contact's gap is its shape.

use contopt_core::{ElasticBody, Interface, Result, RigidBody};
use serde::{Deserialize, Serialize};

use super::{own_surface, BodyKind, Placement, Side, Takes};
use crate::chosen::Chosen;
use crate::load::LoadSpec;
use crate::zone::ZoneKind;

/// Memory per point of a rigid body's surface \[bytes\]: a point, a weight and a normal.
const POINT_BYTES: u64 = 64;

/// A rigid body.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Rigid {
    /// Its name in reports (default `indenter`).
    #[serde(default)]
    pub name: Option<String>,
}

impl BodyKind for Rigid {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "indenter".into())
    }

    fn check(&self, _at: &Placement) -> Result<()> {
        Ok(())
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        at.layout
            .points()
            .and_then(|n| contopt_core::memory::bytes(&[n], POINT_BYTES))
    }

    fn owns_surface(&self) -> bool {
        false
    }

    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Force
    }

    /// Held in place, or, above the zone under a contact force, free to translate along the
    /// normal n¹ (away from the body below) and pressed by the force.
    fn build(&self, at: &Placement, surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let own = own_surface(at, surface)?;
        let partner = own.mirrored();
        Ok(Box::new(match (at.side, at.load) {
            (Side::Above, LoadSpec::ForceN(force)) => {
                let axis = partner.normals()[0];
                RigidBody::pressed(self.name(), &partner, axis, force)?
            }
            _ => RigidBody::fixed(self.name(), &partner),
        }))
    }

    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        Some(0.0)
    }
}
