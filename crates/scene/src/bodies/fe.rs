//! Finite-element bodies generated from a few dimensions on a zone of faces (`fe_base`,
//! `fe_punch`, `fe_block`): the punch on its base of the paper's Fig. 1 (§4, any dimensions,
//! materials and supports) and a large block that stands in for a half-space. The contact
//! plane is y = 0: a body below spans y ≤ 0, the punch y ≥ 0; both mesh the zone's faces
//! alike, so their contact nodes coincide. A plane body is the half x ≥ 0 of a body symmetric
//! about x = 0.

use contopt_core::{check, ElasticBody, Error, Interface, Material, Result};
use contopt_fem::{body_bytes, Analysis, Component, FeBody, FeModel, Mesh, Spacing};
use serde::{Deserialize, Serialize};

use super::{half_space_compliance, misplaced, BodyKind, Placement, Side, Takes};
use crate::chosen::Chosen;
use crate::zone::{FacesZone, ZoneKind};

/// The fewest elements of a base outside the zone.
const MIN_OUTER_ELEMENTS: usize = 4;
/// The most elements of a base outside the zone (the memory estimate counts on it).
const MAX_OUTER_ELEMENTS: usize = 40;
/// Outside the zone a base has about 1/this of the elements a uniform mesh of edge-sized
/// elements would need (they grow from the edge size).
const OUTER_SPARSENESS: f64 = 4.0;
/// Elements of a block outside its zone, growing outwards; its near-surface layer has at most
/// twice as many through its depth.
const BLOCK_OUTER_ELEMENTS: usize = 40;
/// Elements of a block below its near-surface layer, growing with depth.
const BLOCK_DEPTH_ELEMENTS: usize = 24;
/// A block's near-surface layer is this many zone radii deep, meshed with square-ish elements.
const BLOCK_NEAR_RADII: f64 = 2.0;

/// A support of a base's bottom face, or of a plane body's symmetry line.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// The bottom face clamped: u_r = u_z = 0 (the paper's axisymmetric model).
    Clamped,
    /// The bottom face held axially only: u_z = 0, free radially (with `Symmetry`, the paper's
    /// plane-stress model).
    Axial,
    /// A plane model's symmetry line x = 0 held, u_x = 0.
    Symmetry,
}

/// How a punch is driven from its top face.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum PunchLoad {
    /// A uniform pressure \[MPa\] (Tables 1 and 3: 100 MPa); the punch floats on the base.
    PressureMpa(f64),
    /// A prescribed axial displacement of the top face \[mm\] (negative: downwards), radial
    /// motion free (Table 2: −0.05 mm).
    DisplacementMm(f64),
}

/// A base: a cylinder (plane: a rectangle) of its own radius, wider than the zone, below it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeBase {
    /// Its name in reports (default `base`).
    #[serde(default)]
    pub name: Option<String>,
    /// The material.
    pub material: Material,
    /// Radius (plane: half-width) \[mm\], larger than the zone's.
    pub radius_mm: f64,
    /// Height \[mm\].
    pub height_mm: f64,
    /// `"clamped"` or `"axial"` for the bottom face, and `"symmetry"` in a plane analysis.
    pub supports: Vec<Support>,
    /// Elements through its height, graded towards the contact (default: the zone's count).
    #[serde(default)]
    pub layers: Option<usize>,
}

/// A punch: a cylinder (plane: a rectangle) whose bottom face is the zone, above it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FePunch {
    /// Its name in reports (default `punch`).
    #[serde(default)]
    pub name: Option<String>,
    /// The material.
    pub material: Material,
    /// Height \[mm\].
    pub height_mm: f64,
    /// The load on its top face: `{ pressure_mpa }` or `{ displacement_mm }`.
    pub load: PunchLoad,
    /// Elements through its height, graded towards the contact (default: the zone's count).
    #[serde(default)]
    pub layers: Option<usize>,
}

/// A block of radius and depth `size_mm`, clamped at its bottom, below the zone: a stand-in
/// for a half-space (its clamped bottom makes it a little stiffer).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeBlock {
    /// Its name in reports (default `block`).
    #[serde(default)]
    pub name: Option<String>,
    /// The material.
    pub material: Material,
    /// Radius (plane: half-width) and depth \[mm\], more than twice the zone's radius.
    pub size_mm: f64,
}

