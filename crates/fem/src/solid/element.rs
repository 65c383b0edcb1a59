//! Quadratic solid elements in Gmsh's local node order: the 10-node tetrahedron (Gmsh type 11),
//! the 20-node serendipity hexahedron (type 17) and the 27-node Lagrange hexahedron (type 12);
//! their shape functions, volume quadrature and faces (6-node triangles, 8- and 9-node
//! quadrilaterals) with face quadrature.
//!
//! Reference elements: the tetrahedron 0 ≤ ξ, η, ζ, ξ + η + ζ ≤ 1, corners (0,0,0), (1,0,0),
//! (0,1,0), (0,0,1), mid-edge nodes 4 (0–1), 5 (1–2), 6 (0–2), 7 (0–3), 8 (2–3), 9 (1–3); the
//! hexahedron [−1, 1]³ with the nodes of [`HEX_NODES`] (`gmsh.model.mesh.getElementProperties`).
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use crate::element::{lagrange2, ElementKind, GAUSS3, MAX_NODES};

/// Most nodes of a solid element (the 27-node hexahedron).
pub const MAX_SOLID_NODES: usize = 27;
/// Most nodes of a face (the 9-node quadrilateral).
pub const MAX_FACE_NODES: usize = MAX_NODES;

/// Reference coordinates of the hexahedra's nodes in Gmsh's order: 8 corners, 12 mid-edge
/// nodes, 6 face centres and the centre (the 20-node element has the first 20).
pub const HEX_NODES: [[f64; 3]; 27] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
    [0.0, -1.0, -1.0],
    [-1.0, 0.0, -1.0],
    [-1.0, -1.0, 0.0],
    [1.0, 0.0, -1.0],
    [1.0, -1.0, 0.0],
    [0.0, 1.0, -1.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
    [0.0, -1.0, 1.0],
    [-1.0, 0.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.0, 1.0, 1.0],
    [0.0, 0.0, -1.0],
    [0.0, -1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [0.0, 0.0, 0.0],
];

/// The tetrahedron's mid-edge nodes 4–9 and the corners each joins.
const TET_EDGES: [(usize, usize); 6] = [(0, 1), (1, 2), (0, 2), (0, 3), (2, 3), (1, 3)];

/// The tetrahedron's faces: corners counter-clockwise seen from outside, then the mid-edge
/// nodes of the sides 0–1, 1–2, 2–0 of the face.
const TET_FACES: [&[usize]; 4] = [
    &[0, 2, 1, 6, 5, 4],
    &[0, 1, 3, 4, 9, 7],
    &[0, 3, 2, 7, 8, 6],
    &[1, 2, 3, 5, 8, 9],
];

/// The hexahedra's faces: corners counter-clockwise seen from outside, the mid-edge nodes of
/// the sides 0–1, 1–2, 2–3, 3–0 of the face, and its centre (27-node element only).
const HEX_FACES: [&[usize]; 6] = [
    &[0, 3, 2, 1, 9, 13, 11, 8, 20],
    &[4, 5, 6, 7, 16, 18, 19, 17, 25],
    &[0, 1, 5, 4, 8, 12, 16, 10, 21],
    &[1, 2, 6, 5, 11, 14, 18, 12, 23],
    &[2, 3, 7, 6, 13, 15, 19, 14, 24],
    &[3, 0, 4, 7, 9, 10, 17, 15, 22],
];

/// The kind of a solid element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SolidKind {
    /// 10-node tetrahedron (Gmsh type 11).
    Tet10,
    /// 20-node serendipity hexahedron (Gmsh type 17).
    Hex20,
    /// 27-node Lagrange hexahedron (Gmsh type 12).
    Hex27,
}

/// The kind of a face of a solid element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FaceKind {
    /// 6-node triangle, reference 0 ≤ s, t, s + t ≤ 1.
    Tri6,
    /// 8-node serendipity quadrilateral, reference [−1, 1]².
    Quad8,
    /// 9-node Lagrange quadrilateral, reference [−1, 1]².
    Quad9,
}

