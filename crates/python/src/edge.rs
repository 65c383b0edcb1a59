//! The model's limits a grid's answer from numpy is judged by, as the scenes' reports judge
//! theirs (`contopt_scene`'s limits); a solve or a design from numpy says each in its
//! `warnings` and as a Python `RuntimeWarning`:
//! - a contact that reaches the edge of a half-space grid that is not periodic is cut there —
//!   the half-space beyond the last cell carries nothing — so its pressure and all that
//!   follows from it are wrong, unless the indenter itself ends there (a roller as long as the
//!   grid: `Contact(…, indenter_ends="x")`). A `DenseBody` is whatever its matrix says: its
//!   points are all of it, and it has no edge to reach;
//! - a contact whose half-width, where it ends inside the grid, spans fewer than
//!   [`MIN_CELLS_ACROSS`] cells (the patch of carrying cells around its peak) is not resolved
//!   (a rigid sphere on 4 × 4 cells of a/1.3 gives p_max 7 % below Hertz's p₀);
//! - a contact whose pressure rises to its peak at its own edge (a flat punch's rim, the end of
//!   a roller as long as the grid) ends at a sharp edge, where the elastic pressure is
//!   singular: p_max is the value on these cells and grows as they shrink (the scenes' check,
//!   [`contopt_scene::sharp_edge_warning`]);
//! - no cell carrying pressure: the bodies do not touch.

use std::ffi::CString;
use std::sync::Arc;

use contopt_greens::CARRIES;
use contopt_scene::{Layout, MIN_CELLS_ACROSS};
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
    /// through its peak and a peak at a sharp edge; or that no cell carries pressure.
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
            None => (self.resolution(pressure, p_max).into_iter())
                .chain(self.sharp_edge(pressure, p_max))
                .collect(),
        }
    }

    /// The scenes' warning of a peak at a sharp edge ([`contopt_scene::sharp_edge_warning`]),
    /// the grid's cells as a scene's grid zone. A periodic grid's contact that carries on the
    /// grid's boundary runs on across it, where the check would see the contact end: it is not
    /// judged.
    fn sharp_edge(&self, pressure: &[f64], p_max: f64) -> Option<String> {
        let ([ny, nx], [dx, dy], origin) = (self.shape, self.cell, self.origin);
        let periodic = self.grid.as_ref().is_some_and(|g| g.is_periodic());
        let on_boundary = |k: usize| {
            let (i, j) = (k % nx, k / nx);
            i == 0 || j == 0 || i + 1 == nx || j + 1 == ny
        };
        let wraps = (0..pressure.len()).any(|k| on_boundary(k) && pressure[k] > CARRIES * p_max);
        if periodic && wraps {
            return None;
        }
        let layout = Layout::Grid {
            nx,
            ny,
            dx,
            dy,
            origin,
            symmetric: [false; 2],
        };
        let points: Vec<[f64; 3]> = (0..pressure.len())
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                [origin[0] + i as f64 * dx, origin[1] + j as f64 * dy, 0.0]
            })
            .collect();
        contopt_scene::sharp_edge_warning(&layout, &points, pressure)
    }

    /// The contact's half-width in cells along x and y: half the number of columns and of rows
    /// that the patch of carrying cells around the peak occupies (its cells joined by their
    /// sides, across a period's edge on a periodic grid), counted only along an axis where the
    /// patch ends inside the grid (a contact across the whole grid, at an indenter's ends or
    /// around a period, has no edge there to resolve): a warning when the fewer of them is
    /// below [`MIN_CELLS_ACROSS`]. The whole patch, not the row through the peak: a flat
    /// punch peaks at its rim, where that row is a short chord of a well-resolved contact.
    fn resolution(&self, pressure: &[f64], p_max: f64) -> Option<String> {
        let peak = (0..pressure.len()).max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]))?;
        let carries: Vec<bool> = pressure.iter().map(|&p| p > CARRIES * p_max).collect();
        let spans = self.patch_spans(&carries, peak);
        let (along, cells) = (0..2)
            .filter(|&axis| spans[axis] < self.shape[1 - axis])
            .map(|axis| (axis, 0.5 * spans[axis] as f64))
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

    /// The numbers of columns and rows [along x, along y] occupied by the cells marked in
    /// `carries` that are joined to cell `start` by their sides (a flood fill; across the
    /// grid's edges when it is periodic).
    fn patch_spans(&self, carries: &[bool], start: usize) -> [usize; 2] {
        let [ny, nx] = self.shape;
        let periodic = self.grid.as_ref().is_some_and(|g| g.is_periodic());
        let step = |t: usize, n: usize, up: bool| match (up, periodic) {
            (true, _) if t + 1 < n => Some(t + 1),
            (true, true) => Some(0),
            (false, _) if t > 0 => Some(t - 1),
            (false, true) => Some(n - 1),
            _ => None,
        };
        let (mut seen, mut stack) = (vec![false; carries.len()], vec![start]);
        let (mut columns, mut rows) = (vec![false; nx], vec![false; ny]);
        seen[start] = true;
        while let Some(k) = stack.pop() {
            let (i, j) = (k % nx, k / nx);
            (columns[i], rows[j]) = (true, true);
            let sides = [
                step(i, nx, true).map(|i| j * nx + i),
                step(i, nx, false).map(|i| j * nx + i),
                step(j, ny, true).map(|j| j * nx + i),
                step(j, ny, false).map(|j| j * nx + i),
            ];
            for next in sides.into_iter().flatten() {
                if carries[next] && !seen[next] {
                    seen[next] = true;
                    stack.push(next);
                }
            }
        }
        let count = |marks: &[bool]| marks.iter().filter(|&&m| m).count();
        [count(&columns), count(&rows)]
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
