//! The model's limit a grid can reach from numpy: a contact that reaches the edge of a
//! half-space grid that is not periodic is cut there — the half-space beyond the last cell
//! carries nothing — so its pressure and all that follows from it are wrong, unless the
//! indenter itself ends there (a roller as long as the grid: `Contact(…, indenter_ends="x")`).
//! The scenes' reports say so (`contopt_scene`'s limits); a solve or a design from numpy says
//! it in its `warnings` and as a Python `RuntimeWarning`. A `DenseBody` is whatever its
//! matrix says: its points are all of it, and it has no edge to reach.

use std::ffi::CString;
use std::sync::Arc;

use pyo3::exceptions::PyRuntimeWarning;
use pyo3::prelude::*;

/// A grid's cells as the edge check reads them: the shape (ny, nx), the first cell's centre
/// and the cell's sides [mm], and the half-space grid whose edge a contact must not reach
/// with the axes along which the indenter ends with it (`Contact(…, indenter_ends=…)`); no
/// grid for a `DenseBody`.
#[derive(Clone, Debug)]
pub(crate) struct Cells {
    pub shape: [usize; 2],
    pub origin: [f64; 2],
    pub cell: [f64; 2],
    pub grid: Option<Arc<contopt_greens::HalfSpace>>,
    pub indenter_ends: [bool; 2],
}

impl Cells {
    /// What the answer `pressure` [MPa] (C order) says of the grid's limits: the boundary
    /// cell that carries the most, when one carries any
    /// ([`contopt_greens::HalfSpace::edge_reached`]).
    pub fn warnings(&self, pressure: &[f64]) -> Vec<String> {
        let reached = (self.grid.as_ref()).and_then(|grid| {
            grid.edge_reached(pressure, self.indenter_ends)
                .ok()
                .flatten()
        });
        reached.iter().map(|e| e.warning()).collect()
    }
}

/// Each of `warnings` raised as a Python `RuntimeWarning` at the caller's line.
pub(crate) fn warn(py: Python<'_>, warnings: &[String]) -> PyResult<()> {
    let category = py.get_type::<PyRuntimeWarning>();
    for message in warnings {
        let text = CString::new(message.replace('\0', " ")).unwrap_or_default();
        PyErr::warn(py, &category, &text, 1)?;
    }
    Ok(())
}
