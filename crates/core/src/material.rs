use serde::{Deserialize, Serialize};

use crate::{check, Error, Result};

/// Isotropic linear-elastic material, validated on construction, also when it is read from a
/// file: its serialised form is `{ e_mpa, nu }`, and reading it goes through [`Material::new`].
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "MaterialValues", into = "MaterialValues")]
pub struct Material {
    e: f64,
    nu: f64,
}

/// A material as written: Young's modulus and Poisson's ratio, not yet checked.
#[derive(Clone, Copy, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialValues {
    /// Young's modulus E \[MPa\].
    pub e_mpa: f64,
    /// Poisson's ratio ν.
    pub nu: f64,
}

impl TryFrom<MaterialValues> for Material {
    type Error = Error;

    fn try_from(m: MaterialValues) -> Result<Self> {
        Material::new(m.e_mpa, m.nu)
    }
}

impl From<Material> for MaterialValues {
    fn from(m: Material) -> Self {
        Self {
            e_mpa: m.e,
            nu: m.nu,
        }
    }
}

impl Material {
    /// Young's modulus `e` \[MPa\] > 0 and Poisson's ratio −1 < `nu` < 0.5.
    ///
    /// ν = 0.5 (incompressible) is rejected: the displacement formulation locks there and
    /// plane-strain and axisymmetric elasticity matrices are singular. An E whose moduli
    /// E/(1 − ν²) or compliance (1 − ν²)/E overflow f64 (E near 10³⁰⁸ or 10⁻³⁰⁸ MPa) is
    /// refused: no infinite modulus reaches a body.
    pub fn new(e: f64, nu: f64) -> Result<Self> {
        check::positive("e_mpa", e)?;
        check::between("nu", nu, -1.0, 0.5)?;
        let m = Self { e, nu };
        let modulus = m.plane_strain_modulus();
        check::derived("e_mpa", e, "the plane-strain modulus E/(1 − ν²)", modulus)?;
        check::derived(
            "e_mpa",
            e,
            "the compliance (1 − ν²)/E",
            m.contact_compliance(),
        )?;
        Ok(m)
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

    /// The body's share (1 − ν²)/E of the contact compliance 1/E* of a pair (Hertz): the
    /// pair's modulus is 1/E* = Σ (1 − νₖ²)/Eₖ \[1/MPa\].
    pub fn contact_compliance(&self) -> f64 {
        1.0 / self.plane_strain_modulus()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// E positive and finite, ν strictly between −1 and 0.5, each by the shared checks.
    #[test]
    fn rejects_moduli_and_ratios_out_of_range() {
        assert!(Material::new(2.1e5, 0.3).is_ok());
        let e = Material::new(2.1e5, 0.5).unwrap_err().to_string();
        assert_eq!(e, "invalid nu = 0.5: must lie strictly between -1 and 0.5");
        let e = Material::new(f64::INFINITY, 0.3).unwrap_err().to_string();
        assert_eq!(e, "invalid e_mpa = inf: must be positive and finite");
        assert!(Material::new(2.1e5, f64::NAN).is_err());
        assert!(Material::new(2.1e5, -1.0).is_err());
    }

    /// Moduli that overflow f64 are refused, naming E.
    #[test]
    fn rejects_moduli_beyond_f64() {
        let e = Material::new(f64::MAX, 0.3).unwrap_err().to_string();
        assert!(
            e.starts_with("invalid e_mpa = 1797") && e.contains("beyond f64"),
            "{e}"
        );
        assert!(Material::new(5e-324, 0.3).is_err());
        assert!(Material::new(1e300, 0.3).is_ok());
    }
}
