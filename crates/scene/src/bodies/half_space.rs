//! An elastic half-space (`kind = "half_space"`) by Green's functions: Love's rectangles on a
//! grid, Boussinesq's rings, Flamant's strips on a half-plane.

use contopt_core::{ElasticBody, Error, Interface, Material, Result};
use contopt_fem::Analysis;
use contopt_greens::{
    dense_surface_bytes, AxisymmetricHalfSpace, FreeEnds, HalfPlane, HalfSpace, PlaneState,
};
use serde::{Deserialize, Serialize};

use super::{half_space_compliance, misplaced, BodyKind, Placement, Side, Takes};
use crate::chosen::Chosen;
use crate::load::LoadSpec;
use crate::zone::{GridZone, Layout, RingsZone, StripsZone, ZoneKind};

/// The datum of a half-plane's deflections unless the scene sets one \[mm\].
const DEFAULT_DATUM_MM: f64 = 100.0;

/// An elastic half-space under the zone (on a grid, also over it: the roller of a roller
/// pair, which then floats under the contact's force).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HalfSpaceBody {
    /// Its name in reports (default `half-space`).
    #[serde(default)]
    pub name: Option<String>,
    /// The material.
    pub material: Material,
    /// On strips: the depth at which a point load's deflection vanishes \[mm\] (default 100;
    /// a half-plane's deflection is defined up to a constant).
    #[serde(default)]
    pub datum_mm: Option<f64>,
    /// On a grid: the surface ends at free faces across x (a roller's end faces), each
    /// loaded by the image pressure ([`contopt_greens::FreeEnds`]); default none, the surface
    /// goes on.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_ends: Option<FreeEndsSpec>,
}

/// A grid's free faces across x (`free_ends`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FreeEndsSpec {
    /// The faces' x \[mm\]: at or below the grid's first edge, at or beyond its last (a
    /// roller's ends: ±(l/2 + chamfer)).
    pub faces_mm: [f64; 2],
    /// The image pressure's weight: 1 for faces that slide on a wall, more for free faces
    /// (default [`crate::FREE_END_WEIGHT`], Hetényi's free face matched).
    #[serde(default = "FreeEndsSpec::default_weight")]
    pub weight: f64,
}

impl FreeEndsSpec {
    fn default_weight() -> f64 {
        crate::FREE_END_WEIGHT
    }
}

impl HalfSpaceBody {
    /// A half-plane's state and thickness from the strips' analysis.
    fn plane(analysis: &Analysis) -> Result<(PlaneState, f64)> {
        match *analysis {
            Analysis::PlaneStress { thickness } => Ok((PlaneState::Stress, thickness)),
            Analysis::PlaneStrain { thickness } => Ok((PlaneState::Strain, thickness)),
            Analysis::Axisymmetric => Err(Error::invalid(
                "analysis",
                "axisymmetric",
                "a half-plane is plane_stress or plane_strain",
            )),
        }
    }
}

/// The zone's strips, when it is a zone of strips.
fn strips<'z>(at: &Placement<'z>) -> Option<&'z StripsZone> {
    at.zone.downcast::<StripsZone>()
}

