//! Finite-element bodies built from a few dimensions: a punch on a base (the geometry of the
//! paper's Fig. 1, §4, with any dimensions, materials and supports) and a large block that
//! stands in for an elastic half-space.
//!
//! The paper's own numbers live in the bundled scenes (`paper-table1` … `paper-table3`);
//! [`PunchOnBase::bundled`] reads them from there.

use contopt_core::{Error, Material, Result};
use contopt_fem::{
    Analysis, Component, ElementKind, Face, FeBody, FeModel, Mesh, Spacing, MAX_AXIS_ELEMENTS,
};
use serde::{Deserialize, Serialize};

/// The fewest elements of the base outside the punch.
const MIN_OUTER_ELEMENTS: usize = 4;
/// The most elements of the base outside the punch (the memory estimate counts on it).
pub(crate) const MAX_OUTER_ELEMENTS: usize = 40;
/// Outside the punch the base has about 1/this of the elements a uniform mesh of edge-sized
/// elements would need (they grow from the edge size).
const OUTER_SPARSENESS: f64 = 4.0;
/// Elements of a half-space block outside its contact zone, growing outwards; its
/// near-surface layer has at most twice as many through its depth.
pub(crate) const BLOCK_OUTER_ELEMENTS: usize = 40;
/// Elements of a half-space block below its near-surface layer, growing with depth.
pub(crate) const BLOCK_DEPTH_ELEMENTS: usize = 24;
/// A cylinder standing on its axis (in a plane analysis: a rectangle of half-width `radius`,
/// the half x ≥ 0 of a body symmetric about x = 0).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    /// Radius (plane: half-width) \[mm\].
    pub radius: f64,
    /// Height \[mm\].
    pub height: f64,
    /// Material.
    pub material: Material,
}

/// A support of the base. The punch has none: it is held by the contact and its load (a
/// pressure floats it, eq. 2.10), and in a plane analysis on its symmetry line x = 0.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Support {
    /// The bottom face clamped: u_r = u_z = 0 (the paper's axisymmetric model).
    Clamped,
    /// The bottom face held axially only: u_z = 0, free radially (with `Symmetry`, the
    /// paper's plane-stress model).
    Axial,
    /// A plane model's symmetry line x = 0 held, u_x = 0: the base is the half x ≥ 0 of a
    /// symmetric body. An axisymmetric body is symmetric about its axis already.
    Symmetry,
}

/// How the punch is driven from its top face.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub enum PunchLoad {
    /// A uniform pressure \[MPa\] (Tables 1 and 3: 100 MPa); the punch floats on the base.
    #[serde(rename = "pressure_mpa")]
    Pressure(f64),
    /// A prescribed axial displacement of the top face \[mm\] (negative: downwards), radial
    /// motion free (Table 2: −0.05 mm).
    #[serde(rename = "displacement_mm")]
    Displacement(f64),
}

/// The mesh of both bodies: `elements` quadratic elements across the contact radius, graded
/// towards the punch edge so that the outermost is `grading` times smaller than the
/// innermost; the base continues outwards with elements growing from the edge size; each body
/// has `layers` elements through its height, graded towards the contact plane.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct PunchMesh {
    /// Elements across the contact radius.
    pub elements: usize,
    /// Elements through each body's height (`None`: as many as `elements`).
    #[serde(default)]
    pub layers: Option<usize>,
    /// Size ratio innermost / outermost contact element (1: uniform).
    #[serde(default = "uniform_grading")]
    pub grading: f64,
    /// The element: `"q8"` (default) or `"q9"`.
    #[serde(default = "serendipity")]
    pub element: ElementKind,
}

fn uniform_grading() -> f64 {
    1.0
}

fn serendipity() -> ElementKind {
    ElementKind::Q8
}

impl PunchMesh {
    /// `elements` uniform elements of kind `element` across the contact radius and as many
    /// layers through each body.
    pub fn uniform(element: ElementKind, elements: usize) -> Self {
        Self {
            elements,
            layers: None,
            grading: uniform_grading(),
            element,
        }
    }

    /// Elements through each body's height.
    pub fn layers(&self) -> usize {
        self.layers.unwrap_or(self.elements)
    }

    /// Refuses counts and a grading the mesh cannot have, before anything is allocated.
    pub fn check(&self) -> Result<()> {
        for (field, n) in [
            ("mesh.elements", self.elements),
            ("mesh.layers", self.layers()),
        ] {
            if n == 0 || n > MAX_AXIS_ELEMENTS {
                return Err(Error::invalid(
                    field,
                    n,
                    format!("must lie in 1 ..= {MAX_AXIS_ELEMENTS}"),
                ));
            }
        }
        if !(self.grading > 0.0 && self.grading.is_finite()) {
            return Err(Error::invalid(
                "mesh.grading",
                self.grading,
                "must be positive and finite",
            ));
        }
        Ok(())
    }

