//! The model's limit a grid can reach from numpy: a contact that reaches the edge of a
//! half-space grid that is not periodic is cut there — the half-space beyond the last cell
//! carries nothing — so its pressure and all that follows from it are wrong, unless the
//! indenter itself ends there (a roller as long as the grid: `Contact(…, indenter_ends="x")`).
//! The scenes' reports say so (`contopt_scene`'s limits); a solve or a design from numpy says
//! it in its `warnings` and as a Python `RuntimeWarning`. A `DenseBody` is whatever its
//! matrix says: its points are all of it, and it has no edge to reach.

use std::ffi::CString;

use pyo3::exceptions::PyRuntimeWarning;
use pyo3::prelude::*;

/// A grid's cells as the edge check reads them: the shape (ny, nx), the first cell's centre
/// and the cell's sides [mm], and which of its edges cut a body that goes on beyond them:
/// `cuts[0]` the first and last columns (the ends along x), `cuts[1]` the first and last
/// rows (along y).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Cells {
    pub shape: [usize; 2],
    pub origin: [f64; 2],
    pub cell: [f64; 2],
    pub cuts: [bool; 2],
}

impl Cells {
    /// What the answer `pressure` [MPa] (C order) says of the grid's limits: the boundary
    /// cell that carries the most, when one carries any.
    pub fn warnings(&self, pressure: &[f64]) -> Vec<String> {
        let [ny, nx] = self.shape;
        let on_edge = |k: usize| {
            let (i, j) = (k % nx, k / nx);
            (self.cuts[0] && (i == 0 || i + 1 == nx)) || (self.cuts[1] && (j == 0 || j + 1 == ny))
        };
        let edge = (0..nx * ny)
            .filter(|&k| on_edge(k) && pressure[k] > 0.0)
            .max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]));
        let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
        edge.map(|k| {
            let x = [
                self.origin[0] + (k % nx) as f64 * self.cell[0],
                self.origin[1] + (k / nx) as f64 * self.cell[1],
            ];
            format!(
                "the contact reaches the grid's edge at the cell ({:.4}, {:.4}) mm (p = {:.4e} \
                 MPa there, {:.0} % of p_max): the grid ends inside the contact, so the pressure \
                 and all that follows from it are wrong; give the grid more or larger cells",
                x[0],
                x[1],
                pressure[k],
                100.0 * pressure[k] / p_max
            )
        })
        .into_iter()
        .collect()
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
