//! The assembled and factorised stiffness system of one model.

use std::time::{Duration, Instant};

use contopt_core::{memory, Error, Result};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Side};
use nalgebra::{Matrix4, SMatrix};

use crate::element::{ElementKind, GAUSS3, MAX_NODES};
use crate::factor::Factor;
use crate::mesh::mesh_bytes;
use crate::{Analysis, Face, FeModel};

/// A candidate rigid mode whose Gram eigenvalue on the held DOFs (relative to its norm) is
/// below this moves no support: it is free (round-off).
const UNRESTRAINED: f64 = 1e-10;

/// A free mode is one candidate alone when the others' coefficients are below this times its
/// own (round-off).
const ONE_CANDIDATE: f64 = 1e-12;

/// A pinned unknown off the contact face is preferred when its mode residual is within this
/// fraction of the largest (a heuristic: it keeps the face's unknowns free).
const OFF_FACE: f64 = 0.1;

/// Status of a global degree of freedom 2·node + component.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Dof {
    /// Unknown number `i` of the reduced system.
    Free(usize),
    /// Prescribed value (support or prescribed displacement).
    Prescribed(f64),
    /// Held at zero to remove a free rigid-body mode; the mode is carried separately.
    Pinned,
}

/// A rigid-body motion of a model over all its global DOFs (u_x, u_y per node), with its
/// name (`"x translation"`, `"y translation"`, `"rotation"`, `"axial translation"`, or
/// `"combined rigid motion"`): one its supports leave free ([`FeModel::free_motions`]).
#[derive(Clone, Debug, PartialEq)]
pub struct RigidMotion {
    /// Its name, as a body's rigid modes are named.
    pub name: String,
    /// Its nodal displacements (u_x, u_y per node).
    pub values: Vec<f64>,
}

impl RigidMotion {
    /// Its displacement along the outward normal at the three Gauss points of each of `faces`
    /// (boundary faces of `model`'s mesh), face after face: zero where the motion slides along
    /// the faces (a contact on them cannot hold it).
    pub fn along_normals(&self, model: &FeModel, faces: &[Face]) -> Vec<f64> {
        faces
            .iter()
            .flat_map(|&f| {
                let nodes = model.mesh.face_nodes(f);
                GAUSS3.map(|(s, _)| {
                    let fp = model.face_point(f, s);
                    (0..3)
                        .map(|k| {
                            let u = [self.values[2 * nodes[k]], self.values[2 * nodes[k] + 1]];
                            fp.shape[k] * (u[0] * fp.normal[0] + u[1] * fp.normal[1])
                        })
                        .sum::<f64>()
                })
            })
            .collect()
    }
}

/// Stiffness matrix of the free unknowns, factorised, with the free unknowns of `tail_nodes`
/// numbered last.
pub(crate) struct System {
    pub dofs: Vec<Dof>,
    pub n_free: usize,
    pub n_tail: usize,
    pub modes: Vec<RigidMotion>,
    /// K_fp u_p: the effect of prescribed displacements on the free equations.
    pub prescribed_load: Vec<f64>,
    pub factor: Factor,
    pub assembly_time: Duration,
    pub factorisation_time: Duration,
}

/// Gradient operator at a point of an element: shape functions, their x/y derivatives,
/// the integration measure, and the position (its radius for the hoop strain).
pub(crate) struct PointB {
    /// Nₐ (zero past the element's nodes).
    pub n: [f64; MAX_NODES],
    /// ∂Nₐ/∂x (row 0) and ∂Nₐ/∂y (row 1): J⁻¹ (∂Nₐ/∂ξ, ∂Nₐ/∂η)ᵀ.
    pub grad: SMatrix<f64, 2, MAX_NODES>,
    /// Position (x, y), or (r, z) in axisymmetry.
    pub x: [f64; 2],
    /// Integration weight: measure · det J · Gauss weight.
    pub dv: f64,
}

/// Status of every global DOF, with the free unknowns numbered: interior first, then those
/// of `tail_nodes`; with `pin`, one unknown per free rigid mode is held (see [`pins`]).
pub(crate) struct Numbering {
    pub dofs: Vec<Dof>,
    pub n_free: usize,
    pub n_tail: usize,
    pub modes: Vec<RigidMotion>,
}

