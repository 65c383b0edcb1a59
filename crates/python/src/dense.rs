//! A body given by its dense compliance matrix from numpy ([`contopt_greens::DenseCompliance`])
//! on a grid of cells, which a [`crate::library::Contact`] takes as it takes a half-space grid:
//! a finite-element code's condensed compliance, or a kernel tabulated in numpy.

use std::sync::Arc;

use contopt_core::Interface;
use contopt_greens::{DenseCompliance, HalfSpace};
use pyo3::prelude::*;

use crate::convert::with_matrix;
use crate::errors::library_error;

/// A body under nx × ny cells of dx × dy mm whose compliance is the matrix
/// `compliance_mm_per_n`, shape (n, n) with n = nx·ny [mm/N]: entry [i, j] the displacement
/// into the body at cell i under a unit compressive force on cell j, the cells in C order of
/// the (ny, nx) arrays (x fastest). It must be symmetric (within 1e-8 of its largest entry)
/// and positive definite; the body is held (no rigid motion).
#[pyclass(module = "contopt", frozen)]
pub struct DenseBody {
    pub(crate) body: Arc<DenseCompliance>,
    pub(crate) nx: usize,
    pub(crate) ny: usize,
    pub(crate) cell: [f64; 2],
    pub(crate) origin: [f64; 2],
}

/// The body named `name` on `interface` with the compliance `matrix` (a numpy array
/// `compliance_mm_per_n`), checked by the library with the GIL released.
pub fn dense_on(
    py: Python<'_>,
    name: &str,
    interface: Interface,
    matrix: &Bound<'_, PyAny>,
) -> PyResult<DenseCompliance> {
    with_matrix(matrix, "compliance_mm_per_n", |shape, entries| {
        py.detach(|| DenseCompliance::new(name, interface, shape, entries))
    })?
    .map_err(|e| library_error(py, e))
}

#[pymethods]
impl DenseBody {
    /// The body of compliance `compliance_mm_per_n` [mm/N], shape (nx·ny, nx·ny), under
    /// `nx` × `ny` cells of `dx_mm` × `dy_mm` [mm]; the first cell's centre at `origin_mm`
    /// (x, y) [mm], or by default the grid centred on (0, 0).
    #[new]
    #[pyo3(signature = (compliance_mm_per_n, *, nx, ny, dx_mm, dy_mm, origin_mm=None))]
    fn new(
        py: Python<'_>,
        compliance_mm_per_n: &Bound<'_, PyAny>,
        nx: usize,
        ny: usize,
        dx_mm: f64,
        dy_mm: f64,
        origin_mm: Option<(f64, f64)>,
    ) -> PyResult<Self> {
        let centred = (
            -0.5 * (nx as f64 - 1.0) * dx_mm,
            -0.5 * (ny as f64 - 1.0) * dy_mm,
        );
        let (x0, y0) = origin_mm.unwrap_or(centred);
        let interface = HalfSpace::cells_interface(nx, ny, dx_mm, dy_mm, [x0, y0])
            .map_err(|e| library_error(py, e))?;
        let body = dense_on(py, "dense", interface, compliance_mm_per_n)?;
        Ok(Self {
            body: Arc::new(body),
            nx,
            ny,
            cell: [dx_mm, dy_mm],
            origin: [x0, y0],
        })
    }

    /// The arrays' shape: (ny, nx).
    #[getter]
    fn shape(&self) -> (usize, usize) {
        (self.ny, self.nx)
    }

    /// The area of a cell [mm²].
    #[getter]
    fn cell_area_mm2(&self) -> f64 {
        self.cell[0] * self.cell[1]
    }

    fn __repr__(&self) -> String {
        format!(
            "DenseBody(nx={}, ny={}, dx_mm={}, dy_mm={})",
            self.nx, self.ny, self.cell[0], self.cell[1]
        )
    }
}
