//! The quarter-space by Hetényi's superposition of half-spaces: the load on a half-space
//! grid's surface that, with its image about each free face ([`crate::FreeEnds`] of weight
//! 1), leaves those faces free of stress.
//!
//! M. Hetényi (*A general solution for the elastic quarter space*, J. Appl. Mech. 37 (1970)
//! 70–76) solves the quarter-space x < x_f, z > 0 under a surface pressure p by two
//! half-spaces, one bounded by the top face z = 0, one by the end face x = x_f, each loaded
//! so that the other's stresses on its boundary are cancelled. With every load taken
//! together with its image (the top's about x = x_f, the face's about z = 0), the shears on
//! both boundaries vanish by symmetry and only normal stresses are left to cancel:
//!
//! - the face carries the normal load S = σ_xx\[T\](x_f, y, z), the top half-space's stress
//!   there under its load T and the image of T (so that the face is free: the face's own
//!   half-space gives −S on it);
//! - the top carries T = p + σ_zz\[S\](x, y, 0), the face half-space's stress on the top plane
//!   under S and its image (so that the top carries p).
//!
//! Hetényi iterates these two; here T⁰ = p and each round is one pass through both
//! (σ from Love's rectangles: [`crate::subsurface`]'s corner functions). The face's own
//! half-space moves the top plane only across it, not along z (its loads are even in z), so
//! the top surface's deflection is Love's operator on T and its image alone.
//!
//! Truncation: the face's loads are taken on the grid's rows and `margin_rows` more on each
//! side, down to `depth_cells` cells of the grid's size across, and the top's corrections on
//! the `columns` cells nearest each face; loads beyond decay with distance and are left out.

use contopt_core::{check, Error, Result};

use crate::subsurface::rectangle_stress;

/// How far Hetényi's superposition reaches and when it stops.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HetenyiSettings {
    /// Depth of the face's cells, in cells of the grid's size across (`dy` each).
    pub depth_cells: usize,
    /// Rows of the face's cells beyond the grid's rows on each side (the face's stresses
    /// reach wider than the contact).
    pub margin_rows: usize,
    /// The top's columns nearest each face that load it and take its corrections.
    pub columns: usize,
    /// The iteration stops when a round changes the load by this fraction of the largest
    /// pressure.
    pub tolerance: f64,
    /// The most rounds.
    pub max_rounds: usize,
}

impl Default for HetenyiSettings {
    fn default() -> Self {
        Self {
            depth_cells: 80,
            margin_rows: 40,
            columns: 40,
            tolerance: 1e-6,
            max_rounds: 200,
        }
    }
}

/// A half-space grid and its free faces: `nx` × `ny` cells of `dx` × `dy` \[mm\], the first
/// centre at `origin`, Poisson's ratio `nu`, the faces at or beyond its first and last edges
/// (as [`crate::FreeEnds::faces`] places them).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FacedGrid {
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
    /// Cell size along x \[mm\].
    pub dx: f64,
    /// Cell size along y \[mm\].
    pub dy: f64,
    /// The first cell's centre (x, y) \[mm\].
    pub origin: [f64; 2],
    /// Poisson's ratio.
    pub nu: f64,
    /// The faces \[mm\]: below the first column, beyond the last (`None`: no face).
    pub faces: [Option<f64>; 2],
}

/// Hetényi's top load and how the iteration ended.
#[derive(Clone, Debug, PartialEq)]
pub struct HetenyiLoad {
    /// The top load T on the grid's cells \[MPa\] (x fastest).
    pub load: Vec<f64>,
    /// Rounds taken.
    pub rounds: usize,
    /// The last round's largest change over the largest pressure.
    pub change: f64,
}

/// One face's tables: the top cell's pressure (with its image) to the face's σ_xx, and the
/// face cell's pressure (with its image) to the top plane's σ_zz, by column, depth and row
/// distance. The face's rows run `margin` rows beyond the grid's on each side.
struct Face {
    /// Top columns in reach, by index on the grid, nearest the face first.
    columns: Vec<usize>,
    /// The face's rows: the grid's and `margin` more on each side.
    rows: usize,
    margin: usize,
    /// b\[(k·ncol + c)·rows + |Δj|\]: σ_xx at face cell (·, k) under unit top pressure on
    /// column c, |Δj| rows away.
    to_face: Vec<f64>,
    /// a\[(c·nz + k)·rows + |Δj|\]: σ_zz at top column c under unit face pressure at depth k.
    to_top: Vec<f64>,
}

