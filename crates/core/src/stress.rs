//! Stresses below a contact surface and the criteria a designer judges them by: von Mises,
//! Tresca (the largest shear) and the principal stresses, with where each is largest.
//!
//! A contact pressure is not yet a verdict: yield, case-hardening depth and rolling-contact
//! fatigue are judged by these stresses, which peak below the surface (Johnson, *Contact
//! Mechanics*, §4.2). Bodies that can say what happens below their surface implement
//! [`crate::ElasticBody::subsurface`].

use serde::{Deserialize, Serialize};

use crate::{check, Error, Result};

/// A symmetric stress tensor \[MPa\], tension positive. For a body with a contact surface, x
/// and y run along the surface and z into the body; a plane or axisymmetric body puts its
/// in-plane components in `xx`, `zz` and `xz` (x or r along the surface, z the depth) and its
/// out-of-plane (hoop) stress in `yy`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct StressTensor {
    /// σ_xx.
    pub xx: f64,
    /// σ_yy.
    pub yy: f64,
    /// σ_zz.
    pub zz: f64,
    /// τ_xy.
    pub xy: f64,
    /// τ_xz.
    pub xz: f64,
    /// τ_yz.
    pub yz: f64,
}

impl StressTensor {
    /// The principal stresses σ₁ ≥ σ₂ ≥ σ₃, the eigenvalues of the tensor, to a few ε of its
    /// norm also where two are equal, without iteration.
    ///
    /// The trigonometric solution of the characteristic cubic (Smith 1961) gives the
    /// eigenvalue farthest from the other two accurately (it lies √3 deviator sizes or more
    /// from them, where acos is not steep); alone it gives the other two to only √ε of the
    /// deviator where they are equal. So, in the order of Scherzinger & Dohrmann (2008, "A
    /// robust algorithm for finding the eigenvalues and eigenvectors of 3×3 symmetric
    /// matrices", CMAME 197), the farthest eigenvalue comes first, its eigenvector from cross
    /// products of the rows, and the other two from the deviator deflated by that eigenpair:
    /// their mean from the trace, their half-difference from the Frobenius norm of what is
    /// left, a sum of squares without cancellation.
    pub fn principal(&self) -> [f64; 3] {
        let mean = (self.xx + self.yy + self.zz) / 3.0;
        let (a, b, c) = (self.xx - mean, self.yy - mean, self.zz - mean);
        let off = self.xy * self.xy + self.xz * self.xz + self.yz * self.yz;
        let spread = ((a * a + b * b + c * c + 2.0 * off) / 6.0).sqrt();
        // A deviator too small to scale by its reciprocal (below the smallest normal number)
        // is taken as zero, an error below that number; NaN goes on and comes out.
        if spread < f64::MIN_POSITIVE {
            return [mean; 3];
        }
        // The deviator scaled by 1/spread (entries of order 1); its eigenvalues are 2 cos θ
        // for θ = φ, φ ± 2π/3 with cos 3φ = det/2.
        let k = 1.0 / spread;
        let dev = [
            [a * k, self.xy * k, self.xz * k],
            [self.xy * k, b * k, self.yz * k],
            [self.xz * k, self.yz * k, c * k],
        ];
        let det = dev[0][0] * (dev[1][1] * dev[2][2] - dev[1][2] * dev[1][2])
            - dev[0][1] * (dev[0][1] * dev[2][2] - dev[1][2] * dev[0][2])
            + dev[0][2] * (dev[0][1] * dev[1][2] - dev[1][1] * dev[0][2]);
        let cos3 = (0.5 * det).clamp(-1.0, 1.0);
        let phi = cos3.acos() / 3.0;
        // The farthest eigenvalue: the largest (θ = φ ≤ π/6) when cos 3φ ≥ 0, else the
        // smallest (θ = φ + 2π/3 ≥ 5π/6).
        let top = cos3 >= 0.0;
        let far = if top {
            2.0 * phi.cos()
        } else {
            2.0 * (phi + 2.0 * std::f64::consts::FRAC_PI_3).cos()
        };
        // Its eigenvector e: the longest cross product of two rows of dev − far·I (rank 2).
        let rows = [0, 1, 2].map(|i| {
            let mut r = dev[i];
            r[i] -= far;
            r
        });
        let longer = |p: [f64; 3], q: [f64; 3]| if dot(p, p) >= dot(q, q) { p } else { q };
        let e = longer(
            longer(cross(rows[0], rows[1]), cross(rows[0], rows[2])),
            cross(rows[1], rows[2]),
        );
        // The other two are centre ± radius: dev − centre·I − (far − centre)·e eᵀ/|e|² has
        // them as its eigenvalues less the centre, ±radius, and 0, so its Frobenius norm is
        // √2·radius.
        let centre = 0.5 * (dev[0][0] + dev[1][1] + dev[2][2] - far);
        let w = (far - centre) / dot(e, e);
        let rest =
            |i: usize, j: usize| dev[i][j] - if i == j { centre } else { 0.0 } - w * e[i] * e[j];
        let (d0, d1, d2) = (rest(0, 0), rest(1, 1), rest(2, 2));
        let (o01, o02, o12) = (rest(0, 1), rest(0, 2), rest(1, 2));
        let radius =
            (0.5 * (d0 * d0 + d1 * d1 + d2 * d2) + o01 * o01 + o02 * o02 + o12 * o12).sqrt();
        let [far, hi, lo] = [far, centre + radius, centre - radius].map(|x| mean + spread * x);
        if top {
            [far, hi, lo]
        } else {
            [hi, lo, far]
        }
    }

