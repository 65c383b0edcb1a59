//! Quadratic isoparametric elements: the 8-node serendipity and 9-node Lagrange
//! quadrilaterals, and the 6-node triangle.
//!
//! Quadrilaterals, natural coordinates (ξ, η) ∈ [−1, 1]²: corners (−1,−1), (1,−1), (1,1),
//! (−1,1); mid-sides (0,−1), (1,0), (0,1), (−1,0); the 9-node element adds the centre (0,0).
//! Faces run counter-clockwise: face 0 = nodes 0-4-1, face 1 = 1-5-2, face 2 = 2-6-3,
//! face 3 = 3-7-0.
//!
//! The triangle (Gmsh's element type 9, in its local order), natural coordinates the area
//! coordinates (ξ, η) = (L₂, L₃) with L₁ = 1 − ξ − η: corners (0,0), (1,0), (0,1),
//! counter-clockwise; mid-sides 0-1 (½,0), 1-2 (½,½), 2-0 (0,½). Faces: face 0 = nodes 0-3-1,
//! face 1 = 1-4-2, face 2 = 2-5-0. Every face is (start, middle, end), counter-clockwise, and
//! the element's shape functions reduce on it to the 1-D quadratic through its three nodes.

use serde::{Deserialize, Serialize};

/// Largest number of nodes of an element.
pub const MAX_NODES: usize = 9;

/// Largest number of integration points of an element (the quadrilaterals' 3 × 3).
pub const MAX_POINTS: usize = 9;

/// Element type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ElementKind {
    /// 8-node serendipity quadrilateral.
    Q8,
    /// 9-node Lagrange quadrilateral.
    Q9,
    /// 6-node quadratic triangle.
    T6,
}

/// Local nodes of each face of a quadrilateral: (start, middle, end), counter-clockwise.
const QUAD_FACES: [[usize; 3]; 4] = [[0, 4, 1], [1, 5, 2], [2, 6, 3], [3, 7, 0]];

/// Local nodes of each face of a triangle: (start, middle, end), counter-clockwise.
const TRIANGLE_FACES: [[usize; 3]; 3] = [[0, 3, 1], [1, 4, 2], [2, 5, 0]];

const QUAD_NATURAL: [[f64; 2]; 9] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
    [0.0, 0.0],
];

/// Area coordinates (L₂, L₃) of the triangle's nodes.
const TRIANGLE_NATURAL: [[f64; 2]; 6] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
];

/// Abscissae and weights of the 3-point Gauss–Legendre rule on [−1, 1].
pub const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

/// An integration point of an element: natural coordinates and weight (the reference
/// element's measure included: the weights of a quadrilateral sum to 4, of a triangle to ½).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct IntegrationPoint {
    /// ξ (L₂ on a triangle).
    pub xi: f64,
    /// η (L₃ on a triangle).
    pub eta: f64,
    /// Weight.
    pub weight: f64,
}

/// The 3 × 3 Gauss rule of the quadrilaterals, point 3i + j at (ξ, η) = (gᵢ, gⱼ) with weight
/// wᵢwⱼ.
const QUAD_POINTS: [IntegrationPoint; 9] = {
    let mut p = [IntegrationPoint {
        xi: 0.0,
        eta: 0.0,
        weight: 0.0,
    }; 9];
    let mut k = 0;
    while k < 9 {
        let ((xi, wx), (eta, wy)) = (GAUSS3[k / 3], GAUSS3[k % 3]);
        p[k] = IntegrationPoint {
            xi,
            eta,
            weight: wx * wy,
        };
        k += 1;
    }
    p
};

/// Area coordinate a of the first orbit (a, a, 1 − 2a) of the triangle rule, and the
/// weight of each of its points relative to the area.
const TRIANGLE_ORBIT_A: (f64, f64) = (0.445_948_490_915_964_9, 0.223_381_589_678_011_47);

/// The second orbit, its points near the corners.
const TRIANGLE_ORBIT_B: (f64, f64) = (0.091_576_213_509_770_74, 0.109_951_743_655_321_87);

