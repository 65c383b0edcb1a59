//! A body's fields over its own mesh under a case's solution, for a viewer (ParaView): the
//! nodes, the cells with their kind, and the displacement and stress at every node. Bodies
//! with a mesh give them through [`crate::ElasticBody::fields`]; a report writes them (as a
//! VTK file) without knowing which body made them.

use crate::{check, Error, Result, StressTensor};

/// The kind of a cell of a mesh, with its local node order (the order of VTK's cells of the
/// same shape, so that a viewer draws it as it is).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellKind {
    /// The 8-node serendipity quadrilateral: the corners counter-clockwise, then the mid-side
    /// nodes of the sides 0-1, 1-2, 2-3, 3-0 (VTK's quadratic quad).
    QuadraticQuad,
    /// The 9-node Lagrange quadrilateral: a [`CellKind::QuadraticQuad`]'s nodes and the centre
    /// (VTK's bi-quadratic quad).
    BiquadraticQuad,
    /// The 6-node triangle: the corners counter-clockwise, then the mid-side nodes of the
    /// sides 0-1, 1-2, 2-0 (VTK's quadratic triangle).
    QuadraticTriangle,
    /// The 10-node tetrahedron: the corners, then the mid-edge nodes of the edges 0-1, 1-2,
    /// 2-0, 0-3, 1-3, 2-3 (VTK's quadratic tetra).
    QuadraticTetra,
    /// The 20-node hexahedron: the corners of the bottom and the top face, then the mid-edge
    /// nodes of the bottom's edges, the top's, and the four edges between (VTK's quadratic
    /// hexahedron).
    QuadraticHexahedron,
    /// The 27-node hexahedron: a [`CellKind::QuadraticHexahedron`]'s nodes, the centres of
    /// the faces −x, +x, −y, +y, −z, +z and the centre (VTK's tri-quadratic hexahedron).
    TriquadraticHexahedron,
}

impl CellKind {
    /// Number of nodes of a cell of this kind.
    pub fn nodes(self) -> usize {
        match self {
            CellKind::QuadraticQuad => 8,
            CellKind::BiquadraticQuad => 9,
            CellKind::QuadraticTriangle => 6,
            CellKind::QuadraticTetra => 10,
            CellKind::QuadraticHexahedron => 20,
            CellKind::TriquadraticHexahedron => 27,
        }
    }
}

/// One cell: its kind and its nodes (indices into [`BodyFields::points`]) in the kind's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Cell {
    /// Its kind.
    pub kind: CellKind,
    /// Its nodes.
    pub nodes: Vec<usize>,
}

/// A body's fields over its own mesh under a case's solution: where its nodes are, how its
/// cells join them, and the displacement and the stress at every node.
///
/// Everything is in the frame of `points`: a plane or axisymmetric body puts its model's x
/// (r) and y (z) in the first two coordinates and 0 in the third, so that `stress.zz` is the
/// out-of-plane stress (σ_θ, the hoop stress, in axisymmetry; ν(σ_xx + σ_yy) in plane strain;
/// 0 in plane stress), `stress.xy` the in-plane shear τ_xy (τ_rz) and `xz` = `yz` = 0. (This
/// is not the convention of [`StressTensor`] below a contact surface, where z is the depth:
/// a viewer draws the body in its own coordinates.)
#[derive(Clone, Debug, PartialEq)]
pub struct BodyFields {
    /// Node coordinates \[mm\], undeformed.
    pub points: Vec<[f64; 3]>,
    /// The cells.
    pub cells: Vec<Cell>,
    /// Displacement of each node \[mm\]: the deformation and the rigid-body motion (a floating
    /// body's approach), so that the deformed body sits where the solution puts it.
    pub displacement: Vec<[f64; 3]>,
    /// Stress at each node \[MPa\], tension positive.
    pub stress: Vec<StressTensor>,
}

impl BodyFields {
    /// The fields, checked: one displacement and one stress per point, each cell with its
    /// kind's number of nodes, every node index a point, every value finite. `body` names the
    /// body in errors.
    pub fn new(
        body: &str,
        points: Vec<[f64; 3]>,
        cells: Vec<Cell>,
        displacement: Vec<[f64; 3]>,
        stress: Vec<StressTensor>,
    ) -> Result<Self> {
        let n = points.len();
        for (what, len) in [
            ("displacement", displacement.len()),
            ("stress", stress.len()),
        ] {
            if len != n {
                return Err(Error::invalid(
                    format!("{body}.fields.{what}"),
                    len,
                    format!("one per point ({n})"),
                ));
            }
        }
        for (k, cell) in cells.iter().enumerate() {
            let field = format!("{body}.fields.cells[{k}]");
            if cell.nodes.len() != cell.kind.nodes() {
                return Err(Error::invalid(
                    field,
                    format!("{} nodes", cell.nodes.len()),
                    format!("a {:?} has {}", cell.kind, cell.kind.nodes()),
                ));
            }
            if let Some(node) = cell.nodes.iter().find(|&&i| i >= n) {
                return Err(Error::invalid(
                    field,
                    format!("node {node}"),
                    format!("a point below {n}"),
                ));
            }
        }
        let flat = |v: &[[f64; 3]]| v.iter().flatten().copied().collect::<Vec<f64>>();
        check::all_finite(&format!("{body}.fields.points"), &flat(&points))?;
        check::all_finite(&format!("{body}.fields.displacement"), &flat(&displacement))?;
        if let Some(k) = stress.iter().position(|s| !s.is_finite()) {
            return Err(Error::invalid(
                format!("{body}.fields.stress[{k}]"),
                format!("{:?}", stress[k]),
                "is not finite",
            ));
        }
        Ok(Self {
            points,
            cells,
            displacement,
            stress,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn square(kind: CellKind, nodes: Vec<usize>) -> Result<BodyFields> {
        let points = vec![[0.0; 3]; 9];
        BodyFields::new(
            "block",
            points,
            vec![Cell { kind, nodes }],
            vec![[0.0; 3]; 9],
            vec![StressTensor::default(); 9],
        )
    }

    #[test]
    fn cells_and_arrays_are_checked() {
        assert!(square(CellKind::BiquadraticQuad, (0..9).collect()).is_ok());
        let short = square(CellKind::BiquadraticQuad, (0..8).collect()).unwrap_err();
        assert!(
            short.to_string().contains("block.fields.cells[0]"),
            "{short}"
        );
        let outside = square(CellKind::QuadraticTriangle, vec![0, 1, 2, 3, 4, 9]).unwrap_err();
        assert!(outside.to_string().contains("node 9"), "{outside}");
        let few = BodyFields::new("block", vec![[0.0; 3]; 2], vec![], vec![[0.0; 3]], vec![])
            .unwrap_err();
        assert!(
            few.to_string().contains("block.fields.displacement"),
            "{few}"
        );
        let nan = BodyFields::new(
            "block",
            vec![[0.0; 3]],
            vec![],
            vec![[f64::NAN, 0.0, 0.0]],
            vec![StressTensor::default()],
        )
        .unwrap_err();
        assert!(
            nan.to_string().contains("block.fields.displacement"),
            "{nan}"
        );
    }
}
