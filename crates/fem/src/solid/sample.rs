//! Where a solid's contact faces are read: at their own Gauss points, or over the *cells* of a
//! contact region (a half-space grid's cells, another body's cells or points) projected onto
//! them along a normal, each point standing for its cell ([`SolidSample`]).
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::collections::{BTreeMap, HashMap};

use contopt_core::{check, Error, Result};

use super::element::cross;
use super::mesh::{norm, SolidFace, SolidMesh};

/// Newton steps of a projection onto a face, at most.
const NEWTON_STEPS: usize = 30;
/// A projection has converged when its step in the face's coordinates is below this.
const NEWTON_TOLERANCE: f64 = 1e-13;
/// A point on a face's edge belongs to it within this slack of its reference coordinates.
const ON_FACE: f64 = 1e-9;
/// Sub-points per face size along each side of a cell: k = ⌈3 · cell / face⌉, the cell's
/// larger side over the smallest face it covers (the smaller side of the face's box in the
/// cell's plane). At a spacing of a third of a face, a grid of sub-points puts a point in
/// every triangle of that size (its inscribed circle, of radius 0.29 of its edge, is wider
/// than the grid's half-diagonal, 0.24), and a few in each quadrilateral.
pub const SUB_POINTS_PER_FACE: f64 = 3.0;
/// At most this many sub-points along a cell's side (144 per cell): a face seen edge-on
/// (nearly along the normal) has a small box, and would otherwise ask for any number.
pub const MAX_SUB_RULE: usize = 12;

/// A cell of a contact region that one interface point stands for: the parallelogram centred
/// at `centre` with edge vectors `sides` (a grid's cell: [dx, 0, 0] and [0, dy, 0]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Its centre, the point the interface reports \[mm\].
    pub centre: [f64; 3],
    /// Its two edge vectors \[mm\]; zero for a point.
    pub sides: [[f64; 3]; 2],
}

impl Cell {
    /// The rectangle `size[0]` × `size[1]` centred at `centre`, its sides along x and y (a
    /// grid's cell on a plane z = const).
    pub fn xy(centre: [f64; 3], size: [f64; 2]) -> Self {
        Self {
            centre,
            sides: [[size[0], 0.0, 0.0], [0.0, size[1], 0.0]],
        }
    }

    /// A point, without extent: read at it alone (k = 1).
    pub fn point(centre: [f64; 3]) -> Self {
        Self {
            centre,
            sides: [[0.0; 3]; 2],
        }
    }

    /// Its area |s₀ × s₁| \[mm²\].
    pub fn area(&self) -> f64 {
        norm(cross(self.sides[0], self.sides[1]))
    }

    /// The centres of its k × k equal parts, the sub-rule of the cell's mean (the midpoint
    /// rule on each part).
    fn sub_points(&self, k: usize) -> impl Iterator<Item = [f64; 3]> + '_ {
        (0..k * k).map(move |m| {
            let (u, v) = (
                ((m % k) as f64 + 0.5) / k as f64 - 0.5,
                ((m / k) as f64 + 0.5) / k as f64 - 0.5,
            );
            std::array::from_fn(|c| self.centre[c] + u * self.sides[0][c] + v * self.sides[1][c])
        })
    }
}

/// One point of a sample's sub-rule: the face it meets and where.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubSample {
    /// The boundary face.
    pub face: SolidFace,
    /// Face coordinates (s, t).
    pub st: [f64; 2],
    /// Where the face is along the sample's normal from the sub-point of the cell: the face's
    /// point is `sub-point + offset·normal`.
    pub offset: f64,
}

