//! Where a solid's contact faces are read: at their own Gauss points, or over the *cells* of a
//! contact region (a half-space grid's cells, another body's cells or points) projected onto
//! them along a normal, each point standing for its cell ([`SolidSample`]).
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::collections::{BTreeMap, HashMap};

use contopt_core::{check, Error, Result};

use super::element::{cross, FaceKind};
use super::mesh::{norm, SolidFace, SolidMesh};

/// Newton steps of a projection onto a face, at most.
const NEWTON_STEPS: usize = 30;
/// A projection has converged when its step in the face's coordinates is below this (the
/// step converges quadratically, so the point is then exact to round-off; round-off alone
/// moves the step by 10⁻¹³ on a face 0.02 mm wide 5 mm from the origin, ε · 5 / 0.01).
const NEWTON_TOLERANCE: f64 = 1e-10;
/// A point on a face's edge belongs to it within this slack of its reference coordinates.
const ON_FACE: f64 = 1e-9;
/// Parts per face size along each side of a cell: kᵢ = ⌈3 · sideᵢ / face⌉ parts along each of
/// the cell's sides, over the smallest face it covers (the smaller side of the face's box in
/// the cell's plane). At a third of a face, a grid of parts puts a part's centre, and Gauss
/// points around it, in every triangle of that size (its inscribed circle, of radius 0.29 of
/// its edge, is wider than the grid's half-diagonal, 0.24), and a few in each quadrilateral;
/// counted along each side, a long narrow cell gets its parts along its long side, as many
/// per face as a square cell of the same faces gets.
pub const SUB_PARTS_PER_FACE: f64 = 3.0;
/// At most this many parts in a cell, k₀·k₁ (12 × 12 on a square cell, 72 × 2 on a long
/// narrow one; four Gauss points each): a face seen edge-on (nearly along the normal) has a
/// small box, and would otherwise ask for any number.
pub const MAX_SUB_PARTS: usize = 144;