impl Face {
    /// The tables of the face `distance(i)` \[mm\] from the centre of column i.
    fn new(
        grid: &FacedGrid,
        columns: Vec<usize>,
        distance: impl Fn(usize) -> f64,
        nz: usize,
        margin: usize,
    ) -> Self {
        let (dx, dy, nu) = (grid.dx, grid.dy, grid.nu);
        let rows = grid.ny + 2 * margin;
        let (h, w) = (0.5 * dx, 0.5 * dy);
        let ncol = columns.len();
        let mut to_face = vec![0.0; nz * ncol * rows];
        let mut to_top = vec![0.0; ncol * nz * rows];
        for (c, &i) in columns.iter().enumerate() {
            let d = distance(i);
            for k in 0..nz {
                let z = (k as f64 + 0.5) * dy;
                for j in 0..rows {
                    let y = j as f64 * dy;
                    // The top cell and its image are mirror images across the face: equal σ_xx.
                    let sxx = rectangle_stress(0.0, y, z, [-d - h, -d + h], [-w, w], nu)[0];
                    to_face[(k * ncol + c) * rows + j] = 2.0 * sxx;
                    // The face cell and its image below the top plane: equal σ_zz on it. In the
                    // face's frame: depth d, across y, along z (the frame's second axis).
                    let szz = rectangle_stress(y, 0.0, d, [-w, w], [z - w, z + w], nu)[1];
                    to_top[(c * nz + k) * rows + j] = 2.0 * szz;
                }
            }
        }
        Self {
            columns,
            rows,
            margin,
            to_face,
            to_top,
        }
    }

    /// Adds this face's correction σ_zz\[S\], S = σ_xx\[T\], to `out` on the top grid; `face`
    /// holds S (`nz` × the face's rows).
    fn correct(
        &self,
        grid: &FacedGrid,
        nz: usize,
        load: &[f64],
        face: &mut [f64],
        out: &mut [f64],
    ) {
        let (nx, ny, rows, m) = (grid.nx, grid.ny, self.rows, self.margin);
        let ncol = self.columns.len();
        face.fill(0.0);
        for k in 0..nz {
            for (c, &i) in self.columns.iter().enumerate() {
                let table = &self.to_face[(k * ncol + c) * rows..(k * ncol + c + 1) * rows];
                for js in 0..rows {
                    let mut s = 0.0;
                    for jt in 0..ny {
                        s += table[js.abs_diff(jt + m)] * load[jt * nx + i];
                    }
                    face[k * rows + js] += s;
                }
            }
        }
        for (c, &i) in self.columns.iter().enumerate() {
            for k in 0..nz {
                let table = &self.to_top[(c * nz + k) * rows..(c * nz + k + 1) * rows];
                for jt in 0..ny {
                    let mut s = 0.0;
                    for js in 0..rows {
                        s += table[(jt + m).abs_diff(js)] * face[k * rows + js];
                    }
                    out[jt * nx + i] += s;
                }
            }
        }
    }
}