/// One interface point of a solid, standing for a cell: the point, weight (the cell's area)
/// and normal the interface reports, and the k × k sub-points where the body is read, each
/// carrying 1/k² of the point's force.
///
/// The point's force is spread as a uniform pressure over the
/// cell: a sub-rule of k × k points at the centres of equal parts of the cell, each projected
/// onto the faces along the normal and each carrying force/k²; and the displacement the point
/// reports is the cell's mean over the same sub-points. The point's row of the trace map L is
/// thus the mean of its sub-points' shape-function rows, the body's influence L K⁻¹ Lᵀ stays
/// symmetric and is the influence among uniform cell pressures — the solid's counterpart of
/// the half-space grid's Love kernel (uniform pressure on a cell, `contopt_greens`) and, like
/// the plane pairing's mortar ([`crate::ContactPairing`]: T = W̃⁻¹BᵀW, node values as weighted
/// means ∫N¹ₖ v dS / w̃ₖ of the points'), a weighted mean over the faces rather than a point
/// value. A point force spread by a face's shape functions is softer than the pressure of its
/// cell, the more so as the elements get finer than the cells (its own deflection grows like
/// Boussinesq's 1/r as the face shrinks); the cell's mean is not.
///
/// k is chosen per cell ([`SUB_POINTS_PER_FACE`]): enough sub-points that every face the cell
/// covers holds several. A cell without extent (a point, [`SolidSample::projected`], or a face's
/// Gauss point, [`SolidSample::gauss`]) is the case k = 1.
#[derive(Clone, Debug, PartialEq)]
pub struct SolidSample {
    /// The point the interface reports (the cell's centre) \[mm\].
    pub point: [f64; 3],
    /// Its weight (area) \[mm²\].
    pub weight: f64,
    /// The unit normal along which displacement is measured (outward of this body).
    pub normal: [f64; 3],
    /// The cell's edge vectors (zero for a point) \[mm\].
    pub sides: [[f64; 3]; 2],
    /// The sub-rule's points, k² of them (one for a point).
    pub parts: Vec<SubSample>,
    /// Where the face is along the normal, the mean over the cell: the parts' mean offset (0
    /// for a face's own Gauss points).
    pub offset: f64,
}

