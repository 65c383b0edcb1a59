//! A Pasternak foundation: the springs of a Winkler bed tied by a shear layer, on a row of
//! strips.

use contopt_core::{check, ElasticBody, Error, Geometry, Interface, Result, RigidMode};

/// A Pasternak bed under a row of strips of a plane body (Pasternak 1954; Kerr, *J. Appl.
/// Mech.* 31, 1964): springs of modulus k whose tops are tied by a shear layer of stiffness
/// G_p, so that the surface sinks by w(x) under a pressure p(x) with
///
/// p = k·w − G_p·w''.
///
/// A force F on one point sinks the surface by F/(2b√(k G_p))·e^(−|x|/ℓ), ℓ = √(G_p/k), on a
/// long bed of thickness b: the shear layer spreads a load over a few ℓ, unlike the
/// Winkler bed (G_p = 0). On strips of centres xᵢ and widths hᵢ the shear between neighbours
/// is G_p·(wᵢ₊₁ − wᵢ)/(xᵢ₊₁ − xᵢ) and the layer ends with the strips (no shear beyond), so the
/// forces Fᵢ = wᵢpᵢ that give displacements u are K·u with the tridiagonal
///
/// K = b·(k·diag(hᵢ) + G_p·L),
///
/// L the chain's Laplacian with conductances 1/(xᵢ₊₁ − xᵢ). The influence operator is K⁻¹,
/// applied by a tridiagonal solve in O(n) (though its matrix is dense: every strip moves
/// every other), and K is its exact inverse, the body's preconditioner.
#[derive(Clone, Debug)]
pub struct Pasternak {
    name: String,
    interface: Interface,
    /// Spring modulus k \[MPa/mm\].
    k: f64,
    /// Shear stiffness of the layer G_p \[N/mm\].
    shear: f64,
    /// K's diagonal and its off-diagonal (between strip i and i + 1) \[N/mm\].
    diagonal: Vec<f64>,
    coupling: Vec<f64>,
    /// The pivots of K's LDLᵀ factor (factorised once).
    pivots: Vec<f64>,
}

impl Pasternak {
    /// A bed of spring modulus `k` \[MPa/mm\] and shear stiffness `shear` \[N/mm\] (≥ 0; 0 is
    /// the Winkler bed) under the strips of `interface`, a plane surface whose points lie along
    /// x in increasing order (the strips of [`crate::HalfPlane::strips_interface`], or a
    /// partner's mirrored), each weight the strip's width times the thickness.
    pub fn on(name: impl Into<String>, interface: Interface, k: f64, shear: f64) -> Result<Self> {
        check::positive("modulus_mpa_per_mm", k)?;
        check::non_negative("shear_n_per_mm", shear)?;
        let Geometry::Plane { thickness } = interface.geometry() else {
            return Err(Error::invalid(
                "interface",
                format!("{:?}", interface.geometry()),
                "the strips of a plane body (a row of points along x)",
            ));
        };
        let x: Vec<f64> = interface.points().iter().map(|p| p[0]).collect();
        if let Some(i) = (1..x.len()).find(|&i| x[i] <= x[i - 1]) {
            return Err(Error::invalid(
                format!("interface.points[{i}]"),
                x[i],
                format!("a strip to the right of the last one, x > {}", x[i - 1]),
            ));
        }
        let n = x.len();
        let coupling: Vec<f64> = (1..n)
            .map(|i| -thickness * shear / (x[i] - x[i - 1]))
            .collect();
        let diagonal: Vec<f64> = (0..n)
            .map(|i| {
                let left = if i > 0 { -coupling[i - 1] } else { 0.0 };
                let right = if i + 1 < n { -coupling[i] } else { 0.0 };
                k * interface.weights()[i] + left + right
            })
            .collect();
        for (field, value, v) in [
            ("modulus_mpa_per_mm", k, &diagonal),
            ("shear_n_per_mm", shear, &coupling),
        ] {
            check::all_derived(field, value, "the stiffness of a strip", v)?;
        }
        let mut pivots = diagonal.clone();
        for i in 1..n {
            pivots[i] -= coupling[i - 1] * coupling[i - 1] / pivots[i - 1];
        }
        check::all_derived("modulus_mpa_per_mm", k, "a pivot of the stiffness", &pivots)?;
        Ok(Self {
            name: name.into(),
            interface,
            k,
            shear,
            diagonal,
            coupling,
            pivots,
        })
    }

    /// The spring modulus k \[MPa/mm\] and the shear stiffness G_p \[N/mm\].
    pub fn moduli(&self) -> (f64, f64) {
        (self.k, self.shear)
    }
}

