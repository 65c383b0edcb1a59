//! The initial gap h(x) between the bodies (`contact.gap`): flat, a sphere, a cylinder, a flat
//! punch, or a bearing roller on its raceway with its crown and tilt. A gap knows where it is
//! open for good (beyond a punch's rim, past a roller's ends) and, with the pair's modulus and
//! the load, Hertz's nominal contact.

use std::f64::consts::PI;
use std::path::Path;

use contopt_core::{check, Error, Result};
use contopt_roller::{Crown, CrownSettings, Roller};
use serde::{Deserialize, Serialize};

use crate::zone::{Layout, ZoneSpec};

/// A point this far beyond a flat punch's rim, relative to its radius, is under it: the
/// round-off of the points' coordinates.
const RIM_ROUND_OFF: f64 = 1e-12;

/// A sphere's zone, when the scene gives no cell size, reaches this many Hertz radii.
const SPHERE_REACH: f64 = 1.5;

/// The initial gap.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GapSpec {
    /// Zero everywhere: the bodies fit (a punch on its base).
    #[default]
    Flat,
    /// A sphere of radius R, h = r²/(2R) (r from the axis; on rings and axisymmetric faces, r).
    Sphere(Radius),
    /// A cylinder of radius R: along x on a grid, h = y²/(2R) (the zone's length is its
    /// length); across the plane on strips or plane faces, h = x²/(2R).
    Cylinder(Radius),
    /// A flat punch of radius (half-width) a: h = 0 under it, open beyond.
    FlatPunch(Radius),
    /// A bearing roller on its raceway (both half-spaces on a grid, the raceway first): across
    /// the contact the gap of the two curvatures, along the axis the crown's drop and the tilt.
    Roller(RollerGap),
    /// The distance between two imported meshes along the first body's normal n¹ (eq. 2.1),
    /// read as the first body's field: the default of two `fe_mesh` bodies.
    Measured,
}

/// A radius.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Radius {
    /// The radius \[mm\].
    pub radius_mm: f64,
}

/// A roller's gap.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RollerGap {
    /// Roller diameter D \[mm\].
    pub diameter_mm: f64,
    /// Effective length l \[mm\].
    pub length_mm: f64,
    /// Raceway diameter \[mm\]: positive for an inner ring, negative for an outer ring; default
    /// a flat raceway.
    #[serde(default)]
    pub raceway_diameter_mm: Option<f64>,
    /// Misalignment γ \[arc-minutes\]: an extra gap γ·x along the axis (default 0).
    #[serde(default)]
    pub tilt_arcmin: f64,
    /// How far the outer cell centres of a grid without a cell size reach across, in Hertz
    /// half-widths b (default 2.6).
    #[serde(default = "RollerGap::default_reach")]
    pub reach_b: f64,
    /// The crown (default straight).
    #[serde(default)]
    pub profile: CrownSettings,
    /// The raceway's crown along the roller, its drop added to the roller's (default
    /// straight).
    #[serde(default, skip_serializing_if = "is_straight")]
    pub raceway_profile: CrownSettings,
}

/// Whether a crown is the default straight one (left out of a case's resolved input).
fn is_straight(c: &CrownSettings) -> bool {
    *c == CrownSettings::Straight
}

impl RollerGap {
    fn default_reach() -> f64 {
        2.6
    }

    /// The roller of this gap pressed by `load` \[N\] between `raceway` (the first body) and
    /// `roller` (the second); its crown read from `dir` for a table.
    pub fn roller(
        &self,
        materials: [contopt_core::Material; 2],
        load: f64,
        dir: &Path,
    ) -> Result<Roller> {
        let mut roller = Roller {
            diameter: self.diameter_mm,
            length: self.length_mm,
            raceway_diameter: self.raceway_diameter_mm,
            raceway: materials[0],
            roller: materials[1],
            load,
            tilt: (check::finite("tilt_arcmin", self.tilt_arcmin)? / 60.0).to_radians(),
            crown: Crown::Straight,
        };
        roller.hertz()?;
        let raceway = self.raceway_profile.build(&roller, dir)?;
        roller.crown = self.profile.build(&roller, dir)?.plus(raceway);
        Ok(roller)
    }
}

