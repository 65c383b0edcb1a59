//! A mesh of quadratic solid elements: nodes in 3-D, elements in Gmsh's local order, checked
//! for elements that fold or collapse; its boundary faces and their geometry.
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use contopt_core::{check, Error, Result};

use super::element::{cross, FaceKind, FaceShape, SolidKind, SolidShape};

/// An element whose smallest det J (at its nodes and integration points) is below this
/// fraction of its mean over the element has collapsed: its shape is degenerate (a flat
/// tetrahedron, a hexahedron with a side pinched to an edge).
const DEGENERATE: f64 = 1e-6;

/// A boundary face: face `local` of element `element`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SolidFace {
    /// The element.
    pub element: usize,
    /// Its face ([`SolidKind::face`]).
    pub local: usize,
}

/// What is wrong with an element's map from the reference element.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ElementFault {
    /// det J < 0 somewhere: the element is inverted (its nodes numbered the other way) or
    /// folded (a mid-side node past a corner).
    Inverted {
        /// The most negative det J over the mean.
        ratio: f64,
    },
    /// det J nearly zero somewhere: the element has collapsed.
    Degenerate {
        /// The smallest det J over the mean.
        ratio: f64,
    },
}

impl std::fmt::Display for ElementFault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ElementFault::Inverted { ratio } => write!(
                f,
                "is inverted or folded (det J reaches {ratio:.3} of its mean: its nodes run \
                 the wrong way, or a mid-side node lies past a corner)"
            ),
            ElementFault::Degenerate { ratio } => write!(
                f,
                "is degenerate (det J falls to {ratio:.1e} of its mean: flat, or a side \
                 collapsed to an edge)"
            ),
        }
    }
}

/// A point of a face: position, unit outward normal, area element and the face's shape
/// functions there.
#[derive(Clone, Copy, Debug)]
pub struct FacePoint {
    /// Position \[mm\].
    pub x: [f64; 3],
    /// Unit outward normal.
    pub normal: [f64; 3],
    /// Area per unit reference area, |∂x/∂s × ∂x/∂t|.
    pub da: f64,
    /// The face's shape functions and derivatives.
    pub shape: FaceShape,
    /// ∂x/∂s and ∂x/∂t.
    pub tangents: [[f64; 3]; 2],
}

/// A mesh of 10-node tetrahedra and 20- and 27-node hexahedra, mixed or not.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidMesh {
    nodes: Vec<[f64; 3]>,
    kinds: Vec<SolidKind>,
    elements: Vec<Vec<usize>>,
}

impl SolidMesh {
    /// The mesh of `nodes` and `elements` (kind, nodes in Gmsh's local order), each element
    /// checked: its node count, its node indices and its map ([`SolidMesh::fault`]); errors
    /// name the element by its index.
    pub fn new(nodes: Vec<[f64; 3]>, elements: Vec<(SolidKind, Vec<usize>)>) -> Result<Self> {
        if elements.is_empty() {
            return Err(Error::Mesh("the mesh has no elements".into()));
        }
        let flat: Vec<f64> = nodes.iter().flatten().copied().collect();
        check::all_finite("mesh.nodes", &flat)?;
        let (kinds, elements): (Vec<_>, Vec<_>) = elements.into_iter().unzip();
        for (e, (kind, conn)) in kinds.iter().zip(&elements).enumerate() {
            if conn.len() != kind.n_nodes() {
                return Err(Error::Mesh(format!(
                    "element {e} ({kind:?}) has {} nodes, not {}",
                    conn.len(),
                    kind.n_nodes()
                )));
            }
            if let Some(&a) = conn.iter().find(|&&a| a >= nodes.len()) {
                return Err(Error::Mesh(format!(
                    "element {e} refers to node {a} of {}",
                    nodes.len()
                )));
            }
        }
        let mut used = vec![false; nodes.len()];
        elements.iter().flatten().for_each(|&a| used[a] = true);
        if let Some(a) = used.iter().position(|u| !u) {
            return Err(Error::Mesh(format!(
                "node {a} belongs to no element (it would have no stiffness)"
            )));
        }
        let mesh = Self {
            nodes,
            kinds,
            elements,
        };
        for e in 0..mesh.elements.len() {
            if let Some(fault) = mesh.fault(e) {
                return Err(Error::Mesh(format!("element {e} {fault}")));
            }
        }
        Ok(mesh)
    }

    /// Node coordinates \[mm\].
    pub fn nodes(&self) -> &[[f64; 3]] {
        &self.nodes
    }

    /// Number of elements.
    pub fn n_elements(&self) -> usize {
        self.elements.len()
    }