/// The symmetric 6-point rule of degree 4 on the triangle (Cowper 1973, "Gaussian quadrature
/// formulas for triangles", Int. J. Numer. Meth. Engng 7, 405–408; Dunavant 1985, "High
/// degree efficient symmetrical Gaussian quadrature rules for the triangle", Int. J. Numer.
/// Meth. Engng 21, 1129–1148, degree 4): two orbits of three points (a, a, 1 − 2a) in area
/// coordinates, the first orbit's points 0-2, the second's 3-5, the point of each orbit with
/// the odd coordinate 1 − 2a on L₁, L₂, L₃ in turn. Weights are relative to the area, times
/// ½. The constants are the roots of the moment equations to 17 digits (the test
/// `integration_rules_have_their_degree` checks every monomial of degree ≤ 4).
const TRIANGLE_POINTS: [IntegrationPoint; 6] = {
    let mut p = [IntegrationPoint {
        xi: 0.0,
        eta: 0.0,
        weight: 0.0,
    }; 6];
    let orbits = [TRIANGLE_ORBIT_A, TRIANGLE_ORBIT_B];
    let mut k = 0;
    while k < 6 {
        let (a, w) = orbits[k / 3];
        let b = 1.0 - 2.0 * a;
        let (xi, eta) = match k % 3 {
            0 => (a, a),
            1 => (b, a),
            _ => (a, b),
        };
        p[k] = IntegrationPoint {
            xi,
            eta,
            weight: 0.5 * w,
        };
        k += 1;
    }
    p
};

impl ElementKind {
    /// Every kind, in declaration order.
    pub const ALL: [ElementKind; 3] = [ElementKind::Q8, ElementKind::Q9, ElementKind::T6];

    /// Number of nodes.
    pub fn n_nodes(self) -> usize {
        match self {
            ElementKind::Q8 => 8,
            ElementKind::Q9 => 9,
            ElementKind::T6 => 6,
        }
    }

    /// Number of faces (edges).
    pub fn n_faces(self) -> usize {
        match self {
            ElementKind::Q8 | ElementKind::Q9 => QUAD_FACES.len(),
            ElementKind::T6 => TRIANGLE_FACES.len(),
        }
    }

    /// Local nodes (start, middle, end) of face `local` (< [`ElementKind::n_faces`]),
    /// counter-clockwise around the element.
    pub fn face_nodes(self, local: usize) -> [usize; 3] {
        match self {
            ElementKind::Q8 | ElementKind::Q9 => QUAD_FACES[local],
            ElementKind::T6 => TRIANGLE_FACES[local],
        }
    }

    /// Natural coordinates of local node `i` (< [`ElementKind::n_nodes`]): (ξ, η) of a
    /// quadrilateral, the area coordinates (L₂, L₃) of a triangle.
    pub fn natural(self, i: usize) -> [f64; 2] {
        match self {
            ElementKind::Q8 | ElementKind::Q9 => QUAD_NATURAL[i],
            ElementKind::T6 => TRIANGLE_NATURAL[i],
        }
    }

    /// The integration rule of the element's stiffness, stresses and error norms: 3 × 3
    /// Gauss points on a quadrilateral (point 3i + j at (gᵢ, gⱼ)); on the triangle the
    /// symmetric 6-point rule of degree 4 (Cowper 1973, Dunavant 1985). On a straight-sided
    /// triangle B is linear, so BᵀDB (degree 2) is integrated exactly in plane analyses with
    /// room to spare; in axisymmetry the terms of BᵀDB·2πr in ∂N ∂N r and ∂N N (degree 3) are
    /// exact and only the hoop term N N/r, not a polynomial, is approximated.
    pub fn integration_points(self) -> &'static [IntegrationPoint] {
        match self {
            ElementKind::Q8 | ElementKind::Q9 => &QUAD_POINTS,
            ElementKind::T6 => &TRIANGLE_POINTS,
        }
    }

    /// Shape functions N and their derivatives ∂N/∂ξ, ∂N/∂η at (ξ, η) (on a triangle the
    /// area coordinates (L₂, L₃), see [`ElementKind::natural`]).
    pub fn shape(self, xi: f64, eta: f64) -> Shape {
        match self {
            ElementKind::Q8 => serendipity(xi, eta),
            ElementKind::Q9 => lagrange(xi, eta),
            ElementKind::T6 => triangle(xi, eta),
        }
    }
}

/// The 8-node serendipity shape functions.
fn serendipity(xi: f64, eta: f64) -> Shape {
    let mut s = Shape::default();
    for (i, &[xi_i, eta_i]) in QUAD_NATURAL.iter().enumerate().take(8) {
        let (n, dxi, deta) = if i < 4 {
            let (a, b) = (1.0 + xi * xi_i, 1.0 + eta * eta_i);
            let c = xi * xi_i + eta * eta_i - 1.0;
            (
                0.25 * a * b * c,
                0.25 * xi_i * b * (c + a),
                0.25 * eta_i * a * (c + b),
            )
        } else if xi_i == 0.0 {
            let b = 1.0 + eta * eta_i;
            (
                0.5 * (1.0 - xi * xi) * b,
                -xi * b,
                0.5 * (1.0 - xi * xi) * eta_i,
            )
        } else {
            let a = 1.0 + xi * xi_i;
            (
                0.5 * a * (1.0 - eta * eta),
                0.5 * xi_i * (1.0 - eta * eta),
                -eta * a,
            )
        };
        s.n[i] = n;
        s.dxi[i] = dxi;
        s.deta[i] = deta;
    }
    s
}

