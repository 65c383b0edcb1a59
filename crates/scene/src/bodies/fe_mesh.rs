//! A finite-element body of one's own, read from a Gmsh mesh (`kind = "fe_mesh"`): a punch
//! with an edge radius, a hub, a seal, meshed in Gmsh with named physical groups for its
//! surface, its contact face, its supports and its loads. It stands on a zone of imported
//! meshes ([`crate::mesh_zone`]), either side; two of them are paired there segment to
//! segment, a rigid body or a bed stands on its contact faces.
//!
//! Everything the scene names is checked when the scene is read, nothing assembled: the file
//! (a relative path from the scene's folder, [`crate::meshes`]), each group (present, not
//! empty, of the right dimension, on this body: Gmsh's import refuses a group's line that is
//! not a boundary face of the body), the extent against the size the scene states (a mesh
//! drawn in metres is 1000 times too small), the analysis against the mesh (no node at r < 0
//! in axisymmetry), and the supports against the contact: a rigid motion the supports leave
//! free must move the contact faces along their normals, or no frictionless contact can hold
//! it; one that does must be pressed by the body's loads, not pulled away.

use contopt_core::{check, ElasticBody, Error, Interface, Material, Result, GEOMETRY_TOLERANCE};
use contopt_fem::{mesh_bytes, pairing::mortar_bytes, Analysis, Component, FeBody, FeModel};
use serde::{Deserialize, Serialize};

use super::held::{self, Holding};
use super::{misplaced, BodyKind, Placement, Side, Takes};
use crate::chosen::Chosen;
use crate::mesh_surface::MeshPart;
use crate::meshes::{Imported, MeshFiles};
use crate::zone::{Layout, MeshZone, ZoneKind};

/// The mesh's bounding box must agree with the extent the scene states to this fraction: a
/// units check (metres, inches, centimetres are off by 10 or more) that allows a rounded size.
const EXTENT_TOLERANCE: f64 = 0.01;

/// A direction of the plane: x (r in axisymmetry) or y (z).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Direction {
    /// x, or the radial direction r.
    X,
    /// y, or the axial direction z.
    Y,
}

impl Direction {
    fn component(self) -> Component {
        match self {
            Direction::X => Component::X,
            Direction::Y => Component::Y,
        }
    }
}

/// A support: the nodes of a group of points or curves held along `fix`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupSupport {
    /// The physical group (points or curves).
    pub group: String,
    /// The directions held: `["x"]` (a symmetry line x = 0), `["y"]`, or both (clamped).
    pub fix: Vec<Direction>,
}

/// A load on a group: a pressure or a traction on a group of curves, or a displacement of a
/// group's nodes; exactly one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroupLoad {
    /// The physical group: curves for a pressure or a traction, points or curves for a
    /// displacement.
    pub group: String,
    /// A uniform pressure \[MPa\], positive into the body.
    #[serde(default)]
    pub pressure_mpa: Option<f64>,
    /// A uniform traction (t_x, t_y) \[MPa\].
    #[serde(default)]
    pub traction_mpa: Option<[f64; 2]>,
    /// A prescribed displacement of the group's nodes \[mm\] along `along`, free across it.
    #[serde(default)]
    pub displacement_mm: Option<f64>,
    /// The direction of a displacement (default `"y"`).
    #[serde(default)]
    pub along: Option<Direction>,
}

/// A finite-element body read from a Gmsh mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FeMesh {
    /// Its name in reports (default: its surface group, else the file's name).
    #[serde(default)]
    pub name: Option<String>,
    /// The Gmsh file (MSH 4.1), relative to the scene's folder.
    pub mesh: String,
    /// The 2-D physical group of its elements (default: every surface of the file).
    #[serde(default)]
    pub surface: Option<String>,
    /// The 1-D physical group of its contact face: a chain of element edges.
    pub contact: String,
    /// The size of the part [width, height] \[mm\] as the user knows it: the mesh's bounding
    /// box must agree within 1 % (Gmsh has no units).
    pub extent_mm: [f64; 2],
    /// The material.
    pub material: Material,
    /// Its supports (default none: it floats).
    #[serde(default)]
    pub supports: Vec<GroupSupport>,
    /// Its loads (default none).
    #[serde(default)]
    pub loads: Vec<GroupLoad>,
}

impl FeMesh {
    /// Its loads as a scene writes them, for messages: each group and its value.
    fn loads_named(&self) -> String {
        let named: Vec<String> = (self.loads.iter())
            .map(|l| {
                let value = match (l.pressure_mpa, l.traction_mpa, l.displacement_mm) {
                    (Some(p), _, _) => format!("pressure_mpa = {p}"),
                    (_, Some([tx, ty]), _) => format!("traction_mpa = [{tx}, {ty}]"),
                    (_, _, Some(d)) => format!("displacement_mm = {d}"),
                    _ => "no value".into(),
                };
                format!("{{ group = \"{}\", {value} }}", l.group)
            })
            .collect();
        format!("[{}]", named.join(", "))
    }

