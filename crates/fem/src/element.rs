//! Quadratic isoparametric quadrilaterals: 8-node serendipity and 9-node Lagrange.
//!
//! Local node order: corners (−1,−1), (1,−1), (1,1), (−1,1); mid-sides (0,−1), (1,0), (0,1),
//! (−1,0); the 9-node element adds the centre (0,0). Faces run counter-clockwise:
//! face 0 = nodes 0-4-1, face 1 = 1-5-2, face 2 = 2-6-3, face 3 = 3-7-0.

use serde::{Deserialize, Serialize};

/// Largest number of nodes of an element.
pub const MAX_NODES: usize = 9;

/// Element type.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ElementKind {
    /// 8-node serendipity quadrilateral.
    Q8,
    /// 9-node Lagrange quadrilateral.
    Q9,
}

/// Local nodes of each face: (start, middle, end), counter-clockwise.
pub const FACE_NODES: [[usize; 3]; 4] = [[0, 4, 1], [1, 5, 2], [2, 6, 3], [3, 7, 0]];

const NATURAL: [[f64; 2]; 9] = [
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

/// Abscissae and weights of the 3-point Gauss–Legendre rule on [−1, 1].
pub const GAUSS3: [(f64, f64); 3] = [
    (-0.774_596_669_241_483_4, 5.0 / 9.0),
    (0.0, 8.0 / 9.0),
    (0.774_596_669_241_483_4, 5.0 / 9.0),
];

impl ElementKind {
    /// Number of nodes.
    pub fn n_nodes(self) -> usize {
        match self {
            ElementKind::Q8 => 8,
            ElementKind::Q9 => 9,
        }
    }

    /// Natural coordinates of local node `i`.
    pub fn natural(self, i: usize) -> [f64; 2] {
        NATURAL[i]
    }

    /// Shape functions N and their derivatives ∂N/∂ξ, ∂N/∂η at (ξ, η).
    pub fn shape(self, xi: f64, eta: f64) -> Shape {
        let mut s = Shape::default();
        match self {
            ElementKind::Q8 => {
                for (i, &[xi_i, eta_i]) in NATURAL.iter().enumerate().take(8) {
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
            }
            ElementKind::Q9 => {
                for (i, &[xi_i, eta_i]) in NATURAL.iter().enumerate() {
                    let (lx, dlx) = lagrange2(xi_i, xi);
                    let (ly, dly) = lagrange2(eta_i, eta);
                    s.n[i] = lx * ly;
                    s.dxi[i] = dlx * ly;
                    s.deta[i] = lx * dly;
                }
            }
        }
        s
    }
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
        for kind in [ElementKind::Q8, ElementKind::Q9] {
            let n = kind.n_nodes();
            for j in 0..n {
                let [x, y] = kind.natural(j);
                let s = kind.shape(x, y);
                for i in 0..n {
                    let expect = if i == j { 1.0 } else { 0.0 };
                    assert!((s.n[i] - expect).abs() < 1e-14, "{kind:?} N{i} at node {j}");
                }
            }
            let s = kind.shape(0.3, -0.7);
            assert!((s.n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            assert!(s.dxi.iter().sum::<f64>().abs() < 1e-14);
            assert!(s.deta.iter().sum::<f64>().abs() < 1e-14);
        }
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let h = 1e-6;
        for kind in [ElementKind::Q8, ElementKind::Q9] {
            let (x, y) = (0.37, -0.21);
            let s = kind.shape(x, y);
            let (sx, sy) = (kind.shape(x + h, y), kind.shape(x, y + h));
            for i in 0..kind.n_nodes() {
                assert!((s.dxi[i] - (sx.n[i] - s.n[i]) / h).abs() < 1e-5);
                assert!((s.deta[i] - (sy.n[i] - s.n[i]) / h).abs() < 1e-5);
            }
        }
    }
}