impl SolidSample {
    /// The contact points of `faces` ([`crate::solid::FaceKind::contact_points`]), weights
    /// the face's area element times the rule's weight, normals the face's own: points without
    /// a cell (k = 1).
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
                            point: p.x,
                            weight: w * p.da,
                            normal: p.normal,
                            sides: [[0.0; 3]; 2],
                            parts: vec![SubSample {
                                face,
                                st,
                                offset: 0.0,
                            }],
                            offset: 0.0,
                        }
                    })
            })
            .collect()
    }

    /// The samples of `faces` where the lines through `points` along `normal` (a unit
    /// vector, the interface's outward normal for this body) meet them, each reported at its
    /// given point with its given weight and `normal`: points without a cell, read at the
    /// point alone (k = 1; [`SolidSample::cells`] reads each cell's mean). Errors name the
    /// first point no face meets.
    pub fn projected(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        points: &[[f64; 3]],
        weights: &[f64],
        normal: [f64; 3],
    ) -> Result<Vec<Self>> {
        if weights.len() != points.len() {
            return Err(Error::invalid(
                "weights",
                weights.len(),
                format!("one per point ({})", points.len()),
            ));
        }
        let cells: Vec<Cell> = points.iter().map(|&p| Cell::point(p)).collect();
        Self::read(mesh, faces, &cells, weights, &vec![normal; points.len()])
    }

    /// The samples of `faces` standing for `cells`, read along `normal` (a unit vector, the
    /// interface's outward normal for this body): each reported at its cell's centre with the
    /// cell's area, its force a uniform pressure over the cell and its displacement the cell's
    /// mean, both on a k × k sub-rule ([`SUB_POINTS_PER_FACE`]; see [`SolidSample`]). A
    /// grid's cells on the plane of a block's flat face give a body that pairs cell for cell
    /// with a half-space grid. Errors name the first cell whose sub-point no face meets.
    pub fn cells(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        cells: &[Cell],
        normal: [f64; 3],
    ) -> Result<Vec<Self>> {
        let mut weights = Vec::with_capacity(cells.len());
        for (i, cell) in cells.iter().enumerate() {
            check::all_finite(&format!("cells[{i}].centre"), &cell.centre)?;
            check::all_finite(&format!("cells[{i}].sides"), cell.sides.as_flattened())?;
            weights.push(check::positive(&format!("cells[{i}] area"), cell.area())?);
        }
        Self::read(mesh, faces, cells, &weights, &vec![normal; cells.len()])
    }

    /// The samples of a second body facing the first body's samples `first` across a contact
    /// (eq. 2.1: gaps and displacements along the first body's normals n¹): each of `first`'s
    /// cells read on `faces` along −n¹ with a sub-rule chosen for these faces, reported at the
    /// first body's point with its weight and the normal −n¹, so that the two bodies pair
    /// cell for cell, each read as the cell's mean. The initial gap of each cell is
    /// [`SolidSample::initial_gap`].
    pub fn facing(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        first: &[SolidSample],
    ) -> Result<Vec<Self>> {
        let cells: Vec<Cell> = (first.iter())
            .map(|s| Cell {
                centre: s.point,
                sides: s.sides,
            })
            .collect();
        let weights: Vec<f64> = first.iter().map(|s| s.weight).collect();
        let normals: Vec<[f64; 3]> = first.iter().map(|s| s.normal.map(|c| -c)).collect();
        Self::read(mesh, faces, &cells, &weights, &normals)
    }

    /// The initial gap between two bodies paired cell for cell ([`SolidSample::facing`]):
    /// the cell's mean distance from the first body's face to the second's along n¹,
    /// −(offset¹ + offset²).
    pub fn initial_gap(first: &[SolidSample], second: &[SolidSample]) -> Vec<f64> {
        (first.iter().zip(second))
            .map(|(a, b)| -(a.offset + b.offset))
            .collect()
    }

    /// The sub-rule k (k² parts).
    pub fn sub_rule(&self) -> usize {
        (self.parts.len() as f64).sqrt().round() as usize
    }

    /// `cells` read on `faces` along `normals`, each reported with its weight.
    fn read(
        mesh: &SolidMesh,
        faces: &[SolidFace],
        cells: &[Cell],
        weights: &[f64],
        normals: &[[f64; 3]],
    ) -> Result<Vec<Self>> {
        for (i, &n) in normals.iter().enumerate() {
            check::unit_vector(&format!("normals[{i}]"), n)?;
        }
        let mean = normals
            .iter()
            .fold([0.0; 3], |m, n| [m[0] + n[0], m[1] + n[1], m[2] + n[2]]);
        let index = FaceIndex::new(
            mesh,
            faces,
            mean.map(|c| c / norm(mean).max(f64::MIN_POSITIVE)),
        );
        (cells.iter().zip(weights).zip(normals).enumerate())
            .map(|(i, ((cell, &weight), &normal))| {
                let k = index.sub_rule(cell);
                let parts = (cell.sub_points(k))
                    .map(|q| {
                        let (face, st, offset) = index.find(mesh, q, normal).ok_or_else(|| {
                            let part = match k {
                                1 => String::new(),
                                _ => format!(" (at {q:?}, a point of its cell's sub-rule)"),
                            };
                            Error::invalid(
                                format!("points[{i}]"),
                                format!("{:?}", cell.centre),
                                format!(
                                    "no contact face lies along the normal through this \
                                     point{part}"
                                ),
                            )
                        })?;
                        Ok(SubSample { face, st, offset })
                    })
                    .collect::<Result<Vec<_>>>()?;
                let offset = parts.iter().map(|p| p.offset).sum::<f64>() / parts.len() as f64;
                Ok(SolidSample {
                    point: cell.centre,
                    weight,
                    normal,
                    sides: cell.sides,
                    parts,
                    offset,
                })
            })
            .collect()
    }

    /// The sample's weights on the face nodes: the mean over its parts of the faces' shape
    /// functions, Σ Nₖ(sₚ, tₚ)/k² per node (sorted by node, each node once).
    pub(crate) fn node_weights(&self, mesh: &SolidMesh) -> Vec<(usize, f64)> {
        let share = 1.0 / self.parts.len() as f64;
        let mut weights: BTreeMap<usize, f64> = BTreeMap::new();
        for part in &self.parts {
            let shape = mesh.face_kind(part.face).shape(part.st);
            for (k, node) in mesh.face_nodes(part.face).into_iter().enumerate() {
                *weights.entry(node).or_default() += share * shape.n[k];
            }
        }
        weights.into_iter().filter(|&(_, w)| w != 0.0).collect()
    }

    /// The point's normal-displacement row, the cell's mean: the face nodes' DOFs with
    /// (Σ Nₖ/k²)·nᶜ.
    pub(crate) fn row(&self, mesh: &SolidMesh) -> Row {
        let entries = (self.node_weights(mesh).into_iter())
            .flat_map(|(node, w)| (0..3).map(move |c| (3 * node + c, w * self.normal[c])))
            .filter(|&(_, c)| c != 0.0)
            .collect();
        Row { entries }
    }
}