impl ElasticBody for Pasternak {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    /// u = K⁻¹F by the tridiagonal factor (K is diagonally dominant: no pivoting), O(n).
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        let (b, d, u) = (&self.coupling, &self.pivots, displacement);
        let n = d.len();
        u[0] = force[0];
        for i in 1..n {
            u[i] = force[i] - b[i - 1] / d[i - 1] * u[i - 1];
        }
        u[n - 1] /= d[n - 1];
        for i in (0..n - 1).rev() {
            u[i] = (u[i] - b[i] * u[i + 1]) / d[i];
        }
    }

    /// F = K·u: the bed's exact inverse.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        let (a, b, u) = (&self.diagonal, &self.coupling, displacement);
        let n = a.len();
        for i in 0..n {
            let left = if i > 0 { b[i - 1] * u[i - 1] } else { 0.0 };
            let right = if i + 1 < n { b[i] * u[i + 1] } else { 0.0 };
            force[i] = a[i] * u[i] + left + right;
        }
        true
    }

    /// A_CC⁻¹ exactly: the displacement u that is `displacement` on the set and leaves the
    /// strips off it unloaded, (K u)_N = 0 (a tridiagonal solve on each run of them, tied to
    /// the set's strips at its ends), then F = K u on the set, K_CC u_C + K_CN u_N: the
    /// Schur complement K_CC − K_CN K_NN⁻¹ K_NC applied in O(n).
    fn precondition_on(&self, displacement: &[f64], contact: &[bool], force: &mut [f64]) -> bool {
        let (a, b) = (&self.diagonal, &self.coupling);
        let n = a.len();
        let u = force;
        u.copy_from_slice(displacement);
        let mut pivots = vec![0.0; n];
        let mut i = 0;
        while i < n {
            if contact[i] {
                i += 1;
                continue;
            }
            let start = i;
            while i < n && !contact[i] {
                i += 1;
            }
            // The run start..i of unloaded strips: K_NN u_N = −K_NC u_C.
            for k in start..i {
                let mut rhs = 0.0;
                if k == start && k > 0 {
                    rhs -= b[k - 1] * u[k - 1];
                }
                if k + 1 == i && i < n {
                    rhs -= b[k] * u[i];
                }
                if k == start {
                    pivots[k] = a[k];
                    u[k] = rhs;
                } else {
                    let m = b[k - 1] / pivots[k - 1];
                    pivots[k] = a[k] - m * b[k - 1];
                    u[k] = rhs - m * u[k - 1];
                }
            }
            u[i - 1] /= pivots[i - 1];
            for k in (start..i - 1).rev() {
                u[k] = (u[k] - b[k] * u[k + 1]) / pivots[k];
            }
        }
        // F = K u on the set, in place (u of the left neighbour carried along).
        let mut left = 0.0;
        for i in 0..n {
            let here = u[i];
            let mut f = a[i] * here;
            if i > 0 {
                f += b[i - 1] * left;
            }
            if i + 1 < n {
                f += b[i] * u[i + 1];
            }
            left = here;
            u[i] = if contact[i] { f } else { 0.0 };
        }
        true
    }

    /// The strips merged in pairs (the last alone when their number is odd), each pair a
    /// strip of the summed width at their weighted middle; the same moduli.
    fn coarsen(&self) -> Option<(Box<dyn ElasticBody>, Vec<usize>)> {
        let n = self.interface.len();
        if n < 2 {
            return None;
        }
        let (x, w) = (self.interface.points(), self.interface.weights());
        let m = n.div_ceil(2);
        let weights: Vec<f64> = (0..m)
            .map(|j| w[2 * j..n.min(2 * j + 2)].iter().sum())
            .collect();
        let points = (0..m)
            .map(|j| {
                let moment: f64 = (2 * j..n.min(2 * j + 2)).map(|i| w[i] * x[i][0]).sum();
                [moment / weights[j], x[2 * j][1], x[2 * j][2]]
            })
            .collect();
        let surface = Interface::new(
            self.interface.geometry(),
            points,
            weights,
            vec![self.interface.normals()[0]; m],
        )
        .ok()?;
        let coarse = Pasternak::on(self.name.clone(), surface, self.k, self.shear).ok()?;
        Some((Box::new(coarse), (0..n).map(|i| i / 2).collect()))
    }

    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    /// The ground holds the bed.
    fn rigid_modes(&self) -> &[RigidMode] {
        &[]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::HalfPlane;

    /// A force on the middle of a long bed (400 ℓ, strips of ℓ/20) sinks it by
    /// F/(2b√(k G_p))·e^(−|x|/ℓ): the discrete chain's error is O((h/ℓ)²) (1/1200 of the peak
    /// here; a wrong shear term, a missing thickness or a missing end condition is off by
    /// far more). The preconditioner is the operator's exact inverse, to round-off.
    #[test]
    fn point_force_and_exact_inverse() {
        let (k, shear, thickness): (f64, f64, f64) = (50.0, 200.0, 2.0);
        let ell = (shear / k).sqrt();
        let n = 8001;
        let h = ell / 20.0;
        let edges: Vec<f64> = (0..=n).map(|j| (j as f64 - n as f64 / 2.0) * h).collect();
        let strips = HalfPlane::strips_interface(&edges, thickness).unwrap();
        let bed = Pasternak::on("bed", strips, k, shear).unwrap();
        let mut force = vec![0.0; n];
        force[n / 2] = 100.0;
        let mut u = vec![0.0; n];
        bed.apply_influence(&force, &mut u);
        let peak = 100.0 / (2.0 * thickness * (k * shear).sqrt());
        for (i, x) in bed.interface().points().iter().enumerate().step_by(97) {
            let exact = peak * (-x[0].abs() / ell).exp();
            assert!(
                (u[i] - exact).abs() < 1e-3 * peak,
                "x = {}: {} vs {exact}",
                x[0],
                u[i]
            );
        }
        let mut back = vec![0.0; n];
        assert!(bed.precondition(&u, &mut back));
        for (b, f) in back.iter().zip(&force) {
            assert!((b - f).abs() < 1e-10 * 100.0, "{b} vs {f}");
        }
    }

    /// On a contact set of three runs (the bed's ends and a gap inside left unloaded), the
    /// forces [`ElasticBody::precondition_on`] writes are zero off the set and, applied,
    /// give back the displacement on the set to round-off: the exact A_CC⁻¹. The masked
    /// whole inverse (A⁻¹)_CC, the default, misses by the shear ties at the set's edges (a
    /// tenth of the displacement here), which this would catch.
    #[test]
    fn exact_inverse_on_a_contact_set() {
        let n = 200;
        let edges: Vec<f64> = (0..=n).map(|j| j as f64 * 0.1).collect();
        let strips = HalfPlane::strips_interface(&edges, 2.0).unwrap();
        let bed = Pasternak::on("bed", strips, 50.0, 200.0).unwrap();
        let contact: Vec<bool> = (0..n)
            .map(|i| (20..90).contains(&i) || (110..170).contains(&i))
            .collect();
        let u: Vec<f64> = (0..n)
            .map(|i| {
                if contact[i] {
                    1e-3 * (1.0 + (0.1 * i as f64).sin())
                } else {
                    0.0
                }
            })
            .collect();
        let mut force = vec![0.0; n];
        assert!(bed.precondition_on(&u, &contact, &mut force));
        let mut back = vec![0.0; n];
        bed.apply_influence(&force, &mut back);
        for i in 0..n {
            if contact[i] {
                assert!(
                    (back[i] - u[i]).abs() < 1e-12,
                    "{i}: {} vs {}",
                    back[i],
                    u[i]
                );
            } else {
                assert_eq!(force[i], 0.0, "{i}");
            }
        }
        let mut masked = vec![0.0; n];
        assert!(bed.precondition(&u, &mut masked));
        (0..n)
            .filter(|&i| !contact[i])
            .for_each(|i| masked[i] = 0.0);
        bed.apply_influence(&masked, &mut back);
        let miss = (0..n)
            .filter(|&i| contact[i])
            .map(|i| (back[i] - u[i]).abs())
            .fold(0.0, f64::max);
        assert!(
            miss > 1e-2 * 1e-3,
            "the masked inverse misses by only {miss}"
        );
    }

    /// A row out of order, a grid's surface and a negative shear are refused by name.
    #[test]
    fn refuses_bad_input() {
        let strips = HalfPlane::strips_interface(&[0.0, 1.0, 2.0], 1.0).unwrap();
        let e = Pasternak::on("bed", strips.clone(), 1.0, -1.0).unwrap_err();
        assert!(e.to_string().contains("shear_n_per_mm"), "{e}");
        let grid = crate::HalfSpace::cells_interface(2, 2, 1.0, 1.0, [0.0, 0.0]).unwrap();
        let e = Pasternak::on("bed", grid, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("plane body"), "{e}");
        let reversed = Interface::new(
            Geometry::Plane { thickness: 1.0 },
            vec![[1.0, 0.0, 0.0], [0.0, 0.0, 0.0]],
            vec![1.0; 2],
            vec![[0.0, 1.0, 0.0]; 2],
        )
        .unwrap();
        let e = Pasternak::on("bed", reversed, 1.0, 1.0).unwrap_err();
        assert!(e.to_string().contains("points[1]"), "{e}");
    }
}
