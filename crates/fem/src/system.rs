//! The assembled and factorised stiffness system of one model.

use std::time::{Duration, Instant};

use contopt_core::{Error, Result};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use faer::{Mat, Side};

use crate::element::{GAUSS3, MAX_NODES};
use crate::factor::Factor;
use crate::{Analysis, FeModel};

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

/// A rigid-body mode over all global DOFs, with its name.
#[derive(Clone, Debug)]
pub(crate) struct Mode {
    pub name: String,
    pub values: Vec<f64>,
}

/// Stiffness matrix of the free unknowns, factorised, with the free unknowns of `tail_nodes`
/// numbered last.
pub(crate) struct System {
    pub dofs: Vec<Dof>,
    pub n_free: usize,
    pub n_tail: usize,
    pub modes: Vec<Mode>,
    /// K_fp u_p: the effect of prescribed displacements on the free equations.
    pub prescribed_load: Vec<f64>,
    pub factor: Factor,
    pub assembly_time: Duration,
    pub factorisation_time: Duration,
}

/// Gradient operator at a point of an element: shape functions, their x/y derivatives,
/// the integration measure, and the radius (for the hoop strain).
pub(crate) struct PointB {
    pub n: [f64; MAX_NODES],
    pub dx: [f64; MAX_NODES],
    pub dy: [f64; MAX_NODES],
    pub x: [f64; 2],
    pub dv: f64,
}

