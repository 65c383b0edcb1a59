//! A roller on its raceway as two elastic half-space grids.

use std::f64::consts::PI;

use contopt_core::{check, ElasticBody, Error, Material, Result};
use contopt_greens::HalfSpace;

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

    /// The effective radius across the contact, 1/R = 2/D + 2/D_r \[mm\].
    pub fn radius(&self) -> Result<f64> {
        check::positive("diameter_mm", self.diameter)?;
        check::positive("length_mm", self.length)?;
        let curvature = 2.0 / self.diameter + self.raceway_diameter.map_or(0.0, |d| 2.0 / d);
        let curvature = check::positive("curvature", curvature).map_err(|_| {
            Error::invalid(
                "raceway_diameter_mm",
                format!("{:?}", self.raceway_diameter),
                "an outer ring must be larger than the roller (the pair must be convex)",
            )
        })?;
        Ok(1.0 / curvature)
    }

    /// Hertz's line contact for the nominal line load Q/l: the half-width b \[mm\] and the peak
    /// p₀ \[MPa\].
    pub fn hertz(&self) -> Result<(f64, f64)> {
        check::positive("load_n", self.load)?;
        let q = self.load / self.length;
        let b = (4.0 * q * self.radius()? / (PI * self.e_star())).sqrt();
        Ok((b, 2.0 * q / (PI * b)))
    }

    /// The cell size \[mm\] along the axis and across of a grid of `nx` × `ny` cells over the
    /// length and ±`reach`·b (the grid of [`Roller::bodies`]).
    pub fn cell(&self, nx: usize, ny: usize, reach: f64) -> Result<[f64; 2]> {
        if ny.is_multiple_of(2) || ny < 3 {
            return Err(Error::invalid(
                "cells[1]",
                ny,
                "an odd number, at least 3: the centre row lies on y = 0",
            ));
        }
        let (b, _) = self.hertz()?;
        Ok([
            self.length / nx.max(1) as f64,
            reach * b / ((ny - 1) / 2) as f64,
        ])
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
        check::positive("reach_b", reach)?;
        check::finite("tilt", self.tilt)?;
        let radius = self.radius()?;
        // After `cell`, which refuses an even `ny` or one below 3 (`ny - 1` would underflow).
        let [dx, dy] = self.cell(nx, ny, reach)?;
        let half = (ny - 1) / 2;
        let origin = [-0.5 * self.length + 0.5 * dx, -(half as f64) * dy];
        let raceway = HalfSpace::grid("raceway", self.raceway, nx, ny, dx, dy, origin)?;
        let roller = HalfSpace::grid("roller", self.roller, nx, ny, dx, dy, origin)?
            .upper()
            .pressed(self.load)?;
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
        Ok((raceway, roller, gap))
    }
}
