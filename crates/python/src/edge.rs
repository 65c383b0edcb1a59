//! The model's limits a grid's answer from numpy is judged by, as the scenes' reports judge
//! theirs (`contopt_scene`'s limits); a solve or a design from numpy says each in its
//! `warnings` and as a Python `RuntimeWarning`:
//! - a contact that reaches the edge of a half-space grid that is not periodic is cut there —
//!   the half-space beyond the last cell carries nothing — so its pressure and all that
//!   follows from it are wrong, unless the indenter itself ends there (a roller as long as the
//!   grid: `Contact(…, indenter_ends="x")`). A `DenseBody` is whatever its matrix says: its
//!   points are all of it, and it has no edge to reach;
//! - a contact whose half-width, where it ends inside the grid, spans fewer than
//!   [`MIN_CELLS_ACROSS`] cells through its peak is not resolved (a rigid sphere on 4 × 4
//!   cells of a/1.3 gives p_max 7 % below Hertz's p₀);
//! - no cell carrying pressure: the bodies do not touch.

use std::ffi::CString;
use std::sync::Arc;

use contopt_greens::CARRIES;
use contopt_scene::MIN_CELLS_ACROSS;
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
    /// ([`contopt_greens::HalfSpace::edge_reached`]); otherwise the resolution of the contact
    /// through its peak, or that no cell carries pressure.
    pub fn warnings(&self, pressure: &[f64]) -> Vec<String> {
        let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
        if p_max <= 0.0 {
            return vec![
                "no cell carries pressure: the bodies do not touch (or touch on less than a \
                 cell); press them together (a larger force or approach, or a gap that closes)"
                    .into(),
            ];
        }
        let reached = (self.grid.as_ref()).and_then(|grid| {
            grid.edge_reached(pressure, self.indenter_ends)
                .ok()
                .flatten()
        });
        match reached {
            Some(edge) => vec![edge.warning()],
            None => self.resolution(pressure, p_max).into_iter().collect(),
        }
    }

    /// The contact's half-width in cells along x and y through the peak (half the carrying
    /// run of the row and of the column there), counted only along an axis where the run
    /// ends inside the grid (a contact across the whole grid, at an indenter's ends or
    /// around a period, has no edge there to resolve): a warning when the fewer of them is
    /// below [`MIN_CELLS_ACROSS`].
    fn resolution(&self, pressure: &[f64], p_max: f64) -> Option<String> {
        let [ny, nx] = self.shape;
        let peak = (0..pressure.len()).max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]))?;
        let (pi, pj) = (peak % nx, peak / nx);
        let carries = |i: usize, j: usize| pressure[j * nx + i] > CARRIES * p_max;
        let run = |along: usize| -> Option<f64> {
            let n = [nx, ny][along];
            let at = |t: usize| match along {
                0 => carries(t, pj),
                _ => carries(pi, t),
            };
            let count = (0..n).filter(|&t| at(t)).count();
            (count < n).then_some(0.5 * count as f64)
        };
        let (along, cells) = [run(0), run(1)]
            .into_iter()
            .enumerate()
            .filter_map(|(axis, c)| c.map(|c| (axis, c)))
            .min_by(|a, b| a.1.total_cmp(&b.1))?;
        let half_width = cells * self.cell[along];
        (cells < MIN_CELLS_ACROSS).then(|| {
            format!(
                "the contact's half-width along {} ({half_width:.4} mm) spans {cells:.1} cells, \
                 fewer than {MIN_CELLS_ACROSS}: its peak is not resolved; refine the grid \
                 (cells of at most {:.4} mm)",
                ["x", "y"][along],
                half_width / MIN_CELLS_ACROSS
            )
        })
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