/// One interface point's normal-displacement row: the into-body displacement at the point is
/// −Σ coef·u(dof) over the face nodes' global DOFs.
#[derive(Clone, Debug)]
pub(crate) struct Row {
    pub entries: Vec<(usize, f64)>,
}

impl Row {
    pub(crate) fn normal_into(&self, u: &[f64]) -> f64 {
        -self.entries.iter().map(|&(g, c)| c * u[g]).sum::<f64>()
    }
}

/// The faces binned on a grid of the plane normal to the projection direction.
struct FaceIndex {
    /// Two unit vectors spanning the plane.
    axes: [[f64; 3]; 2],
    cell: f64,
    faces: Vec<SolidFace>,
    /// Each face's box in the plane: [low, high].
    boxes: Vec<[[f64; 2]; 2]>,
    /// The faces (their indices) whose boxes, widened by a bin, reach each bin.
    bins: HashMap<[i64; 2], Vec<usize>>,
}

impl FaceIndex {
    fn new(mesh: &SolidMesh, faces: &[SolidFace], normal: [f64; 3]) -> Self {
        let axes = plane_axes(normal);
        let boxes: Vec<[[f64; 2]; 2]> = faces
            .iter()
            .map(|&f| {
                let corners = mesh.face_nodes(f).into_iter().map(|n| mesh.nodes()[n]);
                bounds(corners.map(|p| project(p, &axes)))
            })
            .collect();
        let cell = boxes
            .iter()
            .map(|b| (b[1][0] - b[0][0]).max(b[1][1] - b[0][1]))
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
        let mut bins: HashMap<[i64; 2], Vec<usize>> = HashMap::new();
        for (f, b) in boxes.iter().enumerate() {
            let lo = b[0].map(|c| (c / cell).floor() as i64 - 1);
            let hi = b[1].map(|c| (c / cell).floor() as i64 + 1);
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    bins.entry([i, j]).or_default().push(f);
                }
            }
        }
        Self {
            axes,
            cell,
            faces: faces.to_vec(),
            boxes,
            bins,
        }
    }

    /// The sub-rule of `cell`: k = ⌈[`SUB_POINTS_PER_FACE`] · its larger side / the smallest
    /// face it covers⌉, from 1 (a point) to [`MAX_SUB_RULE`], sides and faces measured in the
    /// plane of the index.
    fn sub_rule(&self, cell: &Cell) -> usize {
        let corners = [[-0.5, -0.5], [0.5, -0.5], [-0.5, 0.5], [0.5, 0.5]].map(|[u, v]| {
            let x = std::array::from_fn(|c| {
                cell.centre[c] + u * cell.sides[0][c] + v * cell.sides[1][c]
            });
            project(x, &self.axes)
        });
        let [lo, hi] = bounds(corners.into_iter());
        let side = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        if side == 0.0 {
            return 1;
        }
        let (first, last) = (
            lo.map(|c| (c / self.cell).floor() as i64),
            hi.map(|c| (c / self.cell).floor() as i64),
        );
        let smallest = (first[0]..=last[0])
            .flat_map(|i| (first[1]..=last[1]).map(move |j| [i, j]))
            .filter_map(|key| self.bins.get(&key))
            .flatten()
            .map(|&f| self.boxes[f])
            .filter(|b| (0..2).all(|c| b[0][c] <= hi[c] && b[1][c] >= lo[c]))
            .map(|b| (b[1][0] - b[0][0]).min(b[1][1] - b[0][1]))
            .fold(f64::INFINITY, f64::min);
        let k = (SUB_POINTS_PER_FACE * side / smallest).ceil();
        match k.is_finite() {
            true => (k as usize).clamp(1, MAX_SUB_RULE),
            false => MAX_SUB_RULE,
        }
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
            .map(|&f| self.faces[f])
            .filter_map(|f| intersect(mesh, f, p, normal).map(|(st, l)| (f, st, l)))
            .min_by(|a, b| a.2.abs().total_cmp(&b.2.abs()))
    }
}