/// The faces zone of a finite-element body on its side, or why it cannot stand there.
fn faces<'z>(at: &Placement<'z>, side: Side) -> Result<&'z FacesZone> {
    match (at.zone.downcast::<FacesZone>(), at.side == side) {
        (Some(f), true) => Ok(f),
        (Some(_), false) => Err(misplaced(
            at,
            match side {
                Side::Below => "a base or a block lies below the zone (the first body)",
                Side::Above => "a punch stands on the zone (the second body)",
            },
        )),
        (None, _) => Err(misplaced(
            at,
            "a finite-element body meshes a zone of faces (zone kind \"faces\")",
        )),
    }
}

/// Layers through a height: the body's own count or the zone's elements, within the mesh's
/// limit.
fn layers(own: Option<usize>, zone: &FacesZone) -> Result<usize> {
    check::count(
        "layers",
        own.unwrap_or(zone.elements),
        1,
        contopt_fem::MAX_AXIS_ELEMENTS,
    )
}

/// Element boundaries through `height`, `layers` of them shrinking towards the contact to at
/// most the zone's edge size: from −height up to 0 (`below`), or from 0 up to height.
fn through(height: f64, layers: usize, edge: f64, below: bool) -> Result<Spacing> {
    let ratio = (height / layers as f64 / edge).max(1.0);
    if below {
        Spacing::geometric(-height, 0.0, layers, 1.0 / ratio)
    } else {
        Spacing::geometric(0.0, height, layers, ratio)
    }
}

/// A plane model's symmetry line x = 0 held over y from `y0` to `y1`.
fn hold_symmetry(model: &mut FeModel, y0: f64, y1: f64) -> Result<()> {
    let axis = model.mesh().nodes_on_x(0.0, y0, y1);
    model.fix(&axis, Component::X)?;
    Ok(())
}

impl FeBase {
    /// The element boundaries along x: the zone's, then growing from its edge size out to the
    /// base's rim.
    fn across(&self, zone: &FacesZone) -> Result<Spacing> {
        let edge = zone.edge_size()?;
        let width = self.radius_mm - zone.radius_mm;
        let outer = ((width / (OUTER_SPARSENESS * edge)).ceil() as usize)
            .clamp(MIN_OUTER_ELEMENTS, MAX_OUTER_ELEMENTS);
        let first = edge.min(width / outer as f64);
        zone.spacing()?.then(&Spacing::geometric_first(
            zone.radius_mm,
            self.radius_mm,
            outer,
            first,
        )?)
    }

    /// One support of the bottom face; symmetry in a plane analysis only, once; a plane base
    /// held axially needs its symmetry line, or it slides sideways (a rigid mode no contact
    /// pressure resists).
    fn check_supports(&self, analysis: Analysis) -> Result<()> {
        let named = || format!("{:?}", self.supports).to_lowercase();
        let count = |s: Support| self.supports.iter().filter(|&&t| t == s).count();
        if count(Support::Clamped) + count(Support::Axial) != 1 {
            return Err(Error::invalid(
                "supports",
                named(),
                "name one support of the bottom face: \"clamped\" or \"axial\"",
            ));
        }
        let symmetry = count(Support::Symmetry);
        let plane = analysis != Analysis::Axisymmetric;
        if symmetry > 1 || (symmetry == 1 && !plane) {
            return Err(Error::invalid(
                "supports",
                named(),
                "\"symmetry\" holds a plane model's line x = 0, once (an axisymmetric body is \
                 symmetric about its axis already)",
            ));
        }
        if plane && symmetry == 0 && count(Support::Axial) == 1 {
            return Err(Error::invalid(
                "supports",
                named(),
                "a plane base held axially slides sideways: add \"symmetry\" (the half model \
                 x ≥ 0) or clamp it",
            ));
        }
        Ok(())
    }