    /// The nodes of element `e`, in its kind's order.
    pub fn element(&self, e: usize) -> &[usize] {
        &self.elements[e]
    }

    /// The kind of element `e`.
    pub fn kind(&self, e: usize) -> SolidKind {
        self.kinds[e]
    }

    /// The Jacobian ∂x/∂(ξ, η, ζ) (rows: x, y, z) of element `e` at reference point `p`, its
    /// determinant and the shape functions there.
    pub fn jacobian(&self, e: usize, p: [f64; 3]) -> ([[f64; 3]; 3], f64, SolidShape) {
        let x = self.elements[e].iter().map(|&a| self.nodes[a]);
        jacobian(self.kinds[e], x, p)
    }

    /// What is wrong with element `e`'s map, if anything ([`element_fault`]).
    pub fn fault(&self, e: usize) -> Option<ElementFault> {
        let x: Vec<[f64; 3]> = self.elements[e].iter().map(|&a| self.nodes[a]).collect();
        element_fault(self.kinds[e], &x)
    }

    /// The mesh's volume \[mm³\].
    pub fn volume(&self) -> f64 {
        (0..self.elements.len())
            .map(|e| {
                (self.kinds[e].integration_points().iter())
                    .map(|&(p, w)| self.jacobian(e, p).1 * w)
                    .sum::<f64>()
            })
            .sum()
    }

    /// The global nodes of face `f`, in the face kind's order.
    pub fn face_nodes(&self, f: SolidFace) -> Vec<usize> {
        let conn = &self.elements[f.element];
        self.kinds[f.element]
            .face(f.local)
            .iter()
            .map(|&a| conn[a])
            .collect()
    }

    /// The kind of face `f`.
    pub fn face_kind(&self, f: SolidFace) -> FaceKind {
        self.kinds[f.element].face_kind()
    }

    /// The point of face `f` at face coordinates `st`.
    pub fn face_point(&self, f: SolidFace, st: [f64; 2]) -> FacePoint {
        let shape = self.face_kind(f).shape(st);
        let mut x = [0.0; 3];
        let mut t = [[0.0; 3]; 2];
        for (a, node) in self.face_nodes(f).into_iter().enumerate() {
            let p = self.nodes[node];
            for c in 0..3 {
                x[c] += shape.n[a] * p[c];
                t[0][c] += shape.d[a][0] * p[c];
                t[1][c] += shape.d[a][1] * p[c];
            }
        }
        let n = cross(t[0], t[1]);
        let da = norm(n);
        FacePoint {
            x,
            normal: n.map(|c| c / da),
            da,
            shape,
            tangents: t,
        }
    }

    /// The faces that belong to one element only, in element order.
    pub fn boundary_faces(&self) -> Vec<SolidFace> {
        let mut count: HashMap<[usize; 4], (usize, SolidFace)> = HashMap::new();
        for e in 0..self.elements.len() {
            for local in 0..self.kinds[e].n_faces() {
                let f = SolidFace { element: e, local };
                count.entry(self.face_key(f)).or_insert((0, f)).0 += 1;
            }
        }
        let mut faces: Vec<SolidFace> = (count.into_values())
            .filter(|(n, _)| *n == 1)
            .map(|(_, f)| f)
            .collect();
        faces.sort();
        faces
    }

    /// A face's corners, sorted (a triangle's fourth is `usize::MAX`): equal for the two
    /// elements that share it.
    pub fn face_key(&self, f: SolidFace) -> [usize; 4] {
        let nodes = self.face_nodes(f);
        let mut key = [usize::MAX; 4];
        let corners = self.face_kind(f).n_corners();
        key[..corners].copy_from_slice(&nodes[..corners]);
        key.sort_unstable();
        key
    }

    /// The nodes at which `on` holds (a support or a symmetry plane by its equation).
    pub fn nodes_where(&self, on: impl Fn([f64; 3]) -> bool) -> Vec<usize> {
        (0..self.nodes.len())
            .filter(|&a| on(self.nodes[a]))
            .collect()
    }

    /// The boundary faces all of whose nodes satisfy `on`.
    pub fn faces_where(&self, on: impl Fn([f64; 3]) -> bool) -> Vec<SolidFace> {
        (self.boundary_faces().into_iter())
            .filter(|&f| self.face_nodes(f).iter().all(|&a| on(self.nodes[a])))
            .collect()
    }

    /// The bounding box, [min, max] per coordinate.
    pub fn bounding_box(&self) -> [[f64; 3]; 2] {
        let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
        for p in &self.nodes {
            for c in 0..3 {
                b[0][c] = b[0][c].min(p[c]);
                b[1][c] = b[1][c].max(p[c]);
            }
        }
        b
    }

