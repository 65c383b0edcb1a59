//! A contact that reaches the edge of a half-space grid ([`HalfSpace::grid`]): the half-space
//! beyond the last cell carries nothing in the model, so a contact the grid cuts is cut short
//! and its pressure, and everything that follows from it, is wrong — unless the indenter itself
//! ends there (a roller as long as the grid). A periodic grid ([`HalfSpace::periodic`]) has no
//! edge. The solvers cannot tell: they solve the model they are given; this is the check a
//! caller makes on the answer (the Python module warns with it).

use contopt_core::{Error, Result};

use crate::HalfSpace;

/// A cell carries pressure when it holds more than this fraction of p_max (round-off of the
/// solvers' exact zeros).
pub const CARRIES: f64 = 1e-6;

/// The boundary cell of a grid that carries the most pressure, where the grid cuts a contact
/// ([`HalfSpace::edge_reached`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EdgeReached {
    /// The cell's index, x fastest.
    pub cell: usize,
    /// Its centre (x, y) \[mm\].
    pub at_mm: [f64; 2],
    /// Its pressure \[MPa\].
    pub p_mpa: f64,
    /// The largest pressure on the grid \[MPa\].
    pub p_max_mpa: f64,
}

impl EdgeReached {
    /// What it means, as a warning.
    pub fn warning(&self) -> String {
        format!(
            "the contact reaches the grid's edge at the cell ({:.4}, {:.4}) mm (p = {:.4e} MPa \
             there, {:.0} % of p_max): the grid ends inside the contact, so the pressure and \
             all that follows from it are wrong; give the grid more or larger cells",
            self.at_mm[0],
            self.at_mm[1],
            self.p_mpa,
            100.0 * self.p_mpa / self.p_max_mpa
        )
    }
}

impl HalfSpace {
    /// Where the pressure `pressure` \[MPa\] (one per cell, x fastest: a
    /// [`ContactState`](contopt_core::ContactState)'s) reaches the grid's edge: the boundary
    /// cell that carries the most ([`CARRIES`]), on the edges across x (its first and last
    /// columns) and across y (its first and last rows), except along an axis where the
    /// indenter itself ends with the grid (`indenter_ends`: [x, y]; a roller as long as the
    /// grid along x is `[true, false]`). `None` when no boundary cell carries, and on a
    /// periodic grid, which has no edge. An error when `pressure` is not one per cell.
    pub fn edge_reached(
        &self,
        pressure: &[f64],
        indenter_ends: [bool; 2],
    ) -> Result<Option<EdgeReached>> {
        let (nx, ny) = (self.nx, self.ny);
        if pressure.len() != nx * ny {
            return Err(Error::invalid(
                "pressure",
                pressure.len(),
                format!("one per cell of the {nx} × {ny} grid"),
            ));
        }
        if self.periodic {
            return Ok(None);
        }
        let cuts = indenter_ends.map(|ends| !ends);
        let on_edge = |k: usize| {
            let (i, j) = (k % nx, k / nx);
            (cuts[0] && (i == 0 || i + 1 == nx)) || (cuts[1] && (j == 0 || j + 1 == ny))
        };
        let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
        let edge = (0..nx * ny)
            .filter(|&k| on_edge(k) && pressure[k] > CARRIES * p_max)
            .max_by(|&a, &b| pressure[a].total_cmp(&pressure[b]));
        Ok(edge.map(|k| {
            let x = self.interface.points()[k];
            EdgeReached {
                cell: k,
                at_mm: [x[0], x[1]],
                p_mpa: pressure[k],
                p_max_mpa: p_max,
            }
        }))
    }
}

#[cfg(test)]
mod tests {
    use contopt_core::Material;

    use super::*;

    /// A 4 × 3 grid of 0.5 × 0.25 mm cells from (1, 2) mm.
    fn grid() -> HalfSpace {
        let steel = Material::new(2.0e5, 0.3).unwrap();
        HalfSpace::grid("g", steel, 4, 3, 0.5, 0.25, [1.0, 2.0]).unwrap()
    }

    /// Pressure on the inner cells alone reaches no edge; on a first-column cell it reaches
    /// the edge across x there (the cell (1, 2.25) mm, 3 of the 9 MPa at the centre, 33 %),
    /// and on both a column's and a row's boundary cells the larger is named. An indenter that
    /// ends with the grid along x is not cut by its columns; a periodic grid has no edge; a
    /// pressure not one per cell is refused.
    #[test]
    fn the_boundary_cell_that_carries_the_most_is_named() {
        let body = grid();
        let mut p = vec![0.0; 12];
        p[5] = 9.0;
        p[6] = 8.0;
        assert_eq!(body.edge_reached(&p, [false; 2]).unwrap(), None);
        p[4] = 3.0;
        let edge = body.edge_reached(&p, [false; 2]).unwrap().unwrap();
        assert_eq!(edge.cell, 4);
        assert_eq!(edge.at_mm, [1.0, 2.25]);
        assert!(edge.warning().contains("(1.0000, 2.2500) mm") && edge.warning().contains("33 %"));
        p[9] = 4.0;
        assert_eq!(body.edge_reached(&p, [false; 2]).unwrap().unwrap().cell, 9);
        assert_eq!(
            body.edge_reached(&p, [true, false]).unwrap().unwrap().cell,
            9
        );
        assert_eq!(
            body.edge_reached(&p, [false, true]).unwrap().unwrap().cell,
            4
        );
        assert_eq!(body.edge_reached(&p, [true; 2]).unwrap(), None);
        let steel = Material::new(2.0e5, 0.3).unwrap();
        let periodic = HalfSpace::periodic("p", steel, 4, 3, 0.5, 0.25, [1.0, 2.0]).unwrap();
        assert_eq!(periodic.edge_reached(&p, [false; 2]).unwrap(), None);
        assert!(body.edge_reached(&p[1..], [false; 2]).is_err());
    }
}
