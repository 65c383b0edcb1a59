//! The initial gap h(x) between the bodies (`contact.gap`). Each kind is a type that
//! implements [`GapKind`], registered by its name in a [`crate::Registry`]
//! ([`crate::Registry::with_gap`]): flat, a sphere, a cylinder, a flat punch, a bearing roller
//! on its raceway with its crown and tilt, or the distance measured between two imported
//! meshes. A gap knows where it is open for good (beyond a punch's rim, past a roller's ends),
//! with the pair's modulus and the load Hertz's nominal contact, and the closed-form pressure
//! of a validation case where one applies.

use std::f64::consts::PI;
use std::path::Path;

use contopt_core::{check, Error, Result};
use contopt_roller::{Crown, CrownSettings, Roller};
use serde::{Deserialize, Serialize};

use crate::chosen::Chosen;
use crate::load::LoadSpec;
use crate::reference::{ClosedForm, Hertz, ReferenceCase};
use crate::zone::{GridZone, Layout, MeshZone, Surface, ZoneKind};

/// A point this far beyond a flat punch's rim, relative to its radius, is under it: the
/// round-off of the points' coordinates.
const RIM_ROUND_OFF: f64 = 1e-12;

/// A sphere's zone, when the scene gives no cell size, reaches this many Hertz radii.
const SPHERE_REACH: f64 = 1.5;

/// What a gap kind says of itself: whether a zone can carry it, h(x), and what the scene asks
/// of a gap. Its name is the one it is registered under ([`crate::Registry::with_gap`]).
pub trait GapKind: Send + Sync {
    /// Refuses a gap the zone cannot carry, and sizes that are not positive and finite.
    fn check(&self, zone: &Chosen<dyn ZoneKind>) -> Result<()>;

    /// The gap h(x) at interface point `x` of `zone` \[mm\]; infinite where the gap is open
    /// for good. `roller` is a roller gap's roller, its crown built.
    fn at(&self, zone: &Chosen<dyn ZoneKind>, x: [f64; 3], roller: Option<&Roller>) -> Result<f64>;

    /// The cell size of a grid of `cells` that the gap spans by itself, for a zone without
    /// `cell_mm`, given Hertz's contact and a roller gap's roller; `None` (the default) for a
    /// gap that spans no grid.
    fn natural_cell(
        &self,
        _cells: [usize; 2],
        _hertz: Option<Hertz>,
        _roller: Option<&Roller>,
    ) -> Result<Option<[f64; 2]>> {
        Ok(None)
    }

    /// Hertz's nominal contact under `force` \[N\] (or the approach `approach` \[mm\]) with
    /// the pair's modulus `e_star` \[MPa\], on a zone whose grid length (a cylinder's length)
    /// or plane thickness is `length` \[mm\]; `None` (the default) where Hertz does not apply.
    fn hertz(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        _e_star: f64,
        _force: Option<f64>,
        _approach: Option<f64>,
        _length: Option<f64>,
    ) -> Option<Hertz> {
        None
    }

    /// Whether the gap stays finite past the zone's edge along `axis` (0: x or r, 1: y) at
    /// the edge point `x`, one `cell` further out: then contact could go on beyond the zone,
    /// and contact at its edge means the zone is too small. Yes by default; a gap's own edges
    /// (a flat punch's rim, a roller's ends) say no.
    fn goes_on(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        _x: [f64; 3],
        _axis: usize,
        _cell: f64,
    ) -> bool {
        true
    }

    /// Whether the gap is finite at `x`, a point past the end of an imported body's contact
    /// faces: then contact could go on beyond them. By default, where [`GapKind::at`] is
    /// finite without a roller (or has no value).
    fn finite_at(&self, zone: &Chosen<dyn ZoneKind>, x: [f64; 3]) -> bool {
        self.at(zone, x, None).map_or(true, f64::is_finite)
    }

    /// The roller gap, when it is one (a roller's bodies, crown and envelope).
    fn roller_gap(&self) -> Option<&RollerGap> {
        None
    }

    /// Whether it is the distance measured between two imported meshes, which their pairing
    /// gives (eq. 2.1), not [`GapKind::at`].
    fn measured(&self) -> bool {
        false
    }

    /// The closed-form pressure of a converged contact analysis on `case`, where one applies
    /// (none by default).
    fn reference(&self, _case: &ReferenceCase) -> Option<ClosedForm> {
        None
    }
}