    /// The nodes of `faces`, sorted and distinct.
    pub fn nodes_of(&self, faces: &[SolidFace]) -> Vec<usize> {
        let mut nodes: Vec<usize> = faces.iter().flat_map(|&f| self.face_nodes(f)).collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    /// A box mesh of `cells` elements of `kind` over [0, a] × [0, b] × [0, c]: each hexahedron
    /// of a regular grid, or cut into six tetrahedra around its diagonal (a test mesh).
    pub fn block(kind: SolidKind, size: [f64; 3], cells: [usize; 3]) -> Result<Self> {
        check::all_positive("size", &size)?;
        if cells.contains(&0) {
            return Err(Error::invalid(
                "cells",
                format!("{cells:?}"),
                "at least 1 each way",
            ));
        }
        let m = cells.map(|c| 2 * c + 1);
        let id = |i: usize, j: usize, k: usize| i + m[0] * (j + m[1] * k);
        let mut nodes = Vec::with_capacity(m[0] * m[1] * m[2]);
        for k in 0..m[2] {
            for j in 0..m[1] {
                for i in 0..m[0] {
                    let f = [i, j, k];
                    nodes.push(std::array::from_fn(|c| {
                        size[c] * f[c] as f64 / (m[c] - 1) as f64
                    }));
                }
            }
        }
        let mut elements = vec![];
        for k in 0..cells[2] {
            for j in 0..cells[1] {
                for i in 0..cells[0] {
                    // The node at reference point r of the cell.
                    let at = |r: [f64; 3]| {
                        id(
                            2 * i + (r[0] + 1.0) as usize,
                            2 * j + (r[1] + 1.0) as usize,
                            2 * k + (r[2] + 1.0) as usize,
                        )
                    };
                    match kind {
                        SolidKind::Hex20 | SolidKind::Hex27 => {
                            let conn = (0..kind.n_nodes())
                                .map(|a| at(super::element::HEX_NODES[a]))
                                .collect();
                            elements.push((kind, conn));
                        }
                        SolidKind::Tet10 => {
                            for tet in KUHN {
                                let corners = tet.map(|c| super::element::HEX_NODES[c]);
                                let conn = (0..10)
                                    .map(|a| {
                                        let l = SolidKind::Tet10.reference_node(a);
                                        let w = [1.0 - l[0] - l[1] - l[2], l[0], l[1], l[2]];
                                        at(std::array::from_fn(|c| {
                                            (0..4).map(|v| w[v] * corners[v][c]).sum()
                                        }))
                                    })
                                    .collect();
                                elements.push((kind, conn));
                            }
                        }
                    }
                }
            }
        }
        compact(nodes, elements)
    }

    /// The same elements with every node moved by `map` (checked again).
    pub fn map(&self, map: impl Fn([f64; 3]) -> [f64; 3]) -> Result<Self> {
        let elements = (self.kinds.iter().copied())
            .zip(self.elements.iter().cloned())
            .collect();
        Self::new(self.nodes.iter().map(|&p| map(p)).collect(), elements)
    }
}

/// The mesh of the nodes that `elements` use, renumbered in their order.
fn compact(nodes: Vec<[f64; 3]>, elements: Vec<(SolidKind, Vec<usize>)>) -> Result<SolidMesh> {
    let mut new = vec![usize::MAX; nodes.len()];
    let mut kept = vec![];
    let elements = elements
        .into_iter()
        .map(|(kind, conn)| {
            let conn = conn
                .into_iter()
                .map(|a| {
                    if new[a] == usize::MAX {
                        new[a] = kept.len();
                        kept.push(nodes[a]);
                    }
                    new[a]
                })
                .collect();
            (kind, conn)
        })
        .collect();
    SolidMesh::new(kept, elements)
}

/// The Jacobian ∂x/∂(ξ, η, ζ) of an element of `kind` with nodes at `x` (in its order) at
/// reference point `p`, its determinant and the shape functions there.
fn jacobian(
    kind: SolidKind,
    x: impl Iterator<Item = [f64; 3]>,
    p: [f64; 3],
) -> ([[f64; 3]; 3], f64, SolidShape) {
    let s = kind.shape(p);
    let mut j = [[0.0; 3]; 3];
    for (a, xa) in x.enumerate() {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += xa[r] * s.d[a][c];
            }
        }
    }
    (j, det3(&j), s)
}