    /// The element boundaries across a contact radius `radius`.
    fn contact(&self, radius: f64) -> Result<Spacing> {
        self.check()?;
        Spacing::geometric(0.0, radius, self.elements, 1.0 / self.grading)
    }

    /// Size of the contact elements next to the punch edge of radius `radius` \[mm\].
    pub fn edge_size(&self, radius: f64) -> Result<f64> {
        let s = self.contact(radius)?;
        let c = s.coords();
        Ok(c[c.len() - 1] - c[c.len() - 2])
    }
}

/// A punch on a base (Fig. 1): two cylinders (plane: rectangles) in frictionless contact over
/// the punch's face 0 ≤ r ≤ R with zero initial gap, the punch driven from its top face.
#[derive(Clone, Debug, PartialEq)]
pub struct PunchOnBase {
    /// The analysis: axisymmetric about the y axis, or a plane half model x ≥ 0.
    pub analysis: Analysis,
    /// The upper body; its radius R is the contact zone's.
    pub punch: Cylinder,
    /// The lower body, wider than the punch; its upward normal is the reference n¹.
    pub base: Cylinder,
    /// How the base is held: one of [`Support::Clamped`] and [`Support::Axial`] for its
    /// bottom face, and [`Support::Symmetry`] in a plane analysis.
    pub supports: Vec<Support>,
    /// The punch's load.
    pub load: PunchLoad,
    /// The mesh.
    pub mesh: PunchMesh,
}

/// The element boundaries of a punch on a base.
struct Spacings {
    /// Across both bodies, from the axis to the base's rim.
    x: Spacing,
    /// Through the base's height.
    base_y: Spacing,
    /// Through the punch's height.
    punch_y: Spacing,
}

impl PunchOnBase {
    /// The punch on its base of the bundled scene `name` (`paper-table1`: the paper's
    /// axisymmetric model of Table 1; `paper-table2`: its displacement load; `paper-table3`:
    /// the plane-stress model).
    pub fn bundled(name: &str) -> std::result::Result<Self, crate::SceneError> {
        let scene = crate::Scene::bundled(name)?;
        let crate::Problem::PunchOnBase(spec) = &scene.spec.problem else {
            return Err(crate::SceneError::Parse {
                file: scene.file,
                message: format!("the bundled scene {name:?} is not a punch_on_base"),
            });
        };
        spec.geometry().map_err(|e| crate::SceneError::Invalid {
            file: scene.file.clone(),
            line: None,
            case: String::new(),
            key: "problem".into(),
            source: Box::new(e),
        })
    }

    /// Checks the dimensions, supports, load and mesh without building anything.
    pub fn check(&self) -> Result<()> {
        self.spacings().map(|_| ())
    }

    /// Size of the contact elements next to the punch edge \[mm\].
    pub fn edge_size(&self) -> Result<f64> {
        self.mesh.edge_size(self.punch.radius)
    }

    /// The two bodies, base first (its upward normal is the reference n¹): assembled,
    /// factorised and condensed to the contact face (§2.2).
    pub fn bodies(&self) -> Result<(FeBody, FeBody)> {
        let (base, base_contact) = self.base_model()?;
        let (punch, punch_contact) = self.punch_model()?;
        Ok((
            FeBody::new("base", base, &base_contact)?,
            FeBody::new("punch", punch, &punch_contact)?,
        ))
    }

    /// The base's model with its supports, and its contact faces (to add loads or supports of
    /// one's own before [`FeBody::new`]).
    pub fn base_model(&self) -> Result<(FeModel, Vec<Face>)> {
        let (lower, _) = self.meshes()?;
        let (radius, height) = (self.base.radius, self.base.height);
        let mut base = FeModel::new(lower, self.base.material, self.analysis)?;
        let bottom = base.mesh().nodes_on_y(0.0, 0.0, radius);
        for support in &self.supports {
            match support {
                Support::Clamped => {
                    base.fix(&bottom, Component::X)?
                        .fix(&bottom, Component::Y)?;
                }
                Support::Axial => {
                    base.fix(&bottom, Component::Y)?;
                }
                Support::Symmetry => {
                    let axis = base.mesh().nodes_on_x(0.0, 0.0, height);
                    base.fix(&axis, Component::X)?;
                }
            }
        }
        let contact = base.mesh().faces_on_y(height, 0.0, self.punch.radius);
        Ok((base, contact))
    }