impl Numbering {
    pub fn new(model: &FeModel, tail_nodes: &[usize], pin: bool) -> Result<Self> {
        let n_nodes = model.mesh.nodes().len();
        let mut dofs = vec![Dof::Free(usize::MAX); 2 * n_nodes];
        for (&(node, c), &v) in &model.prescribed {
            dofs[2 * node + c as usize] = Dof::Prescribed(v);
        }
        let mut on_tail = vec![false; n_nodes];
        for &n in tail_nodes {
            on_tail[n] = true;
        }
        let modes = free_rigid_modes(candidate_modes(model), &dofs)?;
        if pin {
            let tail_dof: Vec<bool> = (0..dofs.len()).map(|g| on_tail[g / 2]).collect();
            for d in pins(&modes, &dofs, &tail_dof) {
                dofs[d] = Dof::Pinned;
            }
        }
        let mut n_free = 0;
        for tail in [false, true] {
            for (g, d) in dofs.iter_mut().enumerate() {
                if on_tail[g / 2] == tail && matches!(d, Dof::Free(_)) {
                    *d = Dof::Free(n_free);
                    n_free += 1;
                }
            }
        }
        if n_free == 0 {
            return Err(Error::invalid(
                "supports",
                "every degree of freedom",
                "leave at least one unknown",
            ));
        }
        let n_tail = dofs
            .iter()
            .enumerate()
            .filter(|(g, d)| on_tail[g / 2] && matches!(d, Dof::Free(_)))
            .count();
        Ok(Self {
            dofs,
            n_free,
            n_tail,
            modes,
        })
    }
}

impl FeModel {
    /// The rigid-body motions its supports leave free: some of the x and y translations and
    /// the rotation about the centroid in a plane analysis, the axial translation in
    /// axisymmetry (none for a held model). A body built of the model floats in them (its
    /// rigid modes), so a contact must hold each ([`RigidMotion::along_normals`] says whether
    /// it moves the contact faces). Nothing is assembled. (Here, beside the numbering that
    /// finds them, so that the model does not import the system built of it.)
    pub fn free_motions(&self) -> Result<Vec<RigidMotion>> {
        Ok(Numbering::new(self, &[], false)?.modes)
    }
}

impl System {
    /// Assembles and factorises `model`'s stiffness, the unknowns of `tail_nodes` last, after
    /// checking the memory of a body condensed to `face_points` contact points
    /// ([`mesh_bytes`]) against [`memory::BODY_LIMIT_BYTES`]: an imported mesh is refused with
    /// its size before its factor is allocated.
    pub fn new(
        model: &FeModel,
        name: &str,
        tail_nodes: &[usize],
        face_points: usize,
    ) -> Result<Self> {
        let nodes = model.mesh.nodes().len();
        memory::require(
            format!("{name}: a body of {nodes} nodes and {face_points} contact points"),
            mesh_bytes(nodes, face_points),
            memory::BODY_LIMIT_BYTES,
            "use fewer elements",
        )?;
        let Numbering {
            dofs,
            n_free,
            n_tail,
            modes,
        } = Numbering::new(model, tail_nodes, true)?;
        let start = Instant::now();
        let stiffness = assemble(model, &dofs, 0)?;
        let matrix = stiffness.matrix(n_free)?;
        let assembly_time = start.elapsed();
        let start = Instant::now();
        let factor = Factor::new(matrix.as_ref(), n_tail, name)?;
        let factorisation_time = start.elapsed();
        Ok(Self {
            dofs,
            n_free,
            n_tail,
            modes,
            prescribed_load: stiffness.prescribed_load,
            factor,
            assembly_time,
            factorisation_time,
        })
    }

