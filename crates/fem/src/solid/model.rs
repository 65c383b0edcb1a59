//! A linear-elastic solid: its mesh, material, supports and loads, its element stiffness and
//! the stresses of a displacement field.
// Loops over the axes x, y, z index several arrays at once, as the formulas do.
#![allow(clippy::needless_range_loop)]

use std::collections::BTreeMap;

use contopt_core::{check, Error, Material, Result, StressTensor};

use super::element::MAX_SOLID_NODES;
use super::mesh::{SolidFace, SolidMesh};
use super::sample::SolidSample;
use crate::system::RigidMotion;

/// A direction of space.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Axis {
    /// x.
    X = 0,
    /// y.
    Y = 1,
    /// z.
    Z = 2,
}

impl Axis {
    /// x, y and z.
    pub const ALL: [Axis; 3] = [Axis::X, Axis::Y, Axis::Z];
}

/// A linear-elastic solid of quadratic elements with its supports and loads: the 3-D
/// counterpart of [`crate::FeModel`], with three displacement unknowns (u_x, u_y, u_z) per
/// node, numbered 3·node + axis.
#[derive(Clone, Debug)]
pub struct SolidModel {
    pub(crate) mesh: SolidMesh,
    pub(crate) material: Material,
    /// Prescribed displacements by (node, axis).
    pub(crate) prescribed: BTreeMap<(usize, usize), f64>,
    /// Nodal forces, 3 per node \[N\].
    pub(crate) forces: Vec<f64>,
}

/// Gradients of the shape functions at a point of an element, with the integration weight.
pub(crate) struct Gradients {
    /// ∂Nₐ/∂(x, y, z).
    pub grad: [[f64; 3]; MAX_SOLID_NODES],
    /// det J times the quadrature weight.
    pub dv: f64,
}

impl SolidModel {
    /// The unsupported, unloaded solid of `mesh` and `material`.
    pub fn new(mesh: SolidMesh, material: Material) -> Self {
        let n = mesh.nodes().len();
        Self {
            mesh,
            material,
            prescribed: BTreeMap::new(),
            forces: vec![0.0; 3 * n],
        }
    }

    /// The mesh.
    pub fn mesh(&self) -> &SolidMesh {
        &self.mesh
    }

    /// The material.
    pub fn material(&self) -> Material {
        self.material
    }

    /// Nodal forces (3 per node) of the given loads \[N\].
    pub fn forces(&self) -> &[f64] {
        &self.forces
    }

    /// Holds `nodes` along `axis` (a support, or a symmetry plane normal to `axis`).
    pub fn fix(&mut self, nodes: &[usize], axis: Axis) -> Result<()> {
        self.prescribe(nodes, axis, 0.0)
    }

    /// Prescribes displacement `value` \[mm\] along `axis` at `nodes`.
    pub fn prescribe(&mut self, nodes: &[usize], axis: Axis, value: f64) -> Result<()> {
        check::finite("displacement_mm", value)?;
        self.check_nodes(nodes)?;
        for &n in nodes {
            self.prescribed.insert((n, axis as usize), value);
        }
        Ok(())
    }

    /// Adds a uniform pressure `p` \[MPa\] on `faces` (boundary faces), positive into the body:
    /// the consistent nodal forces −∫ p n Nₐ dA.
    pub fn add_pressure(&mut self, faces: &[SolidFace], p: f64) -> Result<()> {
        check::finite("pressure_mpa", p)?;
        self.add_surface_load(faces, |normal| normal.map(|c| -p * c))
    }

    /// Adds a uniform traction `t` \[MPa\] on `faces`: the nodal forces ∫ t Nₐ dA.
    pub fn add_traction(&mut self, faces: &[SolidFace], t: [f64; 3]) -> Result<()> {
        check::all_finite("traction_mpa", &t)?;
        self.add_surface_load(faces, |_| t)
    }

