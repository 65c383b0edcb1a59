use serde::{Deserialize, Serialize};

use crate::{Error, Result};

/// Isotropic linear-elastic material, validated on construction.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Material {
    e: f64,
    nu: f64,
}

impl Material {
    /// Young's modulus `e` \[MPa\] > 0 and Poisson's ratio −1 < `nu` < 0.5.
    ///
    /// ν = 0.5 (incompressible) is rejected: the displacement formulation locks there and
    /// plane-strain and axisymmetric elasticity matrices are singular.
    pub fn new(e: f64, nu: f64) -> Result<Self> {
        if !(e.is_finite() && e > 0.0) {
            return Err(Error::invalid(
                "material.e",
                e,
                "Young's modulus must be positive and finite",
            ));
        }
        if !(nu.is_finite() && nu > -1.0 && nu < 0.5) {
            return Err(Error::invalid(
                "material.nu",
                nu,
                "Poisson's ratio must satisfy -1 < nu < 0.5",
            ));
        }
        Ok(Self { e, nu })
    }

    /// Young's modulus E \[MPa\].
    pub fn e(&self) -> f64 {
        self.e
    }

    /// Poisson's ratio ν.
    pub fn nu(&self) -> f64 {
        self.nu
    }

    /// Plane-strain (and half-space) modulus E* = E / (1 − ν²).
    pub fn plane_strain_modulus(&self) -> f64 {
        self.e / (1.0 - self.nu * self.nu)
    }
}
