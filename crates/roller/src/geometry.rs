//! A roller on its raceway as two elastic half-space grids.

use std::f64::consts::PI;

use contopt_core::{check, ElasticBody, Error, Material, Result};
use contopt_greens::{FreeEnds, HalfSpace};

use crate::Crown;

/// A cylindrical roller pressed on its raceway: both bodies elastic half-spaces (the raceway
/// below, the roller above and floating under its load Q), the gap across the contact that of
/// the two curvatures, y²/(2R) with 1/R = 2/D + 2/D_r, plus the crown's drop and the tilt γ·x
/// along the axis.
#[derive(Clone, Debug)]
pub struct Roller {
    /// Roller diameter D \[mm\].
    pub diameter: f64,
    /// Effective length l \[mm\].
    pub length: f64,
    /// Raceway diameter D_r \[mm\]: positive for an inner ring (convex), negative for an outer
    /// ring (concave); `None` for a flat raceway.
    pub raceway_diameter: Option<f64>,
    /// The roller's material.
    pub roller: Material,
    /// The raceway's material.
    pub raceway: Material,
    /// Load Q \[N\].
    pub load: f64,
    /// Misalignment γ \[rad\]: an extra gap γ·x along the axis.
    pub tilt: f64,
    /// The crown.
    pub crown: Crown,
}

impl Roller {
    /// The pair's modulus E*, 1/E* = Σ (1 − νₖ²)/Eₖ \[MPa\].
    pub fn e_star(&self) -> f64 {
        let c = |m: &Material| (1.0 - m.nu().powi(2)) / m.e();
        1.0 / (c(&self.roller) + c(&self.raceway))
    }

    /// The effective radius across the contact, 1/R = 2/D + 2/D_r \[mm\]; an error when it
    /// overflows f64 (diameters beyond 10³⁰⁸ mm, or an outer ring within round-off of the
    /// roller).
    pub fn radius(&self) -> Result<f64> {
        check::positive("diameter_mm", self.diameter)?;
        check::positive("length_mm", self.length)?;
        let curvature = 2.0 / self.diameter + self.raceway_diameter.map_or(0.0, |d| 2.0 / d);
        let raceway = self
            .raceway_diameter
            .map_or("flat".to_string(), |d| format!("{d} mm"));
        let curvature = check::positive("curvature", curvature).map_err(|_| {
            Error::invalid(
                "raceway_diameter_mm",
                &raceway,
                "an outer ring must be larger than the roller (the pair must be convex)",
            )
        })?;
        let what = format!("the effective radius 1/(2/D + 2/D_r) (D_r {raceway})");
        check::derived("diameter_mm", self.diameter, &what, 1.0 / curvature)
    }

    /// Hertz's line contact for the nominal line load Q/l: the half-width b \[mm\] and the peak
    /// p₀ \[MPa\]; an error when either overflows f64 (magnitudes far from physical ones).
    pub fn hertz(&self) -> Result<(f64, f64)> {
        check::positive("load_n", self.load)?;
        let q = self.load / self.length;
        let b = (4.0 * q * self.radius()? / (PI * self.e_star())).sqrt();
        let figures = (b, 2.0 * q / (PI * b));
        let what = "Hertz's contact (b, p₀) with this diameter, length and E*";
        check::all_derived("load_n", self.load, what, &[figures.0, figures.1])?;
        Ok(figures)
    }

    /// The cell size \[mm\] along the axis and across of a grid of `nx` × `ny` cells over the
    /// length and ±`reach`·b (the grid of [`Roller::bodies`]); `reach` positive and finite.
    pub fn cell(&self, nx: usize, ny: usize, reach: f64) -> Result<[f64; 2]> {
        check::positive("reach_b", reach)?;
        if ny.is_multiple_of(2) || ny < 3 {
            return Err(Error::invalid(
                "cells[1]",
                ny,
                "an odd number, at least 3: the centre row lies on y = 0",
            ));
        }
        let (b, _) = self.hertz()?;
        let cell = [
            self.length / nx.max(1) as f64,
            reach * b / ((ny - 1) / 2) as f64,
        ];
        check::all_derived(
            "reach_b",
            reach,
            "the cell size reach·b/((ny − 1)/2)",
            &cell,
        )?;
        Ok(cell)
    }

    /// The tilt γ in arc-minutes.
    pub fn tilt_arcmin(&self) -> f64 {
        60.0 * self.tilt.to_degrees()
    }

    /// The raceway and the roller on `nx` cells along the length and `ny` (odd) across
    /// ±`reach`·b, the roller pressed by Q, and the initial gap at the cell centres.
    pub fn bodies(
        &self,
        nx: usize,
        ny: usize,
        reach: f64,
    ) -> Result<(HalfSpace, HalfSpace, Vec<f64>)> {
        let (raceway, [dx, dy], origin) = self.raceway(nx, ny, reach)?;
        let roller = HalfSpace::grid("roller", self.roller, nx, ny, dx, dy, origin)?
            .upper()
            .pressed(self.load)?;
        let gap = self.gap(&raceway)?;
        Ok((raceway, roller, gap))
    }