    /// Solves for the nodal displacements (one per global DOF) under the model's given nodal
    /// `forces` plus `extra` nodal forces (both one per global DOF).
    pub fn solve(&self, forces: &[f64], extra: Option<&[f64]>) -> Vec<f64> {
        let mut rhs = Mat::<f64>::zeros(self.n_free, 1);
        for (g, d) in self.dofs.iter().enumerate() {
            if let Dof::Free(i) = d {
                rhs[(*i, 0)] = forces[g] + extra.map_or(0.0, |e| e[g]);
            }
        }
        for (i, v) in self.prescribed_load.iter().enumerate() {
            rhs[(i, 0)] -= v;
        }
        self.factor.solve_in_place(rhs.as_mut());
        self.dofs
            .iter()
            .map(|d| match *d {
                Dof::Free(i) => rhs[(i, 0)],
                Dof::Prescribed(v) => v,
                Dof::Pinned => 0.0,
            })
            .collect()
    }

    /// The influence matrix A = L K⁻¹ Lᵀ (eq. 2.22) from the face block T of K⁻¹, the face
    /// unknowns being numbered last; `rows` are the rows of L, each the (global DOF,
    /// coefficient) pairs of one interface point. A row holds a face's unknowns only, so A is
    /// formed from sparse rows — T Lᵀ, then L (T Lᵀ) — in O(points · face unknowns + points²)
    /// rather than the dense products' O(points · face unknowns²).
    pub fn condense<R>(&self, rows: impl IntoIterator<Item = R>) -> Mat<f64>
    where
        R: IntoIterator<Item = (usize, f64)>,
    {
        let tail = self.factor.tail_inverse();
        let first_tail = self.n_free - self.n_tail;
        // The face unknowns of each row, by position in T, with their coefficients.
        let sparse: Vec<Vec<(usize, f64)>> = rows
            .into_iter()
            .map(|r| {
                (r.into_iter())
                    .filter_map(|(g, c)| match self.dofs[g] {
                        Dof::Free(k) if k >= first_tail => Some((k - first_tail, c)),
                        _ => None,
                    })
                    .collect()
            })
            .collect();
        // Tᵀ = T, so the columns of T Lᵀ are sums of columns of T (contiguous).
        let mut t_lt = Mat::<f64>::zeros(self.n_tail, sparse.len());
        for (i, row) in sparse.iter().enumerate() {
            for &(k, c) in row {
                for (out, &v) in t_lt.col_mut(i).iter_mut().zip(tail.col(k).iter()) {
                    *out += c * v;
                }
            }
        }
        Mat::from_fn(sparse.len(), sparse.len(), |i, j| {
            sparse[i].iter().map(|&(k, c)| c * t_lt[(k, j)]).sum()
        })
    }
}

/// Shape functions and x/y derivatives at (ξ, η) of element `e`, with dV = measure·det J·w.
pub(crate) fn point_b(model: &FeModel, e: usize, xi: f64, eta: f64, w: f64) -> Result<PointB> {
    let mesh = &model.mesh;
    let (j, det) = mesh.jacobian(e, xi, eta);
    let s = mesh.element_kind(e).shape(xi, eta);
    let jinv = j
        .try_inverse()
        .filter(|_| det > 0.0)
        .ok_or_else(|| Error::Mesh(format!("element {e} has a singular Jacobian")))?;
    let natural = SMatrix::<f64, 2, MAX_NODES>::from_rows(&[s.dxi.into(), s.deta.into()]);
    let mut x = [0.0; 2];
    for (a, &node) in mesh.elements()[e].iter().enumerate() {
        let p = mesh.nodes()[node];
        x[0] += s.n[a] * p[0];
        x[1] += s.n[a] * p[1];
    }
    Ok(PointB {
        n: s.n,
        grad: jinv * natural,
        x,
        dv: model.analysis.measure(x[0]) * det * w,
    })
}

/// The elasticity matrix D of the model ([`Analysis::elasticity`]).
fn elasticity(model: &FeModel) -> Matrix4<f64> {
    let d = model.analysis.elasticity(&model.material);
    Matrix4::from_fn(|i, k| d[i][k])
}

