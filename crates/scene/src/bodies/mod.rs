//! The body kinds of a scene (`[[body]]`). Each kind is one file with a type that implements
//! [`BodyKind`], registered by its name in a [`crate::Registry`]; every question the scene asks
//! of a body it asks of its kind, so that a kind of one's own (in one's own crate) answers
//! them all.
//!
//! A body is built on the scene's contact zone, on one side of it: the first body below (its
//! outward normal is n¹ of eq. 2.1), the second above. Kinds that mesh or grid their own
//! surface (finite elements, half-spaces) build it from the zone; the others (a rigid body, a
//! Winkler bed) take the zone's surface, or their partner's on finite-element faces. An
//! imported body (`fe_mesh`) brings its own mesh and offers its model to a zone of imported
//! meshes, which pairs two of them before either is condensed ([`BodyKind::part`]). A solid
//! (`solid`) brings its own 3-D mesh and stands on a grid, read at its cells; with a measured
//! gap it supplies its face's shape ([`BodyKind::face_shape`]), so that two solids meshed
//! apart meet on one grid.

mod fe;
mod fe_mesh;
mod half_space;
mod held;
mod rigid;
mod solid;
mod winkler;

use std::path::Path;

use crate::chosen::Chosen;
use crate::load::LoadSpec;
use crate::mesh_surface::MeshPart;
use crate::meshes::MeshFiles;
use crate::zone::{Layout, ZoneKind};
use contopt_core::{ElasticBody, Error, Interface, Material, Result};
use contopt_fem::Analysis;

pub use fe::{FeBase, FeBlock, FePunch, PunchLoad, Support};
pub use fe_mesh::{Direction, FeMesh, GroupLoad, GroupSupport};
pub use half_space::{FreeEndsSpec, HalfSpaceBody};
pub use rigid::Rigid;
pub use solid::{Solid, SolidAxis, SolidLoad, SolidSupport};
pub use winkler::WinklerBed;

/// The pressures a body carries over the zone's points ([`BodyKind::carried_pressures`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Carried {
    /// The points whose read-out is a combination of the points' before them (in the zone's
    /// order): the rank of the body's influence is the points' count less theirs. Empty when
    /// every point carries its own pressure.
    pub dependent: Vec<usize>,
    /// The box of the dependent points' centres, [low, high] (x, y) \[mm\] (empty, low
    /// above high, when none are).
    pub region_mm: [[f64; 2]; 2],
    /// The zone's points whose centres lie in that box (none when it is empty).
    pub region_points: usize,
    /// The face nodes those points are read from.
    pub region_nodes: usize,
}

/// Which side of the zone a body is on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Side {
    /// The first body: its outward normal is the reference n¹.
    Below,
    /// The second body, which a contact force presses.
    Above,
}

/// How a body takes the load of the contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Takes {
    /// It floats under a contact force along the normal (a rigid indenter, a half-space grid).
    Force,
    /// It carries loads of its own and takes none through the contact (a finite-element punch).
    OwnLoad,
    /// It is held: a contact force cannot press it (a bed, the rings of a half-space).
    Nothing,
}

/// Where a body is built: the zone, its sizes, the side, the contact's load, and the folder
/// the scene's files are read from.
pub struct Placement<'a> {
    /// The body's kind, as the scene named it (for messages).
    pub kind: &'a str,
    /// The zone as the scene chose it: a body that needs a particular zone asks for it by
    /// type ([`Chosen::downcast`]).
    pub zone: &'a Chosen<dyn ZoneKind>,
    /// The zone with every size known.
    pub layout: &'a Layout,
    /// The side of the zone.
    pub side: Side,
    /// The contact's load (it presses the body above).
    pub load: LoadSpec,
    /// The scene file's folder.
    pub dir: &'a Path,
    /// The mesh files the scene's bodies read.
    pub meshes: &'a MeshFiles,
    /// The scene's memory limit (`memory_limit_mb`) \[bytes\]: what a body that learns its
    /// size only while it is built (a solid's factor) checks itself against.
    pub memory_limit_bytes: u64,
    /// Whether the gap is measured between the bodies' faces (`contact.gap = { kind =
    /// "measured" }`): a body that brings a face of its own then lies where its mesh puts it,
    /// and its face's shape is counted in the gap ([`BodyKind::face_shape`]); otherwise its
    /// face lies on the zone's surface and the gap kind describes the shapes.
    pub measured: bool,
}

/// What a body kind does: check itself on a zone without building anything, estimate its
/// memory, build its [`ElasticBody`], and answer what the scene asks of a body. Its name is the
/// one it is registered under ([`crate::Registry::with_body`]).
pub trait BodyKind: Send + Sync {
    /// The body's name in reports: its own `name`, or the kind's.
    fn name(&self) -> String;

    /// Refuses a zone, a side or values the body cannot have, without building it.
    fn check(&self, at: &Placement) -> Result<()>;

    /// The memory the built body holds \[bytes\], `None` when the count overflows.
    fn memory(&self, at: &Placement) -> Option<u64>;

    /// Whether it meshes or grids its own surface from the zone; otherwise it is built on the
    /// surface it is given (the zone's, or its partner's).
    fn owns_surface(&self) -> bool;

