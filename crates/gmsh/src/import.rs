//! From a Gmsh file to a body's mesh: the chosen surfaces' elements, their nodes renumbered,
//! every element counter-clockwise, and the checks that refuse what contopt cannot use.

use contopt_core::{Error, Result, GEOMETRY_TOLERANCE};
use contopt_fem::{ElementKind, Face, Mesh};

use crate::body::Body;
use crate::geometry;
use crate::groups::{self, Group};
use crate::msh::{ElementBlock, GmshMesh};
use crate::types::{self, linear};

/// Which surfaces make the body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surfaces<'a> {
    /// Every surface of the file.
    All,
    /// The surfaces of the named 2-D physical group (one body of several in a file).
    Group(&'a str),
}

/// A body's mesh read from Gmsh, with its named groups.
#[derive(Clone, Debug)]
pub struct ImportedMesh {
    /// The mesh: the chosen elements, nodes numbered in the order of the file.
    pub mesh: Mesh,
    /// The named groups of points and curves (0-D and 1-D physical groups), in the order of
    /// `$PhysicalNames`; a group of another body is here without faces or nodes.
    pub groups: Vec<Group>,
    /// Gmsh's tag of each node of [`ImportedMesh::mesh`].
    pub node_tags: Vec<u64>,
    /// Gmsh's tag of each element of [`ImportedMesh::mesh`].
    pub element_tags: Vec<u64>,
    source: String,
}

impl GmshMesh {
    /// The body made of `surfaces`: its 2-D elements (8- and 9-node quadrilaterals, 6-node
    /// triangles), the nodes they use, every element counter-clockwise, and the named groups
    /// of points and curves on it.
    ///
    /// Refused, each with its own message: volume elements, nodes off the plane z = 0,
    /// linear or other unsupported element types, a missing or empty group, an element that
    /// folds (det J changes sign) or runs against the rest of its surface, two nodes at one
    /// point, a group's line that is not a boundary face of the body.
    pub fn import(&self, surfaces: Surfaces) -> Result<ImportedMesh> {
        let (body, groups) = self.prepare(surfaces)?;
        let Body {
            nodes,
            node_tags,
            elements,
            element_tags,
            ..
        } = body;
        let mesh = Mesh::mixed(nodes, elements)?;
        Ok(ImportedMesh {
            mesh,
            groups,
            node_tags,
            element_tags,
            source: self.source().to_string(),
        })
    }

    /// Everything of [`GmshMesh::import`] but building the [`Mesh`].
    pub(crate) fn prepare(&self, surfaces: Surfaces) -> Result<(Body, Vec<Group>)> {
        self.refuse_volumes()?;
        let blocks = self.surface_blocks(surfaces)?;
        let mut body = self.body(&blocks)?;
        body.orient(self.source())?;
        body.refuse_duplicate_nodes(self.source())?;
        let groups = groups::collect(self, &body)?;
        Ok((body, groups))
    }

    /// A 3-D mesh is refused.
    fn refuse_volumes(&self) -> Result<()> {
        let volumes = self.element_count(3);
        if volumes == 0 {
            return Ok(());
        }
        let kinds: Vec<String> = self
            .blocks()
            .iter()
            .filter(|b| b.dim() == 3)
            .map(|b| b.element_type().to_string())
            .collect();
        Err(Error::Mesh(format!(
            "{}: the mesh is 3-D: it has {volumes} volume elements ({}); a plane or \
             axisymmetric body is a surface mesh (`Mesh 2;`, `gmsh -2`), a solid is read by \
             `import_solid`",
            self.source(),
            dedup(kinds).join(", ")
        )))
    }