    /// [`Roller::bodies`] with the roller's free ends: its surface ends at end faces
    /// `ends.chamfer_mm` beyond the effective length's ends, each loaded by the image pressure
    /// of weight `ends.weight` ([`FreeEnds`]); the raceway goes on past them.
    pub fn free_end_bodies(
        &self,
        nx: usize,
        ny: usize,
        reach: f64,
        ends: &RollerEnds,
    ) -> Result<(HalfSpace, FreeEnds, Vec<f64>)> {
        check::non_negative("free_ends.chamfer_mm", ends.chamfer_mm)?;
        let (raceway, [dx, dy], origin) = self.raceway(nx, ny, reach)?;
        let face = 0.5 * self.length + ends.chamfer_mm;
        let faces = [Some(-face), Some(face)];
        let roller = FreeEnds::grid(
            "roller",
            self.roller,
            nx,
            ny,
            dx,
            dy,
            origin,
            faces,
            ends.weight,
        )?
        .upper()
        .pressed(self.load)?;
        let gap = self.gap(&raceway)?;
        Ok((raceway, roller, gap))
    }

    /// The raceway's grid of `nx` × `ny` cells over the length and ±`reach`·b, its cell size
    /// and first centre.
    fn raceway(&self, nx: usize, ny: usize, reach: f64) -> Result<(HalfSpace, [f64; 2], [f64; 2])> {
        check::positive("reach_b", reach)?;
        check::finite("tilt", self.tilt)?;
        // After `cell`, which refuses an even `ny` or one below 3 (`ny - 1` would underflow).
        let [dx, dy] = self.cell(nx, ny, reach)?;
        let half = (ny - 1) / 2;
        let origin = [-0.5 * self.length + 0.5 * dx, -(half as f64) * dy];
        let raceway = HalfSpace::grid("raceway", self.raceway, nx, ny, dx, dy, origin)?;
        Ok((raceway, [dx, dy], origin))
    }

    /// The initial gap at the raceway's points: y²/(2R) + z(x) + γ·x.
    fn gap(&self, raceway: &HalfSpace) -> Result<Vec<f64>> {
        let radius = self.radius()?;
        let gap = raceway
            .interface()
            .points()
            .iter()
            .map(|x| {
                Ok(x[1] * x[1] / (2.0 * radius)
                    + self.crown.drop(x[0], self.length)?
                    + self.tilt * x[0])
            })
            .collect::<Result<Vec<f64>>>()?;
        let what = "the initial gap y²/(2R) + z(x) + γ·x";
        check::all_derived("tilt", self.tilt, what, &gap)?;
        Ok(gap)
    }
}

/// A roller's free ends ([`Roller::free_end_bodies`]): its end faces beyond the effective
/// length, and the weight of the image pressure that models them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RollerEnds {
    /// The axial width from each end of the effective length to the end face \[mm\] (the
    /// chamfer; 0: the contact reaches the face).
    pub chamfer_mm: f64,
    /// The image pressure's weight ([`FreeEnds`]): 1 for the end face that slides on a wall
    /// (the image alone), more for the free face.
    pub weight: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn roller(load: f64, diameter: f64) -> Roller {
        let steel = Material::new(2e5, 0.3).unwrap();
        Roller {
            diameter,
            length: 10.0,
            raceway_diameter: None,
            roller: steel,
            raceway: steel,
            load,
            tilt: 0.0,
            crown: Crown::Straight,
        }
    }

    /// `cell` checks its reach as `bodies` does: a NaN, infinite or negative reach is refused,
    /// and so is one that makes the cell size overflow.
    #[test]
    fn cell_refuses_a_reach_that_is_not_positive() {
        let r = roller(1000.0, 10.0);
        for reach in [f64::NAN, f64::INFINITY, -1.0, 0.0] {
            let e = r.cell(10, 5, reach).unwrap_err().to_string();
            assert!(e.contains("reach_b"), "{e}");
        }
        let e = roller(1e300, 10.0)
            .cell(10, 3, 1e300)
            .unwrap_err()
            .to_string();
        assert!(e.contains("reach_b") && e.contains("beyond f64"), "{e}");
        assert!(r.cell(10, 5, 2.6).is_ok());
    }

    /// Hertz's figures that overflow f64 are an error naming the load, not infinities.
    #[test]
    fn hertz_beyond_f64_is_refused() {
        for (load, diameter) in [(f64::MAX, 10.0), (1e-300, 1e-300), (1000.0, f64::MAX)] {
            let e = roller(load, diameter).hertz().unwrap_err().to_string();
            assert!(e.contains("load_n") && e.contains("beyond f64"), "{e}");
        }
        let (b, p0) = roller(1000.0, 10.0).hertz().unwrap();
        assert!(b > 0.0 && p0 > 0.0);
        let mut ring = roller(1000.0, 1.7e308);
        ring.raceway_diameter = Some(-f64::MAX);
        let e = ring.radius().unwrap_err().to_string();
        assert!(
            e.contains("diameter_mm") && e.contains("effective radius"),
            "{e}"
        );
    }
}
