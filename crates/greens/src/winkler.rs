//! A Winkler foundation: a bed of independent springs, the simplest elastic body — and the
//! worked example of the book's chapter "Write your own body", which adds it to scenes as the
//! body kind `winkler` in one file.

use contopt_core::{check, ElasticBody, Interface, Result, RigidMode};

// ANCHOR: body
/// A Winkler bed under any contact surface: each point sinks by its own pressure over the bed
/// modulus k and feels no other point, so the kernel H(x, x') of eq. (2.5) is δ(x − x')/k and
/// its block of H = H¹ + H² (2.13)₁ is diagonal. The ground holds the bed: it has no rigid
/// mode and no load of its own.
#[derive(Clone, Debug)]
pub struct Winkler {
    name: String,
    interface: Interface,
    /// Bed modulus k \[MPa/mm\]: the pressure that sinks the surface by 1 mm.
    k: f64,
}

impl Winkler {
    /// A bed of modulus `k` \[MPa/mm\] whose surface is `interface`: its points, weights and
    /// outward normals (a grid's cells, rings, strips, or a partner's surface mirrored).
    pub fn on(name: impl Into<String>, interface: Interface, k: f64) -> Result<Self> {
        check::positive("modulus_mpa_per_mm", k)?;
        // Each point's spring k·wᵢ and its compliance 1/(k·wᵢ), which the solvers use, are
        // finite: else k is beyond f64 for these weights (other units than MPa/mm).
        for w in interface.weights() {
            check::derived("modulus_mpa_per_mm", k, "a spring k·wᵢ", k * w)?;
            check::derived(
                "modulus_mpa_per_mm",
                k,
                "a compliance 1/(k·wᵢ)",
                1.0 / (k * w),
            )?;
        }
        Ok(Self {
            name: name.into(),
            interface,
            k,
        })
    }

    /// The bed modulus k \[MPa/mm\].
    pub fn modulus(&self) -> f64 {
        self.k
    }
}
// ANCHOR_END: body

// ANCHOR: trait
impl ElasticBody for Winkler {
    /// The name the solvers' messages use.
    fn name(&self) -> &str {
        &self.name
    }

    /// The proposed contact zone Ω: points, weights wᵢ (∫ p dS ≈ Σ wᵢ pᵢ) and outward normals.
    /// The partner's interface must hold the same points with opposite normals.
    fn interface(&self) -> &Interface {
        &self.interface
    }

    /// The influence operator of eq. (2.5): the displacement into the body at each point under
    /// compressive forces Fⱼ = wⱼpⱼ at the points. A spring bed moves each point by its own
    /// pressure, uᵢ = pᵢ/k = Fᵢ/(k wᵢ). The contact problem sums it with the partner's (A¹ + A²,
    /// the H¹ + H² of eq. 2.13₁) and the matrix-free solver (Polonsky–Keer) needs nothing else.
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        let w = self.interface.weights();
        for ((u, f), w) in displacement.iter_mut().zip(force).zip(w) {
            *u = f / (self.k * w);
        }
    }

    /// Optional: an approximate inverse of the influence operator, which preconditions the
    /// matrix-free solver. The bed's is exact: Fᵢ = k wᵢ uᵢ.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        let w = self.interface.weights();
        for ((f, u), w) in force.iter_mut().zip(displacement).zip(w) {
            *f = self.k * w * u;
        }
        true
    }

    /// f² of eqs. (2.5) and (2.7): the displacement under the body's own given loads, before
    /// any contact pressure. The bed carries none.
    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    /// The rigid motions the supports leave free, the columns of G_R in the equilibrium
    /// (2.10)–(2.11). The ground holds the bed: none. (A floating body lists each mode's
    /// displacement per unit amplitude and the load q it must balance.)
    fn rigid_modes(&self) -> &[RigidMode] {
        &[]
    }

    // Not written, so the defaults hold: the dense matrix A of the dense solvers (QP, active
    // set, penalty, augmented Lagrangian, the LP of eq. 3.5; H = W A W of 2.12–2.14) is built
    // column by column from `apply_influence` (`influence_matrix`); no stresses below the
    // surface (`subsurface`: a spring bed has no interior); no cheaper part of the body
    // (`restrict`); no kernel shared with a partner (`influence_shape`); no pressure field
    // finer than the points (`pressure_basis`).
}
// ANCHOR_END: trait