/// The 9-node Lagrange shape functions: products of the 1-D quadratics.
fn lagrange(xi: f64, eta: f64) -> Shape {
    let mut s = Shape::default();
    for (i, &[xi_i, eta_i]) in QUAD_NATURAL.iter().enumerate() {
        let (lx, dlx) = lagrange2(xi_i, xi);
        let (ly, dly) = lagrange2(eta_i, eta);
        s.n[i] = lx * ly;
        s.dxi[i] = dlx * ly;
        s.deta[i] = lx * dly;
    }
    s
}

/// The 6-node triangle's shape functions in the area coordinates L₁ = 1 − ξ − η, L₂ = ξ,
/// L₃ = η: corners Lᵢ(2Lᵢ − 1), mid-sides 4L₁L₂, 4L₂L₃, 4L₃L₁ (Zienkiewicz, Taylor & Zhu,
/// *The Finite Element Method*, 7th ed., §6.7.1).
fn triangle(xi: f64, eta: f64) -> Shape {
    let (l1, l2, l3) = (1.0 - xi - eta, xi, eta);
    let mut s = Shape::default();
    let n = [
        l1 * (2.0 * l1 - 1.0),
        l2 * (2.0 * l2 - 1.0),
        l3 * (2.0 * l3 - 1.0),
        4.0 * l1 * l2,
        4.0 * l2 * l3,
        4.0 * l3 * l1,
    ];
    // ∂/∂ξ = ∂/∂L₂ − ∂/∂L₁ and ∂/∂η = ∂/∂L₃ − ∂/∂L₁.
    let dxi = [
        1.0 - 4.0 * l1,
        4.0 * l2 - 1.0,
        0.0,
        4.0 * (l1 - l2),
        4.0 * l3,
        -4.0 * l3,
    ];
    let deta = [
        1.0 - 4.0 * l1,
        0.0,
        4.0 * l3 - 1.0,
        -4.0 * l2,
        4.0 * l2,
        4.0 * (l1 - l3),
    ];
    s.n[..6].copy_from_slice(&n);
    s.dxi[..6].copy_from_slice(&dxi);
    s.deta[..6].copy_from_slice(&deta);
    s
}

/// 1-D quadratic Lagrange polynomial of the node at `node` ∈ {−1, 0, 1}, and its derivative.
pub fn lagrange2(node: f64, s: f64) -> (f64, f64) {
    if node < 0.0 {
        (0.5 * s * (s - 1.0), s - 0.5)
    } else if node > 0.0 {
        (0.5 * s * (s + 1.0), s + 0.5)
    } else {
        (1.0 - s * s, -2.0 * s)
    }
}

