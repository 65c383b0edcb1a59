//! An element's Jacobian determinant: its sign over the element (the orientation), its
//! integral (the area), and the local order that reverses an element.

use std::sync::OnceLock;

use contopt_fem::element::{Shape, GAUSS3, MAX_NODES};

use crate::shim::Kind;

/// A Jacobian determinant within this fraction of the element's largest one counts as zero:
/// the element is degenerate there.
const JACOBIAN_ROUND_OFF: f64 = 1e-12;

/// Natural coordinates of a quadrilateral's nodes (Gmsh's and contopt's local order).
const QUAD_NODES: [[f64; 2]; 9] = [
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

/// Area coordinates (ξ, η) of a 6-node triangle's nodes and of its centroid.
const TRIANGLE_POINTS: [[f64; 2]; 7] = [
    [0.0, 0.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [0.5, 0.0],
    [0.5, 0.5],
    [0.0, 0.5],
    [1.0 / 3.0, 1.0 / 3.0],
];

/// The 3-point rule on the triangle (degree 2, exact for the 6-node triangle's det J):
/// points (ξ, η) and weights.
const TRIANGLE_RULE: [([f64; 2], f64); 3] = [
    ([1.0 / 6.0, 1.0 / 6.0], 1.0 / 6.0),
    ([2.0 / 3.0, 1.0 / 6.0], 1.0 / 6.0),
    ([1.0 / 6.0, 2.0 / 3.0], 1.0 / 6.0),
];

/// The local order of an element's nodes mirrored: the same element, run the other way round
/// (first corner kept, corners reversed, each mid-side node on its reversed side).
pub(crate) fn reversed(kind: Kind) -> &'static [usize] {
    match kind {
        Kind::Q8 => &[0, 3, 2, 1, 7, 6, 5, 4],
        Kind::Q9 => &[0, 3, 2, 1, 7, 6, 5, 4, 8],
        Kind::T6 => &[0, 2, 1, 5, 4, 3],
    }
}

/// The 3 × 3 Gauss rule on the square: points (ξ, η) and weights.
const QUAD_RULE: [([f64; 2], f64); 9] = {
    let mut rule = [([0.0; 2], 0.0); 9];
    let mut k = 0;
    while k < 9 {
        let ((x, wx), (y, wy)) = (GAUSS3[k / 3], GAUSS3[k % 3]);
        rule[k] = ([x, y], wx * wy);
        k += 1;
    }
    rule
};

/// Integration points and weights of an element's area: 3 × 3 Gauss points on a
/// quadrilateral (exact for the det J of straight- and curved-sided Q8 and Q9), the 3-point
/// rule on a triangle.
fn rule(kind: Kind) -> &'static [([f64; 2], f64)] {
    match kind {
        Kind::Q8 | Kind::Q9 => &QUAD_RULE,
        Kind::T6 => &TRIANGLE_RULE,
    }
}

/// Where an element's orientation is checked: its nodes (and a triangle's centroid) and its
/// integration points.
fn samples(kind: Kind) -> impl Iterator<Item = [f64; 2]> {
    let nodes: &[[f64; 2]] = match kind {
        Kind::Q8 => &QUAD_NODES[..8],
        Kind::Q9 => &QUAD_NODES,
        Kind::T6 => &TRIANGLE_POINTS,
    };
    nodes
        .iter()
        .copied()
        .chain(rule(kind).iter().map(|(p, _)| *p))
}

/// An element kind's shape functions at its samples and at its rule's points (with the
/// weights), computed once.
struct Tables {
    samples: Vec<Shape>,
    rule: Vec<(Shape, f64)>,
}

/// The [`Tables`] of `kind`.
fn tables(kind: Kind) -> &'static Tables {
    static TABLES: [OnceLock<Tables>; 3] = [const { OnceLock::new() }; 3];
    let k = match kind {
        Kind::Q8 => 0,
        Kind::Q9 => 1,
        Kind::T6 => 2,
    };
    TABLES[k].get_or_init(|| Tables {
        samples: samples(kind).map(|p| kind.shape(p[0], p[1])).collect(),
        rule: (rule(kind).iter())
            .map(|&(p, w)| (kind.shape(p[0], p[1]), w))
            .collect(),
    })
}