/// Hertz's nominal contact: a circle of radius a (point) or a strip of half-width b (line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// A line contact (a cylinder, a roller).
    pub line: bool,
    /// The peak pressure p₀ \[MPa\].
    pub p0: f64,
    /// a or b \[mm\].
    pub half_width: f64,
}

impl Hertz {
    /// A sphere of radius `r` pressed by `force` with the pair's modulus `e_star`
    /// (Johnson, *Contact Mechanics*, eqs. 3.39–3.41).
    pub fn sphere(r: f64, force: f64, e_star: f64) -> Self {
        let a = (3.0 * force * r / (4.0 * e_star)).cbrt();
        Self {
            line: false,
            p0: 3.0 * force / (2.0 * PI * a * a),
            half_width: a,
        }
    }

    /// A sphere of radius `r` pushed in by the approach `delta`.
    pub fn sphere_approach(r: f64, delta: f64, e_star: f64) -> Self {
        let a = (r * delta).sqrt();
        Self {
            line: false,
            p0: 2.0 * a * e_star / (PI * r),
            half_width: a,
        }
    }

    /// A cylinder of radius `r` under the line load `q` \[N/mm\] (Johnson, eqs. 4.43–4.45).
    pub fn line(r: f64, q: f64, e_star: f64) -> Self {
        let b = (4.0 * q * r / (PI * e_star)).sqrt();
        Self {
            line: true,
            p0: 2.0 * q / (PI * b),
            half_width: b,
        }
    }

    /// Whether its numbers are usable.
    fn usable(self) -> Option<Self> {
        (self.p0 > 0.0 && self.p0.is_finite() && self.half_width > 0.0).then_some(self)
    }
}

/// What the zone says of the gap's surface coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Surface {
    /// A 3-D grid: (x, y).
    Grid,
    /// An axisymmetric line: r = x.
    Axisymmetric,
    /// A plane line: x.
    Plane,
}

fn surface(zone: &ZoneSpec) -> Surface {
    match zone {
        ZoneSpec::Grid(_) => Surface::Grid,
        ZoneSpec::Rings(_) => Surface::Axisymmetric,
        ZoneSpec::Strips(_) => Surface::Plane,
        ZoneSpec::Faces(f) if f.analysis == contopt_fem::Analysis::Axisymmetric => {
            Surface::Axisymmetric
        }
        ZoneSpec::Faces(_) => Surface::Plane,
        ZoneSpec::Mesh(m) if m.analysis == contopt_fem::Analysis::Axisymmetric => {
            Surface::Axisymmetric
        }
        ZoneSpec::Mesh(_) => Surface::Plane,
    }
}

impl GapSpec {
    /// The gap of a scene that gives none: the distance measured between two imported meshes
    /// on a zone of meshes, else flat.
    pub fn default_for(zone: &ZoneSpec, bodies: &[crate::Chosen<dyn crate::BodyKind>]) -> Self {
        let imported = bodies.iter().filter(|b| b.imported()).count();
        match zone {
            ZoneSpec::Mesh(_) if imported == 2 => GapSpec::Measured,
            _ => GapSpec::Flat,
        }
    }

