//! Each refusal of an import, on two unit squares written here ([`Msh::two_squares`]), and
//! what a valid file gives.

use contopt_fem::Face;

use super::{Block, Msh};
use crate::Surfaces;

/// The squares as written: 13 nodes, 2 elements, "bottom" from (0, 0) to (2, 0) and "top"
/// from (2, 1) to (0, 1) (the body on their left), "origin", area 2.
#[test]
fn two_squares_import() {
    let m = Msh::two_squares()
        .parse()
        .unwrap()
        .import(Surfaces::All)
        .unwrap();
    assert_eq!((m.mesh.nodes().len(), m.mesh.elements().len()), (13, 2));
    assert_eq!(m.element_tags, [1, 2]);
    let tags = |nodes: &[usize]| nodes.iter().map(|&n| m.node_tags[n]).collect::<Vec<_>>();
    let face = |element, local| Face { element, local };
    assert_eq!(m.faces("bottom").unwrap(), [face(0, 0), face(1, 0)]);
    assert_eq!(tags(m.nodes("bottom").unwrap()), [1, 7, 2, 8, 3]);
    assert_eq!(m.faces("top").unwrap(), [face(1, 2), face(0, 2)]);
    assert_eq!(tags(m.nodes("top").unwrap()), [4, 10, 5, 12, 6]);
    assert_eq!(tags(m.nodes("origin").unwrap()), [1]);
    assert!((m.area() - 2.0).abs() < 1e-14);
    assert_eq!(m.bounding_box(), [[0.0, 0.0], [2.0, 1.0]]);
    let group = Msh::two_squares()
        .parse()
        .unwrap()
        .import(Surfaces::Group("body"));
    assert_eq!(group.unwrap().mesh.elements(), m.mesh.elements());
}

/// Node tags far apart (a hash map instead of a table) give the same mesh.
#[test]
fn sparse_node_tags() {
    let mut msh = Msh::two_squares();
    let sparse = |t: u64| t * 1_000_000_007;
    for n in &mut msh.nodes {
        n.0 = sparse(n.0);
    }
    for b in &mut msh.blocks {
        for (_, nodes) in &mut b.elements {
            nodes.iter_mut().for_each(|n| *n = sparse(*n));
        }
    }
    let m = msh.parse().unwrap().import(Surfaces::All).unwrap();
    let plain = Msh::two_squares()
        .parse()
        .unwrap()
        .import(Surfaces::All)
        .unwrap();
    assert_eq!(m.mesh.elements(), plain.mesh.elements());
    assert_eq!(m.groups, plain.groups);
    assert_eq!(m.node_tags[12], sparse(13));
}

/// Both squares drawn clockwise (a surface whose normal is −z, as Gmsh meshes it) are
/// renumbered counter-clockwise: same area, same chains, the body on their left.
#[test]
fn a_clockwise_surface_is_renumbered() {
    let mut msh = Msh::two_squares();
    for (_, nodes) in &mut msh.block(2, 1).elements {
        *nodes = [0, 3, 2, 1, 7, 6, 5, 4].map(|a| nodes[a]).to_vec();
    }
    let m = msh.parse().unwrap().import(Surfaces::All).unwrap();
    let plain = Msh::two_squares()
        .parse()
        .unwrap()
        .import(Surfaces::All)
        .unwrap();
    assert!((m.area() - 2.0).abs() < 1e-14);
    assert_eq!(m.mesh.elements(), plain.mesh.elements());
    assert_eq!(m.nodes("top").unwrap(), plain.nodes("top").unwrap());
}

/// One square clockwise in a counter-clockwise surface is inverted (the tie of one against
/// one goes to counter-clockwise).
#[test]
fn an_element_against_its_surface() {
    let mut msh = Msh::two_squares();
    let nodes = &mut msh.block(2, 1).elements[1].1;
    *nodes = [0, 3, 2, 1, 7, 6, 5, 4].map(|a| nodes[a]).to_vec();
    assert_eq!(
        msh.import_error(),
        "mesh: t.msh: Gmsh element 2 is inverted (negative Jacobian determinant): clockwise, \
         while 1 of the 2 elements of surface 1 run counter-clockwise"
    );
}

/// A mid-side node moved past the quarter point of its side folds the element: det J changes
/// sign at the corner.
#[test]
fn a_folded_element() {
    let mut msh = Msh::two_squares();
    *msh.node(7) = [0.1, 0.0, 0.0];
    let e = msh.import_error();
    assert!(
        e.starts_with(
            "mesh: t.msh: Gmsh element 1 is inverted: its Jacobian determinant changes sign"
        ),
        "{e}"
    );
}

/// Linear quadrilaterals, and linear lines in a group, ask for `Mesh.ElementOrder = 2`.
#[test]
fn linear_elements() {
    let mut msh = Msh::two_squares();
    let b = msh.block(2, 1);
    b.kind = 3;
    b.elements.iter_mut().for_each(|(_, n)| n.truncate(4));
    let e = msh.import_error();
    assert!(
        e.starts_with(
            "mesh: t.msh: Gmsh element 1 is of type 3 (Quadrilateral 4), a linear element"
        ),
        "{e}"
    );
    assert!(e.contains("`Mesh.ElementOrder = 2;`"), "{e}");

    let mut msh = Msh::two_squares();
    let b = msh.block(1, 1);
    b.kind = 1;
    b.elements.iter_mut().for_each(|(_, n)| n.truncate(2));
    let e = msh.import_error();
    assert!(
        e.starts_with("mesh: t.msh: Gmsh element 11 is of type 1 (Line 2), a linear element"),
        "{e}"
    );
}

