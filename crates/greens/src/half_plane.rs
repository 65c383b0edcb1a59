use std::f64::consts::PI;

use contopt_core::{
    check, Geometry, Interface, Material, Result, StressTensor, Subsurface, SubsurfaceRequest,
};
use faer::Mat;

use crate::check_edges;
use crate::subsurface_2d::{check_point, check_pressure, sweep};

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
///
/// Below the edge it gives the stresses of the strips' uniform pressures
/// ([`HalfPlane::stresses_below`], [`HalfPlane::stress_at`]).
#[derive(Clone, Debug)]
pub struct HalfPlane {
    surface: crate::DenseSurface,
    /// The strip edges \[mm\].
    edges: Vec<f64>,
    /// σ_yy / (σ_xx + σ_zz): ν in plane strain, 0 in plane stress.
    out_of_plane: f64,
}

impl HalfPlane {
    /// The edge of a half-plane of `thickness` \[mm\] cut into strips between `edges` \[mm\]:
    /// each strip's middle, its width times the thickness as its weight, the outward normal +y
    /// of the body below. A rigid body or a bed facing the strips takes this surface
    /// (mirrored).
    pub fn strips_interface(edges: &[f64], thickness: f64) -> Result<Interface> {
        check_edges(edges, "half_plane.edges")?;
        check::positive("thickness_mm", thickness)?;
        let n = edges.len() - 1;
        let points: Vec<[f64; 3]> = (0..n)
            .map(|j| [0.5 * (edges[j] + edges[j + 1]), 0.0, 0.0])
            .collect();
        let weights: Vec<f64> = (0..n)
            .map(|j| (edges[j + 1] - edges[j]) * thickness)
            .collect();
        let what = "a strip's area (edge step × thickness)";
        for &w in &weights {
            check::derived_positive("thickness_mm", thickness, what, w)?;
        }
        Interface::new(
            Geometry::Plane { thickness },
            points,
            weights,
            vec![[0.0, 1.0, 0.0]; n],
        )
    }

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
        check::positive("half_plane.thickness", thickness)?;
        check::positive("half_plane.datum", datum)?;
        let modulus = match state {
            PlaneState::Strain => material.plane_strain_modulus(),
            PlaneState::Stress => material.e(),
        };
        let n = edges.len() - 1;
        let interface = Self::strips_interface(edges, thickness)?;
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
            strip_mean(edges[i], edges[i + 1], edges[j], edges[j + 1]) / interface.weights()[j]
        });
        let out_of_plane = match state {
            PlaneState::Strain => material.nu(),
            PlaneState::Stress => 0.0,
        };
        Ok(Self {
            surface: crate::DenseSurface::symmetric(
                name.into(),
                interface,
                &averaged,
                ("half_plane.edges", edges),
            )?,
            edges: edges.to_vec(),
            out_of_plane,
        })
    }

    /// The stresses below the edge under the pressure `pressure` \[MPa\] on the strips (one
    /// value per strip, uniform over it): what [`contopt_core::ElasticBody::subsurface`]
    /// returns.
    ///
    /// The peaks are taken over every strip centre and, when the strips span it, the line
    /// x = 0, at every requested depth: a contact is usually set up about x = 0, and an even
    /// number of strips placed symmetrically puts a strip edge, not a centre, on the line where
    /// the stresses of a symmetric pressure peak. Each requested section returns the body's own
    /// plane (its axis and `at` are ignored) with the strip centres as positions. Each point
    /// sums every strip in closed form ([`HalfPlane::stress_at`]): the cost is
    /// O(strips² × depths), a fraction of a second for a few hundred strips and depths.
    pub fn stresses_below(
        &self,
        pressure: &[f64],
        request: &SubsurfaceRequest,
    ) -> Result<Subsurface> {
        let name = &self.surface.name;
        let centres: Vec<f64> = self
            .surface
            .interface
            .points()
            .iter()
            .map(|p| p[0])
            .collect();
        let (first, last) = (self.edges[0], self.edges[self.edges.len() - 1]);
        let axis_extra = first <= 0.0 && 0.0 <= last && !centres.contains(&0.0);
        let extra: &[f64] = if axis_extra { &[0.0] } else { &[] };
        sweep(
            name,
            request,
            (pressure, self.edges.len() - 1),
            &centres,
            extra,
            |x, z| self.stress(pressure, x, z),
        )
    }

    /// The stress at `x` \[mm\] and `depth` \[mm\] > 0 below the edge under the strip pressures
    /// `pressure` \[MPa\]: xx along the edge, zz along the depth, xz the shear, yy the
    /// out-of-plane stress (ν(σ_xx + σ_zz) in plane strain, 0 in plane stress).
    pub fn stress_at(&self, pressure: &[f64], x: f64, depth: f64) -> Result<StressTensor> {
        let name = &self.surface.name;
        check_pressure(name, pressure, self.edges.len() - 1)?;
        check_point(name, x, depth, false)?;
        Ok(self.stress(pressure, x, depth))
    }

    /// [`HalfPlane::stress_at`] without the checks.
    fn stress(&self, pressure: &[f64], x: f64, z: f64) -> StressTensor {
        let mut s = StressTensor::default();
        for (j, p) in pressure.iter().enumerate() {
            let [xx, zz, xz] = strip_stress(x - self.edges[j + 1], x - self.edges[j], z);
            s.xx += p * xx;
            s.zz += p * zz;
            s.xz += p * xz;
        }
        s.yy = self.out_of_plane * (s.xx + s.zz);
        s
    }
}