/// Zero everywhere: the bodies fit (a punch on its base).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Flat {}

impl GapKind for Flat {
    /// Any zone.
    fn check(&self, _zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        Ok(())
    }

    fn at(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        _x: [f64; 3],
        _roller: Option<&Roller>,
    ) -> Result<f64> {
        Ok(0.0)
    }
}

/// A sphere of radius R, h = r²/(2R) (r from the axis; on rings and axisymmetric faces, r).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Sphere {
    /// The radius \[mm\].
    pub radius_mm: f64,
}

impl GapKind for Sphere {
    /// A grid or an axisymmetric zone; a plane one meets a cylinder.
    fn check(&self, zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        match zone.surface() {
            Surface::Grid | Surface::Axisymmetric => positive_radius(self.radius_mm),
            Surface::Plane => Err(Error::invalid(
                "kind",
                "sphere",
                "a plane zone meets a cylinder across the plane: kind = \"cylinder\"",
            )),
        }
    }

    fn at(
        &self,
        zone: &Chosen<dyn ZoneKind>,
        x: [f64; 3],
        _roller: Option<&Roller>,
    ) -> Result<f64> {
        let r = zone.surface().radius(x);
        Ok(r * r / (2.0 * self.radius_mm))
    }

    /// Hertz's radius times 1.5 to the grid's edges both ways.
    fn natural_cell(
        &self,
        cells: [usize; 2],
        hertz: Option<Hertz>,
        _roller: Option<&Roller>,
    ) -> Result<Option<[f64; 2]>> {
        Ok(hertz.map(|h| {
            let across = |n: usize| 2.0 * SPHERE_REACH * h.half_width / n as f64;
            [across(cells[0]), across(cells[1])]
        }))
    }

    /// Johnson, eqs. 3.39–3.41, under a force or an approach.
    fn hertz(
        &self,
        zone: &Chosen<dyn ZoneKind>,
        e_star: f64,
        force: Option<f64>,
        approach: Option<f64>,
        _length: Option<f64>,
    ) -> Option<Hertz> {
        if zone.surface() == Surface::Plane {
            return None;
        }
        match (force, approach) {
            (Some(f), _) => Hertz::sphere(self.radius_mm, f, e_star).usable(),
            (None, Some(d)) => Hertz::sphere_approach(self.radius_mm, d, e_star).usable(),
            (None, None) => None,
        }
    }

    /// Hertz, where the plan found it.
    fn reference(&self, case: &ReferenceCase) -> Option<ClosedForm> {
        case.hertz.map(ClosedForm::from)
    }
}

/// A cylinder of radius R: along x on a grid, h = y²/(2R) (the zone's length is its length);
/// across the plane on strips or plane faces, h = x²/(2R).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Cylinder {
    /// The radius \[mm\].
    pub radius_mm: f64,
}

impl GapKind for Cylinder {
    /// A grid or a plane zone; an axisymmetric one meets a sphere.
    fn check(&self, zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        match zone.surface() {
            Surface::Grid | Surface::Plane => positive_radius(self.radius_mm),
            Surface::Axisymmetric => Err(Error::invalid(
                "kind",
                "cylinder",
                "an axisymmetric zone meets a sphere or a flat punch",
            )),
        }
    }

    fn at(
        &self,
        zone: &Chosen<dyn ZoneKind>,
        x: [f64; 3],
        _roller: Option<&Roller>,
    ) -> Result<f64> {
        let across = if zone.surface() == Surface::Grid {
            x[1]
        } else {
            x[0]
        };
        Ok(across * across / (2.0 * self.radius_mm))
    }

    /// Johnson, eqs. 4.43–4.45, under a force spread over `length`.
    fn hertz(
        &self,
        zone: &Chosen<dyn ZoneKind>,
        e_star: f64,
        force: Option<f64>,
        _approach: Option<f64>,
        length: Option<f64>,
    ) -> Option<Hertz> {
        if zone.surface() == Surface::Axisymmetric {
            return None;
        }
        Hertz::line(self.radius_mm, force? / length?, e_star).usable()
    }

    /// Its ends along a grid (the grid is its length) are the gap's own.
    fn goes_on(&self, zone: &Chosen<dyn ZoneKind>, _x: [f64; 3], axis: usize, _cell: f64) -> bool {
        !(zone.surface() == Surface::Grid && axis == 0)
    }