/// What is wrong with the map of an element of `kind` whose nodes are at `x`, if anything:
/// det J at its nodes and integration points against its mean (the volume over the reference
/// volume), and the mean against the size of the nodes' spread.
pub fn element_fault(kind: SolidKind, x: &[[f64; 3]]) -> Option<ElementFault> {
    let det = |p: [f64; 3]| jacobian(kind, x.iter().copied(), p).1;
    let points = kind.integration_points();
    let volume: f64 = points.iter().map(|&(p, w)| det(p) * w).sum();
    let reference: f64 = points.iter().map(|(_, w)| w).sum();
    let mean = volume / reference;
    // The det J of an undistorted element as large as its nodes' spread.
    let spread = (0..3)
        .map(|c| {
            let (lo, hi) = x
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), p| {
                    (lo.min(p[c]), hi.max(p[c]))
                });
            hi - lo
        })
        .fold(0.0, f64::max);
    let size = spread.powi(3) / reference;
    if mean.abs() < DEGENERATE * size {
        return Some(ElementFault::Degenerate { ratio: mean / size });
    }
    let min = (0..kind.n_nodes())
        .map(|a| kind.reference_node(a))
        .chain(points.iter().map(|&(p, _)| p))
        .map(det)
        .fold(f64::INFINITY, f64::min);
    if mean < 0.0 || min < -DEGENERATE * mean {
        return Some(ElementFault::Inverted {
            ratio: min / mean.abs(),
        });
    }
    (min < DEGENERATE * mean).then_some(ElementFault::Degenerate { ratio: min / mean })
}

/// Kuhn's six tetrahedra of a cube about its diagonal 0–6 (corners in [`SolidKind::Hex20`]'s
/// numbering), each positively oriented.
const KUHN: [[usize; 4]; 6] = [
    [0, 1, 2, 6],
    [0, 2, 3, 6],
    [0, 3, 7, 6],
    [0, 7, 4, 6],
    [0, 4, 5, 6],
    [0, 5, 1, 6],
];

/// det of a 3 × 3 matrix.
pub(crate) fn det3(j: &[[f64; 3]; 3]) -> f64 {
    j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0])
}

/// The Euclidean norm.
pub(crate) fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative round-off of a volume or an area.
    const ROUND_OFF: f64 = 1e-12;

    /// A block of each kind has its volume, its boundary faces cover its surface, and each
    /// boundary face's normal points out of the box.
    #[test]
    fn blocks_have_their_volume_and_surface() {
        for kind in SolidKind::ALL {
            let mesh = SolidMesh::block(kind, [2.0, 3.0, 4.0], [2, 1, 3]).unwrap();
            assert!((mesh.volume() - 24.0).abs() < ROUND_OFF * 24.0, "{kind:?}");
            let mut area = 0.0;
            for f in mesh.boundary_faces() {
                let fk = mesh.face_kind(f);
                for (st, w) in fk.contact_points() {
                    let p = mesh.face_point(f, st);
                    area += p.da * w;
                    let out: f64 = (0..3)
                        .map(|c| p.normal[c] * (p.x[c] - [1.0, 1.5, 2.0][c]))
                        .sum();
                    assert!(out > 0.0);
                }
            }
            let want = 2.0 * (6.0 + 8.0 + 12.0);
            assert!((area - want).abs() < ROUND_OFF * want, "{kind:?} {area}");
        }
    }

    /// An element with two corners swapped is inverted, one squashed flat is degenerate, and
    /// the errors name the element.
    #[test]
    fn inverted_and_degenerate_elements_are_named() {
        let mesh = SolidMesh::block(SolidKind::Hex20, [1.0; 3], [2, 1, 1]).unwrap();
        let mut elements: Vec<(SolidKind, Vec<usize>)> = (0..2)
            .map(|e| (mesh.kind(e), mesh.element(e).to_vec()))
            .collect();
        // Mirror element 1: the top and bottom layers swapped.
        let conn = elements[1].1.clone();
        let mirrored: Vec<usize> = (0..20)
            .map(|a| {
                let r = super::super::element::HEX_NODES[a];
                let b = (0..20)
                    .find(|&b| super::super::element::HEX_NODES[b] == [r[0], r[1], -r[2]])
                    .unwrap();
                conn[b]
            })
            .collect();
        elements[1].1 = mirrored;
        let e = SolidMesh::new(mesh.nodes().to_vec(), elements).unwrap_err();
        assert!(e.to_string().contains("element 1 is inverted"), "{e}");

        let flat = SolidMesh::block(SolidKind::Tet10, [1.0; 3], [1, 1, 1])
            .unwrap()
            .map(|p| [p[0], p[1], 0.0]);
        let e = flat.unwrap_err().to_string();
        assert!(e.contains("element 0 is degenerate"), "{e}");
    }
}