/// Strain-displacement rows of node `a`: (coefficient of u_x, coefficient of u_y) for each
/// strain component, in the order of [`Analysis::elasticity`].
pub(crate) fn strain_rows(analysis: Analysis, b: &PointB, a: usize) -> [[f64; 2]; 4] {
    let (dx, dy) = (b.grad[(0, a)], b.grad[(1, a)]);
    match analysis {
        Analysis::Axisymmetric => [[dx, 0.0], [0.0, dy], [b.n[a] / b.x[0], 0.0], [dy, dx]],
        _ => [[dx, 0.0], [0.0, dy], [dy, dx], [0.0, 0.0]],
    }
}

/// Strain-displacement matrix B (4 × `M`) at a point: the strain rows ([`strain_rows`]) of
/// the element's nodes side by side, ε = B uₑ for the element's `M` = 2·nodes displacements
/// uₑ = (u_x, u_y) node after node. Plane analyses leave the fourth row zero.
fn strain_matrix<const M: usize>(analysis: Analysis, b: &PointB) -> SMatrix<f64, 4, M> {
    let mut bm = SMatrix::zeros();
    for a in 0..M / 2 {
        for (k, row) in strain_rows(analysis, b, a).iter().enumerate() {
            bm[(k, 2 * a)] = row[0];
            bm[(k, 2 * a + 1)] = row[1];
        }
    }
    bm
}

/// Element stiffness Kₑ = ∫ Bᵀ D B dV by the element's quadrature
/// ([`ElementKind::integration_points`]), `M` = 2·nodes.
fn element_stiffness<const M: usize>(
    model: &FeModel,
    e: usize,
    d: &Matrix4<f64>,
) -> Result<SMatrix<f64, M, M>> {
    let mut ke = SMatrix::<f64, M, M>::zeros();
    for p in model.mesh.element_kind(e).integration_points() {
        let b = point_b(model, e, p.xi, p.eta, p.weight)?;
        let bm = strain_matrix::<M>(model.analysis, &b);
        ke.gemm_tr(1.0, &bm, &(d * bm * b.dv), 1.0);
    }
    Ok(ke)
}

impl FeModel {
    /// The stiffness matrix Kₑ = ∫ Bᵀ D B dV of element `e` (at its integration points:
    /// 3 × 3 Gauss points on a quadrilateral, 6 on a triangle), of order 2·nodes, its unknowns
    /// (u_x, u_y) node after node in the element's local order ([`crate::element`]).
    /// Errors: no such element, or a singular Jacobian.
    pub fn element_stiffness(&self, e: usize) -> Result<Mat<f64>> {
        let n = self.mesh.elements().len();
        if e >= n {
            return Err(Error::invalid(
                "element",
                e,
                format!("no such element (mesh has {n})"),
            ));
        }
        let d = elasticity(self);
        match self.mesh.element_kind(e) {
            ElementKind::Q8 => element_stiffness::<16>(self, e, &d).map(to_mat),
            ElementKind::Q9 => element_stiffness::<18>(self, e, &d).map(to_mat),
            ElementKind::T6 => element_stiffness::<12>(self, e, &d).map(to_mat),
        }
    }
}

/// A fixed-size matrix copied into a faer matrix.
fn to_mat<const M: usize>(k: SMatrix<f64, M, M>) -> Mat<f64> {
    Mat::from_fn(M, M, |i, j| k[(i, j)])
}

/// The upper triangle of a stiffness matrix as (row, column) pairs and values (duplicates
/// summed when the matrix is built), with K_fp u_p, the effect of prescribed displacements.
pub(crate) struct Triplets {
    pub idx: Vec<Pair<usize, usize>>,
    pub val: Vec<f64>,
    pub prescribed_load: Vec<f64>,
}

impl Triplets {
    /// The n × n sparse matrix (upper triangle).
    pub fn matrix(&self, n: usize) -> Result<SparseColMat<usize, f64>> {
        let (pattern, order) = SymbolicSparseColMat::try_new_from_indices(n, n, &self.idx)
            .map_err(|e| Error::Mesh(format!("sparse pattern: {e:?}")))?;
        SparseColMat::new_from_argsort(pattern, &order, &self.val)
            .map_err(|e| Error::Mesh(format!("sparse values: {e:?}")))
    }
}