/// An element type contopt does not have is named by number and name.
#[test]
fn unsupported_element_type() {
    let mut msh = Msh::two_squares();
    let b = msh.block(2, 1);
    b.kind = 20;
    b.elements.iter_mut().for_each(|(_, n)| n.push(9));
    let e = msh.import_error();
    assert!(
        e.starts_with(
            "mesh: t.msh: Gmsh element 1 is of type 20 (Triangle 9), which contopt does not have"
        ),
        "{e}"
    );
}

/// Volume elements, or nodes off z = 0, make a 3-D mesh.
#[test]
fn a_3d_mesh() {
    let mut msh = Msh::two_squares();
    msh.blocks.push(Block::new(3, 1, 4, &[(20, &[1, 2, 5, 6])]));
    let e = msh.import_error();
    assert!(
        e.starts_with(
            "mesh: t.msh: the mesh is 3-D: it has 1 volume elements (type 4 (Tetrahedron 4))"
        ),
        "{e}"
    );

    let mut msh = Msh::two_squares();
    msh.node(13)[2] = 0.5;
    let e = msh.import_error();
    assert!(
        e.starts_with("mesh: t.msh: node 13 lies at z = 0.5, off the plane z = 0"),
        "{e}"
    );
}

/// A group the file does not name lists the names it has; a named group without elements
/// is empty; a group whose lines all lie on another body has none on this one; a point
/// group has no faces.
#[test]
fn missing_and_empty_groups() {
    let gmsh = Msh::two_squares().parse().unwrap();
    let e = gmsh
        .import(Surfaces::Group("punch"))
        .unwrap_err()
        .to_string();
    assert_eq!(
        e,
        "mesh: t.msh: no 2-D physical group (surfaces) named \"punch\"; the file names surfaces \
         \"body\"; curves \"bottom\", \"top\", \"middle\"; points \"origin\""
    );
    let m = gmsh.import(Surfaces::All).unwrap();
    let e = m.faces("contcat").unwrap_err().to_string();
    assert_eq!(
        e,
        "mesh: t.msh: no physical group of points or curves named \"contcat\"; the file's are \
         \"origin\", \"bottom\", \"top\", \"middle\""
    );
    let e = m.faces("middle").unwrap_err().to_string();
    assert!(
        e.starts_with("mesh: t.msh: the physical group \"middle\" is empty"),
        "{e}"
    );
    let e = m.faces("origin").unwrap_err().to_string();
    assert!(e.contains("\"origin\" holds points, not curves"), "{e}");

    let mut msh = Msh::two_squares();
    msh.names.push((2, 6, "hub"));
    let e = msh
        .parse()
        .unwrap()
        .import(Surfaces::Group("hub"))
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("mesh: t.msh: the physical group \"hub\" has no elements"),
        "{e}"
    );

    let mut msh = Msh::two_squares();
    msh.nodes.extend([
        (14, [5.0, 0.0, 0.0]),
        (15, [6.0, 0.0, 0.0]),
        (16, [5.5, 0.0, 0.0]),
    ]);
    msh.blocks.push(Block::new(1, 3, 8, &[(15, &[14, 15, 16])]));
    let m = msh.parse().unwrap().import(Surfaces::All).unwrap();
    let e = m.faces("middle").unwrap_err().to_string();
    assert_eq!(
        e,
        "mesh: t.msh: the physical group \"middle\" has none of its 1 lines on this body"
    );
}

/// A group's line must be a boundary face of the body: not the side the squares share, not
/// a face with another middle node, not two nodes no face joins.
#[test]
fn lines_that_are_not_boundary_faces() {
    let refused = |line: [u64; 3]| {
        let mut msh = Msh::two_squares();
        msh.blocks.push(Block::new(1, 3, 8, &[(15, &line)]));
        msh.import_error()
    };
    assert_eq!(
        refused([2, 5, 11]),
        "mesh: t.msh: line 15 of the group \"middle\" lies inside the body, between elements 1 \
         and 2: a group's lines must be boundary faces of the body"
    );
    let e = refused([1, 2, 13]);
    assert!(
        e.contains(
            "line 15 of the group \"middle\" has middle node 13, the face of element 1 node 7"
        ),
        "{e}"
    );
    let e = refused([1, 5, 11]);
    assert!(
        e.contains(
            "line 15 of the group \"middle\" joins nodes 1 and 5, which no element face joins"
        ),
        "{e}"
    );
}

/// One name for a group of points and a group of curves is ambiguous.
#[test]
fn one_name_for_two_groups() {
    let mut msh = Msh::two_squares();
    msh.names[0].2 = "bottom";
    assert_eq!(
        msh.import_error(),
        "mesh: t.msh: \"bottom\" names both a group of points and a group of curves: rename one"
    );
}
