//! The map Q of eq. (3.5): how a change of initial gap given at design nodes reaches the
//! interface points.

use crate::{check, Error, Interface, Result, GEOMETRY_TOLERANCE};

/// The gap change Δh(x) = L(x)·Δh (§4): Δh is given by its values at design `nodes`, and row i
/// of Q lists the nodes that point i of the interface depends on, with their weights.
///
/// A finite-element face describes Δh by its nodal values and the face's quadratic shape
/// functions ([`GapShape::new`] with the face rows); a Green's-function grid gives every point
/// its own value ([`GapShape::pointwise`]); a bearing roller changes its profile along its axis
/// only, the same at every point of a generator line ([`GapShape::extruded`]: the map
/// Δh_nv = f(Δh) of eq. 3.3 from the points off the line to those on it).
#[derive(Clone, Debug, PartialEq)]
pub struct GapShape {
    nodes: Vec<[f64; 3]>,
    rows: Vec<Vec<(usize, f64)>>,
}

impl GapShape {
    /// The map with design `nodes` (finite coordinates) and one row (node index, finite
    /// weight) per interface point.
    pub fn new(nodes: Vec<[f64; 3]>, rows: Vec<Vec<(usize, f64)>>) -> Result<Self> {
        if nodes.is_empty() {
            return Err(Error::invalid("gap_shape.nodes", 0, "at least one node"));
        }
        for (k, node) in nodes.iter().enumerate() {
            check::all_finite(&format!("gap_shape.nodes[{k}]"), node)?;
        }
        for (i, row) in rows.iter().enumerate() {
            if let Some(&(k, w)) = row
                .iter()
                .find(|(k, w)| *k >= nodes.len() || !w.is_finite())
            {
                return Err(Error::invalid(
                    format!("gap_shape.rows[{i}]"),
                    format!("({k}, {w})"),
                    format!("a node below {} with a finite weight", nodes.len()),
                ));
            }
        }
        Ok(Self { nodes, rows })
    }

    /// One design value per interface point: Q = I.
    pub fn pointwise(interface: &Interface) -> Self {
        Self {
            nodes: interface.points().to_vec(),
            rows: (0..interface.len()).map(|i| vec![(i, 1.0)]).collect(),
        }
    }

    /// One design value per distinct coordinate `axis` (0, 1 or 2) of the interface points,
    /// shared by every point with that coordinate (within 10⁻⁹ of the interface's size): a
    /// profile along one direction, extruded along the others.
    pub fn extruded(interface: &Interface, axis: usize) -> Result<Self> {
        Self::along(interface, axis, |c| c)
    }

    /// The gap change of [`GapShape::extruded`], symmetric about the plane x_axis = 0: one
    /// node per distinct |x_axis|, which moves the points at x_axis and −x_axis together (a
    /// crown that is the same at both ends of a roller).
    pub fn symmetric(interface: &Interface, axis: usize) -> Result<Self> {
        Self::along(interface, axis, f64::abs)
    }

    /// One node per distinct value of `coordinate` applied to x_axis.
    fn along(interface: &Interface, axis: usize, coordinate: fn(f64) -> f64) -> Result<Self> {
        if axis > 2 {
            return Err(Error::invalid("gap_shape.axis", axis, "0, 1 or 2"));
        }
        let coordinate: Vec<f64> = interface
            .points()
            .iter()
            .map(|x| coordinate(x[axis]))
            .collect();
        let size = coordinate
            .iter()
            .fold(0.0f64, |m, c| m.max(c.abs()))
            .max(f64::MIN_POSITIVE);
        let mut distinct = coordinate.clone();
        distinct.sort_by(f64::total_cmp);
        distinct.dedup_by(|a, b| (*a - *b).abs() <= GEOMETRY_TOLERANCE * size);
        let rows = coordinate
            .iter()
            .map(|c| {
                let k = distinct.partition_point(|d| *d < c - GEOMETRY_TOLERANCE * size);
                vec![(k, 1.0)]
            })
            .collect();
        let nodes = distinct
            .iter()
            .map(|&c| {
                let mut x = [0.0; 3];
                x[axis] = c;
                x
            })
            .collect();
        Ok(Self { nodes, rows })
    }

    /// The design nodes.
    pub fn nodes(&self) -> &[[f64; 3]] {
        &self.nodes
    }

    /// Number of interface points (rows of Q).
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// True when there are no points.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// Row i of Q: (node, weight) pairs.
    pub fn row(&self, i: usize) -> &[(usize, f64)] {
        &self.rows[i]
    }

    /// The gap change at the points, QΔh, from the node values `dh`.
    pub fn apply(&self, dh: &[f64]) -> Vec<f64> {
        self.rows
            .iter()
            .map(|row| row.iter().map(|&(k, w)| w * dh[k]).sum())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Geometry;

    /// Nodes with NaN or infinite coordinates are refused, each by its index.
    #[test]
    fn refuses_non_finite_nodes() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let nodes = vec![[0.0; 3], [1.0, bad, 0.0]];
            let e = GapShape::new(nodes, vec![vec![(0, 1.0)]]).unwrap_err();
            assert!(e.to_string().contains("gap_shape.nodes[1][1]"), "{e}");
        }
        assert!(GapShape::new(vec![[0.0; 3]], vec![vec![(0, 1.0)]]).is_ok());
    }

    #[test]
    fn extruded_shares_a_value_along_lines() {
        let points: Vec<[f64; 3]> = (0..6)
            .map(|k| [(k % 3) as f64 * 0.5, (k / 3) as f64, 0.0])
            .collect();
        let iface = Interface::new(
            Geometry::Surface,
            points,
            vec![1.0; 6],
            vec![[0.0, 0.0, 1.0]; 6],
        )
        .unwrap();
        let shape = GapShape::extruded(&iface, 0).unwrap();
        assert_eq!(shape.nodes().len(), 3);
        assert_eq!(
            shape.apply(&[1.0, 2.0, 3.0]),
            vec![1.0, 2.0, 3.0, 1.0, 2.0, 3.0]
        );
        assert!(GapShape::new(vec![[0.0; 3]], vec![vec![(1, 1.0)]]).is_err());
    }
}
