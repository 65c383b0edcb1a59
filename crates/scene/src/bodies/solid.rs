//! A solid part read from a Gmsh mesh (`kind = "solid"`): 10-node tetrahedra, 20- or 27-node
//! hexahedra, with named surface groups for its contact face, its supports, its symmetry
//! planes and its loads ([`contopt_fem::solid`]). It stands on a grid zone, either side: its
//! contact face is read along z over the grid's cells, each cell's mean pressure and
//! displacement ([`SolidSample::cells`]), so that it pairs cell for cell with a half-space, a
//! rigid body or another solid on the same grid. Its face lies on the zone's plane z = 0 and
//! the zone's gap describes the bodies' shapes; or, with the gap `measured`, it lies where
//! its mesh puts it (a sphere's curved face), and its face's distance from the plane in each
//! cell, the cell's mean, is its share of the gap ([`BodyKind::face_shape`]): two solids
//! meshed apart meet on one grid.
//!
//! Everything the scene names is checked when the scene is read, nothing assembled: the file
//! (relative to the scene's folder, [`crate::meshes`]), the volume group, each surface group
//! (present, not empty, on this solid's boundary: Gmsh's import refuses the rest, naming the
//! element or the group), the extent against the size the scene states (a mesh drawn in
//! metres is 1000 times too small), each symmetry group (a plane across x, y or z), and the
//! contact face against the grid (it lies along z under every cell, on the plane z = 0
//! unless the gap is measured).

use contopt_core::{check, memory, ElasticBody, Error, Interface, Material, Result};
use contopt_fem::solid::{
    dependent_samples, Axis, Cell, SolidBody, SolidFace, SolidModel, SolidSample, SolidSettings,
    DENSE_POINTS,
};
use contopt_gmsh::ImportedSolid;
use serde::{Deserialize, Serialize};

use super::held::{self, Holding};
use super::{misplaced, BodyKind, Carried, Placement, Side, Takes};
use crate::chosen::Chosen;
use crate::mesh_surface::FreeMotion;
use crate::meshes::MeshFiles;
use crate::zone::{GridZone, Layout, ZoneKind};

/// The mesh's bounding box must agree with the extent the scene states to this fraction (a
/// units check that allows a rounded size).
const EXTENT_TOLERANCE: f64 = 0.01;

/// The contact face lies on the zone's plane when it is this fraction of the solid's size
/// from it at every cell (round-off of the mesh's coordinates).
const ON_PLANE: f64 = 1e-6;

/// The nodes of a symmetry group lie on one plane across an axis to this fraction of the
/// solid's size.
const PLANAR: f64 = 1e-6;

/// Bytes per assembled stiffness entry (a row, a column and a value, and their sorted copy):
/// the estimate of [`BodyKind::memory`], as the solid's own assembly counts it.
const BYTES_PER_ENTRY: u64 = 2 * (16 + 8);

/// An axis of space, as a scene names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolidAxis {
    /// x.
    X,
    /// y.
    Y,
    /// z.
    Z,
}

impl SolidAxis {
    fn axis(self) -> Axis {
        match self {
            SolidAxis::X => Axis::X,
            SolidAxis::Y => Axis::Y,
            SolidAxis::Z => Axis::Z,
        }
    }
}

/// A support: the nodes of a surface group held along `fix`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidSupport {
    /// The physical group (surfaces).
    pub group: String,
    /// The directions held: `["z"]`, or `["x", "y", "z"]` (clamped).
    pub fix: Vec<SolidAxis>,
}

/// A load on a surface group: a uniform pressure or a uniform traction, exactly one.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SolidLoad {
    /// The physical group (surfaces).
    pub group: String,
    /// A uniform pressure \[MPa\], positive into the solid.
    #[serde(default)]
    pub pressure_mpa: Option<f64>,
    /// A uniform traction (t_x, t_y, t_z) \[MPa\].
    #[serde(default)]
    pub traction_mpa: Option<[f64; 3]>,
}