    /// The von Mises equivalent stress √(3 J₂).
    pub fn von_mises(&self) -> f64 {
        let (a, b, c) = (self.xx - self.yy, self.yy - self.zz, self.zz - self.xx);
        let shear = self.xy * self.xy + self.xz * self.xz + self.yz * self.yz;
        (0.5 * (a * a + b * b + c * c) + 3.0 * shear).sqrt()
    }

    /// The largest shear stress (σ₁ − σ₃)/2: Tresca's criterion compares it with half the
    /// yield stress.
    pub fn tresca(&self) -> f64 {
        let [s1, _, s3] = self.principal();
        0.5 * (s1 - s3)
    }

    /// Whether every component is finite.
    pub fn is_finite(&self) -> bool {
        [self.xx, self.yy, self.zz, self.xy, self.xz, self.yz]
            .iter()
            .all(|v| v.is_finite())
    }
}

/// The cross product p × q.
fn cross(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [
        p[1] * q[2] - p[2] * q[1],
        p[2] * q[0] - p[0] * q[2],
        p[0] * q[1] - p[1] * q[0],
    ]
}

/// The dot product p · q.
fn dot(p: [f64; 3], q: [f64; 3]) -> f64 {
    p[0] * q[0] + p[1] * q[1] + p[2] * q[2]
}

/// Relative difference below which two values of a criterion count as equal when the peak is
/// placed: a symmetric contact has mirror points whose values differ only by round-off, and
/// which of them is reported must not depend on the order of floating-point operations (an
/// optimisation level, a SIMD path). Far below any printed figure.
pub const PEAK_TIE: f64 = 1e-9;

/// Whether `value` exceeds `held` by more than [`PEAK_TIE`] (relative): a new peak, rather
/// than a mirror point of the one held.
fn exceeds(value: f64, held: f64) -> bool {
    value - held > PEAK_TIE * value.abs().max(held.abs())
}

/// The index of the largest of `values`; of values equal to [`PEAK_TIE`] the first. `None`
/// when `values` is empty. A value that is not a number is never the peak.
pub fn peak_index(values: &[f64]) -> Option<usize> {
    let max = values
        .iter()
        .copied()
        .filter(|v| !v.is_nan())
        .max_by(f64::total_cmp)?;
    values
        .iter()
        .position(|&v| v == max || (v.is_finite() && !exceeds(max, v)))
}

/// Whether `value` replaces the peak `held`: any value above an unset (infinite) peak, else
/// one that [`exceeds`] it.
fn raises(value: f64, held: f64) -> bool {
    if held.is_infinite() {
        value > held
    } else {
        exceeds(value, held)
    }
}

/// Where a criterion is largest and its value there.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Peak {
    /// The criterion's value \[MPa\].
    pub value: f64,
    /// Position along the surface \[mm\]: x of a grid or a strip, r of a ring, the node's
    /// first coordinate in a finite-element body.
    pub x: f64,
    /// The second surface coordinate \[mm\] of a grid (0 for a plane or axisymmetric body; the
    /// node's second coordinate in a finite-element body).
    pub y: f64,
    /// Depth below the contact surface \[mm\].
    pub depth: f64,
}

