//! The dense influence matrix on demand: built once, shared, and refused past a memory limit.

use std::sync::{Arc, OnceLock};

use contopt_core::{Error, Result};
use faer::Mat;

/// The memory the dense matrices of one solve may take unless the caller says otherwise
/// ([`InterfaceProblem::with_dense_limit`](crate::InterfaceProblem::with_dense_limit)): 2 GB,
/// a twelfth of the 24 GB machine we plan for, enough for the dense solvers up to about 8 000
/// interface points.
pub const DEFAULT_DENSE_LIMIT_BYTES: u64 = 2_000_000_000;

/// The n × n matrices that building the dense matrix holds at once: both bodies' and their
/// sum.
const BUILD_COPIES: u64 = 3;

/// The dense summed influence matrix A = A¹ + P A² Pᵀ \[mm/N\] (H = W A W of eq. 2.12), built on
/// the first request and shared by every clone (the problems derived from one with another
/// gap or other modes), with the memory limit that guards its building: a 2-D region of
/// 2·10⁴ points would need 3 GB for one copy.
#[derive(Clone)]
pub(super) struct Dense {
    matrix: Arc<OnceLock<Mat<f64>>>,
    limit: u64,
}

impl Dense {
    /// Not built yet, with the limit `limit` \[bytes\].
    pub(super) fn new(limit: u64) -> Self {
        Self {
            matrix: Arc::default(),
            limit,
        }
    }

    /// The memory limit \[bytes\].
    pub(super) fn limit(&self) -> u64 {
        self.limit
    }

    /// The same matrix with the limit set to `bytes`.
    pub(super) fn with_limit(self, bytes: u64) -> Self {
        Self {
            limit: bytes,
            ..self
        }
    }

    /// The matrix once built.
    pub(super) fn built(&self) -> Option<&Mat<f64>> {
        self.matrix.get()
    }

    /// The n × n matrix, built by `build` on the first call. `copies` is how many n × n
    /// matrices the calling solver will hold at once, this one included; the call fails with
    /// [`Error::TooLarge`] before building anything when they would exceed the limit.
    pub(super) fn get_or_build(
        &self,
        n: usize,
        copies: u64,
        build: impl FnOnce() -> Mat<f64>,
    ) -> Result<&Mat<f64>> {
        let n = n as u64;
        let copies = copies.max(BUILD_COPIES);
        let bytes = n
            .checked_mul(n)
            .and_then(|e| e.checked_mul(std::mem::size_of::<f64>() as u64 * copies))
            .unwrap_or(u64::MAX);
        if bytes > self.limit {
            return Err(Error::TooLarge {
                what: format!("a dense {n} × {n} influence matrix ({copies} copies)"),
                bytes,
                limit: self.limit,
                advice: "use the matrix-free solver (polonsky_keer) and the load split, or raise \
                         the limit (dense_limit_mb)"
                    .into(),
            });
        }
        Ok(self.matrix.get_or_init(build))
    }
}
