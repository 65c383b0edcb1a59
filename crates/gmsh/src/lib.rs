//! Read [Gmsh](https://gmsh.info) meshes (the MSH 4.1 format) into contopt's finite-element
//! meshes ([`contopt_fem::Mesh`]), with their named groups: a user's own punch, hub or seal,
//! meshed in Gmsh.
//!
//! ```
//! use contopt_gmsh::Surfaces;
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../meshes/rectangle-q8.msh");
//! let imported = contopt_gmsh::read(path)?.import(Surfaces::All)?;
//! imported.check_extent([40.0, 20.0], 1e-6)?;
//! let contact = imported.faces("contact")?; // boundary faces, along the curve
//! let bottom = imported.nodes("bottom")?; // the nodes of a curve's faces, for a support
//! assert_eq!(imported.mesh.elements().len(), imported.element_tags.len());
//! # assert!(!contact.is_empty() && !bottom.is_empty());
//! # Ok::<(), contopt_core::Error>(())
//! ```
//!
//! # What is read
//! MSH 4.1 files, ASCII or binary (little-endian, 8-byte `size_t`, as 64-bit Gmsh writes
//! them): `$MeshFormat`, `$PhysicalNames`, `$Entities` (the physical groups of every point,
//! curve, surface and volume), `$Nodes` (parametric coordinates skipped) and `$Elements`;
//! other sections are skipped. [`read`] and [`parse`] give the file's content as a
//! [`GmshMesh`]; [`GmshMesh::import`] makes a body of it:
//! - the body is every surface ([`Surfaces::All`]) or the surfaces of one named 2-D physical
//!   group ([`Surfaces::Group`]), so that one file may hold both bodies of a contact;
//! - its elements are Gmsh's 8-node quadrilaterals (type 16, contopt's Q8), 9-node
//!   quadrilaterals (type 10, Q9) and 6-node triangles (type 9, T6), mixed or not; the local
//!   node orders are Gmsh's;
//! - its nodes are those the elements use, numbered in file order
//!   ([`ImportedMesh::node_tags`] keeps Gmsh's tags, [`ImportedMesh::element_tags`] the
//!   elements');
//! - every named 1-D physical group (3-node lines, type 8) becomes element faces
//!   ([`ImportedMesh::faces`]) in order along the chain, each running counter-clockwise round
//!   its element, so that the body is on the chain's left; its nodes, in the same order, are
//!   [`ImportedMesh::nodes`]; every named 0-D group (points) becomes nodes. A group's lines or
//!   points on another body of the file are left out, so a curve may be named once for
//!   several bodies.
//!
//! - solids ([`GmshMesh::import_solid`]): every volume ([`Volumes::All`]) or those of one named
//!   3-D group; 10-node tetrahedra (type 11), 20- and 27-node hexahedra (types 17, 12) in
//!   Gmsh's local order, each checked for inversion and collapse (named by its Gmsh tag); every
//!   named 2-D group (supports, loads, the contact face, symmetry planes) becomes the solid's
//!   boundary faces ([`ImportedSolid::faces`]) and their nodes, and
//!   [`ImportedSolid::check_extent`] checks the units in x, y and z. The `meshes/solid-*.geo`
//!   files show the physical groups.
//!
//! # What is refused
//! Every error names the file, and for a reading error its line (and byte, in a binary
//! section), what was expected and what was found: another MSH version (with how to save
//! 4.1), a truncated file, a count larger than the rest of the file could hold (refused
//! before anything is allocated), a number that is not one, a node tag defined twice or
//! outside the header's range, an element that refers to an undefined node, a partitioned
//! mesh. An import refuses, with Gmsh's tags: volume elements or nodes off the plane z = 0 (a
//! 3-D mesh); linear elements (say `Mesh.ElementOrder = 2;`); other element types (their
//! number and name); a group the file does not name (the names it has are listed) or that has
//! no elements; an inverted element; two nodes at one point (say `Coherence Mesh;`); a group's
//! line that is not a boundary face of the body.
//!
//! # Orientation
//! contopt's elements run counter-clockwise (positive Jacobian determinant). Gmsh orients a
//! surface's elements by the surface's normal: a surface whose normal points to −z (a curve
//! loop drawn clockwise in a `.geo`) is meshed clockwise throughout. Such a surface is not
//! inverted: its elements are renumbered counter-clockwise (corners reversed from the first,
//! each mid-side node onto its reversed side). An element whose Jacobian determinant changes
//! sign or vanishes at its nodes or integration points, or that runs against the majority of
//! its surface, is inverted and refused.
//!
//! # Units
//! Gmsh has no units: coordinates are read as mm (contopt's N, mm, MPa), x = r and y = z for
//! axisymmetric bodies. [`ImportedMesh::check_extent`] checks the mesh's bounding box against
//! the extent a scene states, and says when a mesh looks drawn in metres (1000 times too
//! small), inches, centimetres or micrometres.
//!
//! # Making meshes for contopt in Gmsh
//! ```text
//! Mesh.ElementOrder = 2;            // quadratic elements
//! Mesh.SecondOrderIncomplete = 1;   // 8-node quadrilaterals (0: 9-node)
//! Mesh.RecombineAll = 1;            // quadrilaterals (0: triangles)
//! Physical Surface("punch") = {1};  // name the body, and the curves of its
//! Physical Curve("contact") = {3};  // contact, supports and loads
//! ```
//! then `gmsh part.geo -2 -format msh41 -o part.msh`. The repository's `meshes/` folder holds
//! examples with their `.geo` sources.

mod body;
mod cursor;
mod extent;
mod geometry;
mod groups;
mod import;
mod msh;
mod solid;
mod types;

use std::path::Path;

use contopt_core::{memory, Error, Result};

pub use groups::Group;
pub use import::{ImportedMesh, Surfaces};
pub use msh::{ElementBlock, Entity, GmshMesh, PhysicalName};
pub use solid::{ImportedSolid, SolidGroup, Volumes};
pub use types::ElementType;

/// Memory a file takes while it is read, per byte of the file: the bytes themselves, and at
/// most as much again for its nodes and elements (a binary node is 32 bytes in the file and
/// in memory, ASCII takes more bytes per number than the values it holds).
const MEMORY_PER_FILE_BYTE: u64 = 3;

/// Reads the MSH 4.1 file at `path` (ASCII or binary); errors name it.
pub fn read(path: impl AsRef<Path>) -> Result<GmshMesh> {
    let path = path.as_ref();
    let shown = path.display().to_string();
    let io = |e: std::io::Error| Error::invalid("mesh file", &shown, e.to_string());
    let len = std::fs::metadata(path).map_err(io)?.len();
    memory::require(
        format!("reading the mesh file {shown} ({len} bytes)"),
        len.checked_mul(MEMORY_PER_FILE_BYTE),
        memory::BODY_LIMIT_BYTES,
        "mesh it coarser, or save it in binary",
    )?;
    let bytes = std::fs::read(path).map_err(io)?;
    parse(&bytes, &shown)
}

/// Reads the bytes of an MSH 4.1 file (ASCII or binary); `source` names it in errors.
pub fn parse(bytes: &[u8], source: &str) -> Result<GmshMesh> {
    msh::parse(bytes, source)
}

#[cfg(test)]
mod tests;