/// Assembles the element stiffnesses over the free unknowns of `dofs`, numbered from
/// `offset`: each element by the kernel of its kind ([`element_stiffness`], compiled for each
/// size), in element order.
pub(crate) fn assemble(model: &FeModel, dofs: &[Dof], offset: usize) -> Result<Triplets> {
    let d = elasticity(model);
    let mesh = &model.mesh;
    let entries: usize = (0..mesh.elements().len())
        .map(|e| {
            let m = 2 * mesh.element_kind(e).n_nodes();
            m * (m + 1) / 2
        })
        .sum();
    let n_free = dofs.iter().filter(|d| matches!(d, Dof::Free(_))).count();
    let mut t = Triplets {
        idx: Vec::with_capacity(entries),
        val: Vec::with_capacity(entries),
        prescribed_load: vec![0.0; n_free],
    };
    for e in 0..mesh.elements().len() {
        let conn = &mesh.elements()[e];
        match mesh.element_kind(e) {
            ElementKind::Q8 => t.add(&element_stiffness::<16>(model, e, &d)?, conn, dofs, offset),
            ElementKind::Q9 => t.add(&element_stiffness::<18>(model, e, &d)?, conn, dofs, offset),
            ElementKind::T6 => t.add(&element_stiffness::<12>(model, e, &d)?, conn, dofs, offset),
        }
    }
    Ok(t)
}

impl Triplets {
    /// Adds the element stiffness `ke` of an element of nodes `conn`: its entries between free
    /// unknowns (upper triangle, numbered from `offset`) and K_fp u_p of its prescribed ones.
    fn add<const M: usize>(
        &mut self,
        ke: &SMatrix<f64, M, M>,
        conn: &[usize],
        dofs: &[Dof],
        offset: usize,
    ) {
        let g = |k: usize| 2 * conn[k / 2] + k % 2;
        for kb in 0..M {
            let Dof::Free(j) = dofs[g(kb)] else { continue };
            for ka in 0..M {
                match dofs[g(ka)] {
                    Dof::Free(i) if i <= j => {
                        self.idx.push(Pair::new(offset + i, offset + j));
                        self.val.push(ke[(ka, kb)]);
                    }
                    Dof::Prescribed(v) if v != 0.0 => self.prescribed_load[j] += ke[(kb, ka)] * v,
                    _ => {}
                }
            }
        }
    }
}

/// Candidate rigid-body modes of the analysis, over all global DOFs: the axial translation
/// in axisymmetry (a radial translation strains the hoop direction); two translations and
/// the rotation about the centroid in plane analyses.
fn candidate_modes(model: &FeModel) -> Vec<RigidMotion> {
    let nodes = model.mesh.nodes();
    let n = nodes.len();
    let field = |f: &dyn Fn([f64; 2]) -> [f64; 2]| -> Vec<f64> {
        nodes.iter().flat_map(|&p| f(p)).collect()
    };
    let mut modes = vec![];
    if model.analysis != Analysis::Axisymmetric {
        modes.push(RigidMotion {
            name: "x translation".into(),
            values: field(&|_| [1.0, 0.0]),
        });
    }
    modes.push(RigidMotion {
        name: if model.analysis == Analysis::Axisymmetric {
            "axial translation"
        } else {
            "y translation"
        }
        .into(),
        values: field(&|_| [0.0, 1.0]),
    });
    if model.analysis != Analysis::Axisymmetric {
        let c = nodes.iter().fold([0.0; 2], |s, p| {
            [s[0] + p[0] / n as f64, s[1] + p[1] / n as f64]
        });
        modes.push(RigidMotion {
            name: "rotation".into(),
            values: field(&|p| [-(p[1] - c[1]), p[0] - c[0]]),
        });
    }
    modes
}