/// The largest value of each criterion over the points a body evaluated.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct StressPeaks {
    /// Largest von Mises stress.
    pub von_mises: Peak,
    /// Largest shear stress (σ₁ − σ₃)/2.
    pub tresca: Peak,
    /// Largest principal stress σ₁ (the largest tension when positive).
    pub max_principal: Peak,
    /// Smallest principal stress σ₃ (the largest compression), its value negative.
    pub min_principal: Peak,
    /// Largest orthogonal shear |τ_xz|: the shear on the planes across x and along the
    /// surface, which reverses as a contact rolls along x past a point (Lundberg and
    /// Palmgren's τ₀, 0.25·p₀ at 0.5·b below a line contact; Johnson, *Contact Mechanics*,
    /// §4.2). A plane or axisymmetric body's in-plane shear.
    pub shear_xz: Peak,
    /// Largest orthogonal shear |τ_yz|: the same for rolling along y (a roller on a grid
    /// along x rolls across it, along y).
    pub shear_yz: Peak,
}

impl Default for StressPeaks {
    fn default() -> Self {
        let low = Peak {
            value: f64::NEG_INFINITY,
            ..Peak::default()
        };
        Self {
            von_mises: low,
            tresca: low,
            max_principal: low,
            min_principal: Peak {
                value: f64::INFINITY,
                ..Peak::default()
            },
            shear_xz: low,
            shear_yz: low,
        }
    }
}

impl StressPeaks {
    /// Takes the stress `s` at surface position (`x`, `y`) and `depth` into account. A value
    /// that is not a number sticks, so that [`StressPeaks::finite`] refuses the peaks. Of
    /// values equal to [`PEAK_TIE`] the first recorded stays the peak.
    pub fn record(&mut self, s: &StressTensor, x: f64, y: f64, depth: f64) {
        let at = |value| Peak { value, x, y, depth };
        let [s1, _, s3] = s.principal();
        let raise = |peak: &mut Peak, value: f64| {
            if !peak.value.is_nan() && (value.is_nan() || raises(value, peak.value)) {
                *peak = at(value);
            }
        };
        raise(&mut self.von_mises, s.von_mises());
        raise(&mut self.tresca, 0.5 * (s1 - s3));
        raise(&mut self.max_principal, s1);
        raise(&mut self.shear_xz, s.xz.abs());
        raise(&mut self.shear_yz, s.yz.abs());
        if !self.min_principal.value.is_nan()
            && (s3.is_nan() || raises(-s3, -self.min_principal.value))
        {
            self.min_principal = at(s3);
        }
    }

    /// The larger of each criterion over `self` and `other`.
    pub fn merge(&mut self, other: &StressPeaks) {
        for (mine, theirs) in [
            (&mut self.von_mises, other.von_mises),
            (&mut self.tresca, other.tresca),
            (&mut self.max_principal, other.max_principal),
            (&mut self.shear_xz, other.shear_xz),
            (&mut self.shear_yz, other.shear_yz),
        ] {
            if raises(theirs.value, mine.value) {
                *mine = theirs;
            }
        }
        if raises(-other.min_principal.value, -self.min_principal.value) {
            self.min_principal = other.min_principal;
        }
    }

    /// The peaks when every value recorded was finite; otherwise an error naming the body.
    pub fn finite(self, body: &str) -> Result<Self> {
        let all = [
            self.von_mises,
            self.tresca,
            self.max_principal,
            self.min_principal,
            self.shear_xz,
            self.shear_yz,
        ];
        match all.iter().find(|p| !p.value.is_finite()) {
            None => Ok(self),
            Some(p) => Err(Error::invalid(
                format!("{body}.subsurface"),
                p.value,
                "a stress below the surface is not finite (no points evaluated, or a pressure \
                 that is not finite)",
            )),
        }
    }
}

/// The direction of a vertical section through a surface grid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SectionAxis {
    /// Along x, at a fixed y.
    X,
    /// Along y, at a fixed x.
    Y,
}

/// A vertical section: the plane through the line `axis` at the other surface coordinate
/// `at` \[mm\]. A plane or axisymmetric body has one section, its own plane, and ignores both.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Section {
    /// The section's direction along the surface.
    pub axis: SectionAxis,
    /// The fixed other coordinate \[mm\]; a grid takes its nearest row or column of cells.
    pub at: f64,
}

/// What to compute below the surface.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct SubsurfaceRequest {
    /// Depths \[mm\], each positive, at which every surface point is evaluated for the peaks.
    pub depths: Vec<f64>,
    /// Sections whose whole stress field is returned, at the same depths.
    pub sections: Vec<Section>,
}