impl BodyKind for HalfSpaceBody {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "half-space".into())
    }

    /// A grid on either side; rings and strips below only (their bodies do not float); not on
    /// finite-element faces, whose Gauss points no Green's body shares.
    fn check(&self, at: &Placement) -> Result<()> {
        let grid = at.zone.downcast::<GridZone>().is_some();
        let line = at.zone.downcast::<RingsZone>().is_some() || strips(at).is_some();
        match (grid, line, at.side) {
            (true, _, _) | (_, true, Side::Below) => {}
            (_, true, Side::Above) => {
                return Err(misplaced(at, "rings and strips lie under the zone"))
            }
            (false, false, _) => {
                return Err(misplaced(
                    at,
                    "finite-element faces are met by a finite-element body, a rigid body or a bed",
                ))
            }
        }
        if at.layout.symmetric().contains(&true) {
            return Err(misplaced(
                at,
                "a half-space's Green's functions load only the cells of its grid, and a grid \
                 with `symmetry` holds a half or a quarter of the contact: give the whole grid \
                 (no `symmetry`)",
            ));
        }
        if let (Some(_), false) = (self.free_ends, grid) {
            return Err(Error::invalid(
                "free_ends",
                "given",
                "free faces end a grid's surface across x: a grid zone only",
            ));
        }
        if let (Some(ends), Layout::Grid { nx, dx, origin, .. }) = (self.free_ends, at.layout) {
            let [lo, hi] = ends.faces_mm;
            let (first, last) = (origin[0] - 0.5 * dx, origin[0] + (*nx as f64 - 0.5) * dx);
            // A face within a quarter cell of the edge is on it (round-off of the lattice).
            if lo.is_nan() || lo > first + 0.25 * dx {
                return Err(Error::invalid(
                    "free_ends.faces_mm[0]",
                    lo,
                    format!("must lie at or below the grid's first edge, x = {first} mm"),
                ));
            }
            if hi.is_nan() || hi < last - 0.25 * dx {
                return Err(Error::invalid(
                    "free_ends.faces_mm[1]",
                    hi,
                    format!("must lie at or beyond the grid's last edge, x = {last} mm"),
                ));
            }
            contopt_core::check::between(
                "free_ends.weight",
                ends.weight,
                -f64::EPSILON,
                2.0 + f64::EPSILON,
            )?;
        }
        if let (Some(d), None) = (self.datum_mm, strips(at)) {
            return Err(Error::invalid(
                "datum_mm",
                d,
                "a datum fixes a half-plane's deflection: strips only",
            ));
        }
        Ok(())
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        match at.zone.downcast::<GridZone>() {
            Some(g) if self.free_ends.is_some() => FreeEnds::grid_bytes(g.cells[0], g.cells[1]),
            Some(g) => HalfSpace::grid_bytes(g.cells[0], g.cells[1]),
            None => at.layout.points().and_then(dense_surface_bytes),
        }
    }

    fn owns_surface(&self) -> bool {
        true
    }

    fn takes(&self, zone: &Chosen<dyn ZoneKind>) -> Takes {
        match zone.downcast::<GridZone>() {
            Some(_) => Takes::Force,
            None => Takes::Nothing,
        }
    }

    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let (name, material) = (self.name(), self.material);
        Ok(match at.layout {
            Layout::Grid {
                nx,
                ny,
                dx,
                dy,
                origin,
                ..
            } => match self.free_ends {
                None => {
                    let grid = HalfSpace::grid(name, material, *nx, *ny, *dx, *dy, *origin)?;
                    match (at.side, at.load) {
                        (Side::Below, _) => Box::new(grid),
                        (Side::Above, LoadSpec::ForceN(force)) => {
                            Box::new(grid.upper().pressed(force)?)
                        }
                        (Side::Above, _) => Box::new(grid.upper()),
                    }
                }
                Some(ends) => {
                    let faces = ends.faces_mm.map(Some);
                    let grid = FreeEnds::grid(
                        name,
                        material,
                        *nx,
                        *ny,
                        *dx,
                        *dy,
                        *origin,
                        faces,
                        ends.weight,
                    )?;
                    match (at.side, at.load) {
                        (Side::Below, _) => Box::new(grid),
                        (Side::Above, LoadSpec::ForceN(force)) => {
                            Box::new(grid.upper().pressed(force)?)
                        }
                        (Side::Above, _) => Box::new(grid.upper()),
                    }
                }
            },
            Layout::Rings(edges) => Box::new(AxisymmetricHalfSpace::new(name, material, edges)?),
            Layout::Strips { edges, thickness } => {
                let strips = strips(at).ok_or_else(|| misplaced(at, "strips need a strip zone"))?;
                let (state, _) = Self::plane(&strips.analysis)?;
                let datum = self.datum_mm.unwrap_or(DEFAULT_DATUM_MM);
                Box::new(HalfPlane::new(
                    name, material, state, *thickness, edges, datum,
                )?)
            }
            Layout::Faces(_) | Layout::Mesh(_) => return Err(misplaced(at, "not on faces")),
        })
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    /// (1 − ν²)/E, or 1/E for a half-plane in plane stress.
    fn compliance(&self, zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        Some(half_space_compliance(self.material, &**zone))
    }

    fn is_half_space(&self) -> bool {
        true
    }

    fn free_ends(&self) -> bool {
        self.free_ends.is_some()
    }
}
