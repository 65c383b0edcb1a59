//! An element's Jacobian determinant: its sign over the element (the orientation), its
//! integral (the area), and the local order that reverses an element.

use std::sync::OnceLock;

use contopt_fem::element::{Shape, MAX_NODES};
use contopt_fem::ElementKind;

/// A Jacobian determinant within this fraction of the element's largest one counts as zero:
/// the element is degenerate there.
const JACOBIAN_ROUND_OFF: f64 = 1e-12;

/// The local order of an element's nodes mirrored: the same element, run the other way round
/// (first corner kept, corners reversed, each mid-side node on its reversed side).
pub(crate) fn reversed(kind: ElementKind) -> &'static [usize] {
    match kind {
        ElementKind::Q8 => &[0, 3, 2, 1, 7, 6, 5, 4],
        ElementKind::Q9 => &[0, 3, 2, 1, 7, 6, 5, 4, 8],
        ElementKind::T6 => &[0, 2, 1, 5, 4, 3],
    }
}

/// An element kind's shape functions at its nodes and integration points (where its
/// orientation is checked), and at its integration points with their weights (its area),
/// computed once.
struct Tables {
    samples: Vec<Shape>,
    rule: Vec<(Shape, f64)>,
}

/// The [`Tables`] of `kind`: contopt-fem's own nodes and integration rule (3 × 3 Gauss points
/// on a quadrilateral, exact for the det J of straight- and curved-sided Q8 and Q9; the
/// degree-4 rule on a triangle, exact for a T6's det J, of degree 2).
fn tables(kind: ElementKind) -> &'static Tables {
    static TABLES: [OnceLock<Tables>; ElementKind::ALL.len()] =
        [const { OnceLock::new() }; ElementKind::ALL.len()];
    let k = ElementKind::ALL
        .iter()
        .position(|&a| a == kind)
        .unwrap_or_default();
    TABLES[k].get_or_init(|| {
        let rule = kind.integration_points();
        let nodes = (0..kind.n_nodes()).map(|i| kind.natural(i));
        Tables {
            samples: nodes
                .chain(rule.iter().map(|p| [p.xi, p.eta]))
                .map(|[xi, eta]| kind.shape(xi, eta))
                .collect(),
            rule: rule
                .iter()
                .map(|p| (kind.shape(p.xi, p.eta), p.weight))
                .collect(),
        }
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
pub(crate) fn orientation(kind: ElementKind, x: &[[f64; 2]]) -> Orientation {
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
pub(crate) fn area(kind: ElementKind, x: &[[f64; 2]]) -> f64 {
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
            (ElementKind::Q8, &square[..8], 1.0),
            (ElementKind::Q9, &square[..], 1.0),
            (ElementKind::T6, &triangle[..], 2.0),
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
            orientation(ElementKind::T6, &x),
            Orientation::Folded { min, max } if min < 0.0 && max > 0.0
        ));
    }
}
