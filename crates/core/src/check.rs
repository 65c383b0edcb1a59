//! The checks every constructor and every settings type applies to its numbers, written once:
//! each returns the value when it passes and an [`Error::InvalidInput`] naming the field, the
//! value and what it must satisfy when it does not. NaN fails every check.

use crate::{Error, Result};

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
}
