//! The fields of a solid body under a contact solution, for ParaView: its mesh (cells in VTK's
//! node order), the displacement of every node (the rigid motion included) and the stress at
//! every node, averaged over the elements that share it; their peaks below the surface.

use contopt_core::{
    BodyFields, Cell, CellKind, ElasticBody, Result, StressPeaks, StressTensor, Subsurface,
};

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
    /// the elements that share a node ([`SolidBody::nodal_stresses`]).
    pub fn mesh_fields(&self, pressure: &[f64], rigid: &[f64]) -> Result<BodyFields> {
        let u = self.displacement(&self.forces(pressure), rigid)?;
        let stress = self.averaged_stresses(&u)?;
        let mesh = self.model.mesh();
        let cells = (0..mesh.n_elements())
            .map(|e| {
                let (cell, order) = vtk_cell(mesh.kind(e));
                let conn = mesh.element(e);
                Cell {
                    kind: cell,
                    nodes: order.iter().map(|&a| conn[a]).collect(),
                }
            })
            .collect();
        let displacement = (0..mesh.nodes().len())
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

    /// The stress at every node of the mesh under the contact pressure `pressure` \[MPa\] at
    /// the interface points and the body's given loads: each element's stress at its nodes,
    /// averaged over the elements that share a node (a rigid motion strains nothing).
    pub fn nodal_stresses(&self, pressure: &[f64]) -> Result<Vec<StressTensor>> {
        let rigid = vec![0.0; self.rigid_modes().len()];
        let u = self.displacement(&self.forces(pressure), &rigid)?;
        self.averaged_stresses(&u)
    }

    /// Compressive normal forces pᵢwᵢ \[N\] at the interface points.
    fn forces(&self, pressure: &[f64]) -> Vec<f64> {
        let weights = self.interface().weights();
        pressure.iter().zip(weights).map(|(p, w)| p * w).collect()
    }

    /// The stresses of the displacement field `u` (3 per node) at each element's nodes,
    /// averaged over the elements that share a node.
    fn averaged_stresses(&self, u: &[f64]) -> Result<Vec<StressTensor>> {
        let mesh = self.model.mesh();
        let n = mesh.nodes().len();
        let mut sum = vec![[0.0; 6]; n];
        let mut count = vec![0usize; n];
        for e in 0..mesh.n_elements() {
            let kind = mesh.kind(e);
            for (a, &node) in mesh.element(e).iter().enumerate() {
                let s = self.model.stress_at(u, e, kind.reference_node(a))?;
                let v = [s.xx, s.yy, s.zz, s.xy, s.xz, s.yz];
                sum[node].iter_mut().zip(v).for_each(|(t, x)| *t += x);
                count[node] += 1;
            }
        }
        let mean = |(s, &c): (&[f64; 6], &usize)| {
            let m = s.map(|x| x / c.max(1) as f64);
            StressTensor {
                xx: m[0],
                yy: m[1],
                zz: m[2],
                xy: m[3],
                xz: m[4],
                yz: m[5],
            }
        };
        Ok(sum.iter().zip(&count).map(mean).collect())
    }

    /// The peaks of each criterion over every node of the mesh ([`SolidBody::nodal_stresses`]),
    /// each at the node's x and y and, as its depth, the node's distance to the nearest
    /// interface point. A mesh has its own points below the surface, so the request's depths
    /// do not apply, and no section is returned (the whole field is
    /// [`SolidBody::mesh_fields`], for ParaView).
    pub fn nodal_subsurface(&self, pressure: &[f64]) -> Result<Subsurface> {
        let stresses = self.nodal_stresses(pressure)?;
        let points = self.interface().points();
        let depth = |x: &[f64; 3]| {
            let distance = |p: &[f64; 3]| (0..3).map(|c| (x[c] - p[c]).powi(2)).sum::<f64>();
            points
                .iter()
                .map(distance)
                .fold(f64::INFINITY, f64::min)
                .sqrt()
        };
        let mut peaks = StressPeaks::default();
        for (s, x) in stresses.iter().zip(self.model.mesh().nodes()) {
            peaks.record(s, x[0], x[1], depth(x));
        }
        Ok(Subsurface {
            peaks: peaks.finite(self.name())?,
            sections: vec![],
        })
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
