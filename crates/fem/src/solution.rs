//! Solving a supported model, stresses at integration points, and error norms.

use contopt_core::{check, Error, Result};

use crate::system::{point_b, strain_rows, PointB, System};
use crate::{Analysis, FeModel};

/// Stress at one point \[MPa\]. In axisymmetry x = r, y = z and `zz` is the hoop stress σ_θ;
/// in plane strain `zz` is the out-of-plane stress ν(σ_xx + σ_yy); in plane stress it is 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stress {
    /// Where the stress was evaluated.
    pub x: [f64; 2],
    /// σ_xx (σ_r).
    pub xx: f64,
    /// σ_yy (σ_z).
    pub yy: f64,
    /// τ_xy (τ_rz).
    pub xy: f64,
    /// σ_zz (σ_θ in axisymmetry).
    pub zz: f64,
}

/// Nodal displacements of a solved model.
#[derive(Clone, Debug)]
pub struct Solution {
    /// (u_x, u_y) of node i at entries 2i, 2i + 1.
    pub displacement: Vec<f64>,
}

impl Solution {
    /// Displacement (u_x, u_y) of `node`.
    pub fn at(&self, node: usize) -> [f64; 2] {
        [self.displacement[2 * node], self.displacement[2 * node + 1]]
    }
}

impl FeModel {
    /// Assembles, factorises and solves. The supports must hold every rigid-body mode;
    /// a floating body belongs in an [`crate::FeBody`], whose contact carries the modes.
    pub fn solve(&self) -> Result<Solution> {
        let system = System::new(self, "model", &[], 0)?;
        if !system.modes.is_empty() {
            let names: Vec<&str> = system.modes.iter().map(|m| m.name.as_str()).collect();
            return Err(Error::invalid(
                "supports",
                names.join(", "),
                "rigid-body modes are left free; add supports",
            ));
        }
        let displacement = system.solve(&self.forces, None);
        self.check_displacement(&displacement)?;
        Ok(Solution { displacement })
    }

    /// Displacements `u` of a solve are finite: else the loads (or prescribed values)
    /// overflow f64 against the stiffness, an error that says so.
    pub(crate) fn check_displacement(&self, u: &[f64]) -> Result<()> {
        let largest = |v: &mut dyn Iterator<Item = f64>| v.fold(0.0f64, |m, f| m.max(f.abs()));
        let force = largest(&mut self.forces.iter().copied());
        let prescribed = largest(&mut self.prescribed.values().copied());
        let loads = format!("forces up to {force:e} N, displacements up to {prescribed:e} mm");
        check::all_derived("loads", loads, "the displacements K⁻¹f", u)
    }

    /// Stresses at the integration points of every element, element by element, in the
    /// order of [`crate::ElementKind::integration_points`]: 9 for a quadrilateral (the 3 × 3
    /// Gauss points), 6 for a triangle.
    pub fn stresses(&self, solution: &Solution) -> Result<Vec<Stress>> {
        let d = self.analysis.elasticity(&self.material);
        let mesh = &self.mesh;
        let points = |e: usize| mesh.element_kind(e).integration_points();
        let n: usize = (0..mesh.elements().len()).map(|e| points(e).len()).sum();
        let mut out = Vec::with_capacity(n);
        for (e, conn) in mesh.elements().iter().enumerate() {
            for p in points(e) {
                let b = point_b(self, e, p.xi, p.eta, 1.0)?;
                out.push(self.point_stress(&d, &b, conn, solution));
            }
        }
        Ok(out)
    }

    /// The stress D B uₑ at the point `b` of an element of nodes `conn`.
    fn point_stress(
        &self,
        d: &[[f64; 4]; 4],
        b: &PointB,
        conn: &[usize],
        solution: &Solution,
    ) -> Stress {
        let ns = self.analysis.n_strain();
        let mut strain = [0.0; 4];
        for (a, &node) in conn.iter().enumerate() {
            let rows = strain_rows(self.analysis, b, a);
            let u = solution.at(node);
            for k in 0..ns {
                strain[k] += rows[k][0] * u[0] + rows[k][1] * u[1];
            }
        }
        let s: Vec<f64> = (0..ns)
            .map(|i| (0..ns).map(|k| d[i][k] * strain[k]).sum())
            .collect();
        let nu = self.material.nu();
        match self.analysis {
            Analysis::Axisymmetric => Stress {
                x: b.x,
                xx: s[0],
                yy: s[1],
                zz: s[2],
                xy: s[3],
            },
            Analysis::PlaneStress { .. } => Stress {
                x: b.x,
                xx: s[0],
                yy: s[1],
                xy: s[2],
                zz: 0.0,
            },
            Analysis::PlaneStrain { .. } => Stress {
                x: b.x,
                xx: s[0],
                yy: s[1],
                xy: s[2],
                zz: nu * (s[0] + s[1]),
            },
        }
    }

    /// L2 norm of the displacement error against a reference field,
    /// (∫_V |u_h − u|² dV)^½, by each element's quadrature (3 × 3 Gauss points on a
    /// quadrilateral, the 6-point rule of degree 4 on a triangle).
    pub fn l2_error(
        &self,
        solution: &Solution,
        exact: impl Fn([f64; 2]) -> [f64; 2],
    ) -> Result<f64> {
        let mut sum = 0.0;
        for (e, conn) in self.mesh.elements().iter().enumerate() {
            for p in self.mesh.element_kind(e).integration_points() {
                let b = point_b(self, e, p.xi, p.eta, p.weight)?;
                let mut uh = [0.0; 2];
                for (a, &node) in conn.iter().enumerate() {
                    let u = solution.at(node);
                    uh[0] += b.n[a] * u[0];
                    uh[1] += b.n[a] * u[1];
                }
                let ue = exact(b.x);
                sum += ((uh[0] - ue[0]).powi(2) + (uh[1] - ue[1]).powi(2)) * b.dv;
            }
        }
        Ok(sum.sqrt())
    }
}