    fn model(&self, zone: &FacesZone) -> Result<FeModel> {
        let edge = zone.edge_size()?;
        let y = through(self.height_mm, layers(self.layers, zone)?, edge, true)?;
        let mesh = Mesh::rectangle(zone.element, &self.across(zone)?, &y)?;
        let mut model = FeModel::new(mesh, self.material, zone.analysis)?;
        let bottom = model
            .mesh()
            .nodes_on_y(-self.height_mm, 0.0, self.radius_mm);
        for support in &self.supports {
            match support {
                Support::Clamped => {
                    model
                        .fix(&bottom, Component::X)?
                        .fix(&bottom, Component::Y)?;
                }
                Support::Axial => {
                    model.fix(&bottom, Component::Y)?;
                }
                Support::Symmetry => hold_symmetry(&mut model, -self.height_mm, 0.0)?,
            }
        }
        Ok(model)
    }
}

impl BodyKind for FeBase {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "base".into())
    }

    fn check(&self, at: &Placement) -> Result<()> {
        let zone = faces(at, Side::Below)?;
        check::positive("height_mm", self.height_mm)?;
        check::positive("radius_mm", self.radius_mm)?;
        if self.radius_mm <= zone.radius_mm {
            return Err(Error::invalid(
                "radius_mm",
                self.radius_mm,
                format!(
                    "must exceed the zone's radius {} (the base carries the whole zone)",
                    zone.radius_mm
                ),
            ));
        }
        layers(self.layers, zone)?;
        self.across(zone)?;
        self.check_supports(zone.analysis)
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        let zone = at.zone.downcast::<FacesZone>()?;
        let across = zone.elements.checked_add(MAX_OUTER_ELEMENTS)?;
        body_bytes(across, self.layers.unwrap_or(zone.elements))
    }

    fn owns_surface(&self) -> bool {
        true
    }

    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Nothing
    }

    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let zone = faces(at, Side::Below)?;
        let model = self.model(zone)?;
        let contact = model.mesh().faces_on_y(0.0, 0.0, zone.radius_mm);
        Ok(Box::new(FeBody::new(self.name(), model, &contact)?))
    }

    fn has_displacement_elements(&self) -> bool {
        true
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        None
    }
}

impl FePunch {
    /// A pressure presses the floating punch onto the base (eq. 2.10 needs a compressive
    /// resultant); a displacement is finite.
    fn check_load(&self) -> Result<()> {
        match self.load {
            PunchLoad::PressureMpa(p) => {
                check::finite("load.pressure_mpa", p)?;
                if p <= 0.0 {
                    return Err(Error::invalid(
                        "load.pressure_mpa",
                        p,
                        "must press the punch onto the base (compressive, above zero): a \
                         frictionless contact cannot carry a pull",
                    ));
                }
                Ok(())
            }
            PunchLoad::DisplacementMm(w) => check::finite("load.displacement_mm", w).map(|_| ()),
        }
    }

    fn model(&self, zone: &FacesZone) -> Result<FeModel> {
        let edge = zone.edge_size()?;
        let y = through(self.height_mm, layers(self.layers, zone)?, edge, false)?;
        let mesh = Mesh::rectangle(zone.element, &zone.spacing()?, &y)?;
        let mut model = FeModel::new(mesh, self.material, zone.analysis)?;
        if zone.analysis != Analysis::Axisymmetric {
            hold_symmetry(&mut model, 0.0, self.height_mm)?;
        }
        let (top, radius) = (self.height_mm, zone.radius_mm);
        match self.load {
            PunchLoad::PressureMpa(p) => {
                let faces = model.mesh().faces_on_y(top, 0.0, radius);
                model.pressure(&faces, p)?;
            }
            PunchLoad::DisplacementMm(w) => {
                let nodes = model.mesh().nodes_on_y(top, 0.0, radius);
                model.prescribe(&nodes, Component::Y, w)?;
            }
        }
        Ok(model)
    }
}