    /// The 2-D element blocks of `surfaces`, at least one element.
    fn surface_blocks(&self, surfaces: Surfaces) -> Result<Vec<&ElementBlock>> {
        let blocks: Vec<&ElementBlock> = match surfaces {
            Surfaces::All => self.blocks().iter().filter(|b| b.dim() == 2).collect(),
            Surfaces::Group(name) => {
                let tag = self
                    .physical_tag(2, name)
                    .ok_or_else(|| self.missing_surfaces(name))?;
                self.group_blocks(2, tag).collect()
            }
        };
        if blocks.iter().all(|b| b.is_empty()) {
            return Err(Error::Mesh(match surfaces {
                Surfaces::All => format!(
                    "{}: the file has no surface elements: mesh the surfaces (`Mesh 2;`, `gmsh -2`)",
                    self.source()
                ),
                Surfaces::Group(name) => format!(
                    "{}: the physical group \"{name}\" has no elements: are its surfaces meshed?",
                    self.source()
                ),
            }));
        }
        Ok(blocks)
    }

    /// The error of a 2-D group that the file does not name.
    fn missing_surfaces(&self, name: &str) -> Error {
        Error::Mesh(format!(
            "{}: no 2-D physical group (surfaces) named \"{name}\"; the file names {}",
            self.source(),
            physical_names_listed(self)
        ))
    }

    /// The elements of `blocks`, the nodes they use (in file order) and their coordinates,
    /// checked in the plane z = 0.
    fn body(&self, blocks: &[&ElementBlock]) -> Result<Body> {
        let mut of_file_node = vec![usize::MAX; self.coords().len()];
        let mut kinds = Vec::with_capacity(blocks.len());
        for block in blocks {
            kinds.push(self.kind(block)?);
            for (_, nodes) in block.elements() {
                for &n in nodes {
                    of_file_node[n] = 0;
                }
            }
        }
        let mut nodes = Vec::new();
        let mut node_tags = Vec::new();
        for (n, slot) in of_file_node.iter_mut().enumerate() {
            if *slot == 0 {
                *slot = nodes.len();
                let [x, y, _] = self.coords()[n];
                nodes.push([x, y]);
                node_tags.push(self.node_tags()[n]);
            }
        }
        self.refuse_off_plane(&of_file_node, &nodes)?;
        let mut body = Body {
            nodes,
            node_tags,
            elements: Vec::new(),
            element_tags: Vec::new(),
            surfaces: Vec::new(),
            of_file_node,
        };
        for (block, kind) in blocks.iter().zip(kinds) {
            for (tag, nodes) in block.elements() {
                let nodes = nodes.iter().map(|&n| body.of_file_node[n]).collect();
                body.elements.push((kind, nodes));
                body.element_tags.push(tag);
                body.surfaces.push(block.entity());
            }
        }
        Ok(body)
    }

    /// The kind of a 2-D block's elements; linear and other types refused.
    fn kind(&self, block: &ElementBlock) -> Result<ElementKind> {
        let t = block.element_type();
        let first = block.tags().first().copied().unwrap_or_default();
        match t.number {
            types::QUADRANGLE8 => Ok(ElementKind::Q8),
            types::QUADRANGLE9 => Ok(ElementKind::Q9),
            types::TRIANGLE6 => Ok(ElementKind::T6),
            types::TRIANGLE3 | types::QUADRANGLE4 => Err(linear(self.source(), first, t)),
            _ => Err(Error::Mesh(format!(
                "{}: Gmsh element {first} is of {t}, which contopt does not have: it reads \
                 8- and 9-node quadrilaterals (types 16, 10) and 6-node triangles (type 9); \
                 set `Mesh.ElementOrder = 2;`",
                self.source()
            ))),
        }
    }