    /// Hertz's line contact on a plane zone, where the plan found it (a cylinder along a grid
    /// has no closed form on a finite length).
    fn reference(&self, case: &ReferenceCase) -> Option<ClosedForm> {
        (case.surface == Surface::Plane)
            .then_some(case.hertz?)
            .map(ClosedForm::from)
    }
}

/// A flat punch of radius (half-width) a: h = 0 under it, open beyond.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FlatPunch {
    /// The radius \[mm\].
    pub radius_mm: f64,
}

impl FlatPunch {
    /// Whether `x` lies under the punch, its rim's round-off included.
    fn under(&self, zone: &Chosen<dyn ZoneKind>, x: [f64; 3]) -> bool {
        zone.surface().radius(x) <= self.radius_mm * (1.0 + RIM_ROUND_OFF)
    }
}

impl GapKind for FlatPunch {
    /// Any zone; its radius positive and finite.
    fn check(&self, _zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        positive_radius(self.radius_mm)
    }

    fn at(
        &self,
        zone: &Chosen<dyn ZoneKind>,
        x: [f64; 3],
        _roller: Option<&Roller>,
    ) -> Result<f64> {
        Ok(if self.under(zone, x) {
            0.0
        } else {
            f64::INFINITY
        })
    }

    /// Its rim is the gap's own edge: contact goes on only while the point one cell further
    /// out is under the punch.
    fn goes_on(&self, zone: &Chosen<dyn ZoneKind>, x: [f64; 3], axis: usize, cell: f64) -> bool {
        let mut beyond = x;
        beyond[axis] += cell * x[axis].signum();
        self.under(zone, beyond)
    }

    /// Sneddon under a force, p(0) = F/(2πa²) (Johnson eq. 3.34), or under an approach δ on a
    /// half-space itself, F = 2aE*δ (a block's approach depends on its size); on a half-plane
    /// under a force, p(0) = q/(πa) with q the force per thickness (eq. 2.64).
    fn reference(&self, case: &ReferenceCase) -> Option<ClosedForm> {
        let a = self.radius_mm;
        match (case.surface, case.load) {
            (Surface::Plane, LoadSpec::ForceN(f)) => Some(ClosedForm::Punch {
                p_centre: f / case.line_length? / (PI * a),
                a,
                plane: true,
            }),
            (Surface::Plane, _) => None,
            (Surface::Grid | Surface::Axisymmetric, load) => {
                let f = match load {
                    LoadSpec::ForceN(f) => f,
                    LoadSpec::ApproachMm(delta) if case.on_half_space => {
                        2.0 * a * case.e_star * delta
                    }
                    _ => return None,
                };
                Some(ClosedForm::Punch {
                    p_centre: f / (2.0 * PI * a * a),
                    a,
                    plane: false,
                })
            }
        }
    }
}

/// The distance between the bodies' faces as meshed, along the first body's normal n¹ (eq.
/// 2.1): between two imported meshes on a zone of meshes, read as the first body's field (the
/// default of two `fe_mesh` bodies), or over a grid's cells between the faces the bodies bring
/// (a solid's, [`crate::bodies::BodyKind::face_shape`]; a body without one has its face on the
/// grid's plane).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Measured {}

impl GapKind for Measured {
    /// A zone of imported meshes, or a grid.
    fn check(&self, zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        match (zone.downcast::<MeshZone>(), zone.downcast::<GridZone>()) {
            (None, None) => Err(Error::invalid(
                "kind",
                "measured",
                "is the distance between the bodies' meshed faces: two imported meshes on a \
                 zone of kind \"mesh\", or a solid on a zone of kind \"grid\"",
            )),
            _ => Ok(()),
        }
    }

    /// No formula: the pairing measures it.
    fn at(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        _x: [f64; 3],
        _roller: Option<&Roller>,
    ) -> Result<f64> {
        Err(Error::invalid(
            "kind",
            "measured",
            "has no formula: it is measured between the meshed faces",
        ))
    }

    /// It goes on wherever the meshes do.
    fn finite_at(&self, _zone: &Chosen<dyn ZoneKind>, _x: [f64; 3]) -> bool {
        true
    }

    fn measured(&self) -> bool {
        true
    }
}