    /// The zone's analysis, or why the body cannot stand on the zone.
    fn analysis(&self, at: &Placement) -> Result<Analysis> {
        let mesh = at.zone.downcast::<MeshZone>().ok_or_else(|| {
            misplaced(
                at,
                "an imported body stands on a zone of imported meshes: contact.zone = { kind = \
                 \"mesh\", analysis = … }",
            )
        })?;
        Ok(mesh.analysis)
    }

    /// The model and contact faces, every named group checked.
    fn import(&self, meshes: &MeshFiles, analysis: Analysis) -> Result<MeshPart> {
        check::all_positive("extent_mm", &self.extent_mm)?;
        let imported = meshes
            .import(&self.mesh, self.surface.as_deref())
            .map_err(|e| self.placed(e))?;
        let body = &imported.mesh;
        body.check_extent(self.extent_mm, EXTENT_TOLERANCE)
            .map_err(|e| at_key("extent_mm", format!("{:?}", self.extent_mm), e))?;
        if analysis == Analysis::Axisymmetric {
            self.check_radii(&imported)?;
        }
        let contact = faces(&imported, "contact", &self.contact)?.to_vec();
        let mut model = FeModel::new(body.mesh.clone(), self.material, analysis)?;
        for (i, support) in self.supports.iter().enumerate() {
            let key = format!("supports[{i}]");
            let nodes = nodes(&imported, &format!("{key}.group"), &support.group)?;
            if support.fix.is_empty() {
                return Err(Error::invalid(
                    format!("{key}.fix"),
                    "[]",
                    "name the directions held: [\"x\"], [\"y\"] or [\"x\", \"y\"]",
                ));
            }
            for d in &support.fix {
                model.fix(nodes, d.component())?;
            }
        }
        for (i, load) in self.loads.iter().enumerate() {
            apply(&mut model, &imported, &format!("loads[{i}]"), load)?;
        }
        Ok(MeshPart {
            name: self.name(),
            group: self.contact.clone(),
            model,
            contact,
        })
    }

    /// An error of the import at the key that names what it is about: the surface group, a
    /// group the body names, else the file.
    fn placed(&self, e: Error) -> Error {
        let Error::Mesh(message) = e else {
            return e;
        };
        let mut keys = vec![];
        if let Some(s) = &self.surface {
            keys.push(("surface".to_string(), s.clone()));
        }
        keys.push(("contact".to_string(), self.contact.clone()));
        for (i, s) in self.supports.iter().enumerate() {
            keys.push((format!("supports[{i}].group"), s.group.clone()));
        }
        for (i, l) in self.loads.iter().enumerate() {
            keys.push((format!("loads[{i}].group"), l.group.clone()));
        }
        match keys
            .into_iter()
            .find(|(_, name)| message.contains(&format!("\"{name}\"")))
        {
            Some((key, name)) => Error::invalid(key, format!("{name:?}"), message),
            None => Error::invalid("mesh", format!("{:?}", self.mesh), message),
        }
    }

    /// No node at r < 0 (to round-off of the mesh's size).
    fn check_radii(&self, imported: &Imported) -> Result<()> {
        let nodes = imported.mesh.mesh.nodes();
        let scale = nodes.iter().fold(0.0f64, |m, p| m.max(p[0].abs()));
        let lowest = (0..nodes.len()).min_by(|&a, &b| nodes[a][0].total_cmp(&nodes[b][0]));
        match lowest {
            Some(i) if nodes[i][0] < -GEOMETRY_TOLERANCE * scale => Err(Error::invalid(
                "mesh",
                format!("{:?}", self.mesh),
                format!(
                    "Gmsh node {} lies at x = r = {}: an axisymmetric body lies at r ≥ 0 (x is \
                     the radius, the axis x = 0): mesh the half x ≥ 0 of its meridian section, \
                     or analyse it in the plane",
                    imported.mesh.node_tags[i], nodes[i][0]
                ),
            )),
            _ => Ok(()),
        }
    }

    /// Every rigid motion the supports leave free can be held by the contact and is pressed
    /// onto it ([`held::check_held`]).
    fn check_held(&self, part: &MeshPart) -> Result<()> {
        let groups: Vec<&str> = self.supports.iter().map(|s| s.group.as_str()).collect();
        let holding = Holding {
            supports: format!("{groups:?}"),
            contact: &self.contact,
            loads: self.loads_named(),
        };
        held::check_held(&part.free_motions()?, &holding)
    }
}

/// A Gmsh error about `value` placed at `key`.
fn at_key(key: &str, value: String, e: Error) -> Error {
    match e {
        Error::Mesh(message) => Error::invalid(key, value, message),
        other => other,
    }
}

/// The nodes of a group of points or curves, named at `key`.
fn nodes<'i>(imported: &'i Imported, key: &str, name: &str) -> Result<&'i [usize]> {
    if imported.dimension(name) == Some(2) {
        return Err(Error::invalid(
            key,
            format!("{name:?}"),
            format!(
                "is a group of surfaces (2-D) in {}: supports and displacements hold the \
                 nodes of a group of points or curves",
                imported.mesh.source()
            ),
        ));
    }
    imported
        .mesh
        .nodes(name)
        .map_err(|e| at_key(key, format!("{name:?}"), e))
}