/// The rigid-body modes that no prescribed DOF restrains: the null space of the candidate
/// modes restricted to the prescribed DOFs (plane, axisymmetric and solid models alike).
pub(crate) fn free_rigid_modes(
    candidates: Vec<RigidMotion>,
    dofs: &[Dof],
) -> Result<Vec<RigidMotion>> {
    let m = candidates.len();
    let held: Vec<usize> = (0..dofs.len())
        .filter(|&g| matches!(dofs[g], Dof::Prescribed(_)))
        .collect();
    // Gram matrix of the candidates on the held DOFs, scaled by their norms over all DOFs.
    let norm: Vec<f64> = candidates
        .iter()
        .map(|c| c.values.iter().map(|v| v * v).sum::<f64>().sqrt())
        .collect();
    let gram = Mat::<f64>::from_fn(m, m, |a, b| {
        held.iter()
            .map(|&g| candidates[a].values[g] * candidates[b].values[g])
            .sum::<f64>()
            / (norm[a] * norm[b])
    });
    let eig = gram
        .self_adjoint_eigen(Side::Lower)
        .map_err(|e| Error::Mesh(format!("rigid modes of the supports: {e:?}")))?;
    let (values, vectors) = (eig.S().column_vector(), eig.U());
    let mut modes = vec![];
    for k in 0..m {
        if values[k] > UNRESTRAINED {
            continue;
        }
        let coef: Vec<f64> = (0..m)
            .map(|a| vectors[(a, k)] / norm[a] * norm[0])
            .collect();
        let single = (0..m)
            .find(|&a| (0..m).all(|b| b == a || coef[b].abs() < ONE_CANDIDATE * coef[a].abs()));
        let mode = match single {
            Some(a) => candidates[a].clone(),
            None => RigidMotion {
                name: "combined rigid motion".into(),
                values: (0..dofs.len())
                    .map(|g| (0..m).map(|a| coef[a] * candidates[a].values[g]).sum())
                    .collect(),
            },
        };
        modes.push(mode);
    }
    Ok(modes)
}