/// A solid part read from a Gmsh mesh.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Solid {
    /// Its name in reports (default: its volume group, else the file's name).
    #[serde(default)]
    pub name: Option<String>,
    /// The Gmsh file (MSH 4.1), relative to the scene's folder.
    pub mesh: String,
    /// The 3-D physical group of its elements (default: every volume of the file).
    #[serde(default)]
    pub volume: Option<String>,
    /// The surface group of its contact face, on the zone's plane z = 0 (anywhere along z
    /// under the grid with a measured gap).
    pub contact: String,
    /// The size of the part [x, y, z] \[mm\] as the user knows it: the mesh's bounding box
    /// must agree within 1 % (Gmsh has no units).
    pub extent_mm: [f64; 3],
    /// The material.
    pub material: Material,
    /// Its supports (default none).
    #[serde(default)]
    pub supports: Vec<SolidSupport>,
    /// Its symmetry planes: surface groups, each a plane across x, y or z whose nodes are held
    /// along its normal (default none).
    #[serde(default)]
    pub symmetry: Vec<String>,
    /// Its loads (default none).
    #[serde(default)]
    pub loads: Vec<SolidLoad>,
}

impl Solid {
    /// The grid the solid stands on, or why it cannot stand on the zone.
    fn grid<'z>(&self, at: &Placement<'z>) -> Result<&'z GridZone> {
        at.zone.downcast::<GridZone>().ok_or_else(|| {
            misplaced(
                at,
                "a solid stands on a grid zone: contact.zone = { kind = \"grid\", cells = …, \
                 cell_mm = … }",
            )
        })
    }

    /// The imported solid, its extent checked.
    fn imported(&self, meshes: &MeshFiles) -> Result<std::sync::Arc<ImportedSolid>> {
        check::all_positive("extent_mm", &self.extent_mm)?;
        let solid = meshes
            .import_solid(&self.mesh, self.volume.as_deref())
            .map_err(|e| self.placed(e))?;
        solid
            .check_extent(self.extent_mm, EXTENT_TOLERANCE)
            .map_err(|e| at_key("extent_mm", format!("{:?}", self.extent_mm), e))?;
        Ok(solid)
    }

    /// The model, supported, held on its symmetry planes and loaded, every group checked.
    fn model(&self, solid: &ImportedSolid) -> Result<SolidModel> {
        let group = |key: String, name: &str| {
            solid
                .group(name)
                .map_err(|e| at_key(&key, format!("{name:?}"), e))
        };
        group("contact".into(), &self.contact)?;
        let mut model = SolidModel::new(solid.mesh.clone(), self.material);
        for (i, support) in self.supports.iter().enumerate() {
            let key = format!("supports[{i}]");
            let nodes = &group(format!("{key}.group"), &support.group)?.nodes;
            if support.fix.is_empty() {
                return Err(Error::invalid(
                    format!("{key}.fix"),
                    "[]",
                    "name the directions held: [\"z\"] … [\"x\", \"y\", \"z\"]",
                ));
            }
            for axis in &support.fix {
                model.fix(nodes, axis.axis())?;
            }
        }
        for (i, name) in self.symmetry.iter().enumerate() {
            let key = format!("symmetry[{i}]");
            let nodes = &group(key.clone(), name)?.nodes;
            model.fix(nodes, plane_normal(solid, &key, name, nodes)?)?;
        }
        for (i, load) in self.loads.iter().enumerate() {
            let key = format!("loads[{i}]");
            let faces = &group(format!("{key}.group"), &load.group)?.faces;
            let within = |e: Error| match e {
                Error::InvalidInput { value, reason, .. } => {
                    Error::invalid(key.clone(), value, reason)
                }
                other => other,
            };
            match (load.pressure_mpa, load.traction_mpa) {
                (Some(p), None) => {
                    check::finite(&format!("{key}.pressure_mpa"), p)?;
                    model.add_pressure(faces, p).map_err(within)?;
                }
                (None, Some(t)) => {
                    check::all_finite(&format!("{key}.traction_mpa"), &t)?;
                    model.add_traction(faces, t).map_err(within)?;
                }
                _ => {
                    return Err(Error::invalid(
                        key,
                        format!("{{ group = \"{}\" … }}", load.group),
                        "give exactly one of { group, pressure_mpa } and { group, \
                         traction_mpa = [tx, ty, tz] }",
                    ))
                }
            }
        }
        Ok(model)
    }

    /// The contact face read over the grid's cells, along the body's outward normal (+z
    /// below the zone, −z above): each cell's mean on a sub-rule of its faces
    /// ([`SolidSample::cells`]), every sub-point on a face of the contact group, and the face
    /// on the plane z = 0 there unless the gap is measured ([`Placement::measured`]).
    fn samples(&self, at: &Placement, solid: &ImportedSolid) -> Result<Vec<SolidSample>> {
        let surface = at
            .layout
            .surface()
            .ok_or_else(|| misplaced(at, "a solid stands on a grid zone"))??;
        let &Layout::Grid { dx, dy, .. } = at.layout else {
            return Err(misplaced(at, "a solid stands on a grid zone"));
        };
        let normal = match at.side {
            Side::Below => [0.0, 0.0, 1.0],
            Side::Above => [0.0, 0.0, -1.0],
        };
        let faces = solid
            .faces(&self.contact)
            .map_err(|e| at_key("contact", format!("{:?}", self.contact), e))?;
        let cells: Vec<Cell> = (surface.points().iter())
            .map(|&p| Cell::xy(p, [dx, dy]))
            .collect();
        let samples =
            SolidSample::cells(&solid.mesh, faces, &cells, normal).map_err(|e| match e {
                Error::InvalidInput { value, reason, .. } => Error::invalid(
                    "contact",
                    format!("{:?}", self.contact),
                    format!(
                        "has no face under the grid's cell centred at {value} mm (along z; \
                         {reason}): the contact face must cover the grid (contact.zone's \
                         cells × cell_mm)"
                    ),
                ),
                other => other,
            })?;
        if at.measured {
            return Ok(samples);
        }
        let size = self.extent_mm.iter().fold(0.0f64, |m, &e| m.max(e));
        let off = (samples.iter()).find_map(|s| {
            (s.parts.iter())
                .find(|p| p.offset.abs() > ON_PLANE * size)
                .map(|p| (s, p))
        });
        if let Some((s, part)) = off {
            return Err(Error::invalid(
                "contact",
                format!("{:?}", self.contact),
                format!(
                    "lies {} mm off the zone's plane z = 0 in the cell centred at ({}, {}) mm: \
                     the solid's contact face lies on z = 0 (move the part in Gmsh), and the \
                     zone's gap describes the bodies' shapes; or, for a face whose shape the \
                     mesh gives, contact.gap = {{ kind = \"measured\" }}",
                    part.offset, s.point[0], s.point[1]
                ),
            ));
        }
        Ok(samples)
    }

    /// On a grid that starts at a plane of symmetry (x = 0, y = 0), the solid is the part on
    /// the grid's side of it: a solid that reaches across is a whole body on a half zone.
    fn check_symmetric(&self, at: &Placement, solid: &ImportedSolid) -> Result<()> {
        let [lo, hi] = solid.mesh.bounding_box();
        let size = (0..3).fold(0.0f64, |m, c| m.max(hi[c] - lo[c]));
        let symmetric = at.layout.symmetric();
        match (0..2).find(|&c| symmetric[c] && lo[c] < -ON_PLANE * size) {
            Some(c) => Err(Error::invalid(
                "mesh",
                format!("{:?}", self.mesh),
                format!(
                    "reaches {} = {} mm across the grid's plane of symmetry {} = 0 \
                     (contact.zone.symmetry): the solid on such a grid is its part on the \
                     grid's side, held on the plane ({{ symmetry = [\"…\"] }})",
                    ["x", "y"][c],
                    lo[c],
                    ["x", "y"][c]
                ),
            )),
            None => Ok(()),
        }
    }

    /// Every rigid motion its supports and symmetry planes leave free can be held by the
    /// contact and is pressed onto it ([`held::check_held`], as for a plane mesh).
    fn check_held(&self, solid: &ImportedSolid, model: &SolidModel) -> Result<()> {
        let faces = solid
            .faces(&self.contact)
            .map_err(|e| at_key("contact", format!("{:?}", self.contact), e))?;
        let free: Vec<FreeMotion> = (model.free_motions()?.into_iter())
            .map(|m| {
                let along = model.along_normals(&m, faces);
                FreeMotion::new(m, along, model.forces())
            })
            .collect();
        let groups: Vec<&str> = (self.supports.iter().map(|s| s.group.as_str()))
            .chain(self.symmetry.iter().map(String::as_str))
            .collect();
        let loads: Vec<String> = (self.loads.iter())
            .map(|l| match (l.pressure_mpa, l.traction_mpa) {
                (Some(p), _) => format!("{{ group = \"{}\", pressure_mpa = {p} }}", l.group),
                (_, Some(t)) => format!("{{ group = \"{}\", traction_mpa = {t:?} }}", l.group),
                _ => format!("{{ group = \"{}\" }}", l.group),
            })
            .collect();
        let holding = Holding {
            supports: format!("{groups:?}"),
            contact: &self.contact,
            loads: format!("[{}]", loads.join(", ")),
        };
        held::check_held(&free, &holding)
    }

    /// An error of Gmsh's import placed at the key that names what it is about: the volume
    /// group, a surface group the body names, else the file.
    fn placed(&self, e: Error) -> Error {
        let Error::Mesh(message) = e else {
            return e;
        };
        let mut keys = vec![];
        if let Some(v) = &self.volume {
            keys.push(("volume".to_string(), v.clone()));
        }
        keys.push(("contact".to_string(), self.contact.clone()));
        for (i, s) in self.supports.iter().enumerate() {
            keys.push((format!("supports[{i}].group"), s.group.clone()));
        }
        for (i, s) in self.symmetry.iter().enumerate() {
            keys.push((format!("symmetry[{i}]"), s.clone()));
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
}

/// The axis a symmetry group is a plane across: its nodes share one coordinate.
fn plane_normal(solid: &ImportedSolid, key: &str, name: &str, nodes: &[usize]) -> Result<Axis> {
    let all = solid.mesh.nodes();
    let [lo, hi] = solid.mesh.bounding_box();
    let size = (0..3).fold(0.0f64, |m, c| m.max(hi[c] - lo[c]));
    let spread = |c: usize| {
        let (a, b) = nodes
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &n| {
                (a.min(all[n][c]), b.max(all[n][c]))
            });
        b - a
    };
    match (0..3).find(|&c| spread(c) <= PLANAR * size) {
        Some(c) => Ok(Axis::ALL[c]),
        None => Err(Error::invalid(
            key,
            format!("{name:?}"),
            format!(
                "is not a plane across x, y or z in {} (its nodes spread {:.3e}, {:.3e}, \
                 {:.3e} mm along x, y, z): a symmetry plane holds the normal displacement of \
                 a flat face normal to an axis",
                solid.source(),
                spread(0),
                spread(1),
                spread(2)
            ),
        )),
    }
}