/// A radius positive and finite.
fn positive_radius(radius_mm: f64) -> Result<()> {
    check::positive("radius_mm", radius_mm).map(|_| ())
}

/// A bearing roller on its raceway (both half-spaces on a grid, the raceway first): across the
/// contact the gap of the two curvatures, along the axis the crown's drop and the tilt.
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

    /// The effective radius across its contact, 1/R = 2/D + 2/D_r.
    fn radius(&self) -> Option<f64> {
        let curvature = 2.0 / self.diameter_mm + self.raceway_diameter_mm.map_or(0.0, |d| 2.0 / d);
        (curvature > 0.0 && curvature.is_finite()).then(|| 1.0 / curvature)
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

impl GapKind for RollerGap {
    /// A grid of an odd number of cells across, at least 3; its sizes positive and finite.
    fn check(&self, zone: &Chosen<dyn ZoneKind>) -> Result<()> {
        let Some(grid) = zone.downcast::<GridZone>() else {
            return Err(Error::invalid(
                "kind",
                "roller",
                format!(
                    "a roller lies on a grid of cells (zone kind \"grid\"), not on {}",
                    zone.name()
                ),
            ));
        };
        if grid.cells[1] < 3 || grid.cells[1].is_multiple_of(2) {
            return Err(Error::invalid(
                "cells[1]",
                grid.cells[1],
                "a roller's grid has an odd number of cells across, at least 3: \
                 its centre row (Ω_v) lies on y = 0",
            ));
        }
        check::positive("diameter_mm", self.diameter_mm)?;
        check::positive("length_mm", self.length_mm)?;
        check::positive("reach_b", self.reach_b)?;
        check::finite("tilt_arcmin", self.tilt_arcmin).map(|_| ())
    }

    /// Across the contact the two curvatures, along the axis the crown's drop and the tilt;
    /// open past the roller's ends.
    fn at(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        x: [f64; 3],
        roller: Option<&Roller>,
    ) -> Result<f64> {
        let roller = roller
            .ok_or_else(|| Error::invalid("kind", "roller", "a roller gap needs its roller"))?;
        if x[0].abs() > 0.5 * self.length_mm {
            return Ok(f64::INFINITY);
        }
        Ok(x[1] * x[1] / (2.0 * roller.radius()?)
            + roller.crown.drop(x[0], self.length_mm)?
            + roller.tilt * x[0])
    }

    /// [`Roller::cell`]: its length along x, ±`reach_b`·b to the outer cell centres across,
    /// as `Roller::bodies` lays its grid.
    fn natural_cell(
        &self,
        cells: [usize; 2],
        _hertz: Option<Hertz>,
        roller: Option<&Roller>,
    ) -> Result<Option<[f64; 2]>> {
        roller
            .map(|r| r.cell(cells[0], cells[1], self.reach_b))
            .transpose()
    }

    /// Hertz's line contact of its effective radius under the force over its length.
    fn hertz(
        &self,
        _zone: &Chosen<dyn ZoneKind>,
        e_star: f64,
        force: Option<f64>,
        _approach: Option<f64>,
        _length: Option<f64>,
    ) -> Option<Hertz> {
        Hertz::line(self.radius()?, force? / self.length_mm, e_star).usable()
    }

    /// Its ends are the gap's own.
    fn goes_on(&self, _zone: &Chosen<dyn ZoneKind>, _x: [f64; 3], axis: usize, _cell: f64) -> bool {
        axis != 0
    }

    fn roller_gap(&self) -> Option<&RollerGap> {
        Some(self)
    }
}

/// The gap at every point of `layout`'s surface is finite for at least one point: a flat punch
/// that covers no point is refused with the nearest point's distance.
pub(crate) fn covers(points: &[[f64; 3]], gap: &[f64], layout: &Layout) -> Result<()> {
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

#[cfg(test)]
mod tests {
    use std::path::Path;

    use contopt_input::{InputError, Node};

    use super::*;
    use crate::{Chosen, Format, Registry};

    /// The gap of `text`'s `gap` key, read by `registry` at `contact.gap`.
    fn read_gap(registry: &Registry, text: &str) -> Result<Chosen<dyn GapKind>, InputError> {
        let node = Node::parse_toml(text).unwrap();
        registry.gap(node.get("gap").unwrap(), "contact.gap")
    }

    #[test]
    fn three_spellings_read_alike() {
        let standard = Registry::standard();
        let read = |text| read_gap(&standard, text).unwrap();
        let a = read("gap = { kind = \"sphere\", radius_mm = 10.0 }");
        let b = read("gap = { sphere = { radius_mm = 10.0 } }");
        assert_eq!(a, b);
        assert_eq!(a.name(), "sphere");
        assert_eq!(
            a.written(),
            &serde_json::json!({ "sphere": { "radius_mm": 10.0 } })
        );
        let zone = Node::parse_toml("zone = { rings = { rings = 4, radius_mm = 1.0 } }").unwrap();
        let zone = (standard.zone(zone.get("zone").unwrap(), "contact.zone")).unwrap();
        assert_eq!(b.at(&zone, [2.0, 0.0, 0.0], None).unwrap(), 0.2);
        let bare = read("gap = \"flat\"");
        assert_eq!(bare, read("gap = { kind = \"flat\" }"));
        assert_eq!(bare, read("gap = { flat = {} }"));
        assert_eq!(bare.written(), &serde_json::json!("flat"));
    }

    #[test]
    fn an_unknown_gap_kind_lists_the_registered_ones() {
        let text = "gap = { kind = \"wedge\", slope = 0.1 }";
        let e = read_gap(&Registry::standard(), text).unwrap_err();
        assert_eq!(e.path, "contact.gap.kind");
        assert_eq!(
            e.message,
            "unknown variant `wedge`, expected one of `flat`, `sphere`, `cylinder`, \
             `flat_punch`, `roller`, `measured`"
        );
        let names: Vec<_> = Registry::standard().gap_kinds().collect();
        assert_eq!(
            names,
            [
                "flat",
                "sphere",
                "cylinder",
                "flat_punch",
                "roller",
                "measured"
            ]
        );
    }

    /// A gap of one's own: a wedge (a cone on rings), h = s·r.
    #[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields)]
    struct Wedge {
        slope: f64,
    }

    impl GapKind for Wedge {
        fn check(&self, _zone: &Chosen<dyn ZoneKind>) -> Result<()> {
            check::positive("slope", self.slope).map(|_| ())
        }

        fn at(
            &self,
            zone: &Chosen<dyn ZoneKind>,
            x: [f64; 3],
            _roller: Option<&Roller>,
        ) -> Result<f64> {
            Ok(self.slope * zone.surface().radius(x))
        }
    }

    /// A rigid wedge pushed δ into a Winkler bed of modulus k: p = k·(δ − s·r) where r < δ/s.
    #[test]
    fn a_gap_of_ones_own_is_read_and_shapes_the_contact() {
        let (k, delta, slope) = (50.0, 0.1, 0.04);
        let text = format!(
            "name = \"wedge\"\n\
             [contact]\n\
             zone = {{ kind = \"rings\", rings = 40, radius_mm = 5.0 }}\n\
             gap = {{ kind = \"wedge\", slope = {slope} }}\n\
             load = {{ approach_mm = {delta} }}\n\
             [[body]]\n\
             kind = \"winkler\"\n\
             modulus_mpa_per_mm = {k}\n\
             [[body]]\n\
             kind = \"rigid\"\n"
        );
        let registry = Registry::standard().with_gap::<Wedge>("wedge");
        let scene = registry
            .parse(&text, Format::Toml, Path::new("wedge.toml"))
            .unwrap();
        let case = &scene.cases()[0];
        assert_eq!(case.spec.contact.gap.name(), "wedge");
        let report = case.run().unwrap();
        assert!(report.is_solved(), "{:?}", report.termination);
        let mut touching = 0;
        for q in &report.interface {
            let expected = k * (delta - slope * q.x_mm[0].abs());
            if expected > 0.0 {
                touching += 1;
                let error = (q.p_mpa - expected).abs() / expected;
                assert!(
                    error < 1e-3,
                    "{} against {expected} at {:?}",
                    q.p_mpa,
                    q.x_mm
                );
            } else {
                assert!(q.p_mpa.abs() < 1e-9, "{} at {:?}", q.p_mpa, q.x_mm);
            }
        }
        assert!(touching > 10, "{touching} points in contact");
        let unknown = Registry::standard().parse(&text, Format::Toml, Path::new("wedge.toml"));
        assert!(unknown
            .unwrap_err()
            .to_string()
            .contains("unknown variant `wedge`"));
    }
}
