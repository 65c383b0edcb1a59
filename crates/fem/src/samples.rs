//! The interface points of a finite-element body on its contact faces (§2.2): where on which
//! face each lies ([`FaceSample`]), the map Q from the faces' nodes to them, and the mortar map
//! that condenses a pairing's points onto the nodes. Shared by the body ([`crate::FeBody`])
//! and the pairing of two meshes ([`crate::ContactPairing`]).

use contopt_core::{GapShape, Result};
use faer::Mat;

use crate::element::GAUSS3;
use crate::{Face, FeModel};

/// One interface point of a finite-element body: where on which face the body's displacement
/// is interpolated, and the point, surface measure and normal the interface reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceSample {
    /// The boundary face.
    pub face: Face,
    /// The parameter along the face, s ∈ [−1, 1] (start node −1, middle 0, end 1), where the
    /// face's shape functions interpolate the displacement.
    pub s: f64,
    /// The interface point (x, y) \[mm\], (r, z) in axisymmetry: the point itself, or the first
    /// body's point for a partner of a [`ContactPairing`](crate::ContactPairing).
    pub point: [f64; 2],
    /// Surface measure w \[mm²\] (quadrature weight × Jacobian × thickness or 2πr).
    pub weight: f64,
    /// Unit outward normal along which the displacement is measured (−n¹ for a partner).
    pub normal: [f64; 2],
}

impl FaceSample {
    /// The three Gauss points of `face`, as [`FeBody::new`](crate::FeBody::new) checks contact (§2.2).
    pub fn gauss(model: &FeModel, face: Face) -> [FaceSample; 3] {
        GAUSS3.map(|(s, w)| {
            let fp = model.face_point(face, s);
            FaceSample {
                face,
                s,
                point: fp.x,
                weight: w * fp.jacobian * model.analysis.measure(fp.x[0]),
                normal: fp.normal,
            }
        })
    }
}

/// The nodes of `faces`, sorted and distinct.
pub(crate) fn nodes_of(model: &FeModel, faces: &[Face]) -> Vec<usize> {
    let mut nodes: Vec<usize> = faces
        .iter()
        .flat_map(|&f| model.mesh.face_nodes(f))
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// The map Q from the faces' nodes `face_nodes` (sorted, distinct; every node of a sample's
/// face among them) to the `samples`: each face's quadratic shape functions at the point.
pub(crate) fn gap_basis(
    model: &FeModel,
    samples: &[FaceSample],
    face_nodes: &[usize],
) -> Result<GapShape> {
    let rows = samples
        .iter()
        .map(|sample| {
            let nodes = model.mesh.face_nodes(sample.face);
            let shape = model.face_point(sample.face, sample.s).shape;
            (0..3)
                .map(|k| (face_nodes.partition_point(|&j| j < nodes[k]), shape[k]))
                .collect()
        })
        .collect();
    let nodes = face_nodes
        .iter()
        .map(|&k| {
            let x = model.mesh.nodes()[k];
            [x[0], x[1], 0.0]
        })
        .collect();
    GapShape::new(nodes, rows)
}

/// The mortar map T = W̃⁻¹ Bᵀ W from the pairing's points to the interface's nodes (see the
/// [module](self)): node k's value of point values v is ∫ N¹ₖ v dS / w̃ₖ, and a node's force
/// spreads over the points as the pressure N¹ₖ/w̃ₖ (Tᵀ).
#[derive(Clone, Debug)]
pub(crate) struct Mortar {
    /// T, nodes × points.
    t: Mat<f64>,
}

impl Mortar {
    /// The map of its matrix T, nodes × points.
    pub(crate) fn new(t: Mat<f64>) -> Self {
        Self { t }
    }

    /// T v: point values onto the nodes.
    pub(crate) fn apply(&self, v: &[f64]) -> Vec<f64> {
        (0..self.t.nrows())
            .map(|k| (0..self.t.ncols()).map(|i| self.t[(k, i)] * v[i]).sum())
            .collect()
    }

    /// Tᵀ f: node forces onto the points.
    pub(crate) fn apply_transpose(&self, f: &[f64]) -> Vec<f64> {
        (0..self.t.ncols())
            .map(|i| (0..self.t.nrows()).map(|k| self.t[(k, i)] * f[k]).sum())
            .collect()
    }

    /// T A Tᵀ.
    pub(crate) fn congruence(&self, a: &Mat<f64>) -> Mat<f64> {
        &self.t * (a * self.t.transpose())
    }
}