    /// Every used node on z = 0 (to [`GEOMETRY_TOLERANCE`] of the body's size).
    fn refuse_off_plane(&self, of_file_node: &[usize], nodes: &[[f64; 2]]) -> Result<()> {
        let [lo, hi] = bounding_box(nodes);
        let tol = GEOMETRY_TOLERANCE * (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        let off = (0..of_file_node.len())
            .find(|&n| of_file_node[n] != usize::MAX && self.coords()[n][2].abs() > tol);
        match off {
            None => Ok(()),
            Some(n) => Err(Error::Mesh(format!(
                "{}: node {} lies at z = {}, off the plane z = 0: the mesh is 3-D or drawn in \
                 another plane; contopt's bodies lie in (x, y) (x = r for axisymmetry)",
                self.source(),
                self.node_tags()[n],
                self.coords()[n][2]
            ))),
        }
    }
}

/// The file's physical names by dimension, for an error that did not find one.
pub(crate) fn physical_names_listed(gmsh: &GmshMesh) -> String {
    const DIMS: [&str; 4] = ["points", "curves", "surfaces", "volumes"];
    let lists: Vec<String> = (0..4)
        .rev()
        .filter_map(|dim| {
            let names: Vec<String> = gmsh
                .physical_names()
                .iter()
                .filter(|p| p.dim == dim)
                .map(|p| format!("\"{}\"", p.name))
                .collect();
            (!names.is_empty()).then(|| format!("{} {}", DIMS[dim], names.join(", ")))
        })
        .collect();
    if lists.is_empty() {
        "no physical group".to_string()
    } else {
        lists.join("; ")
    }
}

/// `items` without repeats, in their first order.
fn dedup(items: Vec<String>) -> Vec<String> {
    let mut seen = Vec::new();
    for item in items {
        if !seen.contains(&item) {
            seen.push(item);
        }
    }
    seen
}

/// The bounding box [min, max] of `nodes`.
fn bounding_box(nodes: &[[f64; 2]]) -> [[f64; 2]; 2] {
    nodes.iter().fold(
        [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]],
        |[lo, hi], p| {
            [
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            ]
        },
    )
}

impl ImportedMesh {
    /// The named group of points or curves `name`: refused when the file has no such group,
    /// when it has no elements, or when none of them lies on this body.
    pub fn group(&self, name: &str) -> Result<&Group> {
        let group = self.groups.iter().find(|g| g.name == name).ok_or_else(|| {
            let names: Vec<String> = self.groups.iter().map(|g| format!("\"{}\"", g.name)).collect();
            let names = if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            };
            Error::Mesh(format!(
                "{}: no physical group of points or curves named \"{name}\"; the file's are {names}",
                self.source
            ))
        })?;
        let what = if group.dim == 0 { "points" } else { "lines" };
        if group.elements_in_file == 0 {
            return Err(Error::Mesh(format!(
                "{}: the physical group \"{name}\" is empty: no {what} of the mesh belong to it \
                 (is it defined on entities that are not meshed?)",
                self.source
            )));
        }
        if group.nodes.is_empty() {
            return Err(Error::Mesh(format!(
                "{}: the physical group \"{name}\" has none of its {} {what} on this body",
                self.source, group.elements_in_file
            )));
        }
        Ok(group)
    }

    /// The faces of the curve group `name`, along the chain (each face runs counter-clockwise
    /// round its element, so the chain runs with the body on its left).
    pub fn faces(&self, name: &str) -> Result<&[Face]> {
        let group = self.group(name)?;
        if group.dim == 0 {
            return Err(Error::Mesh(format!(
                "{}: the physical group \"{name}\" holds points, not curves: it has nodes, no faces",
                self.source
            )));
        }
        Ok(&group.faces)
    }

    /// The nodes of the group `name`: a curve group's face nodes along the chain, a point
    /// group's points.
    pub fn nodes(&self, name: &str) -> Result<&[usize]> {
        Ok(&self.group(name)?.nodes)
    }

    /// The bounding box [[x_min, y_min], [x_max, y_max]] of the mesh.
    pub fn bounding_box(&self) -> [[f64; 2]; 2] {
        bounding_box(self.mesh.nodes())
    }

    /// The area of the mesh, Σ ∫ det J over the elements (for an axisymmetric body, the area
    /// of its meridian section).
    pub fn area(&self) -> f64 {
        let nodes = self.mesh.nodes();
        self.mesh
            .elements()
            .iter()
            .enumerate()
            .map(|(e, element)| {
                let (x, n) = geometry::coords(nodes, element);
                geometry::area(self.mesh.element_kind(e), &x[..n])
            })
            .sum()
    }

    /// The file the mesh was read from.
    pub fn source(&self) -> &str {
        &self.source
    }
}
