//! The fields of a solid body under a contact solution, for ParaView: its mesh (cells in VTK's
//! node order), the displacement of every node (the rigid motion included) and the stress at
//! every node, averaged over the elements that share it.

use contopt_core::{BodyFields, Cell, CellKind, ElasticBody, Result, StressTensor};

use super::body::SolidBody;
use super::element::SolidKind;

/// VTK's cell of an element kind and, for each VTK node, the element's (Gmsh's) local node.
fn vtk_cell(kind: SolidKind) -> (CellKind, &'static [usize]) {
    match kind {
        SolidKind::Tet10 => (CellKind::QuadraticTetra, &[0, 1, 2, 3, 4, 5, 6, 7, 9, 8]),
        SolidKind::Hex20 => (CellKind::QuadraticHexahedron, &HEX_TO_VTK[..20]),
        SolidKind::Hex27 => (CellKind::TriquadraticHexahedron, &HEX_TO_VTK),
    }
}

/// Gmsh's local node of each of VTK's hexahedron nodes: corners alike; VTK's mid-edge nodes
/// run round the bottom, round the top, then up the sides; its face centres are −x, +x, −y,
/// +y, −z, +z.
const HEX_TO_VTK: [usize; 27] = [
    0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25,
    26,
];

impl SolidBody {
    /// The body's fields under the contact pressure `pressure` \[MPa\] at the interface points
    /// and its given loads, with rigid-mode amplitudes `rigid`: the nodal displacements
    /// ([`SolidBody::displacement`]) and the stresses at each element's nodes, averaged over
    /// the elements that share a node.
    pub fn mesh_fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<BodyFields> {
        let weights = self.interface().weights();
        let force: Vec<f64> = pressure.iter().zip(weights).map(|(p, w)| p * w).collect();
        let u = self.displacement(&force, rigid)?;
        let mesh = self.model.mesh();
        let n = mesh.nodes().len();
        let mut sum = vec![[0.0; 6]; n];
        let mut count = vec![0usize; n];
        let mut cells = Vec::with_capacity(mesh.n_elements());
        for e in 0..mesh.n_elements() {
            let kind = mesh.kind(e);
            let conn = mesh.element(e);
            for (a, &node) in conn.iter().enumerate() {
                let s = self.model.stress_at(&u, e, kind.reference_node(a))?;
                let v = [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz];
                sum[node].iter_mut().zip(v).for_each(|(t, x)| *t += x);
                count[node] += 1;
            }
            let (cell, order) = vtk_cell(kind);
            cells.push(Cell {
                kind: cell,
                nodes: order.iter().map(|&a| conn[a]).collect(),
            });
        }
        let stress = sum
            .iter()
            .zip(&count)
            .map(|(s, &c)| {
                let m = s.map(|x| x / c.max(1) as f64);
                StressTensor {
                    xx: m[0],
                    yy: m[1],
                    zz: m[2],
                    xy: m[3],
                    xz: m[4],
                    yz: m[5],
                }
            })
            .collect();
        let displacement = (0..n)
            .map(|k| [u[3 * k], u[3 * k + 1], u[3 * k + 2]])
            .collect();
        BodyFields::new(
            self.name(),
            mesh.nodes().to_vec(),
            cells,
            displacement,
            stress,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every VTK node order is a permutation of the element's nodes, and the VTK nodes sit
    /// where VTK puts them: the tetrahedron's node 8 on the edge 1-3, the hexahedron's node 9
    /// on the edge 1-2, its node 16 on the edge 0-4, its node 20 on the face −x.
    #[test]
    fn vtk_orders_are_vtks() {
        for kind in SolidKind::ALL {
            let (_, order) = vtk_cell(kind);
            let mut sorted = order.to_vec();
            sorted.sort_unstable();
            assert_eq!(sorted, (0..kind.n_nodes()).collect::<Vec<_>>(), "{kind:?}");
        }
        let mid = |kind: SolidKind, a: usize, b: usize| -> [f64; 3] {
            let (p, q) = (kind.reference_node(a), kind.reference_node(b));
            std::array::from_fn(|c| 0.5 * (p[c] + q[c]))
        };
        let tet = SolidKind::Tet10;
        assert_eq!(tet.reference_node(vtk_cell(tet).1[8]), mid(tet, 1, 3));
        let hex = SolidKind::Hex27;
        let order = vtk_cell(hex).1;
        assert_eq!(hex.reference_node(order[9]), mid(hex, 1, 2));
        assert_eq!(hex.reference_node(order[16]), mid(hex, 0, 4));
        assert_eq!(hex.reference_node(order[20]), [-1.0, 0.0, 0.0]);
        assert_eq!(hex.reference_node(order[24]), [0.0, 0.0, -1.0]);
    }
}