/// The in-plane stresses [σ_x, σ_z, τ_xz] at depth z > 0 under a unit pressure on the part
/// lo ≤ ξ ≤ hi of the edge, ξ = x − s for a load at s (Johnson, *Contact Mechanics*, §2.7,
/// uniform pressure on a strip),
///
/// σ_x = −(1/π)[(θ₂ − θ₁) − ½(sin 2θ₂ − sin 2θ₁)],
/// σ_z = −(1/π)[(θ₂ − θ₁) + ½(sin 2θ₂ − sin 2θ₁)],
/// τ_xz = −(1/π)(sin²θ₂ − sin²θ₁),
///
/// with tan θ₁ = lo/z and tan θ₂ = hi/z; Flamant's point load
/// σ_x, σ_z, τ_xz = −(2P/π)(ξ²z, z³, ξz²)/(ξ² + z²)² (Johnson §2.2, eq. 2.15) integrated over
/// ξ with ξ = z tan θ. The differences are formed without cancellation (θ₂ − θ₁ by one atan2), so
/// far from the strip they keep their accuracy relative to Flamant's decay.
fn strip_stress(lo: f64, hi: f64, z: f64) -> [f64; 3] {
    let angle = (z * (hi - lo)).atan2(z * z + hi * lo);
    let (d_lo, d_hi) = (lo * lo + z * z, hi * hi + z * z);
    // ½ sin 2θ = ξz/(ξ² + z²) and sin²θ = ξ²/(ξ² + z²), their differences over a common
    // denominator.
    let half_sin2 = z * (hi - lo) * (z * z - hi * lo) / (d_lo * d_hi);
    let sin_sq = z * z * (hi - lo) * (hi + lo) / (d_lo * d_hi);
    [
        -(angle - half_sin2) / PI,
        -(angle + half_sin2) / PI,
        -sin_sq / PI,
    ]
}

