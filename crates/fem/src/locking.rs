//! Volumetric locking: where the displacement elements stop modelling the material. The
//! quadratic elements here integrate the volumetric strain in full, so as ν → 0.5 the bulk
//! modulus E/(3(1 − 2ν)) grows without bound and the few incompressible displacement fields the
//! mesh can represent stiffen the body (no mixed or B-bar formulation is built).
//!
//! Measured on the bundled `cylinder-on-block` (8-node quadrilaterals in plane strain, both
//! bodies of the same ν, p_max against Hertz's √(1 − ν²) scaling of the ν = 0.3 result):
//! −0.1 % at ν = 0.49, +0.35 % at 0.495, +6.9 % at 0.499, +19 % at 0.4995.

use contopt_core::Material;

/// Poisson's ratio from which a body of displacement elements is reported as locking: the
/// error measured above passes a few tenths of a percent here and grows as 1/(1 − 2ν).
pub const NEARLY_INCOMPRESSIBLE: f64 = 0.495;

/// The warning for `body` of displacement elements when its `material` is nearly
/// incompressible (ν ≥ [`NEARLY_INCOMPRESSIBLE`]), `None` otherwise.
pub fn locking_warning(body: &str, material: &Material) -> Option<String> {
    let nu = material.nu();
    (nu >= NEARLY_INCOMPRESSIBLE).then(|| {
        format!(
            "{body}: ν = {nu} is nearly incompressible, and its quadratic displacement elements \
             lock as ν → 0.5: the body comes out too stiff and the pressure too high (on the \
             bundled cylinder-on-block, p_max +0.35 % at ν = 0.495, +6.9 % at 0.499, +19 % at \
             0.4995; −0.1 % at 0.49); give ν ≤ 0.49, or model the body as a half-space, whose \
             Green's functions hold up to ν = 0.5"
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Named from ν = 0.495 on, with the body and the value; silent below.
    #[test]
    fn nearly_incompressible_bodies_are_named() {
        let at = |nu| locking_warning("block", &Material::new(2.0e5, nu).unwrap());
        assert!(at(0.49).is_none());
        let w = at(0.4995).unwrap();
        assert!(w.starts_with("block: ν = 0.4995"), "{w}");
        assert!(at(0.495).is_some());
    }
}