/// One unknown per free mode to hold at zero, chosen by pivoted Gram–Schmidt on the mode
/// values so the modes stay well determined; unknowns off the contact face (`on_tail[g]`
/// false) are preferred.
pub(crate) fn pins(modes: &[RigidMotion], dofs: &[Dof], on_tail: &[bool]) -> Vec<usize> {
    let m = modes.len();
    let mut rows: Vec<(usize, Vec<f64>)> = (0..dofs.len())
        .filter(|&g| matches!(dofs[g], Dof::Free(_)))
        .map(|g| (g, modes.iter().map(|md| md.values[g]).collect()))
        .collect();
    let mut chosen = vec![];
    let norm2 = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    for _ in 0..m {
        // Largest residual overall; an unknown off the face wins if it is within 10 % of it.
        let largest = rows.iter().map(|r| norm2(&r.1)).fold(0.0, f64::max);
        let near = OFF_FACE * OFF_FACE * largest;
        let pick = |off_face_only: bool| {
            rows.iter()
                .enumerate()
                .filter(|(_, r)| !off_face_only || (!on_tail[r.0] && norm2(&r.1) >= near))
                .max_by(|(_, a), (_, b)| norm2(&a.1).total_cmp(&norm2(&b.1)))
                .map(|(i, _)| i)
        };
        let best = pick(true).or_else(|| pick(false));
        let Some(i) = best else { break };
        let (g, q) = rows.swap_remove(i);
        let qn = norm2(&q).sqrt();
        if qn == 0.0 {
            break;
        }
        chosen.push(g);
        for (_, r) in rows.iter_mut() {
            let dot: f64 = r.iter().zip(&q).map(|(a, b)| a * b).sum::<f64>() / (qn * qn);
            for (rv, qv) in r.iter_mut().zip(&q) {
                *rv -= dot * qv;
            }
        }
    }
    chosen
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Material, Mesh, Spacing};

    /// Round-off of a stiffness entry, of the strain energy and of the forces of a rigid
    /// motion, relative to the largest entry (or the energy).
    const ROUND_OFF: f64 = 1e-12;

    #[test]
    fn element_stiffness_is_symmetric_and_integrates_a_uniform_strain() {
        // One plane-stress parallelogram, 2 mm thick: the affine map (det 0.96) of a 3 × 2
        // rectangle (for T6 two triangles), so det J is constant and the quadrature integrates
        // the energy of a uniform strain exactly.
        let thickness = 2.0;
        let analysis = Analysis::PlaneStress { thickness };
        let material = Material::new(2e5, 0.3).unwrap();
        for kind in ElementKind::ALL {
            let rectangle = Mesh::rectangle(
                kind,
                &Spacing::uniform(0.0, 3.0, 1).unwrap(),
                &Spacing::uniform(0.0, 2.0, 1).unwrap(),
            )
            .unwrap();
            let mesh = rectangle
                .map(|p| [p[0] + 0.4 * p[1], p[1] + 0.1 * p[0]])
                .unwrap();
            // One quadrilateral, or the first of two triangles of half the area.
            let area = 6.0 * 0.96 / mesh.elements().len() as f64;
            let model = FeModel::new(mesh, material, analysis).unwrap();
            let k = model.element_stiffness(0).unwrap();
            let n = 2 * kind.n_nodes();
            assert_eq!((k.nrows(), k.ncols()), (n, n));
            let largest = (0..n).map(|i| k[(i, i)]).fold(0.0, f64::max);
            for i in 0..n {
                for j in 0..n {
                    assert!((k[(i, j)] - k[(j, i)]).abs() <= ROUND_OFF * largest);
                }
            }
            // u = (1e-3 x + 2e-4 y, −3e-4 x + 5e-4 y): uᵀ K u = εᵀ D ε · area · thickness.
            let field = |p: [f64; 2]| [1e-3 * p[0] + 2e-4 * p[1], -3e-4 * p[0] + 5e-4 * p[1]];
            let rotation = |p: [f64; 2]| [-p[1], p[0]];
            let nodal = |f: &dyn Fn([f64; 2]) -> [f64; 2]| -> Vec<f64> {
                model.mesh.elements()[0]
                    .iter()
                    .flat_map(|&a| f(model.mesh.nodes()[a]))
                    .collect()
            };
            let (u, r) = (nodal(&field), nodal(&rotation));
            let ku = |v: &[f64], i: usize| (0..n).map(|j| k[(i, j)] * v[j]).sum::<f64>();
            let energy: f64 = (0..n).map(|i| u[i] * ku(&u, i)).sum();
            let strain = [1e-3, 5e-4, 2e-4 - 3e-4];
            let d = analysis.elasticity(&material);
            let want = (0..3)
                .map(|i| (0..3).map(|j| strain[i] * d[i][j] * strain[j]).sum::<f64>())
                .sum::<f64>()
                * area
                * thickness;
            assert!((energy - want).abs() <= ROUND_OFF * want, "{energy} {want}");
            let scale = largest * r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!((0..n).all(|i| ku(&r, i).abs() <= ROUND_OFF * scale));
            assert!(model
                .element_stiffness(model.mesh.elements().len())
                .is_err());
        }
    }

    /// A body whose condensation would not fit is refused with its size before anything is
    /// assembled: a 1 × 20 000 strip of Q8 is small, but condensed onto its 20 000 side faces
    /// (60 000 points) its dense matrices would take 115 GB.
    #[test]
    fn a_body_too_large_to_condense_is_refused_before_assembly() {
        let mesh = Mesh::rectangle(
            ElementKind::Q8,
            &Spacing::uniform(0.0, 1.0, 1).unwrap(),
            &Spacing::uniform(0.0, 20_000.0, 20_000).unwrap(),
        )
        .unwrap();
        let material = Material::new(2e5, 0.3).unwrap();
        let mut model = FeModel::new(mesh, material, Analysis::Axisymmetric).unwrap();
        let bottom = model.mesh().nodes_on_y(0.0, 0.0, 1.0);
        model.fix(&bottom, crate::Component::Y).unwrap();
        let side = model.mesh().faces_on_x(1.0, 0.0, 20_000.0);
        assert_eq!(side.len(), 20_000);
        let e = crate::FeBody::new("strip", model, &side).err().unwrap();
        let message = e.to_string();
        assert!(
            matches!(e, Error::TooLarge { .. })
                && message.contains("strip: a body of 100003 nodes and 60000 contact points"),
            "{message}"
        );
    }
}