/// Shape functions and their derivatives with respect to the reference coordinates at a
/// point (zero past the element's nodes).
#[derive(Clone, Copy, Debug)]
pub struct SolidShape {
    /// Nₐ.
    pub n: [f64; MAX_SOLID_NODES],
    /// ∂Nₐ/∂(ξ, η, ζ).
    pub d: [[f64; 3]; MAX_SOLID_NODES],
}

/// A face's shape functions and their derivatives with respect to (s, t).
#[derive(Clone, Copy, Debug)]
pub struct FaceShape {
    /// Nₐ.
    pub n: [f64; MAX_FACE_NODES],
    /// ∂Nₐ/∂(s, t).
    pub d: [[f64; 2]; MAX_FACE_NODES],
}

/// One quadrature point of a reference element: coordinates and weight.
pub type QuadraturePoint = ([f64; 3], f64);

/// The 4-point rule of the tetrahedron, exact to degree 2 (Keast): a stiffness of straight
/// 10-node tetrahedra exactly; the barycentric coordinates (a, b, b, b) and permutations.
const TET4_A: f64 = 0.585_410_196_624_968_5;
/// See [`TET4_A`].
const TET4_B: f64 = 0.138_196_601_125_010_5;

impl SolidKind {
    /// Every kind.
    pub const ALL: [SolidKind; 3] = [SolidKind::Tet10, SolidKind::Hex20, SolidKind::Hex27];

    /// Number of nodes.
    pub const fn n_nodes(self) -> usize {
        match self {
            SolidKind::Tet10 => 10,
            SolidKind::Hex20 => 20,
            SolidKind::Hex27 => 27,
        }
    }

    /// Number of corner nodes (numbered first).
    pub const fn n_corners(self) -> usize {
        match self {
            SolidKind::Tet10 => 4,
            SolidKind::Hex20 | SolidKind::Hex27 => 8,
        }
    }

    /// The kind of its faces.
    pub const fn face_kind(self) -> FaceKind {
        match self {
            SolidKind::Tet10 => FaceKind::Tri6,
            SolidKind::Hex20 => FaceKind::Quad8,
            SolidKind::Hex27 => FaceKind::Quad9,
        }
    }

    /// Number of faces.
    pub const fn n_faces(self) -> usize {
        match self {
            SolidKind::Tet10 => 4,
            SolidKind::Hex20 | SolidKind::Hex27 => 6,
        }
    }

    /// The local nodes of face `local`, in the face's order (outward normal by the right-hand
    /// rule on the corners).
    pub fn face(self, local: usize) -> &'static [usize] {
        match self {
            SolidKind::Tet10 => TET_FACES[local],
            SolidKind::Hex20 => &HEX_FACES[local][..8],
            SolidKind::Hex27 => HEX_FACES[local],
        }
    }

    /// Reference coordinates of node `a`.
    pub fn reference_node(self, a: usize) -> [f64; 3] {
        match self {
            SolidKind::Tet10 => {
                const CORNERS: [[f64; 3]; 4] = [
                    [0.0, 0.0, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0, 0.0, 1.0],
                ];
                if a < 4 {
                    CORNERS[a]
                } else {
                    let (i, j) = TET_EDGES[a - 4];
                    std::array::from_fn(|c| 0.5 * (CORNERS[i][c] + CORNERS[j][c]))
                }
            }
            SolidKind::Hex20 | SolidKind::Hex27 => HEX_NODES[a],
        }
    }

    /// The reference centroid.
    pub fn centre(self) -> [f64; 3] {
        match self {
            SolidKind::Tet10 => [0.25; 3],
            SolidKind::Hex20 | SolidKind::Hex27 => [0.0; 3],
        }
    }

    /// Shape functions and their reference derivatives at `p`.
    pub fn shape(self, p: [f64; 3]) -> SolidShape {
        let mut s = SolidShape {
            n: [0.0; MAX_SOLID_NODES],
            d: [[0.0; 3]; MAX_SOLID_NODES],
        };
        match self {
            SolidKind::Tet10 => tet10(p, &mut s),
            SolidKind::Hex20 => hex20(p, &mut s),
            SolidKind::Hex27 => hex27(p, &mut s),
        }
        s
    }

    /// The volume quadrature: 4 points on the tetrahedron (degree 2), 3 × 3 × 3 Gauss points
    /// on the hexahedra.
    pub fn integration_points(self) -> Vec<QuadraturePoint> {
        match self {
            SolidKind::Tet10 => (0..4)
                .map(|k| {
                    let mut l = [TET4_B; 4];
                    l[k] = TET4_A;
                    ([l[1], l[2], l[3]], 1.0 / 24.0)
                })
                .collect(),
            SolidKind::Hex20 | SolidKind::Hex27 => {
                let mut points = Vec::with_capacity(27);
                for (z, wz) in GAUSS3 {
                    for (y, wy) in GAUSS3 {
                        for (x, wx) in GAUSS3 {
                            points.push(([x, y, z], wx * wy * wz));
                        }
                    }
                }
                points
            }
        }
    }
}