/// A Gmsh error about `value` placed at `key`.
fn at_key(key: &str, value: String, e: Error) -> Error {
    match e {
        Error::Mesh(message) => Error::invalid(key, value, message),
        other => other,
    }
}

impl BodyKind for Solid {
    fn name(&self) -> String {
        let stem = || {
            std::path::Path::new(&self.mesh)
                .file_stem()
                .map_or("solid".into(), |s| s.to_string_lossy().into_owned())
        };
        self.name
            .clone()
            .or_else(|| self.volume.clone())
            .unwrap_or_else(stem)
    }

    /// A grid zone, either side; the file, its groups, its extent, its symmetry planes and
    /// loads, and the contact face under every cell, nothing assembled.
    fn check(&self, at: &Placement) -> Result<()> {
        self.grid(at)?;
        let solid = self.imported(at.meshes)?;
        self.check_symmetric(at, &solid)?;
        let model = self.model(&solid)?;
        self.check_held(&solid, &model)?;
        self.samples(at, &solid).map(drop)
    }

    /// The assembled stiffness (as the solid's assembly counts it) and, up to
    /// [`DENSE_POINTS`] cells, the dense influence; the factor's size is known only after its
    /// symbolic analysis, where the solid checks it against the scene's `memory_limit_mb`
    /// ([`Placement::memory_limit_bytes`]) before allocating.
    fn memory(&self, at: &Placement) -> Option<u64> {
        let solid = self.imported(at.meshes).ok()?;
        let mesh = &solid.mesh;
        let entries = (0..mesh.n_elements()).try_fold(0usize, |sum, e| {
            let m = 3 * mesh.kind(e).n_nodes();
            sum.checked_add(m * (m + 1) / 2)
        })?;
        let points = at.layout.points()?;
        let dense = match points <= DENSE_POINTS {
            true => memory::bytes(&[points, points], 8),
            false => Some(0),
        };
        memory::sum(&[memory::bytes(&[entries], BYTES_PER_ENTRY), dense])
    }