    /// Its name in messages.
    pub fn kind(&self) -> &'static str {
        match self {
            GapSpec::Flat => "flat",
            GapSpec::Sphere(_) => "sphere",
            GapSpec::Cylinder(_) => "cylinder",
            GapSpec::FlatPunch(_) => "flat_punch",
            GapSpec::Roller(_) => "roller",
            GapSpec::Measured => "measured",
        }
    }

    /// Refuses a gap the zone cannot carry, and sizes that are not positive and finite.
    pub fn check(&self, zone: &ZoneSpec) -> Result<()> {
        let on = surface(zone);
        match (self, on) {
            (GapSpec::Flat, _) => Ok(()),
            (GapSpec::Measured, _) if matches!(zone, ZoneSpec::Mesh(_)) => Ok(()),
            (GapSpec::Measured, _) => Err(Error::invalid(
                "kind",
                "measured",
                "is the distance between two imported meshes: a zone of kind \"mesh\"",
            )),
            (GapSpec::Sphere(r) | GapSpec::FlatPunch(r), Surface::Grid | Surface::Axisymmetric) => {
                check::positive("radius_mm", r.radius_mm).map(|_| ())
            }
            (GapSpec::Cylinder(r) | GapSpec::FlatPunch(r), Surface::Grid | Surface::Plane) => {
                check::positive("radius_mm", r.radius_mm).map(|_| ())
            }
            (GapSpec::Sphere(_), Surface::Plane) => Err(Error::invalid(
                "kind",
                "sphere",
                "a plane zone meets a cylinder across the plane: kind = \"cylinder\"",
            )),
            (GapSpec::Cylinder(_), Surface::Axisymmetric) => Err(Error::invalid(
                "kind",
                "cylinder",
                "an axisymmetric zone meets a sphere or a flat punch",
            )),
            (GapSpec::Roller(g), Surface::Grid) => {
                if let ZoneSpec::Grid(grid) = zone {
                    if grid.cells[1] < 3 || grid.cells[1].is_multiple_of(2) {
                        return Err(Error::invalid(
                            "cells[1]",
                            grid.cells[1],
                            "a roller's grid has an odd number of cells across, at least 3: \
                             its centre row (Ω_v) lies on y = 0",
                        ));
                    }
                }
                check::positive("diameter_mm", g.diameter_mm)?;
                check::positive("length_mm", g.length_mm)?;
                check::positive("reach_b", g.reach_b)?;
                check::finite("tilt_arcmin", g.tilt_arcmin).map(|_| ())
            }
            (GapSpec::Roller(_), _) => Err(Error::invalid(
                "kind",
                "roller",
                format!(
                    "a roller lies on a grid of cells (zone kind \"grid\"), not on {}",
                    zone.kind()
                ),
            )),
        }
    }

    /// The cell size of a grid of `cells` that the gap spans by itself, for a zone without
    /// `cell_mm`: a roller's, [`Roller::cell`] (its length along x, ±`reach_b`·b to the outer
    /// cell centres across, as `Roller::bodies` lays its grid); a sphere's, its Hertz radius
    /// times 1.5 to the grid's edges both ways (given `hertz`). `None` for other gaps.
    pub fn natural_cell(
        &self,
        cells: [usize; 2],
        hertz: Option<Hertz>,
        roller: Option<&Roller>,
    ) -> Result<Option<[f64; 2]>> {
        Ok(match (self, hertz, roller) {
            (GapSpec::Roller(g), _, Some(r)) => Some(r.cell(cells[0], cells[1], g.reach_b)?),
            (GapSpec::Sphere(_), Some(h), _) => {
                let across = |n: usize| 2.0 * SPHERE_REACH * h.half_width / n as f64;
                Some([across(cells[0]), across(cells[1])])
            }
            _ => None,
        })
    }

    /// Hertz's nominal contact under `force` \[N\] (or the approach `approach` \[mm\]) with the
    /// pair's modulus `e_star` \[MPa\], on a zone whose grid length (a cylinder's length) or
    /// plane thickness is `length` \[mm\]; `None` where Hertz does not apply.
    pub fn hertz(
        &self,
        zone: &ZoneSpec,
        e_star: f64,
        force: Option<f64>,
        approach: Option<f64>,
        length: Option<f64>,
    ) -> Option<Hertz> {
        let line = |r: f64, f: f64| Hertz::line(r, f / length?, e_star).usable();
        match (self, surface(zone), force, approach) {
            (GapSpec::Sphere(r), Surface::Grid | Surface::Axisymmetric, Some(f), _) => {
                Hertz::sphere(r.radius_mm, f, e_star).usable()
            }
            (GapSpec::Sphere(r), Surface::Grid | Surface::Axisymmetric, None, Some(d)) => {
                Hertz::sphere_approach(r.radius_mm, d, e_star).usable()
            }
            (GapSpec::Cylinder(r), Surface::Grid | Surface::Plane, Some(f), _) => {
                line(r.radius_mm, f)
            }
            (GapSpec::Roller(g), _, Some(f), _) => {
                let radius = roller_radius(g)?;
                Hertz::line(radius, f / g.length_mm, e_star).usable()
            }
            _ => None,
        }
    }

    /// The gap at interface point `x` of `zone` \[mm\]; infinite where the gap is open for
    /// good (beyond a flat punch's rim, past a roller's ends). `crown` is a roller's built
    /// crown and tilt (the roller kind only).
    pub fn at(&self, zone: &ZoneSpec, x: [f64; 3], roller: Option<&Roller>) -> Result<f64> {
        let on = surface(zone);
        let r = match on {
            Surface::Grid => x[0].hypot(x[1]),
            _ => x[0].abs(),
        };
        Ok(match self {
            GapSpec::Flat => 0.0,
            GapSpec::Sphere(s) => r * r / (2.0 * s.radius_mm),
            GapSpec::Cylinder(c) => {
                let across = if on == Surface::Grid { x[1] } else { x[0] };
                across * across / (2.0 * c.radius_mm)
            }
            GapSpec::FlatPunch(p) if r <= p.radius_mm * (1.0 + RIM_ROUND_OFF) => 0.0,
            GapSpec::FlatPunch(_) => f64::INFINITY,
            GapSpec::Measured => {
                return Err(Error::invalid(
                    "kind",
                    "measured",
                    "has no formula: the pairing of the two meshes measures it",
                ))
            }
            GapSpec::Roller(g) => match roller {
                Some(roller) if x[0].abs() <= 0.5 * g.length_mm => {
                    x[1] * x[1] / (2.0 * roller.radius()?)
                        + roller.crown.drop(x[0], g.length_mm)?
                        + roller.tilt * x[0]
                }
                Some(_) => f64::INFINITY,
                None => {
                    return Err(Error::invalid(
                        "kind",
                        "roller",
                        "a roller gap needs its roller",
                    ))
                }
            },
        })
    }

    /// Whether the gap stays finite past the zone's edge along `axis` (0: x or r, 1: y) at
    /// the edge point `x`, one `cell` further out: then contact could go on beyond the zone,
    /// and contact at its edge means the zone is too small. A flat punch's rim, a roller's
    /// ends and a cylinder's ends along a grid (the grid is its length) are edges of the gap
    /// itself.
    pub fn goes_on(&self, zone: &ZoneSpec, x: [f64; 3], axis: usize, cell: f64) -> bool {
        let mut beyond = x;
        beyond[axis] += cell * x[axis].signum();
        match self {
            GapSpec::Cylinder(_) if matches!(zone, ZoneSpec::Grid(_)) && axis == 0 => false,
            GapSpec::Roller(_) if axis == 0 => false,
            GapSpec::FlatPunch(p) => {
                let r = match zone {
                    ZoneSpec::Grid(_) => beyond[0].hypot(beyond[1]),
                    _ => beyond[0].abs(),
                };
                r <= p.radius_mm * (1.0 + RIM_ROUND_OFF)
            }
            _ => true,
        }
    }

    /// Whether the gap is finite at `x`, a point past the end of an imported body's contact
    /// faces: then contact could go on beyond them. The measured gap goes on wherever the
    /// meshes do.
    pub fn finite_at(&self, zone: &ZoneSpec, x: [f64; 3]) -> bool {
        match self {
            GapSpec::Measured => true,
            gap => gap.at(zone, x, None).map_or(true, f64::is_finite),
        }
    }

    /// The roller gap, when it is one.
    pub fn roller_gap(&self) -> Option<&RollerGap> {
        match self {
            GapSpec::Roller(g) => Some(g),
            _ => None,
        }
    }

    /// The gap at every point of `layout`'s surface is finite for at least one point: a flat
    /// punch that covers no point is refused with the nearest point's distance.
    pub fn covers(&self, points: &[[f64; 3]], gap: &[f64], layout: &Layout) -> Result<()> {
        if gap.iter().any(|h| h.is_finite()) {
            return Ok(());
        }
        let nearest = points
            .iter()
            .map(|x| match layout {
                Layout::Grid { .. } => x[0].hypot(x[1]),
                _ => x[0].abs(),
            })
            .fold(f64::INFINITY, f64::min);
        Err(Error::invalid(
            "radius_mm",
            format!("less than {nearest:.4e}"),
            "no point of the zone lies under the gap (that is the nearest point's distance from \
             its axis): enlarge the punch, or refine the zone",
        ))
    }
}

/// The effective radius across a roller's contact, 1/R = 2/D + 2/D_r.
fn roller_radius(g: &RollerGap) -> Option<f64> {
    let curvature = 2.0 / g.diameter_mm + g.raceway_diameter_mm.map_or(0.0, |d| 2.0 / d);
    (curvature > 0.0 && curvature.is_finite()).then(|| 1.0 / curvature)
}
