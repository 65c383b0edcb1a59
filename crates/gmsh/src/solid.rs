//! From a Gmsh file to a solid's mesh ([`contopt_fem::solid::SolidMesh`]): the volumes'
//! quadratic elements, their nodes renumbered, every element checked, and the named surface
//! groups as the solid's boundary faces (supports, loads, the contact face, symmetry planes).

use std::collections::HashMap;

use contopt_core::{Error, Result};
use contopt_fem::solid::{element_fault, SolidFace, SolidKind, SolidMesh};

use crate::import::physical_names_listed;
use crate::msh::{ElementBlock, GmshMesh};
use crate::types::linear;
use crate::types::ElementType;

/// Gmsh's 10-node tetrahedron.
const TETRAHEDRON10: i32 = 11;
/// Gmsh's 27-node hexahedron.
const HEXAHEDRON27: i32 = 12;
/// Gmsh's 20-node hexahedron.
const HEXAHEDRON20: i32 = 17;
/// Gmsh's linear volume elements: tetrahedron, hexahedron, prism, pyramid.
const LINEAR_VOLUMES: [i32; 4] = [4, 5, 6, 7];

/// Which volumes make the solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Volumes<'a> {
    /// Every volume of the file.
    All,
    /// The volumes of the named 3-D physical group (one body of several in a file).
    Group(&'a str),
}

/// A named surface group on a solid: its boundary faces and their nodes.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidGroup {
    /// The physical name.
    pub name: String,
    /// The solid's boundary faces the group's surface elements lie on.
    pub faces: Vec<SolidFace>,
    /// Their nodes, sorted.
    pub nodes: Vec<usize>,
    /// The group's surface elements in the whole file (some may lie on another body).
    pub elements_in_file: usize,
}

/// A solid read from Gmsh, with its named surface groups.
#[derive(Clone, Debug)]
pub struct ImportedSolid {
    /// The mesh: the chosen volume elements, nodes numbered in file order.
    pub mesh: SolidMesh,
    /// The named 2-D physical groups, in the order of `$PhysicalNames`.
    pub groups: Vec<SolidGroup>,
    /// Gmsh's tag of each node of the mesh.
    pub node_tags: Vec<u64>,
    /// Gmsh's tag of each element of the mesh.
    pub element_tags: Vec<u64>,
    source: String,
}

impl GmshMesh {
    /// The solid made of `volumes`: its 10-node tetrahedra, 20- and 27-node hexahedra, the
    /// nodes they use, and every named surface group as boundary faces.
    ///
    /// Refused, each naming the Gmsh element or the group: a file without volumes (a plane
    /// mesh: import it with [`GmshMesh::import`]), linear or other element types, an
    /// inverted or degenerate element, a surface group's element that is not a boundary face
    /// of the solid, a volume group the file does not name.
    pub fn import_solid(&self, volumes: Volumes) -> Result<ImportedSolid> {
        let blocks = self.volume_blocks(volumes)?;
        let mut of_file_node = vec![usize::MAX; self.coords().len()];
        let mut elements: Vec<(SolidKind, Vec<usize>)> = vec![];
        let mut element_tags = vec![];
        let (mut nodes, mut node_tags) = (vec![], vec![]);
        for block in &blocks {
            let kind = self.solid_kind(block)?;
            for (tag, conn) in block.elements() {
                let conn: Vec<usize> = conn
                    .iter()
                    .map(|&n| {
                        if of_file_node[n] == usize::MAX {
                            of_file_node[n] = nodes.len();
                            nodes.push(self.coords()[n]);
                            node_tags.push(self.node_tags()[n]);
                        }
                        of_file_node[n]
                    })
                    .collect();
                elements.push((kind, conn));
                element_tags.push(tag);
            }
        }
        for ((kind, conn), tag) in elements.iter().zip(&element_tags) {
            let x: Vec<[f64; 3]> = conn.iter().map(|&a| nodes[a]).collect();
            if let Some(fault) = element_fault(*kind, &x) {
                return Err(Error::Mesh(format!(
                    "{}: Gmsh element {tag} {fault}; remesh it (`Mesh.HighOrderOptimize = 2;` \
                     straightens curved elements that fold)",
                    self.source()
                )));
            }
        }
        let mesh = SolidMesh::new(nodes, elements)?;
        let groups = self.surface_groups(&mesh, &of_file_node)?;
        Ok(ImportedSolid {
            mesh,
            groups,
            node_tags,
            element_tags,
            source: self.source().to_string(),
        })
    }

    /// The 3-D blocks of `volumes`, at least one element.
    fn volume_blocks(&self, volumes: Volumes) -> Result<Vec<&ElementBlock>> {
        if self.element_count(3) == 0 {
            return Err(Error::Mesh(format!(
                "{}: the mesh has no volume elements: it is a plane or axisymmetric mesh \
                 (import it as a plane body), or the volumes were not meshed (`Mesh 3;`, \
                 `gmsh -3`)",
                self.source()
            )));
        }
        let entities: Option<Vec<i32>> = match volumes {
            Volumes::All => None,
            Volumes::Group(name) => {
                let tag = self.physical_tag(3, name).ok_or_else(|| {
                    Error::Mesh(format!(
                        "{}: no 3-D physical group (volumes) named \"{name}\"; the file names {}",
                        self.source(),
                        physical_names_listed(self)
                    ))
                })?;
                Some(
                    (self.entities().iter())
                        .filter(|e| e.dim == 3 && e.physical_tags.contains(&tag))
                        .map(|e| e.tag)
                        .collect(),
                )
            }
        };
        Ok(self
            .blocks()
            .iter()
            .filter(|b| b.dim() == 3)
            .filter(|b| entities.as_ref().is_none_or(|es| es.contains(&b.entity())))
            .collect())
    }

