//! Memory estimates, checked before large allocations: an input too large for the machine is
//! an [`Error::TooLarge`] that names the size, never an allocator abort or an overflowing
//! product of sizes.

use crate::{Error, Result};

/// The most memory one body may take to build \[bytes\]: a third of the 24 GB machine we plan
/// for. Scenes check their whole estimate against their own, lower limit first.
pub const BODY_LIMIT_BYTES: u64 = 8_000_000_000;

/// `bytes_each` times the product of `counts`, or `None` when it overflows u64.
pub fn bytes(counts: &[usize], bytes_each: u64) -> Option<u64> {
    counts
        .iter()
        .try_fold(bytes_each, |acc, &c| acc.checked_mul(c as u64))
}

/// The sum of estimates, `None` when one is unknown or the sum overflows.
pub fn sum(parts: &[Option<u64>]) -> Option<u64> {
    parts
        .iter()
        .try_fold(0u64, |acc, part| part.and_then(|p| acc.checked_add(p)))
}

/// The estimate `bytes` of `what` when it is within `limit`, else [`Error::TooLarge`] with the
/// `advice` (an estimate that overflows counts as `u64::MAX`).
pub fn require(
    what: impl Into<String>,
    bytes: Option<u64>,
    limit: u64,
    advice: &str,
) -> Result<u64> {
    match bytes {
        Some(b) if b <= limit => Ok(b),
        _ => Err(Error::TooLarge {
            what: what.into(),
            bytes: bytes.unwrap_or(u64::MAX),
            limit,
            advice: advice.into(),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Products and sums that overflow are `None`, not wrapped; within the limit the estimate
    /// passes, past it the error names both numbers.
    #[test]
    fn overflow_and_limit() {
        assert_eq!(bytes(&[3, 4], 8), Some(96));
        assert_eq!(bytes(&[4_294_967_296, 4_294_967_296], 8), None);
        assert_eq!(sum(&[Some(1), Some(2)]), Some(3));
        assert_eq!(sum(&[Some(u64::MAX), Some(1)]), None);
        assert_eq!(require("x", Some(10), 10, "").unwrap(), 10);
        let e = require(
            "a grid",
            Some(3_000_000_000),
            2_000_000_000,
            "use fewer cells",
        );
        let message = e.unwrap_err().to_string();
        assert!(
            message.contains("3000 MB") && message.contains("2000 MB"),
            "{message}"
        );
        assert!(require("a grid", None, 1, "").is_err());
    }
}