    /// The punch's model with its load (and in a plane analysis its symmetry line held), and
    /// its contact faces.
    pub fn punch_model(&self) -> Result<(FeModel, Vec<Face>)> {
        let (_, upper) = self.meshes()?;
        let (radius, bottom) = (self.punch.radius, self.base.height);
        let top = bottom + self.punch.height;
        let mut punch = FeModel::new(upper, self.punch.material, self.analysis)?;
        if self.analysis != Analysis::Axisymmetric {
            let axis = punch.mesh().nodes_on_x(0.0, bottom, top);
            punch.fix(&axis, Component::X)?;
        }
        match self.load {
            PunchLoad::Pressure(p) => {
                let faces = punch.mesh().faces_on_y(top, 0.0, radius);
                punch.pressure(&faces, p)?;
            }
            PunchLoad::Displacement(w) => {
                let nodes = punch.mesh().nodes_on_y(top, 0.0, radius);
                punch.prescribe(&nodes, Component::Y, w)?;
            }
        }
        let contact = punch.mesh().faces_on_y(bottom, 0.0, radius);
        Ok((punch, contact))
    }

    /// The meshes of the base and the punch, whose contact nodes coincide.
    fn meshes(&self) -> Result<(Mesh, Mesh)> {
        let s = self.spacings()?;
        Mesh::stacked(
            self.mesh.element,
            &s.x,
            &s.base_y,
            (0.0, self.punch.radius),
            &s.punch_y,
        )
    }

    /// The element boundaries, after checking every input.
    fn spacings(&self) -> Result<Spacings> {
        self.check_dimensions()?;
        self.check_supports()?;
        self.check_load()?;
        let (radius, base_radius) = (self.punch.radius, self.base.radius);
        let contact = self.mesh.contact(radius)?;
        let edge = self.mesh.edge_size(radius)?;
        // Outside the punch the base's elements grow from the edge size.
        let width = base_radius - radius;
        let outer = ((width / (OUTER_SPARSENESS * edge)).ceil() as usize)
            .clamp(MIN_OUTER_ELEMENTS, MAX_OUTER_ELEMENTS);
        let first = edge.min(width / outer as f64);
        let x = contact.then(&Spacing::geometric_first(
            radius,
            base_radius,
            outer,
            first,
        )?)?;
        // Each body's layers shrink towards the contact plane to at most the edge size.
        let layers = self.mesh.layers();
        let ratio = |height: f64| (height / layers as f64 / edge).max(1.0);
        let (hb, hp) = (self.base.height, self.punch.height);
        let base_y = Spacing::geometric(0.0, hb, layers, 1.0 / ratio(hb))?;
        let punch_y = Spacing::geometric(hb, hb + hp, layers, ratio(hp))?;
        Ok(Spacings { x, base_y, punch_y })
    }

