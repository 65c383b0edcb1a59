//! Where a solid's contact faces are sampled: at their own Gauss points, or where the lines
//! through given points along a normal meet them (a half-space grid's cell centres, another
//! body's Gauss points).
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::collections::HashMap;

use contopt_core::{check, Error, Result};

use super::body::Row;
use super::mesh::{norm, SolidFace, SolidMesh};

/// Newton steps of a projection onto a face, at most.
const NEWTON_STEPS: usize = 30;
/// A projection has converged when its step in the face's coordinates is below this.
const NEWTON_TOLERANCE: f64 = 1e-13;
/// A point on a face's edge belongs to it within this slack of its reference coordinates.
const ON_FACE: f64 = 1e-9;

/// One interface point of a solid: a face, the face coordinates where the body's displacement
/// is read, and the point, weight and normal the interface reports.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SolidSample {
    /// The boundary face.
    pub face: SolidFace,
    /// Face coordinates (s, t).
    pub st: [f64; 2],
    /// The point the interface reports \[mm\].
    pub point: [f64; 3],
    /// Its weight (area) \[mm²\].
    pub weight: f64,
    /// The unit normal along which displacement is measured (outward of this body).
    pub normal: [f64; 3],
    /// Where the face is along the normal: the face's point is `point + offset·normal` (0 for
    /// a face's own Gauss points).
    pub offset: f64,
}

impl SolidSample {
    /// The contact points of `faces` ([`crate::solid::FaceKind::contact_points`]), weights
    /// the face's area element times the rule's weight, normals the face's own.
    pub fn gauss(mesh: &SolidMesh, faces: &[SolidFace]) -> Vec<Self> {
        faces
            .iter()
            .flat_map(|&face| {
                mesh.face_kind(face)
                    .contact_points()
                    .into_iter()
                    .map(move |(st, w)| {
                        let p = mesh.face_point(face, st);
                        SolidSample {
                            face,
                            st,
                            point: p.x,
                            weight: w * p.da,
                            normal: p.normal,
                            offset: 0.0,
                        }
                    })
            })
            .collect()
    }

    /// The samples of `faces` where the lines through `points` along `normal` (a unit
    /// vector, the interface's outward normal for this body) meet them, each reported at its
    /// given point with its given weight and `normal`. A grid's cell centres on the plane of
    /// a block's flat face give a body that pairs point for point with a half-space grid.
    /// Errors name the first point no face meets.
    pub fn projected(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        points: &[[f64; 3]],
        weights: &[f64],
        normal: [f64; 3],
    ) -> Result<Vec<Self>> {
        Self::projected_each(mesh, faces, points, weights, &vec![normal; points.len()])
    }

    /// The samples of a second body facing the first body's samples `first` across a contact
    /// (eq. 2.1: gaps and displacements along the first body's normals n¹): each point of
    /// `first` projected along n¹ onto `faces`, reported at the first body's point with its
    /// weight and the normal −n¹, so the two bodies pair point for point. The initial gap
    /// at each point is the returned sample's −`offset`. Point-to-face collocation at the
    /// first body's Gauss points (not a mortar projection): the first body's faces should be
    /// the finer.
    pub fn facing(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        first: &[SolidSample],
    ) -> Result<Vec<Self>> {
        let points: Vec<[f64; 3]> = first.iter().map(|s| s.point).collect();
        let weights: Vec<f64> = first.iter().map(|s| s.weight).collect();
        let normals: Vec<[f64; 3]> = first.iter().map(|s| s.normal.map(|c| -c)).collect();
        Self::projected_each(mesh, faces, &points, &weights, &normals)
    }

    /// [`SolidSample::projected`] with a normal per point.
    fn projected_each(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        points: &[[f64; 3]],
        weights: &[f64],
        normals: &[[f64; 3]],
    ) -> Result<Vec<Self>> {
        for (i, &n) in normals.iter().enumerate() {
            check::unit_vector(&format!("normals[{i}]"), n)?;
        }
        if weights.len() != points.len() {
            return Err(Error::invalid(
                "weights",
                weights.len(),
                format!("one per point ({})", points.len()),
            ));
        }
        let mean = normals
            .iter()
            .fold([0.0; 3], |m, n| [m[0] + n[0], m[1] + n[1], m[2] + n[2]]);
        let index = FaceIndex::new(
            mesh,
            faces,
            mean.map(|c| c / norm(mean).max(f64::MIN_POSITIVE)),
        );
        points
            .iter()
            .zip(weights)
            .zip(normals)
            .enumerate()
            .map(|(i, ((&p, &w), &normal))| {
                let (face, st, offset) = index.find(mesh, p, normal).ok_or_else(|| {
                    Error::invalid(
                        format!("points[{i}]"),
                        format!("{p:?}"),
                        "no contact face lies along the normal through this point",
                    )
                })?;
                Ok(SolidSample {
                    face,
                    st,
                    point: p,
                    weight: w,
                    normal,
                    offset,
                })
            })
            .collect()
    }