/// 10-node tetrahedron: Lᵢ(2Lᵢ − 1) at the corners, 4LᵢLⱼ at the mid-edge nodes, with the
/// barycentric L = (1 − ξ − η − ζ, ξ, η, ζ).
fn tet10(p: [f64; 3], s: &mut SolidShape) {
    let l = [1.0 - p[0] - p[1] - p[2], p[0], p[1], p[2]];
    // ∂Lᵢ/∂(ξ, η, ζ).
    let dl = [
        [-1.0, -1.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    for i in 0..4 {
        s.n[i] = l[i] * (2.0 * l[i] - 1.0);
        for c in 0..3 {
            s.d[i][c] = (4.0 * l[i] - 1.0) * dl[i][c];
        }
    }
    for (k, &(i, j)) in TET_EDGES.iter().enumerate() {
        s.n[4 + k] = 4.0 * l[i] * l[j];
        for c in 0..3 {
            s.d[4 + k][c] = 4.0 * (dl[i][c] * l[j] + l[i] * dl[j][c]);
        }
    }
}

/// 20-node serendipity hexahedron: ⅛∏(1 + ξξₐ)(ξξₐ + ηηₐ + ζζₐ − 2) at the corners,
/// ¼(1 − ξ²)(1 + ηηₐ)(1 + ζζₐ) at a mid-edge node with ξₐ = 0 (and its permutations).
fn hex20(p: [f64; 3], s: &mut SolidShape) {
    for (a, r) in HEX_NODES[..20].iter().enumerate() {
        let zero = r.iter().position(|&c| c == 0.0);
        match zero {
            None => {
                let f: [f64; 3] = std::array::from_fn(|c| 1.0 + p[c] * r[c]);
                let sum = p[0] * r[0] + p[1] * r[1] + p[2] * r[2] - 2.0;
                s.n[a] = 0.125 * f[0] * f[1] * f[2] * sum;
                for c in 0..3 {
                    let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
                    s.d[a][c] = 0.125 * f[c1] * f[c2] * r[c] * (sum + f[c]);
                }
            }
            Some(z) => {
                let (c1, c2) = ((z + 1) % 3, (z + 2) % 3);
                let g = 1.0 - p[z] * p[z];
                let (f1, f2) = (1.0 + p[c1] * r[c1], 1.0 + p[c2] * r[c2]);
                s.n[a] = 0.25 * g * f1 * f2;
                s.d[a][z] = -0.5 * p[z] * f1 * f2;
                s.d[a][c1] = 0.25 * g * r[c1] * f2;
                s.d[a][c2] = 0.25 * g * f1 * r[c2];
            }
        }
    }
}

/// 27-node Lagrange hexahedron: products of quadratic Lagrange polynomials.
fn hex27(p: [f64; 3], s: &mut SolidShape) {
    for (a, r) in HEX_NODES.iter().enumerate() {
        let l: [(f64, f64); 3] = std::array::from_fn(|c| lagrange2(r[c], p[c]));
        s.n[a] = l[0].0 * l[1].0 * l[2].0;
        s.d[a] = [
            l[0].1 * l[1].0 * l[2].0,
            l[0].0 * l[1].1 * l[2].0,
            l[0].0 * l[1].0 * l[2].1,
        ];
    }
}

impl FaceKind {
    /// Number of nodes.
    pub const fn n_nodes(self) -> usize {
        match self {
            FaceKind::Tri6 => 6,
            FaceKind::Quad8 => 8,
            FaceKind::Quad9 => 9,
        }
    }

    /// Number of corners.
    pub const fn n_corners(self) -> usize {
        match self {
            FaceKind::Tri6 => 3,
            FaceKind::Quad8 | FaceKind::Quad9 => 4,
        }
    }

    /// The plane element whose shape functions the face's are, in the same node order: the
    /// 6-node triangle, the 8-node serendipity or the 9-node Lagrange quadrilateral.
    pub const fn plane_kind(self) -> ElementKind {
        match self {
            FaceKind::Tri6 => ElementKind::T6,
            FaceKind::Quad8 => ElementKind::Q8,
            FaceKind::Quad9 => ElementKind::Q9,
        }
    }

    /// Shape functions and (s, t) derivatives: the quadratic triangle (corners, then the
    /// sides 0–1, 1–2, 2–0) or quadrilateral (corners, sides 0–1, 1–2, 2–3, 3–0, centre), the
    /// plane element's ([`FaceKind::plane_kind`]).
    pub fn shape(self, st: [f64; 2]) -> FaceShape {
        let s = self.plane_kind().shape(st[0], st[1]);
        FaceShape {
            n: s.n,
            d: std::array::from_fn(|a| [s.dxi[a], s.deta[a]]),
        }
    }

    /// Whether (s, t) lies on the reference face, to `slack`.
    pub fn contains(self, st: [f64; 2], slack: f64) -> bool {
        match self {
            FaceKind::Tri6 => st[0] >= -slack && st[1] >= -slack && st[0] + st[1] <= 1.0 + slack,
            FaceKind::Quad8 | FaceKind::Quad9 => st.iter().all(|c| c.abs() <= 1.0 + slack),
        }
    }

    /// The reference centre.
    pub fn centre(self) -> [f64; 2] {
        match self {
            FaceKind::Tri6 => [1.0 / 3.0; 2],
            FaceKind::Quad8 | FaceKind::Quad9 => [0.0; 2],
        }
    }

    /// The contact points of a face, with their weights: the load quadrature
    /// ([`FaceKind::load_points`]). At least as many points as the face has nodes, so that the
    /// faces' quadratic field that the point pressures sample (the body's pressure basis) is
    /// determined by them: with 3 points on a 6-node triangle or 2 × 2 on an 8-node
    /// quadrilateral the field's least-squares fit would be singular.
    pub fn contact_points(self) -> Vec<([f64; 2], f64)> {
        self.load_points()
    }

    /// The load quadrature of a face, the plane element's integration rule
    /// ([`ElementKind::integration_points`]): 6 points on a triangle (degree 4), 3 × 3 Gauss
    /// points on a quadrilateral (degree 5), so that pressures on curved faces integrate well.
    pub fn load_points(self) -> Vec<([f64; 2], f64)> {
        (self.plane_kind().integration_points().iter())
            .map(|p| ([p.xi, p.eta], p.weight))
            .collect()
    }
}

/// The cross product a × b.
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Round-off of a sum of shape functions or of a reproduced coordinate.
    const ROUND_OFF: f64 = 1e-13;
    /// Step of the central differences that check the derivatives, and their tolerance.
    const STEP: f64 = 1e-6;
    const DIFFERENCE: f64 = 1e-8;

    /// Each shape function is 1 at its node and 0 at the others; they sum to 1 and reproduce
    /// the reference coordinates (so a linear field exactly); the derivatives match central
    /// differences.
    #[test]
    fn shape_functions_interpolate_and_differentiate() {
        for kind in SolidKind::ALL {
            let n = kind.n_nodes();
            for a in 0..n {
                let s = kind.shape(kind.reference_node(a));
                for b in 0..n {
                    let want = if a == b { 1.0 } else { 0.0 };
                    assert!((s.n[b] - want).abs() < ROUND_OFF, "{kind:?} {a} {b}");
                }
            }
            let p = match kind {
                SolidKind::Tet10 => [0.21, 0.33, 0.17],
                _ => [0.3, -0.45, 0.6],
            };
            let s = kind.shape(p);
            assert!((s.n[..n].iter().sum::<f64>() - 1.0).abs() < ROUND_OFF);
            for c in 0..3 {
                let x: f64 = (0..n).map(|a| s.n[a] * kind.reference_node(a)[c]).sum();
                assert!((x - p[c]).abs() < ROUND_OFF);
                let mut plus = p;
                let mut minus = p;
                plus[c] += STEP;
                minus[c] -= STEP;
                let (sp, sm) = (kind.shape(plus), kind.shape(minus));
                for a in 0..n {
                    let fd = (sp.n[a] - sm.n[a]) / (2.0 * STEP);
                    assert!((fd - s.d[a][c]).abs() < DIFFERENCE, "{kind:?} {a} {c}");
                }
            }
        }
    }

    /// Each face's nodes are the element's nodes on it, in the face kind's order: the face's
    /// shape functions at its own nodes reproduce the element nodes' reference coordinates
    /// (mid-side between its corners), and the corners run counter-clockwise seen from outside
    /// (the normal points away from the centre).
    #[test]
    fn faces_are_ordered_and_outward() {
        for kind in SolidKind::ALL {
            let fk = kind.face_kind();
            for local in 0..kind.n_faces() {
                let face = kind.face(local);
                assert_eq!(face.len(), fk.n_nodes());
                let x: Vec<[f64; 3]> = face.iter().map(|&a| kind.reference_node(a)).collect();
                let nc = fk.n_corners();
                for k in 0..nc {
                    let (a, b) = (x[k], x[(k + 1) % nc]);
                    let mid: [f64; 3] = std::array::from_fn(|c| 0.5 * (a[c] + b[c]));
                    assert_eq!(x[nc + k], mid, "{kind:?} face {local} side {k}");
                }
                let fs = fk.shape(fk.centre());
                let mut t = [[0.0; 3]; 2];
                let mut centre = [0.0; 3];
                for (a, xa) in x.iter().enumerate() {
                    for c in 0..3 {
                        centre[c] += fs.n[a] * xa[c];
                        t[0][c] += fs.d[a][0] * xa[c];
                        t[1][c] += fs.d[a][1] * xa[c];
                    }
                }
                let normal = cross(t[0], t[1]);
                let out: f64 = (0..3)
                    .map(|c| normal[c] * (centre[c] - kind.centre()[c]))
                    .sum();
                assert!(out > 0.0, "{kind:?} face {local} points inwards");
            }
        }
    }

    /// The quadratures integrate their degree exactly: the volumes and ∫ξ²ηζ of the
    /// reference elements, the areas and ∫s²t of the reference faces.
    #[test]
    fn quadratures_integrate_exactly() {
        let tet: f64 = SolidKind::Tet10
            .integration_points()
            .iter()
            .map(|(p, w)| w * p[0] * p[1])
            .sum();
        assert!((tet - 1.0 / 120.0).abs() < ROUND_OFF);
        let hex: f64 = SolidKind::Hex20
            .integration_points()
            .iter()
            .map(|(p, w)| w * p[0] * p[0] * p[1] * p[1] * p[2] * p[2])
            .sum();
        assert!((hex - 8.0 / 27.0).abs() < ROUND_OFF);
        for (fk, area, s2t) in [
            (FaceKind::Tri6, 0.5, 1.0 / 60.0),
            (FaceKind::Quad8, 4.0, 0.0),
        ] {
            for rule in [fk.contact_points(), fk.load_points()] {
                let a: f64 = rule.iter().map(|(_, w)| w).sum();
                assert!((a - area).abs() < ROUND_OFF, "{fk:?}");
            }
            let m: f64 = (fk.load_points().iter())
                .map(|(p, w)| w * p[0] * p[0] * p[1])
                .sum();
            assert!((m - s2t).abs() < 1e-12, "{fk:?} {m}");
        }
    }
}