    /// Adds a nodal force `f` \[N\] along `axis` at `node`.
    pub fn add_force(&mut self, node: usize, axis: Axis, f: f64) -> Result<()> {
        check::finite("force_n", f)?;
        self.check_nodes(&[node])?;
        self.forces[3 * node + axis as usize] += f;
        Ok(())
    }

    /// Adds ∫ t(n) Nₐ dA over `faces` at each face's load points.
    fn add_surface_load(
        &mut self,
        faces: &[SolidFace],
        traction: impl Fn([f64; 3]) -> [f64; 3],
    ) -> Result<()> {
        self.check_faces(faces)?;
        for &f in faces {
            let nodes = self.mesh.face_nodes(f);
            for (st, w) in self.mesh.face_kind(f).load_points() {
                let p = self.mesh.face_point(f, st);
                let t = traction(p.normal);
                for (a, &node) in nodes.iter().enumerate() {
                    for c in 0..3 {
                        self.forces[3 * node + c] += t[c] * p.shape.n[a] * p.da * w;
                    }
                }
            }
        }
        Ok(())
    }

    fn check_nodes(&self, nodes: &[usize]) -> Result<()> {
        let n = self.mesh.nodes().len();
        match nodes.iter().find(|&&a| a >= n) {
            Some(a) => Err(Error::invalid(
                "node",
                a,
                format!("no such node (mesh has {n})"),
            )),
            None => Ok(()),
        }
    }

    fn check_faces(&self, faces: &[SolidFace]) -> Result<()> {
        let n = self.mesh.n_elements();
        match faces
            .iter()
            .find(|f| f.element >= n || f.local >= self.mesh.kind(f.element).n_faces())
        {
            Some(f) => Err(Error::invalid("face", format!("{f:?}"), "no such face")),
            None => Ok(()),
        }
    }

    /// The gradients of element `e`'s shape functions at reference point `p` (quadrature
    /// weight `w`).
    pub(crate) fn gradients(&self, e: usize, p: [f64; 3], w: f64) -> Result<Gradients> {
        let (j, det, s) = self.mesh.jacobian(e, p);
        if det.is_nan() || det <= 0.0 {
            return Err(Error::Mesh(format!("element {e} has a singular Jacobian")));
        }
        let inv = inverse(&j, det);
        let mut grad = [[0.0; 3]; MAX_SOLID_NODES];
        for a in 0..self.mesh.kind(e).n_nodes() {
            // ∂N/∂x = J⁻ᵀ ∂N/∂ξ, with J = ∂x/∂ξ.
            for c in 0..3 {
                grad[a][c] = (0..3).map(|k| inv[k][c] * s.d[a][k]).sum();
            }
        }
        Ok(Gradients { grad, dv: det * w })
    }