/// The box [low, high] of points in a plane.
fn bounds(points: impl Iterator<Item = [f64; 2]>) -> [[f64; 2]; 2] {
    points.fold([[f64::INFINITY; 2], [f64::NEG_INFINITY; 2]], |b, q| {
        [
            [b[0][0].min(q[0]), b[0][1].min(q[1])],
            [b[1][0].max(q[0]), b[1][1].max(q[1])],
        ]
    })
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
    let a = cross(n, helper);
    let a = a.map(|c| c / norm(a));
    [a, cross(n, a)]
}

fn project(p: [f64; 3], axes: &[[f64; 3]; 2]) -> [f64; 2] {
    axes.map(|a| a[0] * p[0] + a[1] * p[1] + a[2] * p[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::SolidKind;

    const UP: [f64; 3] = [0.0, 0.0, 1.0];

    /// A cell straddling several faces of a flat top (faces 1 mm, the cell 1.5 × 1 mm) is read
    /// on k = ⌈3 · 1.5 / 1⌉ = 5 sub-points per side, and its row is the mid-point rule of the
    /// cell's mean: the weights sum to 1, their first moments are the centre, and their second
    /// moment in x is xc² + hx²(1 − 1/k²)/12 (the faces' shape functions reproduce quadratics
    /// on straight faces), for every element kind.
    #[test]
    fn a_cell_reads_its_mean_over_the_faces() {
        let (centre, size) = ([1.7, 2.2, 1.0], [1.5, 1.0]);
        for kind in SolidKind::ALL {
            let mesh = SolidMesh::block(kind, [4.0, 4.0, 1.0], [4, 4, 1]).unwrap();
            let top = mesh.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
            let cell = Cell::xy(centre, size);
            let s = &SolidSample::cells(&mesh, &top, &[cell], UP).unwrap()[0];
            assert_eq!(s.sub_rule(), 5, "{kind:?}");
            assert!((s.weight - 1.5).abs() < 1e-12 && s.offset.abs() < 1e-12);
            let w = s.node_weights(&mesh);
            let moment = |f: &dyn Fn([f64; 3]) -> f64| -> f64 {
                w.iter().map(|&(n, c)| c * f(mesh.nodes()[n])).sum()
            };
            assert!((moment(&|_| 1.0) - 1.0).abs() < 1e-12, "{kind:?}");
            assert!((moment(&|x| x[0]) - centre[0]).abs() < 1e-12, "{kind:?}");
            assert!((moment(&|x| x[1]) - centre[1]).abs() < 1e-12, "{kind:?}");
            let second = centre[0] * centre[0] + size[0] * size[0] * (1.0 - 1.0 / 25.0) / 12.0;
            assert!(
                (moment(&|x| x[0] * x[0]) - second).abs() < 1e-12,
                "{kind:?}"
            );
        }
    }

    /// A second block 0.1 mm above the first, meshed apart (3 against 4 faces a side), faces
    /// the first's cells: the initial gap is 0.1 mm at every cell, read along −z.
    #[test]
    fn facing_cells_measure_the_gap_between_the_meshes() {
        let below = SolidMesh::block(SolidKind::Hex20, [3.0, 3.0, 1.0], [4, 4, 1]).unwrap();
        let above = SolidMesh::block(SolidKind::Tet10, [3.0, 3.0, 1.0], [3, 3, 1])
            .unwrap()
            .map(|x| [x[0], x[1], x[2] + 1.1])
            .unwrap();
        let top = below.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
        let bottom = above.faces_where(|x| (x[2] - 1.1).abs() < 1e-9);
        let cells: Vec<Cell> = (0..9)
            .map(|k| {
                Cell::xy(
                    [(k % 3) as f64 + 0.5, (k / 3) as f64 + 0.5, 1.0],
                    [1.0, 1.0],
                )
            })
            .collect();
        let first = SolidSample::cells(&below, &top, &cells, UP).unwrap();
        let second = SolidSample::facing(&above, &bottom, &first).unwrap();
        for (g, s) in SolidSample::initial_gap(&first, &second)
            .iter()
            .zip(&second)
        {
            assert!((g - 0.1).abs() < 1e-12, "{g}");
            assert_eq!(s.normal, [0.0, 0.0, -1.0]);
            assert_eq!(s.sub_rule(), 3);
        }
    }
}