/// The faces of a group of curves, named at `key`.
fn faces<'i>(imported: &'i Imported, key: &str, name: &str) -> Result<&'i [contopt_fem::Face]> {
    if imported.dimension(name) == Some(2) {
        return Err(Error::invalid(
            key,
            format!("{name:?}"),
            format!(
                "is a group of surfaces (2-D) in {}: a contact face, a pressure or a traction \
                 lies on a group of curves (element edges)",
                imported.mesh.source()
            ),
        ));
    }
    imported
        .mesh
        .faces(name)
        .map_err(|e| at_key(key, format!("{name:?}"), e))
}

/// Applies the load at `key`: exactly one of a pressure, a traction and a displacement.
fn apply(model: &mut FeModel, imported: &Imported, key: &str, load: &GroupLoad) -> Result<()> {
    let group = format!("{key}.group");
    let given = [
        load.pressure_mpa.is_some(),
        load.traction_mpa.is_some(),
        load.displacement_mm.is_some(),
    ];
    if given.iter().filter(|g| **g).count() != 1 {
        return Err(Error::invalid(
            key,
            format!(
                "{} of pressure_mpa, traction_mpa, displacement_mm",
                given.iter().filter(|g| **g).count()
            ),
            "give exactly one: { group, pressure_mpa }, { group, traction_mpa = [tx, ty] } or \
             { group, displacement_mm, along }",
        ));
    }
    if load.along.is_some() && load.displacement_mm.is_none() {
        return Err(Error::invalid(
            format!("{key}.along"),
            "given",
            "is the direction of a displacement_mm",
        ));
    }
    let within = |e: Error| match e {
        Error::InvalidInput { value, reason, .. } => Error::invalid(key.to_string(), value, reason),
        other => other,
    };
    if let Some(p) = load.pressure_mpa {
        let faces = faces(imported, &group, &load.group)?;
        check::finite(&format!("{key}.pressure_mpa"), p)?;
        model.pressure(faces, p).map_err(within)?;
    } else if let Some(t) = load.traction_mpa {
        let faces = faces(imported, &group, &load.group)?;
        check::all_finite(&format!("{key}.traction_mpa"), &t)?;
        model.traction(faces, t).map_err(within)?;
    } else if let Some(d) = load.displacement_mm {
        let nodes = nodes(imported, &group, &load.group)?;
        check::finite(&format!("{key}.displacement_mm"), d)?;
        let along = load.along.unwrap_or(Direction::Y);
        model
            .prescribe(nodes, along.component(), d)
            .map_err(within)?;
    }
    Ok(())
}

impl BodyKind for FeMesh {
    fn name(&self) -> String {
        let stem = || {
            std::path::Path::new(&self.mesh)
                .file_stem()
                .map_or("mesh".into(), |s| s.to_string_lossy().into_owned())
        };
        self.name
            .clone()
            .or_else(|| self.surface.clone())
            .unwrap_or_else(stem)
    }

    /// A zone of imported meshes, either side; the file, its groups, its extent, its
    /// analysis, its loads and its supports, nothing assembled.
    fn check(&self, at: &Placement) -> Result<()> {
        let analysis = self.analysis(at)?;
        let part = self.import(at.meshes, analysis)?;
        self.check_held(&part)
    }

    /// The sparse factor of its nodes and the condensation on the zone's points
    /// ([`mesh_bytes`]), and when paired its map from the pairing's points onto the first
    /// body's face nodes.
    fn memory(&self, at: &Placement) -> Option<u64> {
        let Layout::Mesh(surface) = at.layout else {
            return None;
        };
        let k = usize::from(at.side == Side::Above);
        let points = surface.points.len();
        let (own, mortar) = match surface.paired {
            // Condensed at the pairing's points, then mapped onto the nodes.
            true => (
                mesh_bytes(surface.nodes[k]?, surface.samples)?,
                mortar_bytes(surface.samples, points)?,
            ),
            false => (mesh_bytes(surface.nodes[k]?, points)?, 0),
        };
        own.checked_add(mortar)
    }

    fn owns_surface(&self) -> bool {
        true
    }

    /// Its own loads, or nothing: a finite-element body takes no contact force, which would
    /// need a place to act.
    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        match self.loads.is_empty() {
            true => Takes::Nothing,
            false => Takes::OwnLoad,
        }
    }

    /// Sampled at its contact faces' Gauss points, for a partner that stands on them (two
    /// imported bodies are built together by their zone).
    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let part = self.import(at.meshes, self.analysis(at)?)?;
        Ok(Box::new(FeBody::new(part.name, part.model, &part.contact)?))
    }

    fn has_displacement_elements(&self) -> bool {
        true
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    /// None: Hertz's nominal contact needs the load of the whole contact, which a mesh of a
    /// half model (symmetric about x = 0) carries only half of, and nothing says which a
    /// mesh is.
    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        None
    }

    fn part(&self, meshes: &MeshFiles, analysis: Analysis) -> Option<Result<MeshPart>> {
        Some(self.import(meshes, analysis))
    }

    fn imported(&self) -> bool {
        true
    }
}
