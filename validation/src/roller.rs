//! The bearing roller of the optimisation and performance chapters on a half-space grid, and a
//! strip of points only in contact: the grids the load split, the linear programme and their
//! benchmarks share.

use contopt_core::{ElasticBody, Material, Result};
use contopt_greens::HalfSpace;
use contopt_optimise::Region;

use crate::closed_form::HertzLine;

/// The roller: D = 10 mm, l = 10 mm, Q = 5446 N, steel on steel as a rigid cylinder
/// (R = 5 mm) on one half-space of the pair's modulus (E = 1.05·10⁵ MPa, ν = 0.3). Hertz's
/// line contact under the nominal 544.6 N/mm: b = 0.17334 mm, p₀ = 2000.1 MPa.
pub struct Roller;

impl Roller {
    /// The half-space's Young's modulus \[MPa\]: the steel pair's, on one body.
    pub const E: f64 = 1.05e5;
    /// Poisson's ratio.
    pub const NU: f64 = 0.3;
    /// The cylinder's radius \[mm\].
    pub const RADIUS: f64 = 5.0;
    /// The roller's length \[mm\].
    pub const LENGTH: f64 = 10.0;
    /// The load \[N\].
    pub const LOAD: f64 = 5446.0;
    /// The grid reaches ±`REACH`·b across the roller.
    pub const REACH: f64 = 2.6;

    /// Hertz's line contact of the cylinder on the half-space.
    pub fn line() -> HertzLine {
        HertzLine {
            radius: Self::RADIUS,
            modulus: Self::E / (1.0 - Self::NU * Self::NU),
        }
    }

    /// The raceway on `nx` cells along the length × `ny` (odd: a row at y = 0) across
    /// ±[`Roller::REACH`]·b, under the cylinder.
    pub fn grid(nx: usize, ny: usize) -> Result<CylinderGrid> {
        let line = Self::line();
        let half = ((ny.max(2) - 1) / 2) as f64;
        let b = line.half_width(Self::LOAD / Self::LENGTH);
        let (dx, dy) = (Self::LENGTH / nx.max(1) as f64, Self::REACH * b / half);
        let origin = [-0.5 * Self::LENGTH + 0.5 * dx, -half * dy];
        let material = Material::new(Self::E, Self::NU)?;
        let body = HalfSpace::grid("raceway", material, nx, ny, dx, dy, origin)?;
        Ok(CylinderGrid::under(body, Self::RADIUS, dy))
    }
}

/// Steel's Young's modulus \[MPa\] and Poisson's ratio.
const STEEL: (f64, f64) = (2.0e5, 0.3);

/// A half-space grid under a rigid cylinder along x: the body, the cylinder's initial gap
/// y²/2R at its points and the cell across \[mm\].
pub struct CylinderGrid {
    /// The half-space.
    pub body: HalfSpace,
    /// The initial gap at its points \[mm\].
    pub gap: Vec<f64>,
    /// The cell across the cylinder \[mm\].
    pub dy: f64,
}

impl CylinderGrid {
    /// `nx` × `ny` cells of `dx` × `dy` centred on the origin, on a steel half-space
    /// (E = 2·10⁵ MPa, ν = 0.3), under a rigid cylinder of `radius` along x: 40 × 25 cells of
    /// 0.25 × 0.04 mm under R = 10 mm are the strip of the linear programme's checks.
    pub fn steel(nx: usize, ny: usize, dx: f64, dy: f64, radius: f64) -> Result<Self> {
        let origin = [
            -0.5 * (nx.max(1) - 1) as f64 * dx,
            -0.5 * (ny.max(1) - 1) as f64 * dy,
        ];
        let material = Material::new(STEEL.0, STEEL.1)?;
        let body = HalfSpace::grid("half-space", material, nx, ny, dx, dy, origin)?;
        Ok(Self::under(body, radius, dy))
    }

    fn under(body: HalfSpace, radius: f64, dy: f64) -> Self {
        let gap = body
            .interface()
            .points()
            .iter()
            .map(|x| x[1] * x[1] / (2.0 * radius))
            .collect();
        Self { body, gap, dy }
    }

    /// Ω_v the row at y = 0 (within half a cell), `outside` (Ω_nv, or only in contact)
    /// elsewhere.
    pub fn centre_row(&self, outside: Region) -> Vec<Region> {
        self.body
            .interface()
            .points()
            .iter()
            .map(|x| match x[1].abs() < 0.5 * self.dy {
                true => Region::OmegaV,
                false => outside,
            })
            .collect()
    }
}