    /// With a measured gap, its face's distance from the zone's plane in each cell (the cell's
    /// mean along the body's outward normal, away from its partner): −offset of
    /// [`SolidSample`], so that two solids' shapes add up to [`SolidSample::initial_gap`].
    fn face_shape(&self, at: &Placement) -> Option<Result<Vec<f64>>> {
        at.measured.then(|| {
            let solid = self.imported(at.meshes)?;
            let samples = self.samples(at, &solid)?;
            Ok(samples.iter().map(|s| -s.offset).collect())
        })
    }

    /// The cells whose means of the contact faces' normal displacement (the faces flat on the
    /// grid's plane) are combinations of other cells' ([`dependent_samples`]: the rank of the
    /// read-out S, and so of the influence S K⁻¹ Sᵀ among the cells), with the box they lie
    /// in and the cells and face nodes there.
    fn carried_pressures(&self, at: &Placement) -> Option<Result<Carried>> {
        let carried = || -> Result<Carried> {
            let solid = self.imported(at.meshes)?;
            let samples = self.samples(at, &solid)?;
            let dependent = dependent_samples(&solid.mesh, &samples);
            let [lo, hi] = (dependent.iter().map(|&i| samples[i].point)).fold(
                [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
                |[lo, hi], p| {
                    [
                        [lo[0].min(p[0]), lo[1].min(p[1])],
                        [hi[0].max(p[0]), hi[1].max(p[1])],
                    ]
                },
            );
            let region: Vec<&SolidSample> = (samples.iter())
                .filter(|s| (0..2).all(|c| s.point[c] >= lo[c] && s.point[c] <= hi[c]))
                .collect();
            let faces: Vec<SolidFace> = (region.iter())
                .flat_map(|s| s.parts.iter().map(|p| p.face))
                .collect();
            Ok(Carried {
                dependent,
                region_mm: [lo, hi],
                region_points: region.len(),
                region_nodes: solid.mesh.nodes_of(&faces).len(),
            })
        };
        Some(carried())
    }

    fn owns_surface(&self) -> bool {
        true
    }

    /// Its own loads, or nothing: a solid takes no contact force (it is held, or pressed by
    /// its loads).
    fn takes(&self, _zone: &Chosen<dyn ZoneKind>) -> Takes {
        match self.loads.is_empty() {
            true => Takes::Nothing,
            false => Takes::OwnLoad,
        }
    }

    /// Read over the grid's cells: dense influence up to [`DENSE_POINTS`] cells, products
    /// through the factorisation above.
    fn build(&self, at: &Placement, _surface: Option<&Interface>) -> Result<Box<dyn ElasticBody>> {
        let solid = self.imported(at.meshes)?;
        let model = self.model(&solid)?;
        let samples = self.samples(at, &solid)?;
        Ok(Box::new(SolidBody::sampled(
            self.name(),
            model,
            &samples,
            SolidSettings {
                memory_limit_bytes: at.memory_limit_bytes,
                ..Default::default()
            },
        )?))
    }

    fn has_displacement_elements(&self) -> bool {
        true
    }

    fn material(&self) -> Option<Material> {
        Some(self.material)
    }

    /// A half-space's (1 − ν²)/E: near the contact a solid is a body standing in for a
    /// half-space (a block, a sphere), stiffer as it is finite; Hertz's figure with it is the
    /// nominal one.
    fn compliance(&self, _zone: &Chosen<dyn ZoneKind>) -> Option<f64> {
        Some(self.material.contact_compliance())
    }
}