/// Status of every global DOF, with the free unknowns numbered: interior first, then those
/// of `tail_nodes`; with `pin`, one unknown per free rigid mode is held (see [`pins`]).
pub(crate) struct Numbering {
    pub dofs: Vec<Dof>,
    pub n_free: usize,
    pub n_tail: usize,
    pub modes: Vec<Mode>,
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
        let modes = free_rigid_modes(model, &dofs)?;
        if pin {
            for d in pins(&modes, &dofs, &on_tail) {
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

impl System {
    pub fn new(model: &FeModel, name: &str, tail_nodes: &[usize]) -> Result<Self> {
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

    /// Solves for the nodal displacements (length 2·nodes) under the model's given loads plus
    /// `extra` nodal forces (length 2·nodes).
    pub fn solve(&self, model: &FeModel, extra: Option<&[f64]>) -> Vec<f64> {
        let mut rhs = Mat::<f64>::zeros(self.n_free, 1);
        for (g, d) in self.dofs.iter().enumerate() {
            if let Dof::Free(i) = d {
                rhs[(*i, 0)] = model.forces[g] + extra.map_or(0.0, |e| e[g]);
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
}

/// Shape functions and x/y derivatives at (ξ, η) of element `e`, with dV = measure·det J·w.
pub(crate) fn point_b(model: &FeModel, e: usize, xi: f64, eta: f64, w: f64) -> Result<PointB> {
    let mesh = &model.mesh;
    let (j, det) = mesh.jacobian(e, xi, eta);
    let s = mesh.kind().shape(xi, eta);
    if det.is_nan() || det <= 0.0 {
        return Err(Error::Mesh(format!("element {e} has a singular Jacobian")));
    }
    let jinv = [
        [j[1][1] / det, -j[0][1] / det],
        [-j[1][0] / det, j[0][0] / det],
    ];
    let mut b = PointB {
        n: s.n,
        dx: [0.0; MAX_NODES],
        dy: [0.0; MAX_NODES],
        x: [0.0; 2],
        dv: 0.0,
    };
    for (a, &node) in mesh.elements()[e].iter().enumerate() {
        b.dx[a] = jinv[0][0] * s.dxi[a] + jinv[0][1] * s.deta[a];
        b.dy[a] = jinv[1][0] * s.dxi[a] + jinv[1][1] * s.deta[a];
        let p = mesh.nodes()[node];
        b.x[0] += s.n[a] * p[0];
        b.x[1] += s.n[a] * p[1];
    }
    b.dv = model.analysis.measure(b.x[0]) * det * w;
    Ok(b)
}

/// Strain-displacement rows of node `a`: (coefficient of u_x, coefficient of u_y) for each
/// strain component, in the order of [`Analysis::elasticity`].
pub(crate) fn strain_rows(analysis: Analysis, b: &PointB, a: usize) -> [[f64; 2]; 4] {
    match analysis {
        Analysis::Axisymmetric => [
            [b.dx[a], 0.0],
            [0.0, b.dy[a]],
            [b.n[a] / b.x[0], 0.0],
            [b.dy[a], b.dx[a]],
        ],
        _ => [
            [b.dx[a], 0.0],
            [0.0, b.dy[a]],
            [b.dy[a], b.dx[a]],
            [0.0, 0.0],
        ],
    }
}

/// Element stiffness ∫ Bᵀ D B dV by 3 × 3 Gauss quadrature.
fn element_stiffness(
    model: &FeModel,
    e: usize,
    d: &[[f64; 4]; 4],
    ke: &mut [[f64; 2 * MAX_NODES]; 2 * MAX_NODES],
) -> Result<()> {
    let nn = model.mesh.kind().n_nodes();
    let ns = model.analysis.n_strain();
    for row in ke.iter_mut() {
        row.fill(0.0);
    }
    for &(xi, wx) in &GAUSS3 {
        for &(eta, wy) in &GAUSS3 {
            let b = point_b(model, e, xi, eta, wx * wy)?;
            let rows: [[[f64; 2]; 4]; MAX_NODES] =
                std::array::from_fn(|a| strain_rows(model.analysis, &b, a));
            let rows = &rows[..nn];
            for a in 0..nn {
                for ca in 0..2 {
                    // (D B)_{:, (a, ca)}
                    let mut db = [0.0; 4];
                    for (i, dbi) in db.iter_mut().enumerate().take(ns) {
                        *dbi = (0..ns).map(|k| d[i][k] * rows[a][k][ca]).sum::<f64>() * b.dv;
                    }
                    for (bn, row_b) in rows.iter().enumerate() {
                        for cb in 0..2 {
                            ke[2 * bn + cb][2 * a + ca] +=
                                (0..ns).map(|k| row_b[k][cb] * db[k]).sum::<f64>();
                        }
                    }
                }
            }
        }
    }
    Ok(())
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
/// `offset`.
pub(crate) fn assemble(model: &FeModel, dofs: &[Dof], offset: usize) -> Result<Triplets> {
    let d = model.analysis.elasticity(&model.material);
    let nn = model.mesh.kind().n_nodes();
    let n_el = model.mesh.elements().len();
    let per = (2 * nn) * (2 * nn + 1) / 2;
    let n_free = dofs.iter().filter(|d| matches!(d, Dof::Free(_))).count();
    let mut t = Triplets {
        idx: Vec::with_capacity(n_el * per),
        val: Vec::with_capacity(n_el * per),
        prescribed_load: vec![0.0; n_free],
    };
    let mut ke = [[0.0; 2 * MAX_NODES]; 2 * MAX_NODES];
    for (e, conn) in model.mesh.elements().iter().enumerate() {
        element_stiffness(model, e, &d, &mut ke)?;
        let g = |k: usize| 2 * conn[k / 2] + k % 2;
        for kb in 0..2 * nn {
            let Dof::Free(j) = dofs[g(kb)] else { continue };
            for ka in 0..2 * nn {
                match dofs[g(ka)] {
                    Dof::Free(i) if i <= j => {
                        t.idx.push(Pair::new(offset + i, offset + j));
                        t.val.push(ke[ka][kb]);
                    }
                    Dof::Prescribed(v) if v != 0.0 => t.prescribed_load[j] += ke[kb][ka] * v,
                    _ => {}
                }
            }
        }
    }
    Ok(t)
}

/// Candidate rigid-body modes of the analysis, over all global DOFs: the axial translation
/// in axisymmetry (a radial translation strains the hoop direction); two translations and
/// the rotation about the centroid in plane analyses.
fn candidate_modes(model: &FeModel) -> Vec<Mode> {
    let nodes = model.mesh.nodes();
    let n = nodes.len();
    let field = |f: &dyn Fn([f64; 2]) -> [f64; 2]| -> Vec<f64> {
        nodes.iter().flat_map(|&p| f(p)).collect()
    };
    let mut modes = vec![];
    if model.analysis != Analysis::Axisymmetric {
        modes.push(Mode {
            name: "x translation".into(),
            values: field(&|_| [1.0, 0.0]),
        });
    }
    modes.push(Mode {
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
        modes.push(Mode {
            name: "rotation".into(),
            values: field(&|p| [-(p[1] - c[1]), p[0] - c[0]]),
        });
    }
    modes
}

/// The rigid-body modes that no prescribed DOF restrains: the null space of the candidate
/// modes restricted to the prescribed DOFs.
fn free_rigid_modes(model: &FeModel, dofs: &[Dof]) -> Result<Vec<Mode>> {
    let candidates = candidate_modes(model);
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
            None => Mode {
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
/// values so the modes stay well determined; unknowns off the contact face are preferred.
fn pins(modes: &[Mode], dofs: &[Dof], on_tail: &[bool]) -> Vec<usize> {
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
                .filter(|(_, r)| !off_face_only || (!on_tail[r.0 / 2] && norm2(&r.1) >= near))
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