    /// The kind of a 3-D block's elements; linear and other types refused.
    fn solid_kind(&self, block: &ElementBlock) -> Result<SolidKind> {
        let t: ElementType = block.element_type();
        let first = block.tags().first().copied().unwrap_or_default();
        match t.number {
            TETRAHEDRON10 => Ok(SolidKind::Tet10),
            HEXAHEDRON20 => Ok(SolidKind::Hex20),
            HEXAHEDRON27 => Ok(SolidKind::Hex27),
            n if LINEAR_VOLUMES.contains(&n) => Err(linear(self.source(), first, t)),
            _ => Err(Error::Mesh(format!(
                "{}: Gmsh element {first} is of {t}, which contopt does not have: it reads \
                 10-node tetrahedra (type 11), 20- and 27-node hexahedra (types 17, 12)",
                self.source()
            ))),
        }
    }

    /// Every named 2-D group, its surface elements matched to the solid's boundary faces by
    /// their corners.
    fn surface_groups(&self, mesh: &SolidMesh, of_file_node: &[usize]) -> Result<Vec<SolidGroup>> {
        let boundary: HashMap<[usize; 4], SolidFace> = (mesh.boundary_faces().into_iter())
            .map(|f| (mesh.face_key(f), f))
            .collect();
        let mut groups = vec![];
        for name in self.physical_names().iter().filter(|p| p.dim == 2) {
            let entities: Vec<i32> = (self.entities().iter())
                .filter(|e| e.dim == 2 && e.physical_tags.contains(&name.tag))
                .map(|e| e.tag)
                .collect();
            let mut group = SolidGroup {
                name: name.name.clone(),
                faces: vec![],
                nodes: vec![],
                elements_in_file: 0,
            };
            for block in self
                .blocks()
                .iter()
                .filter(|b| b.dim() == 2 && entities.contains(&b.entity()))
            {
                let corners = match block.element_type().number {
                    2 | 9 | 20 | 21 => 3,
                    _ => 4,
                };
                for (tag, conn) in block.elements() {
                    group.elements_in_file += 1;
                    let mut key = [usize::MAX; 4];
                    for (k, &n) in conn[..corners].iter().enumerate() {
                        key[k] = of_file_node[n];
                    }
                    if key[..corners].contains(&usize::MAX) {
                        continue; // on another body of the file
                    }
                    key.sort_unstable();
                    let face = boundary.get(&key).ok_or_else(|| {
                        Error::Mesh(format!(
                            "{}: Gmsh element {tag} of the surface group \"{}\" is not a \
                             boundary face of the solid (a surface inside it, or on another \
                             body that shares its nodes)",
                            self.source(),
                            name.name
                        ))
                    })?;
                    group.faces.push(*face);
                }
            }
            group.nodes = mesh.nodes_of(&group.faces);
            groups.push(group);
        }
        Ok(groups)
    }
}

impl ImportedSolid {
    /// The named surface group `name`: refused when the file has no such group, when it has
    /// no elements, or when none lies on this solid.
    pub fn group(&self, name: &str) -> Result<&SolidGroup> {
        let group = self.groups.iter().find(|g| g.name == name).ok_or_else(|| {
            let names: Vec<String> = self
                .groups
                .iter()
                .map(|g| format!("\"{}\"", g.name))
                .collect();
            let names = if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            };
            Error::Mesh(format!(
                "{}: no physical group of surfaces named \"{name}\"; the file's are {names}",
                self.source
            ))
        })?;
        if group.elements_in_file == 0 {
            return Err(Error::Mesh(format!(
                "{}: the physical group \"{name}\" is empty: no surface elements of the mesh \
                 belong to it (is it defined on surfaces that are not meshed?)",
                self.source
            )));
        }
        if group.faces.is_empty() {
            return Err(Error::Mesh(format!(
                "{}: the physical group \"{name}\" has none of its {} surface elements on this \
                 solid",
                self.source, group.elements_in_file
            )));
        }
        Ok(group)
    }

    /// The boundary faces of the surface group `name`.
    pub fn faces(&self, name: &str) -> Result<&[SolidFace]> {
        Ok(&self.group(name)?.faces)
    }

    /// The nodes of the surface group `name`.
    pub fn nodes(&self, name: &str) -> Result<&[usize]> {
        Ok(&self.group(name)?.nodes)
    }

    /// Checks the sides of the solid's bounding box against `expected_mm` (x, y, z), each to
    /// the relative `tolerance`: the units check of [`crate::ImportedMesh::check_extent`].
    pub fn check_extent(&self, expected_mm: [f64; 3], tolerance: f64) -> Result<()> {
        let [lo, hi] = self.mesh.bounding_box();
        let extent: [f64; 3] = std::array::from_fn(|c| hi[c] - lo[c]);
        crate::extent::check_units(&self.source, &extent, &expected_mm, tolerance)
    }

    /// The file the solid was read from.
    pub fn source(&self) -> &str {
        &self.source
    }
}