    /// The point's normal-displacement row: the face nodes' DOFs with Nₖ·nᶜ.
    pub(crate) fn row(&self, mesh: &SolidMesh) -> Row {
        let shape = mesh.face_kind(self.face).shape(self.st);
        let entries = (mesh.face_nodes(self.face).into_iter().enumerate())
            .flat_map(|(k, node)| (0..3).map(move |c| (3 * node + c, shape.n[k] * self.normal[c])))
            .filter(|&(_, c)| c != 0.0)
            .collect();
        Row { entries }
    }
}

/// The faces binned on a grid of the plane normal to the projection direction.
struct FaceIndex {
    /// Two unit vectors spanning the plane.
    axes: [[f64; 3]; 2],
    cell: f64,
    bins: HashMap<[i64; 2], Vec<SolidFace>>,
}

impl FaceIndex {
    fn new(mesh: &SolidMesh, faces: &[SolidFace], normal: [f64; 3]) -> Self {
        let axes = plane_axes(normal);
        let boxes: Vec<[[f64; 2]; 2]> = faces
            .iter()
            .map(|&f| {
                let mut b = [[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]];
                for node in mesh.face_nodes(f) {
                    let q = project(mesh.nodes()[node], &axes);
                    for c in 0..2 {
                        b[0][c] = b[0][c].min(q[c]);
                        b[1][c] = b[1][c].max(q[c]);
                    }
                }
                b
            })
            .collect();
        let cell = boxes
            .iter()
            .map(|b| (b[1][0] - b[0][0]).max(b[1][1] - b[0][1]))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut bins: HashMap<[i64; 2], Vec<SolidFace>> = HashMap::new();
        for (&f, b) in faces.iter().zip(&boxes) {
            let lo = b[0].map(|c| (c / cell).floor() as i64 - 1);
            let hi = b[1].map(|c| (c / cell).floor() as i64 + 1);
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    bins.entry([i, j]).or_default().push(f);
                }
            }
        }
        Self { axes, cell, bins }
    }

    /// The face (its coordinates, and the distance λ along `normal`) the line through `p`
    /// along `normal` meets: the nearest, when it meets several.
    fn find(
        &self,
        mesh: &SolidMesh,
        p: [f64; 3],
        normal: [f64; 3],
    ) -> Option<(SolidFace, [f64; 2], f64)> {
        let q = project(p, &self.axes);
        let key = q.map(|c| (c / self.cell).floor() as i64);
        self.bins
            .get(&key)?
            .iter()
            .filter_map(|&f| intersect(mesh, f, p, normal).map(|(st, l)| (f, st, l)))
            .min_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
    }
}

/// The face coordinates and λ where the line p + λn meets face `f`, if it does (Newton on
/// x(s, t) − λn = p from the face's centre).
fn intersect(mesh: &SolidMesh, f: SolidFace, p: [f64; 3], n: [f64; 3]) -> Option<([f64; 2], f64)> {
    let kind = mesh.face_kind(f);
    let mut st = kind.centre();
    let mut lambda = 0.0;
    for _ in 0..NEWTON_STEPS {
        let fp = mesh.face_point(f, st);
        let r: [f64; 3] = std::array::from_fn(|c| fp.x[c] - lambda * n[c] - p[c]);
        let cols = [fp.tangents[0], fp.tangents[1], n.map(|c| -c)];
        let step = solve3(cols, r.map(|c| -c))?;
        st = [st[0] + step[0], st[1] + step[1]];
        lambda += step[2];
        if step[0].abs().max(step[1].abs()) < NEWTON_TOLERANCE {
            return kind.contains(st, ON_FACE).then_some((st, lambda));
        }
        if st.iter().any(|c| c.abs() > 10.0) {
            return None;
        }
    }
    None
}

/// Solves [c₀ c₁ c₂] x = b by Cramer's rule; `None` when singular.
fn solve3(cols: [[f64; 3]; 3], b: [f64; 3]) -> Option<[f64; 3]> {
    let m = |c: [[f64; 3]; 3]| {
        [
            [c[0][0], c[1][0], c[2][0]],
            [c[0][1], c[1][1], c[2][1]],
            [c[0][2], c[1][2], c[2][2]],
        ]
    };
    let det = super::mesh::det3(&m(cols));
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some(std::array::from_fn(|k| {
        let mut c = cols;
        c[k] = b;
        super::mesh::det3(&m(c)) / det
    }))
}

/// Two unit vectors orthogonal to `n` and to each other.
fn plane_axes(n: [f64; 3]) -> [[f64; 3]; 2] {
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let a = super::element::cross(n, helper);
    let a = a.map(|c| c / norm(a));
    [a, super::element::cross(n, a)]
}

fn project(p: [f64; 3], axes: &[[f64; 3]; 2]) -> [f64; 2] {
    axes.map(|a| a[0] * p[0] + a[1] * p[1] + a[2] * p[2])
}