/// Gauss–Legendre's two points on a part [−½, ½]: ±1/(2√3), exact for cubics.
const GAUSS_POINT: f64 = 0.288_675_134_594_812_9;

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

    /// The points of its sub-rule, the cell's mean: k₀ × k₁ equal parts (kᵢ along side i),
    /// each read at Gauss–Legendre's 2 × 2 points (equal weights), 2k₀ × 2k₁ points along
    /// side 0 first; a point's centre alone. On a part within one flat, straight-edged face the
    /// rule is exact for the face's fields (biquadratic on a 9-node face, quadratic on the
    /// others: cubics are exact), on a curved one to the order of its curvature; on a part
    /// across a face's edge it is a product rule over the field's kink, the part's error
    /// shrinking as the parts do.
    fn sub_points(&self, k: [usize; 2]) -> Vec<[f64; 3]> {
        if self.sides == [[0.0; 3]; 2] {
            return vec![self.centre];
        }
        let along = |i: usize, k: usize| {
            let side = if i.is_multiple_of(2) {
                -GAUSS_POINT
            } else {
                GAUSS_POINT
            };
            ((i / 2) as f64 + 0.5 + side) / k as f64 - 0.5
        };
        (0..4 * k[0] * k[1])
            .map(|m| {
                let (u, v) = (along(m % (2 * k[0]), k[0]), along(m / (2 * k[0]), k[1]));
                std::array::from_fn(|c| {
                    self.centre[c] + u * self.sides[0][c] + v * self.sides[1][c]
                })
            })
            .collect()
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
/// and normal the interface reports, and the sub-points where the body is read: 2 × 2 Gauss
/// points on each of the cell's k₀ × k₁ equal parts (kᵢ along the cell's side i), each
/// carrying 1/(4k₀k₁) of the point's force.
///
/// The point's force is spread as a uniform pressure over the cell: a sub-rule of Gauss points
/// on equal parts of the cell, each projected onto the faces along the normal and each
/// carrying an equal share of the force; and the displacement the point reports is the
/// cell's mean over the same sub-points, exact where a part lies within one face. The point's
/// row of the trace map L is thus the mean of its sub-points' shape-function rows, the body's
/// influence L K⁻¹ Lᵀ stays
/// symmetric and is the influence among uniform cell pressures — the solid's counterpart of
/// the half-space grid's Love kernel (uniform pressure on a cell, `contopt_greens`) and, like
/// the plane pairing's mortar ([`crate::ContactPairing`]: T = W̃⁻¹BᵀW, node values as weighted
/// means ∫N¹ₖ v dS / w̃ₖ of the points'), a weighted mean over the faces rather than a point
/// value. A point force spread by a face's shape functions is softer than the pressure of its
/// cell, the more so as the elements get finer than the cells (its own deflection grows like
/// Boussinesq's 1/r as the face shrinks); the cell's mean is not.
///
/// k₀ and k₁ are chosen per cell, each along its side ([`SUB_PARTS_PER_FACE`],
/// [`MAX_SUB_PARTS`]): enough parts that every face the cell covers holds several, a long
/// narrow cell's along its long side. A cell without extent (a point,
/// [`SolidSample::projected`], or a face's Gauss point, [`SolidSample::gauss`]) is read at its
/// point alone, the rule [1, 1].
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
    /// The sub-rule [k₀, k₁]: equal parts along the cell's sides ([1, 1] for a point).
    pub rule: [usize; 2],
    /// The sub-rule's points, 2 × 2 on each part, 4k₀k₁ of them (one for a point), along side
    /// 0 first.
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
                            rule: [1, 1],
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
    /// mean, both on a k₀ × k₁ sub-rule ([`SUB_PARTS_PER_FACE`]; see [`SolidSample`]). A
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

    /// The sub-rule [k₀, k₁]: equal parts along the cell's sides 0 and 1, each read at 2 × 2
    /// Gauss points ([`SolidSample`]).
    pub fn sub_rule(&self) -> [usize; 2] {
        self.rule
    }

    /// The size of the largest face the sample reads: the longest edge between the corners of
    /// a face its sub-points meet \[mm\].
    pub fn face_size(&self, mesh: &SolidMesh) -> f64 {
        let mut faces: Vec<SolidFace> = self.parts.iter().map(|p| p.face).collect();
        faces.sort_unstable();
        faces.dedup();
        let longest_edge = |f: SolidFace| {
            let corners = match mesh.face_kind(f) {
                FaceKind::Tri6 => 3,
                FaceKind::Quad8 | FaceKind::Quad9 => 4,
            };
            let nodes = mesh.face_nodes(f);
            (0..corners)
                .map(|k| {
                    let (a, b) = (
                        mesh.nodes()[nodes[k]],
                        mesh.nodes()[nodes[(k + 1) % corners]],
                    );
                    norm(std::array::from_fn(|c| a[c] - b[c]))
                })
                .fold(0.0, f64::max)
        };
        faces.into_iter().map(longest_edge).fold(0.0, f64::max)
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
                let parts = (cell.sub_points(k).into_iter())
                    .map(|q| {
                        let (face, st, offset) = index.find(mesh, q, normal).ok_or_else(|| {
                            let part = match cell.sides == [[0.0; 3]; 2] {
                                true => String::new(),
                                false => format!(" (at {q:?}, a point of its cell's sub-rule)"),
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
                    rule: k,
                    parts,
                    offset,
                })
            })
            .collect()
    }

    /// The sample's weights on the face nodes: the mean over its parts of the faces' shape
    /// functions, Σ Nₖ(sₚ, tₚ)/(4k₀k₁) per node (sorted by node, each node once).
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
    /// (Σ Nₖ/(4k₀k₁))·nᶜ.
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

    /// The sub-rule of `cell`: kᵢ = ⌈[`SUB_PARTS_PER_FACE`] · its side i / the smallest face
    /// it covers⌉ along each side, 1 on a side without length, sides and faces measured in the
    /// plane of the index; at most [`MAX_SUB_PARTS`] in all ([`capped`]).
    fn sub_rule(&self, cell: &Cell) -> [usize; 2] {
        let sides = cell.sides.map(|s| norm2(project(s, &self.axes)));
        if sides == [0.0; 2] {
            return [1, 1];
        }
        let corners = [[-0.5, -0.5], [0.5, -0.5], [-0.5, 0.5], [0.5, 0.5]].map(|[u, v]| {
            let x = std::array::from_fn(|c| {
                cell.centre[c] + u * cell.sides[0][c] + v * cell.sides[1][c]
            });
            project(x, &self.axes)
        });
        let [lo, hi] = bounds(corners.into_iter());
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
        capped(sides.map(|side| {
            if side == 0.0 {
                1.0
            } else {
                (SUB_PARTS_PER_FACE * side / smallest).ceil().max(1.0)
            }
        }))
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

/// The sub-rule `k`, parts along each side (each at least 1, either possibly infinite: a face
/// without width), held to [`MAX_SUB_PARTS`] in all: the smaller side keeps its count up to √max, the larger
/// side at most as many as the rest of the budget allows; within the budget, `k` rounded.
fn capped(k: [f64; 2]) -> [usize; 2] {
    let max = MAX_SUB_PARTS as f64;
    if k[0] * k[1] <= max {
        return k.map(|c| c as usize);
    }
    let small = k[0].min(k[1]).min(max.sqrt().floor());
    let large = k[0].max(k[1]).min((max / small).floor());
    match k[0] <= k[1] {
        true => [small as usize, large as usize],
        false => [large as usize, small as usize],
    }
}

/// The length of a vector of a plane.
fn norm2(v: [f64; 2]) -> f64 {
    v[0].hypot(v[1])
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
    /// on k₀ = ⌈3 · 1.5 / 1⌉ = 5 parts along x and k₁ = 3 along y, 2 × 2 Gauss points each, and
    /// its row is the cell's mean: the weights sum to 1, their first moments are the centre,
    /// and their second moments the exact means xc² + hx²/12 and yc² + hy²/12 (the faces'
    /// shape functions reproduce quadratics on straight faces, and the parts' Gauss points
    /// integrate them exactly), for every element kind.
    #[test]
    fn a_cell_reads_its_mean_over_the_faces() {
        let (centre, size) = ([1.7, 2.2, 1.0], [1.5, 1.0]);
        for kind in SolidKind::ALL {
            let mesh = SolidMesh::block(kind, [4.0, 4.0, 1.0], [4, 4, 1]).unwrap();
            let top = mesh.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
            let cell = Cell::xy(centre, size);
            let s = &SolidSample::cells(&mesh, &top, &[cell], UP).unwrap()[0];
            assert_eq!(s.sub_rule(), [5, 3], "{kind:?}");
            assert_eq!(s.parts.len(), 60, "{kind:?}");
            assert!((s.weight - 1.5).abs() < 1e-12 && s.offset.abs() < 1e-12);
            let w = s.node_weights(&mesh);
            let moment = |f: &dyn Fn([f64; 3]) -> f64| -> f64 {
                w.iter().map(|&(n, c)| c * f(mesh.nodes()[n])).sum()
            };
            assert!((moment(&|_| 1.0) - 1.0).abs() < 1e-12, "{kind:?}");
            assert!((moment(&|x| x[0]) - centre[0]).abs() < 1e-12, "{kind:?}");
            assert!((moment(&|x| x[1]) - centre[1]).abs() < 1e-12, "{kind:?}");
            for c in 0..2 {
                let second = centre[c] * centre[c] + size[c] * size[c] / 12.0;
                let error = moment(&|x| x[c] * x[c]) - second;
                assert!(error.abs() < 1e-12, "{kind:?}: {error}");
            }
        }
    }

    /// A long narrow cell, 5.9 × 0.25 mm over faces of 0.5 mm, gets its parts along its long
    /// side: k₀ = ⌈3 · 5.9 / 0.5⌉ = 36 along x and k₁ = 2 across, as many per face along x as
    /// on a square cell (a rule of k ≤ 12 a side put one part on 0.49 mm, a whole face). Its
    /// means of the faces' fields x² (every kind) and x²y² (a 9-node face's biquadratic) are
    /// exact to round-off, xc² + hx²/12 and its product with yc² + hy²/12: the midpoint rule
    /// of 12 × 12 points was off by (hx/12)²/12 = 0.0201 mm² on x², and of 36 × 2 points by
    /// 0.0022 mm².
    #[test]
    fn a_long_narrow_cell_is_read_along_its_long_side() {
        let (centre, size) = ([4.1, 0.5, 1.0], [5.9, 0.25]);
        let mean_sq = |c: usize| centre[c] * centre[c] + size[c] * size[c] / 12.0;
        for kind in SolidKind::ALL {
            let mesh = SolidMesh::block(kind, [8.0, 1.0, 1.0], [16, 2, 1]).unwrap();
            let top = mesh.faces_where(|x| (x[2] - 1.0).abs() < 1e-9);
            let s = &SolidSample::cells(&mesh, &top, &[Cell::xy(centre, size)], UP).unwrap()[0];
            assert_eq!(s.sub_rule(), [36, 2], "{kind:?}");
            let w = s.node_weights(&mesh);
            let mean = |f: &dyn Fn([f64; 3]) -> f64| -> f64 {
                w.iter().map(|&(n, c)| c * f(mesh.nodes()[n])).sum()
            };
            let linear = |x: [f64; 3]| 0.3 + 2.0 * x[0] - 0.7 * x[1];
            assert!((mean(&linear) - linear(centre)).abs() < 1e-12, "{kind:?}");
            let error = mean(&|x| x[0] * x[0]) - mean_sq(0);
            assert!(error.abs() < 1e-12, "{kind:?}: {error}");
            if kind == SolidKind::Hex27 {
                let error = mean(&|x| x[0] * x[0] * x[1] * x[1]) - mean_sq(0) * mean_sq(1);
                assert!(error.abs() < 1e-12, "{kind:?}: {error}");
            }
        }
    }

    /// The cap holds a cell to `MAX_SUB_PARTS` (144) parts: the smaller side keeps its
    /// count up to 12 and the larger takes the rest; a face without width (an infinite count)
    /// gives 12 × 12, or 144 along a cell's only side.
    #[test]
    fn the_sub_rule_is_capped_in_all() {
        assert_eq!(capped([36.0, 2.0]), [36, 2]);
        assert_eq!(capped([300.0, 5.0]), [28, 5]);
        assert_eq!(capped([5.0, 300.0]), [5, 28]);
        assert_eq!(capped([20.0, 20.0]), [12, 12]);
        assert_eq!(capped([f64::INFINITY; 2]), [12, 12]);
        assert_eq!(capped([f64::INFINITY, 1.0]), [144, 1]);
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
            assert_eq!(s.sub_rule(), [3, 3]);
        }
    }
}
