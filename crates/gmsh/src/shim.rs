//! What this crate needs of contopt-fem's 6-node triangle and mixed meshes, which another
//! branch adds (the contract: `ElementKind::{Q8, Q9, T6}` with `n_nodes`, `n_faces`,
//! `face_nodes`, `shape` (T6 in area coordinates), `Mesh::mixed`, `Mesh::element_kind`).
//!
//! **At merge** this module goes: [`Kind`] becomes `contopt_fem::ElementKind`, [`Kind::shape`]
//! its `shape`, [`build_mesh`] `Mesh::mixed`, [`element_kind`] `Mesh::element_kind`. Until
//! then a mesh holding a 6-node triangle is refused when the `Mesh` is built, after every
//! check of the import has passed.

use contopt_core::{Error, Result};
use contopt_fem::element::Shape;
use contopt_fem::{ElementKind, Mesh};

/// An element kind of contopt-fem: `ElementKind` with the 6-node triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// 8-node serendipity quadrilateral.
    Q8,
    /// 9-node Lagrange quadrilateral.
    Q9,
    /// 6-node triangle.
    T6,
}

/// Local nodes (start, middle, end) of the faces of a quadrilateral, counter-clockwise.
const QUAD_FACES: [[usize; 3]; 4] = [[0, 4, 1], [1, 5, 2], [2, 6, 3], [3, 7, 0]];
/// Local nodes (start, middle, end) of the faces of a 6-node triangle, counter-clockwise.
const TRIANGLE_FACES: [[usize; 3]; 3] = [[0, 3, 1], [1, 4, 2], [2, 5, 0]];

impl Kind {
    /// Number of faces.
    pub fn n_faces(self) -> usize {
        match self {
            Kind::Q8 | Kind::Q9 => 4,
            Kind::T6 => 3,
        }
    }

    /// Local nodes (start, middle, end) of face `local`.
    pub fn face_nodes(self, local: usize) -> [usize; 3] {
        match self {
            Kind::Q8 | Kind::Q9 => QUAD_FACES[local],
            Kind::T6 => TRIANGLE_FACES[local],
        }
    }

    /// Shape functions and their derivatives at (ξ, η); for the triangle ξ and η are the area
    /// coordinates of nodes 1 and 2 (node 0 at (0, 0), 1 at (1, 0), 2 at (0, 1), Gmsh's
    /// reference triangle).
    pub fn shape(self, xi: f64, eta: f64) -> Shape {
        match self {
            Kind::Q8 => ElementKind::Q8.shape(xi, eta),
            Kind::Q9 => ElementKind::Q9.shape(xi, eta),
            Kind::T6 => triangle6(xi, eta),
        }
    }
}

/// The 6-node triangle's shape functions: corners Lᵢ(2Lᵢ − 1), mid-sides 4LᵢLⱼ.
fn triangle6(xi: f64, eta: f64) -> Shape {
    let l0 = 1.0 - xi - eta;
    let mut s = Shape::default();
    s.n[..6].copy_from_slice(&[
        l0 * (2.0 * l0 - 1.0),
        xi * (2.0 * xi - 1.0),
        eta * (2.0 * eta - 1.0),
        4.0 * l0 * xi,
        4.0 * xi * eta,
        4.0 * eta * l0,
    ]);
    s.dxi[..6].copy_from_slice(&[
        1.0 - 4.0 * l0,
        4.0 * xi - 1.0,
        0.0,
        4.0 * (l0 - xi),
        4.0 * eta,
        -4.0 * eta,
    ]);
    s.deta[..6].copy_from_slice(&[
        1.0 - 4.0 * l0,
        0.0,
        4.0 * eta - 1.0,
        -4.0 * xi,
        4.0 * xi,
        4.0 * (l0 - eta),
    ]);
    s
}

/// The `Mesh` of `nodes` and `elements` (`Mesh::mixed` at merge): today one kind of
/// quadrilateral only.
pub(crate) fn build_mesh(nodes: Vec<[f64; 2]>, elements: Vec<(Kind, Vec<usize>)>) -> Result<Mesh> {
    let kind = match elements.first() {
        Some((Kind::Q8, _)) => ElementKind::Q8,
        Some((Kind::Q9, _)) => ElementKind::Q9,
        Some((Kind::T6, _)) | None => return Err(not_yet()),
    };
    let same = |k: Kind| {
        matches!(
            (k, kind),
            (Kind::Q8, ElementKind::Q8) | (Kind::Q9, ElementKind::Q9)
        )
    };
    if !elements.iter().all(|(k, _)| same(*k)) {
        return Err(not_yet());
    }
    Mesh::new(kind, nodes, elements.into_iter().map(|(_, c)| c).collect())
}

/// The error of a mesh this branch's contopt-fem cannot hold.
fn not_yet() -> Error {
    Error::Mesh(
        "6-node triangles and meshes of mixed element kinds need contopt-fem's `Mesh::mixed`, \
         not merged yet"
            .to_string(),
    )
}

/// The kind of element `e` of `mesh` (`Mesh::element_kind` at merge).
pub(crate) fn element_kind(mesh: &Mesh, _e: usize) -> Kind {
    match mesh.kind() {
        ElementKind::Q8 => Kind::Q8,
        ElementKind::Q9 => Kind::Q9,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The triangle's shape functions are 1 at their node and 0 at the others, sum to 1, and
    /// their derivatives match finite differences.
    #[test]
    fn triangle6_interpolates() {
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [0.5, 0.5],
            [0.0, 0.5],
        ];
        for (j, &[x, y]) in nodes.iter().enumerate() {
            let s = triangle6(x, y);
            for i in 0..6 {
                let expect = if i == j { 1.0 } else { 0.0 };
                assert!((s.n[i] - expect).abs() < 1e-15, "N{i} at node {j}");
            }
        }
        let (x, y, h) = (0.23, 0.41, 1e-7);
        let (s, sx, sy) = (triangle6(x, y), triangle6(x + h, y), triangle6(x, y + h));
        assert!((s.n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        for i in 0..6 {
            assert!((s.dxi[i] - (sx.n[i] - s.n[i]) / h).abs() < 1e-6, "dN{i}/dξ");
            assert!(
                (s.deta[i] - (sy.n[i] - s.n[i]) / h).abs() < 1e-6,
                "dN{i}/dη"
            );
        }
    }
}