impl SubsurfaceRequest {
    /// Checks the depths (at least one, each finite and positive).
    pub fn check(&self) -> Result<()> {
        if self.depths.is_empty() {
            return Err(Error::invalid(
                "subsurface.depths",
                "[]",
                "give at least one depth",
            ));
        }
        // Positive: the surface itself (depth 0) is the contact pressure.
        check::all_positive("subsurface.depths", &self.depths)?;
        for (i, s) in self.sections.iter().enumerate() {
            check::finite(&format!("subsurface.sections[{i}].at"), s.at)?;
        }
        Ok(())
    }
}

/// The stress field on one vertical section.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SectionField {
    /// The section as the body took it (`at` moved to the grid row it used).
    pub section: Section,
    /// Positions along the section \[mm\].
    pub positions: Vec<f64>,
    /// Depths \[mm\].
    pub depths: Vec<f64>,
    /// The stress at each depth and position, depth after depth:
    /// `tensors[k·positions.len() + i]`.
    pub tensors: Vec<StressTensor>,
}

impl SectionField {
    /// The stress at depth index `k` and position index `i`.
    pub fn at(&self, k: usize, i: usize) -> &StressTensor {
        &self.tensors[k * self.positions.len() + i]
    }
}

/// Stresses below a body's surface under a contact pressure.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Subsurface {
    /// The largest value of each criterion over every surface point and requested depth.
    pub peaks: StressPeaks,
    /// The requested sections.
    pub sections: Vec<SectionField>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Largest error of a principal stress relative to the tensor's Frobenius norm: a few
    /// hundred ε, the round-off of forming R Λ Rᵀ and of a backward-stable eigen-solution.
    const PRINCIPAL_TOLERANCE: f64 = 1e-13;

    /// R diag(λ) Rᵀ with R the rotation of Euler angles (α, β, γ) about z, x and z.
    fn rotated(lambda: [f64; 3], [a, b, g]: [f64; 3]) -> StressTensor {
        let rz = |t: f64| {
            [
                [t.cos(), -t.sin(), 0.0],
                [t.sin(), t.cos(), 0.0],
                [0.0, 0.0, 1.0],
            ]
        };
        let rx = |t: f64| {
            [
                [1.0, 0.0, 0.0],
                [0.0, t.cos(), -t.sin()],
                [0.0, t.sin(), t.cos()],
            ]
        };
        let mul = |p: [[f64; 3]; 3], q: [[f64; 3]; 3]| {
            std::array::from_fn::<_, 3, _>(|i| {
                std::array::from_fn::<_, 3, _>(|j| (0..3).map(|k| p[i][k] * q[k][j]).sum())
            })
        };
        let r = mul(mul(rz(a), rx(b)), rz(g));
        let s = |i: usize, j: usize| (0..3).map(|k| r[i][k] * lambda[k] * r[j][k]).sum();
        StressTensor {
            xx: s(0, 0),
            yy: s(1, 1),
            zz: s(2, 2),
            xy: s(0, 1),
            xz: s(0, 2),
            yz: s(1, 2),
        }
    }

    /// Asserts that `t`'s principal stresses are `want` (sorted) to [`PRINCIPAL_TOLERANCE`]
    /// of the norm of `want`.
    fn assert_principal(t: &StressTensor, want: [f64; 3]) {
        let norm = want.iter().map(|l| l * l).sum::<f64>().sqrt();
        let got = t.principal();
        let error = got
            .iter()
            .zip(want)
            .map(|(g, w)| (g - w).abs())
            .fold(0.0, f64::max);
        assert!(
            error <= PRINCIPAL_TOLERANCE * norm,
            "{t:?}: {got:?} against {want:?}, error {:.1e} of the norm",
            error / norm
        );
    }

    #[test]
    fn principal_stresses_to_round_off_of_the_norm() {
        let angles = [
            [0.0; 3],
            [0.3, 1.1, -0.7],
            [2.9, 0.05, 1.3],
            [-1.2, 2.3, 0.4],
        ];
        let cases = [
            // Uniaxial tension, pure shear (±τ, 0), hydrostatic pressure.
            [250.0, 0.0, 0.0],
            [2.0, 0.0, -2.0],
            [-5.0, -5.0, -5.0],
            // Two equal principal stresses, below and above the third: the trigonometric
            // solution loses √ε here (acos is steep at ±1).
            [300.0, 100.0, 100.0],
            [50.0, 50.0, -200.0],
            // A pair 1e-9 apart (relative), and a small deviator on a large mean.
            [100.0, 100.0 * (1.0 - 1e-9), -200.0],
            [1e3 + 3e-3, 1e3 + 1e-3, 1e3 + 1e-3],
        ];
        for want in cases {
            for angles in angles {
                assert_principal(&rotated(want, angles), want);
            }
        }
    }

    #[test]
    fn principal_stresses_of_a_rotated_tensor() {
        // diag(3, −1, 2) rotated by 30° about z: the eigenvalues come back, sorted.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let t = StressTensor {
            xx: 3.0 * c * c - s * s,
            yy: 3.0 * s * s - c * c,
            zz: 2.0,
            xy: 4.0 * c * s,
            xz: 0.0,
            yz: 0.0,
        };
        let p = t.principal();
        for (got, want) in p.iter().zip([3.0, 2.0, -1.0]) {
            assert!((got - want).abs() < 1e-12, "{p:?}");
        }
        assert!((t.tresca() - 2.0).abs() < 1e-12);
        // von Mises from the principal stresses: √(½[(3−2)² + (2+1)² + (−1−3)²]) = √13.
        assert!((t.von_mises() - 13f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn hydrostatic_and_pure_shear() {
        let h = StressTensor {
            xx: -5.0,
            yy: -5.0,
            zz: -5.0,
            ..Default::default()
        };
        assert_eq!(h.principal(), [-5.0; 3]);
        assert_eq!(h.von_mises(), 0.0);
        let shear = StressTensor {
            yz: 2.0,
            ..Default::default()
        };
        let p = shear.principal();
        assert!((p[0] - 2.0).abs() < 1e-12 && p[1].abs() < 1e-12 && (p[2] + 2.0).abs() < 1e-12);
        assert!((shear.von_mises() - 2.0 * 3f64.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn peaks_keep_the_largest_and_reject_nothing_recorded() {
        let mut peaks = StressPeaks::default();
        assert!(peaks.finite("b").is_err());
        let small = StressTensor {
            zz: -1.0,
            ..Default::default()
        };
        let large = StressTensor {
            zz: -3.0,
            ..Default::default()
        };
        peaks.record(&small, 0.0, 0.0, 1.0);
        peaks.record(&large, 2.0, 0.0, 0.5);
        peaks.record(&small, 4.0, 0.0, 2.0);
        let mut poisoned = peaks;
        let nan = StressTensor {
            xz: f64::NAN,
            ..Default::default()
        };
        poisoned.record(&nan, 0.0, 0.0, 1.0);
        poisoned.record(&large, 0.0, 0.0, 1.0);
        assert!(poisoned.finite("b").is_err(), "a NaN must not be outgrown");
        let peaks = peaks.finite("b").unwrap();
        assert_eq!((peaks.von_mises.value, peaks.von_mises.x), (3.0, 2.0));
        assert_eq!(peaks.min_principal.value, -3.0);
        assert!(peaks.max_principal.value.abs() <= PRINCIPAL_TOLERANCE * 3.0);
    }

    #[test]
    fn mirror_points_equal_to_round_off_report_the_first() {
        let peak = 2812.2;
        let mirror = peak * (1.0 + 4.0 * f64::EPSILON);
        assert_eq!(peak_index(&[1.0, peak, 2.0, mirror]), Some(1));
        assert_eq!(peak_index(&[1.0, mirror, 2.0, peak]), Some(1));
        assert_eq!(peak_index(&[1.0, peak, peak * (1.0 + 1e-6)]), Some(2));
        assert_eq!(peak_index(&[f64::NAN, -1.0, -2.0]), Some(1));
        assert_eq!(peak_index(&[]), None);
        let tensor = |zz: f64| StressTensor {
            zz,
            ..Default::default()
        };
        let mut peaks = StressPeaks::default();
        peaks.record(&tensor(-peak), -0.006, -0.006, 0.16);
        peaks.record(&tensor(-mirror), 0.006, -0.006, 0.16);
        assert_eq!(peaks.von_mises.x, -0.006, "a mirror point moved the peak");
        assert_eq!(peaks.min_principal.x, -0.006);
        peaks.record(&tensor(-1.001 * peak), 0.5, 0.0, 0.16);
        assert_eq!((peaks.von_mises.x, peaks.min_principal.x), (0.5, 0.5));
    }
}