crate::surface_body!(HalfPlane);

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::{ElasticBody, Section, SectionAxis};

    /// Plane strain, ν = 0.3, E = 210 GPa: the stresses do not depend on E.
    fn body(state: PlaneState, edges: &[f64]) -> HalfPlane {
        let steel = Material::new(2.1e5, 0.3).unwrap();
        HalfPlane::new("hp", steel, state, 1.0, edges, 100.0).unwrap()
    }

    /// Strips whose influence or areas overflow f64 are refused, naming the edges or the
    /// thickness; so is a bed whose springs or compliances do.
    #[test]
    fn magnitudes_beyond_f64_are_refused() {
        let steel = Material::new(2.1e5, 0.3).unwrap();
        let strain = PlaneState::Strain;
        let e = HalfPlane::new("hp", steel, strain, 1.0, &[-1e200, 1e200], 1.0).unwrap_err();
        assert!(e.to_string().contains("half_plane.edges"), "{e}");
        let e = HalfPlane::new("hp", steel, strain, 1e300, &[0.0, 1e10], 1.0).unwrap_err();
        assert!(e.to_string().contains("thickness_mm"), "{e}");
        assert!(HalfPlane::new("hp", steel, strain, 1.0, &[-1.0, 0.0, 1.0], 1.0).is_ok());
        let strips = || HalfPlane::strips_interface(&[0.0, 2.0, 4.0], 1.0).unwrap();
        for k in [f64::MAX, 1e-320] {
            let e = crate::Winkler::on("bed", strips(), k)
                .unwrap_err()
                .to_string();
            assert!(
                e.contains("modulus_mpa_per_mm") && e.contains("beyond f64"),
                "{e}"
            );
        }
        assert!(crate::Winkler::on("bed", strips(), 1.0).is_ok());
    }

    /// Far from a strip of width w, its stresses approach Flamant's point load P = p w
    /// (Johnson eq. 2.15): the strip's second moment makes the difference, relative to the
    /// largest component, about 0.2 (w/ρ)² (measured 0.17–0.25); the cancellation-free
    /// differences keep round-off far below it, out to ρ = 2000 w.
    #[test]
    fn uniform_strip_tends_to_flamant_far_away() {
        let (lo, hi) = (-0.5, 0.5);
        for (x, z) in [
            (30.0, 40.0),
            (-300.0, 400.0),
            (0.0, 1000.0),
            (2000.0, 100.0),
        ] {
            let [sx, sz, txz] = strip_stress(x - hi, x - lo, z);
            let r2: f64 = x * x + z * z;
            let scale = 2.0 / (PI * r2 * r2);
            let flamant = [-scale * x * x * z, -scale * z.powi(3), -scale * x * z * z];
            let size = flamant.iter().map(|v: &f64| v.abs()).fold(0.0, f64::max);
            for (got, want) in [sx, sz, txz].iter().zip(flamant) {
                assert!(
                    (got - want).abs() <= 0.3 * size / r2,
                    "at ({x}, {z}): {got} vs Flamant {want}"
                );
            }
        }
    }

    /// Just below a uniform strip σ_x = σ_z = −p and τ_xz = 0 (Johnson §2.7); outside it
    /// all vanish.
    #[test]
    fn uniform_strip_just_below_its_surface() {
        let [sx, sz, txz] = strip_stress(-1.3, 0.7, 1e-9);
        assert!((sx + 1.0).abs() < 1e-8 && (sz + 1.0).abs() < 1e-8 && txz.abs() < 1e-8);
        let outside = strip_stress(0.5, 1.5, 1e-9);
        assert!(outside.iter().all(|v| v.abs() < 1e-8), "{outside:?}");
    }

    /// Hertz line contact sampled on strips: on the axis, Tresca's maximum 0.3003 p₀ at
    /// 0.786 b and von Mises' 0.5575 p₀ at 0.704 b for ν = 0.3 (Johnson, Ch. 4,
    /// Hertz line contact);
    /// measured 0.30028 p₀ at 0.786 b and 0.55751 p₀ at 0.704 b with 300 strips.
    #[test]
    fn hertz_line_contact_peaks_below_the_axis() {
        let (b, p0, n) = (1.0, 1000.0, 300);
        let span = 1.2 * b;
        let edges: Vec<f64> = (0..=n)
            .map(|i| -span + 2.0 * span * i as f64 / n as f64)
            .collect();
        let hp = body(PlaneState::Strain, &edges);
        let pressure: Vec<f64> = hp
            .interface()
            .points()
            .iter()
            .map(|p| p0 * (1.0 - (p[0] / b).powi(2)).max(0.0).sqrt())
            .collect();
        // Depths every 0.002 b: the maxima are flat, so the sampling costs no value.
        let request = SubsurfaceRequest {
            depths: (0..=250).map(|k| (0.5 + 0.002 * k as f64) * b).collect(),
            sections: vec![],
        };
        let peaks = hp.stresses_below(&pressure, &request).unwrap().peaks;
        // Strip sampling changes the maxima by ~1e-4; 0.5 % is a tenth of the gap to the
        // values of a wrong ν or a lost factor.
        let (tresca, mises) = (peaks.tresca, peaks.von_mises);
        assert_eq!((tresca.x, mises.x), (0.0, 0.0), "{peaks:?}");
        assert!(
            (tresca.value / p0 / 0.3003 - 1.0).abs() < 5e-3,
            "{tresca:?}"
        );
        assert!((tresca.depth / b / 0.786 - 1.0).abs() < 0.02, "{tresca:?}");
        assert!((mises.value / p0 / 0.5575 - 1.0).abs() < 5e-3, "{mises:?}");
        assert!((mises.depth / b / 0.704 - 1.0).abs() < 0.02, "{mises:?}");
        // The axis against Hertz's closed form (Johnson, Ch. 4): σ_z = −p₀/√(1 + ζ²),
        // σ_x = −p₀[(1 + 2ζ²)/√(1 + ζ²) − 2ζ], ζ = z/b.
        for zeta in [0.1, 0.5, 1.0, 2.0] {
            let s = hp.stress_at(&pressure, 0.0, zeta * b).unwrap();
            let root = (1.0 + zeta * zeta).sqrt();
            let (sz, sx) = (
                -p0 / root,
                -p0 * ((1.0 + 2.0 * zeta * zeta) / root - 2.0 * zeta),
            );
            assert!(
                (s.zz - sz).abs() < 2e-3 * p0,
                "ζ = {zeta}: {} vs {sz}",
                s.zz
            );
            assert!(
                (s.xx - sx).abs() < 2e-3 * p0,
                "ζ = {zeta}: {} vs {sx}",
                s.xx
            );
            assert!((s.yy - 0.3 * (s.xx + s.zz)).abs() < 1e-9 * p0);
            assert!(s.xz.abs() < 1e-9 * p0);
        }
    }

    /// Plane stress: no out-of-plane stress, the in-plane ones as in plane strain; one
    /// section per request, the body's plane at the strip centres.
    #[test]
    fn plane_stress_and_sections() {
        let edges = [-1.0, -0.5, 0.0, 0.5, 1.0];
        let pressure = [10.0, 30.0, 30.0, 10.0];
        let request = SubsurfaceRequest {
            depths: vec![0.25, 1.0],
            sections: vec![
                Section {
                    axis: SectionAxis::Y,
                    at: 3.0,
                },
                Section {
                    axis: SectionAxis::X,
                    at: -1.0,
                },
            ],
        };
        let stress = body(PlaneState::Stress, &edges)
            .stresses_below(&pressure, &request)
            .unwrap();
        let strain = body(PlaneState::Strain, &edges)
            .stresses_below(&pressure, &request)
            .unwrap();
        assert_eq!(stress.sections.len(), 2);
        let (a, b) = (&stress.sections[1], &strain.sections[0]);
        assert_eq!(a.positions, vec![-0.75, -0.25, 0.25, 0.75]);
        assert_eq!((a.section.axis, a.section.at), (SectionAxis::X, 0.0));
        assert_eq!(a.depths, request.depths);
        for (s, t) in a.tensors.iter().zip(&b.tensors) {
            assert_eq!(s.yy, 0.0);
            assert_eq!((s.xx, s.zz, s.xz), (t.xx, t.zz, t.xz));
            assert!(t.yy != 0.0);
        }
        // Symmetric pressure: τ_xz is odd in x, σ_z even.
        let (left, right) = (a.at(0, 1), a.at(0, 2));
        assert!((left.xz + right.xz).abs() < 1e-12 && (left.zz - right.zz).abs() < 1e-12);
    }
}
