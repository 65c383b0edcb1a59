use std::f64::consts::PI;

use contopt_core::{Error, Geometry, Interface, Material, Result};
use faer::Mat;

use crate::check_edges;

/// The plane idealisation of a [`HalfPlane`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PlaneState {
    /// Plane strain (E' = E/(1 − ν²)).
    Strain,
    /// Plane stress (E' = E).
    Stress,
}

/// An elastic half-plane y ≤ 0 of thickness b loaded on its edge: the contact points are the
/// midpoints of strips x_j ≤ x ≤ x_{j+1}, each a strip of uniform pressure.
///
/// Flamant: a uniform pressure p on [a, b] moves the edge by
/// u(x) = 2p/(πE') [(b − a)(ln d₀ + 1) − (x − a) ln|x − a| + (x − b) ln|x − b|]
/// into the body. In two dimensions displacements are fixed only up to a constant; the datum
/// d₀ \[mm\] is the distance at which a point load's deflection vanishes (a length of the order
/// of the body's depth). Differences of displacement, and so contact pressures under a
/// floating punch, do not depend on it. The influence coefficient Aᵢⱼ is u averaged over strip
/// i (in closed form, with ∫ t ln|t| dt = t² ln|t|/2 − t²/4) per unit force on strip j: the
/// Galerkin form, symmetric for any strip widths.
#[derive(Clone, Debug)]
pub struct HalfPlane {
    surface: crate::DenseSurface,
}

impl HalfPlane {
    /// A half-plane of `material` and `thickness` \[mm\] in `state`, with contact strips between
    /// `edges` \[mm\], deflections measured from the datum `datum` \[mm\] > 0.
    pub fn new(
        name: impl Into<String>,
        material: Material,
        state: PlaneState,
        thickness: f64,
        edges: &[f64],
        datum: f64,
    ) -> Result<Self> {
        check_edges(edges, "half_plane.edges")?;
        if !(thickness > 0.0 && thickness.is_finite()) {
            return Err(Error::invalid(
                "half_plane.thickness",
                thickness,
                "must be positive and finite",
            ));
        }
        if !(datum > 0.0 && datum.is_finite()) {
            return Err(Error::invalid(
                "half_plane.datum",
                datum,
                "must be positive and finite",
            ));
        }
        let modulus = match state {
            PlaneState::Strain => material.plane_strain_modulus(),
            PlaneState::Stress => material.e(),
        };
        let n = edges.len() - 1;
        let points: Vec<[f64; 3]> = (0..n)
            .map(|j| [0.5 * (edges[j] + edges[j + 1]), 0.0, 0.0])
            .collect();
        let weights: Vec<f64> = (0..n)
            .map(|j| (edges[j + 1] - edges[j]) * thickness)
            .collect();
        let interface = Interface::new(
            Geometry::Plane { thickness },
            points,
            weights,
            vec![[0.0, 1.0, 0.0]; n],
        )?;
        // ∫ t ln|t| dt, for the average of −(x − a) ln|x − a| + (x − b) ln|x − b| over [c, d].
        let primitive = |t: f64| {
            if t == 0.0 {
                0.0
            } else {
                0.5 * t * t * t.abs().ln() - 0.25 * t * t
            }
        };
        let strip_mean = |c: f64, d: f64, a: f64, b: f64| {
            let logs =
                -(primitive(d - a) - primitive(c - a)) + (primitive(d - b) - primitive(c - b));
            2.0 / (PI * modulus) * ((b - a) * (datum.ln() + 1.0) + logs / (d - c))
        };
        let averaged = Mat::from_fn(n, n, |i, j| {
            strip_mean(edges[i], edges[i + 1], edges[j], edges[j + 1]) / interface.weights[j]
        });
        Ok(Self {
            surface: crate::DenseSurface::symmetric(name.into(), interface, &averaged),
        })
    }
}

crate::surface_body!(HalfPlane);
