use std::f64::consts::PI;

use contopt_core::{Error, Geometry, Interface, Material, Result};
use faer::Mat;

use crate::{check_edges, elliptic};

/// An elastic half-space z ≤ 0 loaded axisymmetrically on its surface: the contact points are
/// the mid-radii of rings ρ_j ≤ r ≤ ρ_{j+1}, each ring an annulus of uniform pressure.
///
/// A uniform pressure p on a disc of radius a deflects the surface by (Timoshenko & Goodier
/// §138) w(r) = 4(1 − ν²) p a E(r/a) / (πE) for r ≤ a and
/// 4(1 − ν²) p r [E(a/r) − (1 − a²/r²) K(a/r)] / (πE) for r > a; an annulus is the difference
/// of two discs. The influence coefficient Aᵢⱼ is the deflection averaged over ring i (8-point
/// Gauss in r, weighted by 2πr) per unit force spread over ring j: the Galerkin form, symmetric
/// by reciprocity. (Collocating at mid-radii instead gives a matrix whose symmetric part, which
/// the solvers need, misses the flat punch's centre pressure by 3 %.)
#[derive(Clone, Debug)]
pub struct AxisymmetricHalfSpace {
    surface: crate::DenseSurface,
}

/// 8-point Gauss–Legendre abscissae and weights on [−1, 1].
const GAUSS8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// Deflection at radius r of a half-space under unit pressure on the disc r < a, divided by
/// 4(1 − ν²)/(πE).
fn disc(r: f64, a: f64) -> f64 {
    if a <= 0.0 {
        0.0
    } else if r <= a {
        a * elliptic::complete(r / a).1
    } else {
        let (k, e) = elliptic::complete(a / r);
        r * (e - (1.0 - a * a / (r * r)) * k)
    }
}

impl AxisymmetricHalfSpace {
    /// A half-space of `material` with contact rings between the radii `edges` \[mm\]
    /// (increasing, from 0 or more). The surface is at z = 0 with outward normal +z.
    pub fn new(name: impl Into<String>, material: Material, edges: &[f64]) -> Result<Self> {
        check_edges(edges, "half_space.edges")?;
        if edges[0] < 0.0 {
            return Err(Error::invalid(
                "half_space.edges[0]",
                edges[0],
                "radii must be >= 0",
            ));
        }
        let n = edges.len() - 1;
        let points: Vec<[f64; 3]> = (0..n)
            .map(|j| [0.5 * (edges[j] + edges[j + 1]), 0.0, 0.0])
            .collect();
        let weights: Vec<f64> = (0..n)
            .map(|j| PI * (edges[j + 1].powi(2) - edges[j].powi(2)))
            .collect();
        let interface = Interface::new(
            Geometry::Axisymmetric,
            points,
            weights,
            vec![[0.0, 1.0, 0.0]; n],
        )?;
        let scale = 4.0 / (PI * material.plane_strain_modulus());
        let w = &interface.weights;
        let averaged = Mat::from_fn(n, n, |i, j| {
            let (lo, hi) = (edges[i], edges[i + 1]);
            let mean: f64 = GAUSS8
                .iter()
                .map(|&(x, wg)| {
                    let r = 0.5 * (lo + hi) + 0.5 * (hi - lo) * x;
                    wg * 0.5
                        * (hi - lo)
                        * 2.0
                        * PI
                        * r
                        * (disc(r, edges[j + 1]) - disc(r, edges[j]))
                })
                .sum::<f64>()
                / w[i];
            scale * mean / w[j]
        });
        Ok(Self {
            surface: crate::DenseSurface::symmetric(name.into(), interface, &averaged),
        })
    }
}

crate::surface_body!(AxisymmetricHalfSpace);

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::ElasticBody;

    /// Uniform pressure on a disc: the centre and edge deflections of the closed form.
    #[test]
    fn uniform_disc_load() {
        let (e, nu, a, p) = (2e5, 0.3, 10.0, 100.0);
        let edges: Vec<f64> = (0..=40).map(|i| a * i as f64 / 40.0).collect();
        let body = AxisymmetricHalfSpace::new("hs", Material::new(e, nu).unwrap(), &edges).unwrap();
        let force: Vec<f64> = body.interface().weights.iter().map(|w| w * p).collect();
        let mut w = vec![0.0; 40];
        body.apply_influence(&force, &mut w);
        let centre = 2.0 * (1.0 - nu * nu) * p * a / e;
        // The innermost ring's mid-radius is a/80: the deflection there is within 1e-4 of
        // the centre value; symmetrising costs less than 1e-3.
        assert!((w[0] / centre - 1.0).abs() < 1e-3, "{} vs {centre}", w[0]);
        let edge = 4.0 * (1.0 - nu * nu) * p * a / (PI * e);
        let last = body.interface().points[39][0];
        let near_edge = 4.0 * (1.0 - nu * nu) * p * a / (PI * e) * elliptic::complete(last / a).1;
        assert!(
            (w[39] / near_edge - 1.0).abs() < 2e-3,
            "{} vs {near_edge} (edge {edge})",
            w[39]
        );
    }
}