impl BodyKind for FePunch {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "punch".into())
    }

    fn check(&self, at: &Placement) -> Result<()> {
        let zone = faces(at, Side::Above)?;
        check::positive("height_mm", self.height_mm)?;
        layers(self.layers, zone)?;
        self.check_load()
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        let zone = at.zone.downcast::<FacesZone>()?;
        body_bytes(zone.elements, self.layers.unwrap_or(zone.elements))
    }

    fn owns_surface(&self) -> bool {
        true
    }

    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::OwnLoad
    }

    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let zone = faces(at, Side::Above)?;
        let model = self.model(zone)?;
        let contact = model.mesh().faces_on_y(0.0, 0.0, zone.radius_mm);
        Ok(Box::new(FeBody::new(self.name(), model, &contact)?))
    }

    fn has_displacement_elements(&self) -> bool {
        true
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        None
    }

    /// The punch's face is the zone: contact at its rim is the punch's edge.
    fn ends_at_rim(&self) -> bool {
        true
    }

    /// Under a pressure on its top it floats; a displacement holds it.
    fn floats(&self) -> bool {
        matches!(self.load, PunchLoad::PressureMpa(_))
    }
}

impl FeBlock {
    /// The element boundaries along r and through the depth: the zone's faces, then 40
    /// growing out to the size from the zone's edge size (or from the 40th of the width
    /// outside the zone when that is less: a block little wider than its near-surface layer,
    /// as a base's [`FeBase::across`]); a near-surface layer of [`BLOCK_NEAR_RADII`] zone
    /// radii of square-ish elements, then 24 growing down to the clamped bottom.
    fn spacings(&self, zone: &FacesZone) -> Result<(Spacing, Spacing)> {
        let a = zone.radius_mm;
        let near_depth = BLOCK_NEAR_RADII * a;
        if !(self.size_mm > near_depth && self.size_mm.is_finite()) {
            return Err(Error::invalid(
                "size_mm",
                self.size_mm,
                format!("must be finite and exceed twice the zone's radius, {near_depth}"),
            ));
        }
        let h = zone.edge_size()?;
        let first = h.min((self.size_mm - a) / BLOCK_OUTER_ELEMENTS as f64);
        let across = zone.spacing()?.then(&Spacing::geometric_first(
            a,
            self.size_mm,
            BLOCK_OUTER_ELEMENTS,
            first,
        )?)?;
        let near = Spacing::uniform(
            -near_depth,
            0.0,
            2 * zone.elements.min(BLOCK_OUTER_ELEMENTS),
        )?;
        let depth = Spacing::geometric(
            -self.size_mm,
            -near_depth,
            BLOCK_DEPTH_ELEMENTS,
            (h / (self.size_mm / BLOCK_DEPTH_ELEMENTS as f64)).min(1.0),
        )?
        .then(&near)?;
        Ok((across, depth))
    }
}

impl BodyKind for FeBlock {
    fn name(&self) -> String {
        self.name.clone().unwrap_or_else(|| "block".into())
    }

    fn check(&self, at: &Placement) -> Result<()> {
        let zone = faces(at, Side::Below)?;
        self.spacings(zone).map(|_| ())
    }

    fn memory(&self, at: &Placement) -> Option<u64> {
        let zone = at.zone.downcast::<FacesZone>()?;
        let across = zone.elements.checked_add(BLOCK_OUTER_ELEMENTS)?;
        let depth = zone.elements.min(BLOCK_OUTER_ELEMENTS) * 2 + BLOCK_DEPTH_ELEMENTS;
        body_bytes(across, depth)
    }

    fn owns_surface(&self) -> bool {
        true
    }

    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        Takes::Nothing
    }

    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let zone = faces(at, Side::Below)?;
        let (across, depth) = self.spacings(zone)?;
        let mesh = Mesh::rectangle(zone.element, &across, &depth)?;
        let mut model = FeModel::new(mesh, self.material, zone.analysis)?;
        let bottom = model.mesh().nodes_on_y(-self.size_mm, 0.0, self.size_mm);
        model
            .fix(&bottom, Component::X)?
            .fix(&bottom, Component::Y)?;
        if zone.analysis != Analysis::Axisymmetric {
            hold_symmetry(&mut model, -self.size_mm, 0.0)?;
        }
        let contact = model.mesh().faces_on_y(0.0, 0.0, zone.radius_mm);
        Ok(Box::new(FeBody::new(self.name(), model, &contact)?))
    }

    fn has_displacement_elements(&self) -> bool {
        true
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    /// A half-space's (1 − ν²)/E (plane stress: 1/E), which the block stands in for.
    fn compliance(&self, zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        Some(half_space_compliance(self.material, &**zone))
    }
}