/// Shape functions and natural derivatives at one point (unused trailing entries are zero).
#[derive(Clone, Copy, Debug, Default)]
pub struct Shape {
    /// N_i.
    pub n: [f64; MAX_NODES],
    /// ∂N_i/∂ξ.
    pub dxi: [f64; MAX_NODES],
    /// ∂N_i/∂η.
    pub deta: [f64; MAX_NODES],
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kronecker_and_partition_of_unity() {
        for kind in ElementKind::ALL {
            let n = kind.n_nodes();
            for j in 0..n {
                let [x, y] = kind.natural(j);
                let s = kind.shape(x, y);
                for i in 0..n {
                    let expect = if i == j { 1.0 } else { 0.0 };
                    assert!((s.n[i] - expect).abs() < 1e-14, "{kind:?} N{i} at node {j}");
                }
            }
            let s = kind.shape(0.3, 0.2);
            assert!((s.n.iter().sum::<f64>() - 1.0).abs() < 1e-14, "{kind:?}");
            assert!(s.dxi.iter().sum::<f64>().abs() < 1e-14, "{kind:?}");
            assert!(s.deta.iter().sum::<f64>().abs() < 1e-14, "{kind:?}");
            // Linear completeness: Σ Nₐ ξₐ = ξ, Σ Nₐ ηₐ = η (isoparametric: the element can
            // take a uniform strain).
            let (xi, eta) = (0.3, 0.2);
            let sum = |f: &dyn Fn(usize) -> f64| (0..n).map(|a| s.n[a] * f(a)).sum::<f64>();
            assert!(
                (sum(&|a| kind.natural(a)[0]) - xi).abs() < 1e-14,
                "{kind:?}"
            );
            assert!(
                (sum(&|a| kind.natural(a)[1]) - eta).abs() < 1e-14,
                "{kind:?}"
            );
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for kind in ElementKind::ALL {
            let (x, y) = (0.37, 0.21);
            let s = kind.shape(x, y);
            let (sx, sy) = (kind.shape(x + h, y), kind.shape(x, y + h));
            let (mx, my) = (kind.shape(x - h, y), kind.shape(x, y - h));
            for i in 0..kind.n_nodes() {
                // Central differences: error O(h²) ≈ 1e-12 for quadratics (round-off 1e-10).
                let (fx, fy) = (
                    (sx.n[i] - mx.n[i]) / (2.0 * h),
                    (sy.n[i] - my.n[i]) / (2.0 * h),
                );
                assert!((s.dxi[i] - fx).abs() < 1e-8, "{kind:?} dN{i}/dxi");
                assert!((s.deta[i] - fy).abs() < 1e-8, "{kind:?} dN{i}/deta");
            }
        }
    }

    /// A face's three nodes carry the element's shape functions along it as the 1-D
    /// quadratic of the face (start, middle, end), and the others vanish there: what face
    /// loads and contact points assume.
    #[test]
    fn faces_reduce_to_the_one_dimensional_quadratic() {
        for kind in ElementKind::ALL {
            for local in 0..kind.n_faces() {
                let [a, m, b] = kind.face_nodes(local);
                let (pa, pb) = (kind.natural(a), kind.natural(b));
                let mid = kind.natural(m);
                assert_eq!(mid, [0.5 * (pa[0] + pb[0]), 0.5 * (pa[1] + pb[1])]);
                for s in [-0.8, -0.3, 0.4, 0.9] {
                    let t = 0.5 * (1.0 + s);
                    let p = [pa[0] + t * (pb[0] - pa[0]), pa[1] + t * (pb[1] - pa[1])];
                    let shape = kind.shape(p[0], p[1]);
                    for i in 0..kind.n_nodes() {
                        let want = match [a, m, b].iter().position(|&k| k == i) {
                            Some(k) => lagrange2([-1.0, 0.0, 1.0][k], s).0,
                            None => 0.0,
                        };
                        assert!((shape.n[i] - want).abs() < 1e-14, "{kind:?} face {local}");
                    }
                }
            }
        }
    }

    /// The triangle rule integrates every monomial ξⁱηʲ of degree ≤ 4 over the reference
    /// triangle exactly, ∫ ξⁱηʲ = i! j! / (i + j + 2)!, and not every one of degree 5 (it is
    /// the rule of degree 4, not a mislabelled rule of higher degree); the quadrilateral rule
    /// integrates ξⁱηʲ, i, j ≤ 5.
    #[test]
    fn integration_rules_have_their_degree() {
        let factorial = |n: i32| (1..=n).map(f64::from).product::<f64>();
        let rule = |kind: ElementKind, i: i32, j: i32| {
            kind.integration_points()
                .iter()
                .map(|p| p.weight * p.xi.powi(i) * p.eta.powi(j))
                .sum::<f64>()
        };
        let mut worst_fifth: f64 = 0.0;
        for degree in 0..=5 {
            for i in 0..=degree {
                let j = degree - i;
                let exact = factorial(i) * factorial(j) / factorial(i + j + 2);
                let error = (rule(ElementKind::T6, i, j) - exact).abs() / exact;
                if degree <= 4 {
                    assert!(error < 1e-14, "xi^{i} eta^{j}: {error:e}");
                } else {
                    worst_fifth = worst_fifth.max(error);
                }
            }
        }
        assert!(worst_fifth > 1e-3, "{worst_fifth:e}");
        let one_d = |k: i32| {
            if k % 2 == 1 {
                0.0
            } else {
                2.0 / f64::from(k + 1)
            }
        };
        for i in 0..=5 {
            for j in 0..=5 {
                let exact = one_d(i) * one_d(j);
                assert!(
                    (rule(ElementKind::Q8, i, j) - exact).abs() < 1e-14,
                    "{i} {j}"
                );
            }
        }
    }
}