    /// Lamé's constants (λ, μ).
    pub(crate) fn lame(&self) -> (f64, f64) {
        let (e, nu) = (self.material.e(), self.material.nu());
        let mu = e / (2.0 * (1.0 + nu));
        (e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), mu)
    }

    /// The stiffness matrix of element `e`, of order 3·nodes, unknowns (u_x, u_y, u_z) node
    /// after node in the element's order: Kₐᵦ = ∫ (λ ∇Nₐ ⊗ ∇Nᵦ + μ ∇Nᵦ ⊗ ∇Nₐ + μ ∇Nₐ·∇Nᵦ I) dV.
    pub fn element_stiffness(&self, e: usize) -> Result<Vec<f64>> {
        if e >= self.mesh.n_elements() {
            return Err(Error::invalid("element", e, "no such element"));
        }
        let kind = self.mesh.kind(e);
        let n = kind.n_nodes();
        let m = 3 * n;
        let (lambda, mu) = self.lame();
        let mut k = vec![0.0; m * m];
        for (p, w) in kind.integration_points() {
            let g = self.gradients(e, p, w)?;
            for a in 0..n {
                for b in 0..n {
                    let (ga, gb) = (g.grad[a], g.grad[b]);
                    let dot = ga[0] * gb[0] + ga[1] * gb[1] + ga[2] * gb[2];
                    for i in 0..3 {
                        for j in 0..3 {
                            let mut v = lambda * ga[i] * gb[j] + mu * ga[j] * gb[i];
                            if i == j {
                                v += mu * dot;
                            }
                            k[(3 * a + i) * m + 3 * b + j] += v * g.dv;
                        }
                    }
                }
            }
        }
        Ok(k)
    }

    /// The stress of displacement field `u` (3 per node) in element `e` at reference point `p`.
    pub fn stress_at(&self, u: &[f64], e: usize, p: [f64; 3]) -> Result<StressTensor> {
        let g = self.gradients(e, p, 1.0)?;
        let mut h = [[0.0; 3]; 3]; // ∂uᵢ/∂xⱼ
        for (a, &node) in self.mesh.element(e).iter().enumerate() {
            for i in 0..3 {
                for j in 0..3 {
                    h[i][j] += u[3 * node + i] * g.grad[a][j];
                }
            }
        }
        let (lambda, mu) = self.lame();
        let trace = h[0][0] + h[1][1] + h[2][2];
        let s = |i: usize, j: usize| {
            mu * (h[i][j] + h[j][i]) + if i == j { lambda * trace } else { 0.0 }
        };
        Ok(StressTensor {
            xx: s(0, 0),
            yy: s(1, 1),
            zz: s(2, 2),
            xy: s(0, 1),
            xz: s(0, 2),
            yz: s(1, 2),
        })
    }

    /// The displacement of `motion` along the outward normal at the contact points of each of
    /// `faces` ([`SolidSample::gauss`]), face after face: zero where it slides along them (a
    /// frictionless contact on them cannot hold it).
    pub fn along_normals(&self, motion: &RigidMotion, faces: &[SolidFace]) -> Vec<f64> {
        (SolidSample::gauss(&self.mesh, faces).iter())
            .map(|s| -s.row(&self.mesh).normal_into(&motion.values))
            .collect()
    }
}

