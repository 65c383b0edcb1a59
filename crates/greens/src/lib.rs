//! Elastic bodies given by closed-form Green's functions (§2.1 of Páczelt 1994): the
//! influence matrix comes from the surface displacement of a uniformly loaded region, with no
//! mesh below the surface.
//!
//! - [`AxisymmetricHalfSpace`]: rings on the surface of a half-space, each an annulus loaded
//!   uniformly (Boussinesq; complete elliptic integrals);
//! - [`HalfSpace`]: a regular grid of rectangular cells on the surface of a half-space (Love);
//! - [`HalfPlane`]: strips on the edge of a half-plane in plane strain or plane stress
//!   (Flamant);
//! - [`Winkler`]: a bed of independent springs under any surface (kernel δ(x − x')/k);
//! - [`DenseCompliance`]: any surface whose compliance matrix is given (made elsewhere:
//!   numpy, a finite-element code), checked symmetric and positive definite;
//! - [`Pasternak`]: springs tied by a shear layer, under a row of strips (p = kw − G_p w'').
//!
//! Each also gives the stresses below its surface under a contact pressure
//! ([`contopt_core::ElasticBody::subsurface`]): FFT products of Love's rectangle kernels on a
//! grid, closed forms for strips and on the axis of rings, a rim quadrature off it.

mod axisymmetric;
mod dense;
pub mod elliptic;
mod fft;
mod free_ends;
mod grid_edge;
mod half_plane;
mod half_space;
mod pasternak;
mod quarter_space;
mod subsurface;
mod subsurface_2d;
mod winkler;

pub use axisymmetric::AxisymmetricHalfSpace;
pub use dense::{dense_compliance_bytes, DenseCompliance, PIVOT_TOLERANCE, SYMMETRY_TOLERANCE};
pub use free_ends::FreeEnds;
pub use grid_edge::{EdgeReached, CARRIES};
pub use half_plane::{HalfPlane, PlaneState};
pub use half_space::HalfSpace;
pub use pasternak::Pasternak;
pub use quarter_space::{hetenyi_load, FacedGrid, HetenyiLoad, HetenyiSettings};
pub use winkler::Winkler;

use contopt_core::{check, Error, Result};

/// Checks that region edges are finite and strictly increasing, at least two.
fn check_edges(edges: &[f64], field: &str) -> Result<()> {
    if edges.len() < 2 {
        return Err(Error::invalid(
            field,
            edges.len(),
            "at least two edges (one region)",
        ));
    }
    let n = edges.len() - 1;
    contopt_core::memory::require(
        format!("the dense {n} × {n} influence matrix of {n} rings or strips"),
        dense_surface_bytes(n),
        contopt_core::memory::BODY_LIMIT_BYTES,
        "use fewer rings or strips",
    )?;
    check::all_finite(field, edges)?;
    if let Some(i) = (1..edges.len()).find(|&i| edges[i] <= edges[i - 1]) {
        return Err(Error::invalid(
            format!("{field}[{i}]"),
            edges[i],
            format!("must exceed {}", edges[i - 1]),
        ));
    }
    Ok(())
}

/// Every entry of `matrix` (a kernel, an influence matrix) finite: else the error of
/// [`check::derived`] naming the input `field` = `input` whose magnitude overflowed it.
fn check_matrix(field: &str, input: f64, what: &str, matrix: &faer::Mat<f64>) -> Result<()> {
    let mut entries = (0..matrix.ncols()).flat_map(|j| matrix.col(j).iter().copied());
    match entries.find(|v| !v.is_finite()) {
        Some(v) => check::derived(field, input, what, v).map(|_| ()),
        None => Ok(()),
    }
}

/// The memory a ring or strip body of `n` regions takes to build \[bytes\]: its averaged
/// matrix and the symmetric one it keeps; `None` when the count overflows.
pub fn dense_surface_bytes(n: usize) -> Option<u64> {
    contopt_core::memory::bytes(&[n, n], 2 * 8)
}

/// A surface body given by its dense, symmetric influence matrix, with no given loads and no
/// rigid modes: what the ring and strip bodies share.
#[derive(Clone, Debug)]
struct DenseSurface {
    name: String,
    interface: contopt_core::Interface,
    influence: faer::Mat<f64>,
}

impl DenseSurface {
    /// The body with the symmetric part of `influence`, which the Galerkin forms produce up
    /// to quadrature or round-off error (the solvers need it exactly symmetric); an error
    /// naming the `edges` when an entry is not finite (edges or a modulus whose magnitudes
    /// overflow f64).
    fn symmetric(
        name: String,
        interface: contopt_core::Interface,
        influence: &faer::Mat<f64>,
        (field, edges): (&str, &[f64]),
    ) -> Result<Self> {
        let n = influence.nrows();
        // Halves first: the sum of two entries near f64::MAX does not overflow.
        let influence = faer::Mat::from_fn(n, n, |i, j| {
            0.5 * influence[(i, j)] + 0.5 * influence[(j, i)]
        });
        let spread = edges.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let what = "the influence matrix of these regions and modulus";
        check_matrix(field, spread, what, &influence)?;
        Ok(Self {
            name,
            interface,
            influence,
        })
    }
}

/// Implements `ElasticBody` for a type with a `surface: DenseSurface` field and an inherent
/// `stresses_below(&self, pressure, request)`, to which `subsurface` delegates.
macro_rules! surface_body {
    ($body:ty) => {
        impl contopt_core::ElasticBody for $body {
            fn name(&self) -> &str {
                &self.surface.name
            }

            fn interface(&self) -> &contopt_core::Interface {
                &self.surface.interface
            }

            fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
                let a = &self.surface.influence;
                for (i, d) in displacement.iter_mut().enumerate() {
                    *d = (0..force.len()).map(|j| a[(i, j)] * force[j]).sum();
                }
            }

            fn influence_matrix(&self) -> faer::Mat<f64> {
                self.surface.influence.clone()
            }

            fn influence_block(&self, points: &[usize]) -> Option<faer::Mat<f64>> {
                contopt_core::block_among(&self.surface.influence, points)
            }

            fn load_displacement(&self) -> contopt_core::Result<Vec<f64>> {
                Ok(vec![0.0; self.surface.interface.len()])
            }

            fn rigid_modes(&self) -> &[contopt_core::RigidMode] {
                &[]
            }

            fn subsurface(
                &self,
                pressure: &[f64],
                request: &contopt_core::SubsurfaceRequest,
            ) -> contopt_core::Result<Option<contopt_core::Subsurface>> {
                self.stresses_below(pressure, request).map(Some)
            }
        }
    };
}
pub(crate) use surface_body;