    /// How it takes the contact's load on `zone`.
    fn takes(&self, zone: &Chosen<dyn ZoneKind>) -> Takes;

    /// Builds the body. A kind that does not own its surface is built on `surface`: the zone's
    /// surface as the body below sees it (outward normal n¹), which a body above mirrors.
    fn build(&self, at: &Placement, surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>>;

    /// Its material, when it has one (default none).
    fn material(&self) -> Option<Material> {
        None
    }

    /// Its share of the pair's contact compliance 1/E* on this zone \[1/MPa\]: (1 − ν²)/E for
    /// a half-space or a block standing in for one, 1/E for a half-plane in plane stress, 0 for
    /// a rigid body; `None` (the default) for a body whose compliance Hertz does not describe
    /// (a punch, a bed).
    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        None
    }

    /// Whether its surface ends at the zone's rim (a punch's face is the zone): contact there
    /// is the body's edge, not the zone's limit.
    fn ends_at_rim(&self) -> bool {
        false
    }

    /// For a zone of imported meshes, the body's model (supported and loaded) and its contact
    /// faces, from the scene's `meshes` under `analysis`, nothing assembled: the zone pairs
    /// two such bodies before either is condensed, since the second is sampled where the
    /// first body's normals meet it. `None` for the kinds that mesh a zone or stand on one.
    fn part(&self, _meshes: &MeshFiles, _analysis: Analysis) -> Option<Result<MeshPart>> {
        None
    }

    /// Where its contact face lies, as meshed, at each of the zone's points: its distance from
    /// the zone's surface along the body's outward normal, positive away from the partner
    /// \[mm\]. A measured gap on a zone that defines its own surface (a grid) is the sum of
    /// the two bodies' face shapes (eq. 2.1: the distance between the faces along n¹), so that
    /// a kind that brings its face (a solid whose contact face is curved) supplies its shape,
    /// and its partner's face is the zone's surface or its own. `None` (the default) for a
    /// body whose face is the zone's surface (a half-space, a rigid body, a bed) and for any
    /// body when the gap is not measured ([`Placement::measured`]); checked without building
    /// anything.
    fn face_shape(&self, _at: &Placement) -> Option<Result<Vec<f64>>> {
        None
    }

    /// Which of the zone's points carry no pressure of their own: a body read as means over
    /// its faces (a solid, [`SolidBody`](contopt_fem::solid::SolidBody)) has the influence
    /// C = S K⁻¹ Sᵀ, S the points' read-out of its face nodes, singular wherever the points'
    /// rows of S are dependent (cells finer than the faces under them, anywhere on the face),
    /// and against a rigid partner the pressure there is then not determined. `None` (the
    /// default): a body whose influence is definite, every point its own. Checked without
    /// building anything.
    fn carried_pressures(&self, _at: &Placement) -> Option<Result<Carried>> {
        None
    }

    /// Whether it brings a mesh of its own, which a zone of imported meshes pairs
    /// ([`BodyKind::part`]).
    fn imported(&self) -> bool {
        false
    }

    /// Whether it floats under a load of its own: a rigid mode that the contact's equilibrium
    /// holds (a punch under a pressure; eq. 2.10).
    fn floats(&self) -> bool {
        false
    }

    /// Whether it is a half-space itself, by its Green's functions (not a block standing in
    /// for one): a roller gap pairs two of them, and Sneddon's approach holds on it.
    fn is_half_space(&self) -> bool {
        false
    }

    /// Whether it is built of displacement finite elements, which lock as ν → 0.5
    /// ([`contopt_fem::locking_warning`]; default no).
    fn has_displacement_elements(&self) -> bool {
        false
    }

    /// Whether its surface ends free across x (a roller's free ends), so that the stresses
    /// below it are its own, not its partner's.
    fn free_ends(&self) -> bool {
        false
    }
}

/// The side's name in messages.
pub fn side_name(side: Side) -> &'static str {
    match side {
        Side::Below => "the first body (below the zone)",
        Side::Above => "the second body (above the zone)",
    }
}

/// A kind refused on a side or a zone, with what it needs.
pub fn misplaced(at: &Placement, needs: &str) -> Error {
    Error::invalid(
        "kind",
        at.kind,
        format!(
            "cannot be {} on {}: {needs}",
            side_name(at.side),
            at.zone.name()
        ),
    )
}

/// A half-space's share of the pair's compliance on `zone` (or a block's standing in for one):
/// 1/E in plane stress, else (1 − ν²)/E.
fn half_space_compliance(material: Material, zone: &dyn ZoneKind) -> f64 {
    match zone.analysis() {
        Some(Analysis::PlaneStress { .. }) => 1.0 / material.e(),
        _ => material.contact_compliance(),
    }
}

/// The surface a body that does not own one stands on: `surface` (the zone's, as the body
/// below sees it) for the body below, mirrored for the body above; an error when none was
/// given.
pub fn own_surface(at: &Placement, surface: Option<&Interface>) -> Result<Interface> {
    let surface = surface.ok_or_else(|| {
        Error::invalid(
            "kind",
            at.kind,
            "needs a surface to stand on: the zone's, or a finite-element partner's",
        )
    })?;
    Ok(match at.side {
        Side::Below => surface.clone(),
        Side::Above => surface.mirrored(),
    })
}
