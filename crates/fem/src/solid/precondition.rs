//! An approximate inverse of a solid's contact compliance for the matrix-free contact solvers:
//! near its contact a solid is nearly a half-space, so Boussinesq's influence among the
//! interface points (with the images of the solid's symmetry planes) is factorised once, and
//! its inverse preconditions the conjugate-gradient steps through the sparse factor.

use std::f64::consts::{PI, SQRT_2};

use contopt_core::Interface;
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

use super::model::SolidModel;

/// Above this many interface points the half-space matrix (n² doubles, and its factor: 256 MB
/// at the limit) is not built, and the solid runs unpreconditioned.
pub const PRECONDITIONED_POINTS: usize = 4000;

/// A node lies on a bounding plane within this fraction of the box's largest side.
const ON_PLANE: f64 = 1e-9;

/// Boussinesq's half-space influence among a solid's interface points, factorised:
/// B_ij = (1 − ν²)/(πE) Σ_g 1/√(|x_i − g x_j|² + s_i s_j) over the images g of the symmetry
/// planes, with s = √w / (4 ln(1 + √2)) so that a point's own term is the centre deflection
/// of a uniform pressure on a square of its area w (Johnson 1985, §3.5). The softened
/// 1/r (an inverse multiquadric, positive definite for equal s) keeps B positive definite where
/// the points of a face's Gauss rule lie closer than their squares' sides; far apart it is
/// Boussinesq's 1/r.
pub(crate) struct HalfSpaceInverse {
    llt: Llt<f64>,
}

impl HalfSpaceInverse {
    /// The factorised half-space influence of `interface` on `model`'s material; `None` when
    /// there are more than [`PRECONDITIONED_POINTS`] points or the matrix is not positive
    /// definite (then the solvers run without it).
    pub fn new(model: &SolidModel, interface: &Interface) -> Option<Self> {
        let n = interface.len();
        if n > PRECONDITIONED_POINTS {
            return None;
        }
        let m = model.material();
        let c = (1.0 - m.nu() * m.nu()) / (PI * m.e());
        let images = images(model);
        let points = interface.points();
        // The points' sizes: the self-term of a point of area w is 1/s = 4 ln(1 + √2)/√w.
        let size: Vec<f64> = (interface.weights().iter())
            .map(|w| w.sqrt() / (4.0 * (1.0 + SQRT_2).ln()))
            .collect();
        let b = Mat::from_fn(n, n, |i, j| {
            let s2 = size[i] * size[j];
            images
                .iter()
                .map(|g| 1.0 / (distance2(points[i], g.apply(points[j])) + s2).sqrt())
                .sum::<f64>()
                * c
        });
        let llt = b.llt(Side::Lower).ok()?;
        Some(Self { llt })
    }

    /// Forces that produce `displacement` on the half-space: B⁻¹ d.
    pub fn apply(&self, displacement: &[f64], force: &mut [f64]) {
        let mut x = Mat::from_fn(displacement.len(), 1, |i, _| displacement[i]);
        self.llt.solve_in_place(x.as_mut());
        for (f, v) in force.iter_mut().zip(x.col(0).iter()) {
            *f = *v;
        }
    }
}

fn distance2(a: [f64; 3], b: [f64; 3]) -> f64 {
    (a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)
}

/// A composition of reflections in planes x_axis = value.
#[derive(Clone, Debug, Default)]
struct Image {
    planes: Vec<(usize, f64)>,
}

impl Image {
    fn apply(&self, mut x: [f64; 3]) -> [f64; 3] {
        for &(axis, v) in &self.planes {
            x[axis] = 2.0 * v - x[axis];
        }
        x
    }
}

/// The images of the solid's symmetry planes (at most one per axis): a face of the bounding box
/// whose every node is held along its normal, and not every node along all three axes (that is
/// a clamp).
fn images(model: &SolidModel) -> Vec<Image> {
    let mut images = vec![Image::default()];
    for (axis, value) in symmetry_planes(model) {
        let reflected: Vec<Image> = images
            .iter()
            .map(|g| {
                let mut planes = g.planes.clone();
                planes.push((axis, value));
                Image { planes }
            })
            .collect();
        images.extend(reflected);
    }
    images
}

fn symmetry_planes(model: &SolidModel) -> Vec<(usize, f64)> {
    let mesh = model.mesh();
    let [lo, hi] = mesh.bounding_box();
    let size = (0..3).map(|a| hi[a] - lo[a]).fold(0.0, f64::max);
    let held = |node: usize, axis: usize| model.prescribed.get(&(node, axis)) == Some(&0.0);
    (0..3)
        .filter_map(|axis| {
            [lo[axis], hi[axis]].into_iter().find_map(|v| {
                let on = mesh.nodes_where(|x| (x[axis] - v).abs() <= ON_PLANE * size);
                let symmetric = !on.is_empty()
                    && on.iter().all(|&k| held(k, axis))
                    && !on.iter().all(|&k| (0..3).all(|a| held(k, a)));
                symmetric.then_some((axis, v))
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::{Axis, SolidKind, SolidMesh};
    use contopt_core::Material;

    /// The quarter block of the scaling example: x = 0 and y = 0 held along their normals are
    /// symmetry planes (four images); the clamped bottom and the free faces are not.
    #[test]
    fn symmetry_planes_are_the_planes_held_along_their_normals() {
        let mesh = SolidMesh::block(SolidKind::Hex20, [2.0, 3.0, 4.0], [2, 2, 2]).unwrap();
        let mut model = SolidModel::new(mesh, Material::new(2.0e5, 0.3).unwrap());
        let on = |c: usize, v: f64| move |x: [f64; 3]| (x[c] - v).abs() < 1e-9;
        let x0 = model.mesh().nodes_where(on(0, 0.0));
        let y0 = model.mesh().nodes_where(on(1, 0.0));
        let bottom = model.mesh().nodes_where(on(2, 0.0));
        model.fix(&x0, Axis::X).unwrap();
        model.fix(&y0, Axis::Y).unwrap();
        for axis in Axis::ALL {
            model.fix(&bottom, axis).unwrap();
        }
        assert_eq!(symmetry_planes(&model), vec![(0, 0.0), (1, 0.0)]);
        let images = images(&model);
        assert_eq!(images.len(), 4);
        let far = images[3].apply([0.5, 1.0, 4.0]);
        assert_eq!(far, [-0.5, -1.0, 4.0]);
    }
}