/// det J = ∂x/∂ξ ∂y/∂η − ∂y/∂ξ ∂x/∂η of an element with node coordinates `x`, at a point
/// whose shape functions are `s`.
fn det_j(s: &Shape, x: &[[f64; 2]]) -> f64 {
    let mut j = [[0.0; 2]; 2];
    for (a, xa) in x.iter().enumerate() {
        for c in 0..2 {
            j[0][c] += s.dxi[a] * xa[c];
            j[1][c] += s.deta[a] * xa[c];
        }
    }
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

/// The coordinates of the nodes `element` of `nodes`, on the stack.
pub(crate) fn coords(nodes: &[[f64; 2]], element: &[usize]) -> ([[f64; 2]; MAX_NODES], usize) {
    let mut x = [[0.0; 2]; MAX_NODES];
    for (xa, &n) in x.iter_mut().zip(element) {
        *xa = nodes[n];
    }
    (x, element.len().min(MAX_NODES))
}

/// How an element's nodes run, from the sign of its Jacobian determinant.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Orientation {
    /// det J > 0 everywhere checked: counter-clockwise.
    CounterClockwise,
    /// det J < 0 everywhere checked: clockwise.
    Clockwise,
    /// det J changes sign or vanishes: the element folds over itself.
    Folded {
        /// The smallest det J found.
        min: f64,
        /// The largest det J found.
        max: f64,
    },
}

/// The orientation of an element with node coordinates `x`: the sign of det J at its nodes
/// and integration points.
pub(crate) fn orientation(kind: Kind, x: &[[f64; 2]]) -> Orientation {
    let (min, max) = (tables(kind).samples.iter())
        .map(|s| det_j(s, x))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
            (lo.min(d), hi.max(d))
        });
    let zero = JACOBIAN_ROUND_OFF * min.abs().max(max.abs());
    if min > zero {
        Orientation::CounterClockwise
    } else if max < -zero {
        Orientation::Clockwise
    } else {
        Orientation::Folded { min, max }
    }
}

/// The area of an element with node coordinates `x`, ∫ det J dξ dη.
pub(crate) fn area(kind: Kind, x: &[[f64; 2]]) -> f64 {
    tables(kind).rule.iter().map(|(s, w)| w * det_j(s, x)).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit square and the right triangle of legs 2: areas 1 and 2, counter-clockwise;
    /// reversed, the same areas negated and clockwise.
    #[test]
    fn areas_and_reversal() {
        let square = [
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
            [0.5, 0.0],
            [1.0, 0.5],
            [0.5, 1.0],
            [0.0, 0.5],
            [0.5, 0.5],
        ];
        let triangle = [
            [0.0, 0.0],
            [2.0, 0.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
        ];
        for (kind, x, expect) in [
            (Kind::Q8, &square[..8], 1.0),
            (Kind::Q9, &square[..], 1.0),
            (Kind::T6, &triangle[..], 2.0),
        ] {
            assert!((area(kind, x) - expect).abs() < 1e-14, "{kind:?}");
            assert_eq!(orientation(kind, x), Orientation::CounterClockwise);
            let back: Vec<[f64; 2]> = reversed(kind).iter().map(|&a| x[a]).collect();
            assert!(
                (area(kind, &back) + expect).abs() < 1e-14,
                "{kind:?} reversed"
            );
            assert_eq!(orientation(kind, &back), Orientation::Clockwise);
        }
    }

    /// A mid-side node pulled past the opposite side folds the element: det J takes both
    /// signs.
    #[test]
    fn a_folded_element() {
        let mut x = [
            [0.0, 0.0],
            [2.0, 0.0],
            [0.0, 2.0],
            [1.0, 0.0],
            [1.0, 1.0],
            [0.0, 1.0],
        ];
        x[3] = [1.0, 1.9];
        assert!(matches!(
            orientation(Kind::T6, &x),
            Orientation::Folded { min, max } if min < 0.0 && max > 0.0
        ));
    }
}