    fn check_dimensions(&self) -> Result<()> {
        for (field, value) in [
            ("punch.radius_mm", self.punch.radius),
            ("punch.height_mm", self.punch.height),
            ("base.height_mm", self.base.height),
            ("base.radius_mm", self.base.radius),
        ] {
            if !(value > 0.0 && value.is_finite()) {
                return Err(Error::invalid(field, value, "must be positive and finite"));
            }
        }
        if self.base.radius <= self.punch.radius {
            return Err(Error::invalid(
                "base.radius_mm",
                self.base.radius,
                format!(
                    "must exceed the punch's radius {} (the base carries the whole punch)",
                    self.punch.radius
                ),
            ));
        }
        if let Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } =
            self.analysis
        {
            if !(thickness > 0.0 && thickness.is_finite()) {
                return Err(Error::invalid(
                    "analysis.thickness_mm",
                    thickness,
                    "must be positive and finite",
                ));
            }
        }
        Ok(())
    }

    /// One support of the bottom face; symmetry in a plane analysis only; nothing twice; a
    /// plane base held axially needs its symmetry line, or it slides sideways (a rigid mode
    /// that no contact pressure resists).
    fn check_supports(&self) -> Result<()> {
        let field = "base.supports";
        let named = |s: &[Support]| format!("{s:?}").to_lowercase();
        let count = |s: Support| self.supports.iter().filter(|&&t| t == s).count();
        let bottom = count(Support::Clamped) + count(Support::Axial);
        if bottom != 1 {
            return Err(Error::invalid(
                field,
                named(&self.supports),
                "name one support of the bottom face: \"clamped\" or \"axial\"",
            ));
        }
        let symmetry = count(Support::Symmetry);
        let plane = self.analysis != Analysis::Axisymmetric;
        if symmetry > 1 || (symmetry == 1 && !plane) {
            return Err(Error::invalid(
                field,
                named(&self.supports),
                "\"symmetry\" holds a plane model's line x = 0, once (an axisymmetric body is \
                 symmetric about its axis already)",
            ));
        }
        if plane && symmetry == 0 && count(Support::Axial) == 1 {
            return Err(Error::invalid(
                field,
                named(&self.supports),
                "a plane base held axially slides sideways: add \"symmetry\" (the half model \
                 x ≥ 0) or clamp it",
            ));
        }
        Ok(())
    }

    /// A pressure presses the floating punch onto the base (eq. 2.10 needs a compressive
    /// resultant); a displacement is finite.
    fn check_load(&self) -> Result<()> {
        match self.load {
            PunchLoad::Pressure(p) if !p.is_finite() => {
                Err(Error::invalid("load.pressure_mpa", p, "must be finite"))
            }
            PunchLoad::Pressure(p) if p < 0.0 => Err(Error::invalid(
                "load.pressure_mpa",
                p,
                "pulls the bodies apart: compressive contact cannot carry it",
            )),
            PunchLoad::Pressure(p) if p == 0.0 => Err(Error::invalid(
                "load.pressure_mpa",
                p,
                "is zero: the floating punch is not pressed into contact",
            )),
            PunchLoad::Displacement(w) if !w.is_finite() => {
                Err(Error::invalid("load.displacement_mm", w, "must be finite"))
            }
            _ => Ok(()),
        }
    }
}

/// An axisymmetric Q8 block of radius and depth `size`, clamped at its bottom (y = −`size`),
/// with its top face at y = 0: a stand-in for an elastic half-space. The contact zone
/// r < `zone` carries `zone_elements` uniform elements; outside it the elements grow
/// geometrically from that size (40 of them), and a layer of depth 2·`zone` under the surface
/// is meshed with square-ish elements before the depth grading starts. Returns the model and
/// the contact zone's faces, ordered by r.
pub fn half_space_block(
    zone: f64,
    zone_elements: usize,
    size: f64,
    material: Material,
) -> Result<(FeModel, Vec<Face>)> {
    let (r, z) = block_spacings(zone, zone_elements, size)?;
    let mut model = FeModel::new(
        Mesh::rectangle(ElementKind::Q8, &r, &z)?,
        material,
        Analysis::Axisymmetric,
    )?;
    let bottom = model.mesh().nodes_on_y(-size, 0.0, size);
    model
        .fix(&bottom, Component::X)?
        .fix(&bottom, Component::Y)?;
    let contact = model.mesh().faces_on_y(0.0, 0.0, zone);
    Ok((model, contact))
}

/// The element boundaries of [`half_space_block`] along r and along y, after checking its
/// numbers (nothing of the mesh's size is allocated first).
pub(crate) fn block_spacings(
    zone: f64,
    zone_elements: usize,
    size: f64,
) -> Result<(Spacing, Spacing)> {
    if !(zone > 0.0 && zone.is_finite()) {
        return Err(Error::invalid(
            "block.zone",
            zone,
            "must be positive and finite",
        ));
    }
    if zone_elements == 0 || zone_elements > MAX_AXIS_ELEMENTS {
        return Err(Error::invalid(
            "block.elements",
            zone_elements,
            format!("must lie in 1 ..= {MAX_AXIS_ELEMENTS}"),
        ));
    }
    if !(size > 2.0 * zone && size.is_finite()) {
        return Err(Error::invalid(
            "block.size",
            size,
            format!("must be finite and exceed twice the zone, {}", 2.0 * zone),
        ));
    }
    let h = zone / zone_elements as f64;
    let r = Spacing::uniform(0.0, zone, zone_elements)?.then(&Spacing::geometric_first(
        zone,
        size,
        BLOCK_OUTER_ELEMENTS,
        h,
    )?)?;
    let near = Spacing::uniform(
        -2.0 * zone,
        0.0,
        2 * zone_elements.min(BLOCK_OUTER_ELEMENTS),
    )?;
    let z = Spacing::geometric(
        -size,
        -2.0 * zone,
        BLOCK_DEPTH_ELEMENTS,
        (h / (size / BLOCK_DEPTH_ELEMENTS as f64)).min(1.0),
    )?
    .then(&near)?;
    Ok((r, z))
}
