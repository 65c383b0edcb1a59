//! The checks every constructor and every settings type applies to its numbers, written once:
//! each returns the value when it passes and an [`Error::InvalidInput`] naming the field, the
//! value and what it must satisfy when it does not. NaN fails every check.

use std::fmt::Display;

use crate::{Error, Result, GEOMETRY_TOLERANCE};

/// Units every magnitude is read in: a derived quantity beyond f64 almost always means an
/// input in other units.
const UNITS: &str = "check the units: N, mm, MPa";

/// Positive and finite (false for NaN).
fn is_positive(value: f64) -> bool {
    value > 0.0 && value.is_finite()
}

/// `value` when it is positive and finite.
pub fn positive(field: &str, value: f64) -> Result<f64> {
    if is_positive(value) {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be positive and finite"))
    }
}

/// `value` when it is zero or positive, and finite.
pub fn non_negative(field: &str, value: f64) -> Result<f64> {
    if value >= 0.0 && value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            value,
            "must be zero or positive, and finite",
        ))
    }
}

/// `value` when it is finite.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be finite"))
    }
}

/// `value` when it lies strictly between `low` and `high`.
pub fn between(field: &str, value: f64, low: f64, high: f64) -> Result<f64> {
    if value > low && value < high {
        Ok(value)
    } else {
        Err(Error::invalid(
            field,
            value,
            format!("must lie strictly between {low} and {high}"),
        ))
    }
}

/// `count` when it lies in `low ..= high`.
pub fn count(field: &str, count: usize, low: usize, high: usize) -> Result<usize> {
    if (low..=high).contains(&count) {
        Ok(count)
    } else {
        Err(Error::invalid(
            field,
            count,
            format!("must lie in {low} ..= {high}"),
        ))
    }
}

/// Every value of `values` finite, each reported by its index when it is not.
pub fn all_finite(field: &str, values: &[f64]) -> Result<()> {
    match values.iter().position(|v| !v.is_finite()) {
        Some(k) => Err(Error::invalid(
            format!("{field}[{k}]"),
            values[k],
            "must be finite",
        )),
        None => Ok(()),
    }
}

/// Every value of `values` positive and finite, each reported by its index when it is not.
pub fn all_positive(field: &str, values: &[f64]) -> Result<()> {
    match values.iter().position(|&v| !is_positive(v)) {
        Some(k) => positive(&format!("{field}[{k}]"), values[k]).map(|_| ()),
        None => Ok(()),
    }
}

/// `value`, the quantity `what` that a constructor derives from the input `field` = `input`,
/// when it is finite; else an error naming that input: its magnitude overflows (or, divided
/// by, underflows) f64 on the way. Inputs are checked finite first; this catches the
/// magnitudes far from any physical one (E = 10³⁰⁸ MPa, a cell of 10⁻³⁰⁰ mm), where a bound
/// on each input would be arbitrary.
pub fn derived(field: &str, input: impl Display, what: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(overflow(field, input, what, value))
    }
}

/// [`derived`], `value` positive too: a size or a stiffness that must not underflow to 0.
pub fn derived_positive(field: &str, input: impl Display, what: &str, value: f64) -> Result<f64> {
    if is_positive(value) {
        Ok(value)
    } else {
        Err(overflow(field, input, what, value))
    }
}

/// [`derived`] for every value of `values`, all derived from the input `field` = `input`.
pub fn all_derived(field: &str, input: impl Display, what: &str, values: &[f64]) -> Result<()> {
    match values.iter().find(|v| !v.is_finite()) {
        Some(&v) => Err(overflow(field, input, what, v)),
        None => Ok(()),
    }
}

/// The error of [`derived`].
fn overflow(field: &str, input: impl Display, what: &str, value: f64) -> Error {
    Error::invalid(
        field,
        input,
        format!("its magnitude makes {what} {value}, beyond f64 ({UNITS})"),
    )
}

/// `v` when it has unit length within [`GEOMETRY_TOLERANCE`]; NaN and infinite components
/// fail (checked first, since a NaN length passes any comparison written the other way).
pub fn unit_vector(field: &str, v: [f64; 3]) -> Result<[f64; 3]> {
    let len = v.iter().map(|c| c * c).sum::<f64>().sqrt();
    if v.iter().any(|c| !c.is_finite()) || (len - 1.0).abs() > GEOMETRY_TOLERANCE {
        return Err(Error::invalid(
            field,
            format!("{v:?}"),
            "must be a unit vector",
        ));
    }
    Ok(v)
}

/// An initial gap: one finite value per interface point (`n` of them) \[mm\].
pub fn gap(initial_gap: &[f64], n: usize) -> Result<()> {
    if initial_gap.len() != n {
        return Err(Error::invalid(
            "initial_gap",
            initial_gap.len(),
            format!("one value per interface point ({n})"),
        ));
    }
    all_finite("initial_gap", initial_gap)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nan_and_infinity_fail_every_check() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            assert!(positive("x", bad).is_err());
            assert!(non_negative("x", bad).is_err());
            assert!(finite("x", bad).is_err());
            assert!(between("x", bad, 0.0, 1.0).is_err());
        }
        assert_eq!(positive("x", 2.0).unwrap(), 2.0);
        assert!(positive("x", 0.0).is_err());
        assert_eq!(non_negative("x", 0.0).unwrap(), 0.0);
        assert!(between("x", 1.0, 0.0, 1.0).is_err());
        let e = count("mesh.elements", 0, 1, 10).unwrap_err().to_string();
        assert_eq!(e, "invalid mesh.elements = 0: must lie in 1 ..= 10");
        let e = all_finite("v", &[1.0, f64::NAN]).unwrap_err().to_string();
        assert!(e.starts_with("invalid v[1] = NaN"), "{e}");
        let e = all_positive("w", &[1.0, 0.5, 0.0]).unwrap_err().to_string();
        assert_eq!(e, "invalid w[2] = 0: must be positive and finite");
        assert!(all_positive("w", &[1.0, f64::INFINITY]).is_err());
        assert!(all_positive("w", &[1.0, 2.0]).is_ok());
    }

    #[test]
    fn derived_quantities_name_their_input() {
        assert_eq!(derived("e_mpa", 2e5, "E*", 2.2e5).unwrap(), 2.2e5);
        let e = derived("e_mpa", f64::MAX, "E/(1 − ν²)", f64::INFINITY)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("invalid e_mpa = 1797"), "{e}");
        assert!(
            e.contains("E/(1 − ν²) inf, beyond f64") && e.contains("units"),
            "{e}"
        );
        assert!(all_derived("dx", 1e-300, "the kernel", &[1.0, f64::NAN]).is_err());
        assert!(all_derived("dx", 1.0, "the kernel", &[1.0, 2.0]).is_ok());
        let e = derived_positive("dx", 1e-300, "the area", 0.0).unwrap_err();
        assert!(e.to_string().contains("the area 0, beyond f64"), "{e}");
        assert!(derived_positive("dx", 1.0, "the area", 1.0).is_ok());
    }

    #[test]
    fn unit_vectors_refuse_nan() {
        assert!(unit_vector("axis", [0.0, 0.0, 1.0]).is_ok());
        assert!(unit_vector("axis", [0.0, 0.0, 1.1]).is_err());
        for bad in [f64::NAN, f64::INFINITY] {
            let e = unit_vector("axis", [bad, 0.0, 0.0])
                .unwrap_err()
                .to_string();
            assert!(e.contains("axis") && e.contains("unit vector"), "{e}");
            assert!(unit_vector("axis", [0.0, bad, 1.0]).is_err());
        }
    }
}