/// J⁻¹ of a 3 × 3 matrix of determinant `det` (the adjugate over the determinant).
fn inverse(j: &[[f64; 3]; 3], det: f64) -> [[f64; 3]; 3] {
    let c =
        |r0: usize, c0: usize, r1: usize, c1: usize| j[r0][c0] * j[r1][c1] - j[r0][c1] * j[r1][c0];
    [
        [
            c(1, 1, 2, 2) / det,
            -c(0, 1, 2, 2) / det,
            c(0, 1, 1, 2) / det,
        ],
        [
            -c(1, 0, 2, 2) / det,
            c(0, 0, 2, 2) / det,
            -c(0, 0, 1, 2) / det,
        ],
        [
            c(1, 0, 2, 1) / det,
            -c(0, 0, 2, 1) / det,
            c(0, 0, 1, 1) / det,
        ],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solid::SolidKind;

    /// Relative round-off of a displacement or a stress of the patch test.
    const ROUND_OFF: f64 = 1e-10;

    fn steel() -> Material {
        Material::new(2e5, 0.3).unwrap()
    }

    /// A 2 × 2 × 2 block of `kind` over [0, 2] × [0, 3] × [0, 4] whose interior corners are
    /// moved off the grid (every element distorted: trilinearly for hexahedra, each
    /// tetrahedron straight-sided), the other nodes placed by the corners' linear or trilinear
    /// interpolation.
    fn distorted_block(kind: SolidKind) -> SolidMesh {
        let size = [2.0, 3.0, 4.0];
        let block = SolidMesh::block(kind, size, [2, 2, 2]).unwrap();
        let interior = |p: [f64; 3]| (0..3).all(|c| p[c] > 1e-9 && p[c] < size[c] - 1e-9);
        let mut nodes = block.nodes().to_vec();
        for (k, p) in nodes.iter_mut().enumerate() {
            let corner =
                (0..block.n_elements()).any(|e| block.element(e)[..kind.n_corners()].contains(&k));
            if corner && interior(*p) {
                *p = [p[0] + 0.13, p[1] - 0.21, p[2] + 0.17];
            }
        }
        for e in 0..block.n_elements() {
            let conn = block.element(e);
            for a in kind.n_corners()..kind.n_nodes() {
                let r = kind.reference_node(a);
                let w: Vec<f64> = match kind {
                    SolidKind::Tet10 => vec![1.0 - r[0] - r[1] - r[2], r[0], r[1], r[2]],
                    _ => (0..8)
                        .map(|c| {
                            let q = kind.reference_node(c);
                            (0..3).map(|i| 0.5 * (1.0 + q[i] * r[i])).product()
                        })
                        .collect(),
                };
                nodes[conn[a]] = std::array::from_fn(|i| {
                    w.iter()
                        .enumerate()
                        .map(|(c, wc)| wc * nodes[conn[c]][i])
                        .sum()
                });
            }
        }
        let elements = (0..block.n_elements())
            .map(|e| (block.kind(e), block.element(e).to_vec()))
            .collect();
        SolidMesh::new(nodes, elements).unwrap()
    }

    /// The patch test: a distorted block under uniform pressure p on its top, held by
    /// symmetry planes x = 0, y = 0 and z = 0, has the uniform stress σ_zz = −p and the
    /// displacement u = (νpx, νpy, −pz)/E exactly: every node and every Gauss point to
    /// round-off, for each kind.
    #[test]
    fn patch_test_uniform_pressure_is_exact() {
        let p = 50.0;
        for kind in SolidKind::ALL {
            let mesh = distorted_block(kind);
            let mut model = SolidModel::new(mesh, steel());
            for (axis, c) in [(Axis::X, 0), (Axis::Y, 1), (Axis::Z, 2)] {
                let plane = model.mesh().nodes_where(|x| x[c].abs() < 1e-9);
                model.fix(&plane, axis).unwrap();
            }
            let top = model.mesh().faces_where(|x| (x[2] - 4.0).abs() < 1e-9);
            assert_eq!(top.len(), if kind == SolidKind::Tet10 { 8 } else { 4 });
            model.add_pressure(&top, p).unwrap();
            let u = model.solve().unwrap();
            let (e, nu) = (2e5, 0.3);
            let scale = p * 4.0 / e;
            for (k, x) in model.mesh().nodes().iter().enumerate() {
                let want = [nu * p * x[0] / e, nu * p * x[1] / e, -p * x[2] / e];
                for c in 0..3 {
                    let err = (u[3 * k + c] - want[c]).abs();
                    assert!(
                        err < ROUND_OFF * scale,
                        "{kind:?} node {k} axis {c}: {err:e}"
                    );
                }
            }
            for el in 0..model.mesh().n_elements() {
                for (q, _) in kind.integration_points() {
                    let s = model.stress_at(&u, el, q).unwrap();
                    let others = [s.xx, s.yy, s.xy, s.xz, s.yz];
                    assert!((s.zz + p).abs() < ROUND_OFF * p, "{kind:?} {s:?}");
                    assert!(
                        others.iter().all(|v| v.abs() < ROUND_OFF * p),
                        "{kind:?} {s:?}"
                    );
                }
            }
        }
    }

    /// Lamé's thick cylinder (a = 10, b = 20 mm) under internal pressure p = 100 MPa in plane
    /// strain, a quarter of it (symmetry planes x = 0, y = 0, ends held along z): the radial
    /// displacement at the bore and the outside, and the hoop stress at the bore's Gauss
    /// points, against the closed form. Hexahedra 4 × 8 through the wall and round, the
    /// tetrahedra of the same grid.
    #[test]
    fn thick_cylinder_matches_lame() {
        let (a, b, p, length) = (10.0, 20.0, 100.0, 2.0);
        let (e, nu) = (2e5, 0.3);
        let c1 = p * a * a / (b * b - a * a);
        let c2 = p * a * a * b * b / (b * b - a * a);
        let sigma_r = |r: f64| c1 - c2 / (r * r);
        let sigma_t = |r: f64| c1 + c2 / (r * r);
        // Plane strain: ε_θ = ((1 − ν²)σ_θ − ν(1 + ν)σ_r)/E.
        let u_r = |r: f64| r * ((1.0 - nu * nu) * sigma_t(r) - nu * (1.0 + nu) * sigma_r(r)) / e;
        // Tolerances: measured 0.007 % (hexahedra) and 0.13 % (tetrahedra) on u_r, 0.71 % and
        // 1.4 % on the hoop stress at the bore's Gauss points; ν = 0.25 instead of 0.3 would
        // move u_r at the bore by 1.7 %, plane stress instead of plane strain by 9 %.
        for (kind, tol_u, tol_s) in [
            (SolidKind::Hex20, 2e-4, 1e-2),
            (SolidKind::Hex27, 2e-4, 1e-2),
            (SolidKind::Tet10, 2e-3, 2.5e-2),
        ] {
            let block = SolidMesh::block(kind, [b - a, 1.0, length], [4, 8, 1]).unwrap();
            let mesh = block
                .map(|q| {
                    let (r, t) = (a + q[0], std::f64::consts::FRAC_PI_2 * q[1]);
                    [r * t.cos(), r * t.sin(), q[2]]
                })
                .unwrap();
            let mut model = SolidModel::new(mesh, Material::new(e, nu).unwrap());
            let on = |c: usize, v: f64| move |x: [f64; 3]| (x[c] - v).abs() < 1e-9;
            let (x0, y0) = (
                model.mesh().nodes_where(on(0, 0.0)),
                model.mesh().nodes_where(on(1, 0.0)),
            );
            model.fix(&x0, Axis::X).unwrap();
            model.fix(&y0, Axis::Y).unwrap();
            let ends = model
                .mesh()
                .nodes_where(|x| x[2].abs() < 1e-9 || (x[2] - length).abs() < 1e-9);
            model.fix(&ends, Axis::Z).unwrap();
            let bore = model
                .mesh()
                .faces_where(|x| (x[0].hypot(x[1]) - a).abs() < 1e-9);
            assert_eq!(bore.len(), if kind == SolidKind::Tet10 { 16 } else { 8 });
            model.add_pressure(&bore, p).unwrap();
            let u = model.solve().unwrap();
            for (k, x) in model.mesh().nodes().iter().enumerate() {
                let r = x[0].hypot(x[1]);
                let radial = (u[3 * k] * x[0] + u[3 * k + 1] * x[1]) / r;
                let err = (radial / u_r(r) - 1.0).abs();
                assert!(
                    err < tol_u,
                    "{kind:?} node {k} r = {r}: u_r {radial} vs {}",
                    u_r(r)
                );
            }
            for f in &bore {
                for (q, _) in kind.integration_points() {
                    let x = {
                        let (_, _, s) = model.mesh().jacobian(f.element, q);
                        let conn = model.mesh().element(f.element);
                        let mut x = [0.0; 3];
                        for (i, &n) in conn.iter().enumerate() {
                            for c in 0..3 {
                                x[c] += s.n[i] * model.mesh().nodes()[n][c];
                            }
                        }
                        x
                    };
                    let r = x[0].hypot(x[1]);
                    let st = model.stress_at(&u, f.element, q).unwrap();
                    let (cs, sn) = (x[0] / r, x[1] / r);
                    let hoop = st.xx * sn * sn + st.yy * cs * cs - 2.0 * st.xy * sn * cs;
                    let err = (hoop / sigma_t(r) - 1.0).abs();
                    assert!(
                        err < tol_s,
                        "{kind:?} r = {r}: σ_θ {hoop} vs {}",
                        sigma_t(r)
                    );
                }
            }
        }
    }
}
