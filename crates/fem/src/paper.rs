//! The bodies of the paper's examples (§4, Fig. 1), with the geometry of DESIGN §4
//! (recovered from the paper's own tables): a punch of radius 50 mm and height 50 mm on a base
//! of radius 100 mm and height 50 mm, both steel (E = 2·10⁵ MPa, ν = 0.3), in frictionless
//! contact over 0 ≤ r ≤ 50 mm with zero initial gap.

use contopt_core::Result;

use crate::{Analysis, Component, ElementKind, FeBody, FeModel, Material, Mesh, Spacing};

/// Punch radius R = L₂ \[mm\].
pub const PUNCH_RADIUS: f64 = 50.0;
/// Height of each body \[mm\].
pub const HEIGHT: f64 = 50.0;
/// Base radius (or plane half-width) \[mm\].
pub const BASE_RADIUS: f64 = 100.0;
/// Young's modulus \[MPa\].
pub const E: f64 = 2.0e5;
/// Poisson's ratio.
pub const NU: f64 = 0.3;

/// How the punch is driven from its top face.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PunchLoad {
    /// A uniform pressure \[MPa\] (Tables 1 and 3: 100 MPa); the punch floats on the base.
    Pressure(f64),
    /// A prescribed axial displacement of the top face \[mm\], radial motion free
    /// (Table 2: −0.05 mm).
    Displacement(f64),
}

/// The mesh of both bodies: `contact_elements` quadratic elements across the contact radius,
/// graded towards the punch edge so that the outermost is `grading` times smaller than the
/// innermost; the base continues outwards with elements growing from the edge size; each body
/// has `layers` elements through its height, graded towards the contact plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PaperMesh {
    /// Element type.
    pub kind: ElementKind,
    /// Elements across 0 ≤ r ≤ 50 mm.
    pub contact_elements: usize,
    /// Size ratio innermost / outermost contact element (1 = uniform).
    pub grading: f64,
    /// Elements through each body's height.
    pub layers: usize,
}

impl Default for PaperMesh {
    /// 18 uniform Q8 elements across the contact radius (edge elements 2.8 mm, which DESIGN §4
    /// identifies as the probable mesh of the paper) and 18 layers per body.
    fn default() -> Self {
        Self {
            kind: ElementKind::Q8,
            contact_elements: 18,
            grading: 1.0,
            layers: 18,
        }
    }
}

impl PaperMesh {
    /// Size of the contact elements next to the punch edge \[mm\].
    pub fn edge_size(&self) -> Result<f64> {
        self.edge_size_over(PUNCH_RADIUS)
    }

    fn edge_size_over(&self, radius: f64) -> Result<f64> {
        let s = self.radial_contact(radius)?;
        let c = s.coords();
        Ok(c[c.len() - 1] - c[c.len() - 2])
    }

    fn radial_contact(&self, radius: f64) -> Result<Spacing> {
        Spacing::geometric(0.0, radius, self.contact_elements, 1.0 / self.grading)
    }
}

/// The two bodies, base first (its upward normal is the reference n¹), for an analysis.
///
/// Supports as DESIGN §4 found them: axisymmetric — the base's bottom clamped; plane stress
/// (thickness 10 mm, half model) — u_x = 0 on the symmetry line of both bodies and the base's
/// bottom held vertically only.
pub fn bodies(analysis: Analysis, load: PunchLoad, mesh: &PaperMesh) -> Result<(FeBody, FeBody)> {
    bodies_with(&PunchGeometry::default(), analysis, load, mesh)
}

/// The dimensions and materials of a punch on a base (Fig. 1).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PunchGeometry {
    /// Punch radius (plane: half-width) \[mm\]: the contact zone.
    pub punch_radius: f64,
    /// Height of each body \[mm\].
    pub height: f64,
    /// Base radius (plane: half-width) \[mm\], larger than the punch's.
    pub base_radius: f64,
    /// Material of the punch.
    pub punch: Material,
    /// Material of the base.
    pub base: Material,
}

impl Default for PunchGeometry {
    /// The paper's: R = 50 mm, heights 50 mm, base radius 100 mm, both steel.
    fn default() -> Self {
        let steel = Material::new(E, NU).expect("the paper's steel is a valid material");
        Self {
            punch_radius: PUNCH_RADIUS,
            height: HEIGHT,
            base_radius: BASE_RADIUS,
            punch: steel,
            base: steel,
        }
    }
}

/// The two bodies of [`bodies`] with other dimensions and materials.
pub fn bodies_with(
    geometry: &PunchGeometry,
    analysis: Analysis,
    load: PunchLoad,
    mesh: &PaperMesh,
) -> Result<(FeBody, FeBody)> {
    let &PunchGeometry {
        punch_radius,
        height,
        base_radius,
        ..
    } = geometry;
    for (field, value) in [
        ("punch_radius", punch_radius),
        ("height", height),
        ("base_radius - punch_radius", base_radius - punch_radius),
    ] {
        if !(value > 0.0 && value.is_finite()) {
            return Err(contopt_core::Error::invalid(
                format!("geometry.{field}"),
                value,
                "must be positive and finite",
            ));
        }
    }
    let contact = mesh.radial_contact(punch_radius)?;
    let edge = mesh.edge_size_over(punch_radius)?;
    // Outside the punch the base's elements grow from the edge size: about a quarter as
    // many as a uniform mesh of edge-sized elements would need, between 4 and 40.
    let width = base_radius - punch_radius;
    let outer_elements = ((width / (4.0 * edge)).ceil() as usize).clamp(4, 40);
    let first = edge.min(width / outer_elements as f64);
    let outer = Spacing::geometric_first(punch_radius, base_radius, outer_elements, first)?;
    let x = contact.then(&outer)?;
    let ratio = (height / mesh.layers as f64 / edge).max(1.0);
    let base_y = Spacing::geometric(0.0, height, mesh.layers, 1.0 / ratio)?;
    let punch_y = Spacing::geometric(height, 2.0 * height, mesh.layers, ratio)?;
    let (lower, upper) = Mesh::stacked(mesh.kind, &x, &base_y, (0.0, punch_radius), &punch_y)?;
    let mut base = FeModel::new(lower, geometry.base, analysis)?;
    let bottom = base.mesh().nodes_on_y(0.0, 0.0, base_radius);
    base.fix(&bottom, Component::Y)?;
    if analysis == Analysis::Axisymmetric {
        base.fix(&bottom, Component::X)?;
    } else {
        let axis = base.mesh().nodes_on_x(0.0, 0.0, height);
        base.fix(&axis, Component::X)?;
    }
    let base_contact = base.mesh().faces_on_y(height, 0.0, punch_radius);

    let mut punch = FeModel::new(upper, geometry.punch, analysis)?;
    if analysis != Analysis::Axisymmetric {
        let axis = punch.mesh().nodes_on_x(0.0, height, 2.0 * height);
        punch.fix(&axis, Component::X)?;
    }
    let top = 2.0 * height;
    match load {
        PunchLoad::Pressure(p) => {
            let faces = punch.mesh().faces_on_y(top, 0.0, punch_radius);
            punch.pressure(&faces, p)?;
        }
        PunchLoad::Displacement(w) => {
            let nodes = punch.mesh().nodes_on_y(top, 0.0, punch_radius);
            punch.prescribe(&nodes, Component::Y, w)?;
        }
    }
    let punch_contact = punch.mesh().faces_on_y(height, 0.0, punch_radius);
    Ok((
        FeBody::new("base", base, &base_contact)?,
        FeBody::new("punch", punch, &punch_contact)?,
    ))
}