/// Hetényi's top load for `pressure` on `grid` (see the module's account): the load whose
/// deflection with its images, [`crate::FreeEnds`] of weight 1 on the same faces, is the
/// quarter-space's (or the slab's between two faces, each face's reflection in the other
/// left out). An error when the iteration does not settle within `settings`.
pub fn hetenyi_load(
    grid: &FacedGrid,
    pressure: &[f64],
    settings: &HetenyiSettings,
) -> Result<HetenyiLoad> {
    let (nx, ny) = (grid.nx, grid.ny);
    check::count("pressure (its length)", pressure.len(), nx * ny, nx * ny)?;
    check::all_finite("pressure", pressure)?;
    check::count("settings.depth_cells", settings.depth_cells, 1, 100_000)?;
    check::count("settings.columns", settings.columns, 1, usize::MAX)?;
    check::positive("settings.tolerance", settings.tolerance)?;
    let (nz, margin) = (settings.depth_cells, settings.margin_rows);
    check::count("settings.margin_rows", margin, 0, 100_000)?;
    let reach = settings.columns.min(nx);
    let (lo, hi) = (
        grid.origin[0] - 0.5 * grid.dx,
        grid.origin[0] + (nx as f64 - 0.5) * grid.dx,
    );
    let centre = |i: usize| grid.origin[0] + i as f64 * grid.dx;
    // A face within a quarter cell of the edge is on it (the lattice's round-off).
    let gap = |field: &str, d: f64| -> Result<f64> {
        check::finite(field, d)?;
        if d < -0.25 * grid.dx {
            return Err(Error::invalid(
                field,
                d,
                "a face lies at or beyond the grid's edge",
            ));
        }
        Ok(d.max(0.0))
    };
    let mut faces = vec![];
    if let Some(f) = grid.faces[0] {
        let g = gap("faces[0]", lo - f)?;
        faces.push(Face::new(
            grid,
            (0..reach).collect(),
            |i| g + centre(i) - lo,
            nz,
            margin,
        ));
    }
    if let Some(f) = grid.faces[1] {
        let g = gap("faces[1]", f - hi)?;
        faces.push(Face::new(
            grid,
            (nx - reach..nx).rev().collect(),
            |i| g + hi - centre(i),
            nz,
            margin,
        ));
    }
    let scale = pressure.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let mut load = pressure.to_vec();
    let mut next = vec![0.0; nx * ny];
    let mut face = vec![0.0; nz * (ny + 2 * margin)];
    for round in 1..=settings.max_rounds {
        next.copy_from_slice(pressure);
        for f in &faces {
            f.correct(grid, nz, &load, &mut face, &mut next);
        }
        let change = load
            .iter()
            .zip(&next)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
            / scale.max(f64::MIN_POSITIVE);
        std::mem::swap(&mut load, &mut next);
        if !change.is_finite() {
            break;
        }
        if change <= settings.tolerance {
            return Ok(HetenyiLoad {
                load,
                rounds: round,
                change,
            });
        }
    }
    Err(Error::invalid(
        "settings.max_rounds",
        settings.max_rounds,
        "Hetényi's superposition did not settle: raise the rounds or the tolerance",
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{FreeEnds, HalfSpace};
    use contopt_core::{ElasticBody, Material};
    use std::f64::consts::PI;

    /// Boussinesq's σ_xx at (x, y, z) under a unit point force at the origin (Johnson,
    /// *Contact Mechanics*, eq. 3.20).
    fn boussinesq_xx(x: f64, y: f64, z: f64, nu: f64) -> f64 {
        let r2 = x * x + y * y;
        let rho = (r2 + z * z).sqrt();
        (1.0 / (2.0 * PI))
            * ((1.0 - 2.0 * nu) / r2
                * ((1.0 - z / rho) * (x * x - y * y) / r2 + z * y * y / rho.powi(3))
                - 3.0 * z * x * x / rho.powi(5))
    }

    /// The rectangle's σ_xx is Boussinesq's point force integrated over it (a 400 × 400
    /// midpoint rule, away from the rectangle so that the integrand is smooth), to 1e-5, on
    /// either side of it and across the face plane where the tables evaluate it.
    #[test]
    fn rectangle_stress_is_boussinesq_integrated() {
        let nu = 0.3;
        let (xs, ys) = ([-0.3, -0.1], [-0.05, 0.07]);
        for (x, y, z) in [(0.0, 0.2, 0.15), (0.4, -0.3, 0.05), (-0.2, 0.5, 0.3)] {
            let n = 400;
            let (hx, hy) = ((xs[1] - xs[0]) / n as f64, (ys[1] - ys[0]) / n as f64);
            let mut sum = 0.0;
            for a in 0..n {
                for b in 0..n {
                    let (u, v) = (xs[0] + (a as f64 + 0.5) * hx, ys[0] + (b as f64 + 0.5) * hy);
                    sum += boussinesq_xx(x - u, y - v, z, nu) * hx * hy;
                }
            }
            let got = rectangle_stress(x, y, z, xs, ys, nu)[0];
            // Both under a compressive load, tension positive.
            assert!(
                (got - sum).abs() < 1e-5 * sum.abs(),
                "({x}, {y}, {z}): {got} vs {sum}"
            );
        }
    }

    fn strip(grid: &FacedGrid, b: f64) -> Vec<f64> {
        (0..grid.nx * grid.ny)
            .map(|k| {
                let y = grid.origin[1] + (k / grid.nx) as f64 * grid.dy;
                (1.0 - (y / b).powi(2)).max(0.0).sqrt()
            })
            .collect()
    }

    /// Hetényi's free face is softer than the image's sliding one, which is softer than the
    /// half-space: a Hertz strip running into the face loads the top more near it (T > p at
    /// the end, T = p far from it) and sinks its end deepest.
    #[test]
    fn the_free_face_is_softer_than_the_sliding_one() {
        let grid = FacedGrid {
            nx: 30,
            ny: 21,
            dx: 0.05,
            dy: 0.02,
            origin: [-1.475, -0.2],
            nu: 0.3,
            faces: [None, Some(0.0)],
        };
        let p = strip(&grid, 0.15);
        let settings = HetenyiSettings {
            depth_cells: 15,
            margin_rows: 10,
            columns: 30,
            ..Default::default()
        };
        let found = hetenyi_load(&grid, &p, &settings).unwrap();
        assert!(found.rounds > 2 && found.change <= 1e-6, "{found:?}");
        let row = (grid.ny / 2) * grid.nx;
        let (end, far) = (row + grid.nx - 1, row);
        assert!(
            found.load[end] > 1.05 * p[end],
            "{} vs {}",
            found.load[end],
            p[end]
        );
        assert!(
            (found.load[far] / p[far] - 1.0).abs() < 0.01,
            "{}",
            found.load[far]
        );
        let steel = Material::new(2.1e5, 0.3).unwrap();
        let (g, n) = (grid, grid.nx * grid.ny);
        let half = HalfSpace::grid("h", steel, g.nx, g.ny, g.dx, g.dy, g.origin).unwrap();
        let image =
            FreeEnds::grid("f", steel, g.nx, g.ny, g.dx, g.dy, g.origin, g.faces, 1.0).unwrap();
        let (mut a, mut b, mut c) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        half.apply_influence(&p, &mut a);
        image.apply_influence(&p, &mut b);
        image.apply_influence(&found.load, &mut c);
        assert!(
            a[end] < b[end] && b[end] < c[end],
            "{} {} {}",
            a[end],
            b[end],
            c[end]
        );
    }
}
