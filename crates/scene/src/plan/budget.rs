//! The memory a case needs, estimated before anything is built from what each part says of
//! itself — each body kind its own, each solver and method its dense matrices — and refused
//! past the scene's limit with the number.

use contopt_contact::ContactSolver;
use contopt_core::{check, memory, Result};

use crate::error::Locator;
use crate::meshes::MeshFiles;
use crate::spec::CaseSpec;
use crate::zone::Layout;
use crate::SceneError;

/// The memory limit of a case unless the scene sets `memory_limit_mb` \[bytes\]: a sixth of
/// the 24 GB machine we plan for.
pub const DEFAULT_MEMORY_LIMIT_BYTES: u64 = 4_000_000_000;

/// Memory per interface point that every case holds: the problem's vectors, the solver's
/// buffers and the reports (values, and their JSON text) \[bytes\].
const POINT_BYTES: u64 = 2_000;

/// Bytes in a megabyte, as the limits are written.
const MB: f64 = 1e6;

/// The scene's limit for dense matrices \[bytes\].
pub(crate) fn dense_limit(spec: &CaseSpec) -> Result<u64> {
    match spec.dense_limit_mb {
        None => Ok(contopt_contact::DEFAULT_DENSE_LIMIT_BYTES),
        Some(mb) => Ok((check::positive("dense_limit_mb", mb)? * MB) as u64),
    }
}

/// The scene's memory limit (`memory_limit_mb`, else [`DEFAULT_MEMORY_LIMIT_BYTES`])
/// \[bytes\].
pub(crate) fn limit(spec: &CaseSpec) -> Result<u64> {
    match spec.memory_limit_mb {
        None => Ok(DEFAULT_MEMORY_LIMIT_BYTES),
        Some(mb) => Ok((check::positive("memory_limit_mb", mb)? * MB) as u64),
    }
}

/// A case's memory: what it needs, estimated before anything is built, and the scene's limit.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Memory {
    /// The estimate of the case: its bodies, dense matrices and per-point vectors \[bytes\].
    pub estimate_bytes: u64,
    /// The scene's limit (`memory_limit_mb`, else [`DEFAULT_MEMORY_LIMIT_BYTES`]) \[bytes\].
    pub limit_bytes: u64,
}

/// The case's estimate against its limit.
pub(crate) fn check(
    spec: &CaseSpec,
    layout: &Layout,
    solver: &dyn ContactSolver,
    at: &Locator,
    meshes: &MeshFiles,
) -> std::result::Result<Memory, SceneError> {
    let limit = limit(spec).map_err(|e| at.library("", e))?;
    let points = layout.points();
    let bodies: Vec<Option<u64>> = (0..spec.body.len())
        .map(|k| {
            let place = super::placement(spec, layout, k, at, meshes);
            spec.body[k].memory(&place)
        })
        .collect();
    let design = spec.design();
    let copies = points.map(|n| solver.dense_copies(n).max(design.dense_copies(n, solver)));
    let dense = points
        .zip(copies)
        .and_then(|(n, c)| memory::bytes(&[n, n, c as usize], 8));
    let vectors = points.and_then(|n| memory::bytes(&[n], POINT_BYTES));
    let total = memory::sum(&[memory::sum(&bodies), dense, vectors]);
    let what = match (points, copies) {
        (Some(n), Some(c)) if c > 0 => format!(
            "the case ({n} interface points, their bodies, and {c} dense {n} × {n} matrices for \
             the dense solver or method)"
        ),
        (Some(n), _) => format!("the case ({n} interface points and their bodies)"),
        (None, _) => "the case (its point count overflows)".to_string(),
    };
    let advice = if copies.is_some_and(|c| c > 0) {
        "use fewer points, the matrix-free solver (polonsky_keer) with the load split, or raise \
         memory_limit_mb"
    } else {
        "use fewer points or raise memory_limit_mb"
    };
    let estimate_bytes =
        memory::require(what, total, limit, advice).map_err(|e| at.library("contact.zone", e))?;
    Ok(Memory {
        estimate_bytes,
        limit_bytes: limit,
    })
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::{Format, Registry};

    /// A sphere on a bed on `rings` rings, with `extra` settings.
    fn scene(rings: usize, extra: &str) -> Result<crate::Scene, crate::SceneError> {
        let text = format!(
            "name = \"budget\"\n{extra}\n[contact]\nzone = {{ kind = \"rings\", rings = {rings}, \
             radius_mm = 5.0 }}\ngap = {{ kind = \"sphere\", radius_mm = 20.0 }}\nload = {{ \
             force_n = 1000.0 }}\n[[body]]\nkind = \"winkler\"\nmodulus_mpa_per_mm = 50.0\n\
             [[body]]\nkind = \"rigid\"\n"
        );
        Registry::standard().parse(&text, Format::Toml, Path::new("budget.toml"))
    }

    /// The estimate grows with the points, each point's vectors and dense copies counted.
    #[test]
    fn the_estimate_counts_the_points() {
        let memory = |rings| scene(rings, "").unwrap().cases()[0].memory();
        let [small, large] = [memory(100), memory(200)];
        assert_eq!(small.limit_bytes, super::DEFAULT_MEMORY_LIMIT_BYTES);
        assert!(large.estimate_bytes > small.estimate_bytes);
        // At least the per-point vectors of every point.
        assert!(small.estimate_bytes >= 100 * super::POINT_BYTES);
    }

    /// A case past its limit is refused before anything is built, with both numbers.
    #[test]
    fn a_case_past_its_limit_is_refused_with_its_estimate() {
        let refused = scene(2000, "memory_limit_mb = 1.0")
            .unwrap_err()
            .to_string();
        assert!(refused.contains("2000 interface points"), "{refused}");
        assert!(refused.contains("memory_limit_mb"), "{refused}");
        let refused = scene(100, "memory_limit_mb = -1.0")
            .unwrap_err()
            .to_string();
        assert!(refused.contains("memory_limit_mb"), "{refused}");
    }
}
