use serde::{Deserialize, Serialize};

use crate::observe::Method;
use crate::{Quantity, Termination};

/// How well a contact solution satisfies the conditions (2.15).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Residuals {
    /// Largest equilibrium error of a rigid mode, |Σ wᵢ pᵢ Rᵢₖ + qₖ| \[N\], eq. (2.10).
    pub equilibrium: f64,
    /// Largest penetration max(0, −dᵢ) \[mm\].
    pub penetration: f64,
    /// Largest |pᵢ dᵢ| \[MPa·mm\].
    pub complementarity: f64,
}

impl Residuals {
    /// Residuals of pressure `p` with gap `d`, given the largest equilibrium error.
    /// A NaN anywhere makes the residual it enters NaN (`f64::max` would drop it).
    pub fn new(equilibrium: f64, pressure: &[f64], gap: &[f64]) -> Self {
        Self {
            equilibrium,
            penetration: gap.iter().fold(0.0, |m, &d| largest(m, -d)),
            complementarity: pressure
                .iter()
                .zip(gap)
                .fold(0.0, |m, (p, d)| largest(m, (p * d).abs())),
        }
    }
}

/// The larger of two values, NaN when either is.
fn largest(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

/// The solution of a normal contact problem at the interface points.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ContactState {
    /// Contact pressure pᵢ ≥ 0 \[MPa\].
    pub pressure: Vec<f64>,
    /// Gap after deformation dᵢ ≥ 0 \[mm\], eq. (2.7).
    pub gap: Vec<f64>,
    /// Rigid-mode amplitudes λ (the rigid-body approach, eq. 2.6), one per free mode.
    pub rigid: Vec<f64>,
    /// Points in contact (the set C of the Kalker iteration).
    pub active: Vec<bool>,
    /// Outer iterations (Uzawa steps for the augmented Lagrangian; interior-point steps for
    /// the QP).
    pub iterations: usize,
    /// Kalker's solves on a contact set C, each followed by the sign check of p (the paper's
    /// `iterp`; 1 when the first set was the answer). `iterp − iterd` solves had negative
    /// pressure.
    pub iterp: usize,
    /// Kalker's penetration checks: the solves whose pressure was non-negative, after which C
    /// gains the penetrating points or the iteration stops (the paper's `iterd`).
    pub iterd: usize,
    /// Residuals of the returned solution.
    pub residuals: Residuals,
    /// The method that solved it.
    pub method: Method,
    /// How the method ended: [`Termination::Converged`], or why it stopped short (the state
    /// then holds its last iterate and that iterate's residuals).
    pub termination: Termination,
}

impl ContactState {
    /// Whether the method met its tolerance.
    pub fn is_converged(&self) -> bool {
        self.termination.is_converged()
    }

    /// The approach δ of the floating body \[mm\]: how far it moved towards its partner
    /// along the contact normal, positive when the bodies are pressed together. It is the
    /// negated amplitude of the first rigid mode (a mode's unit amplitude moves the body away
    /// from its partner, eq. 2.6); `None` when no body floats.
    pub fn approach(&self) -> Option<f64> {
        self.rigid.first().map(|lambda| -lambda)
    }

    /// The first quantity of the state that holds a NaN or an infinity, with its first such
    /// value; `None` when every value is finite.
    pub fn non_finite(&self) -> Option<(Quantity, f64)> {
        let first = |v: &[f64]| v.iter().copied().find(|x| !x.is_finite());
        let r = &self.residuals;
        [
            (Quantity::Pressure, first(&self.pressure)),
            (Quantity::Gap, first(&self.gap)),
            (Quantity::RigidAmplitude, first(&self.rigid)),
            (
                Quantity::Residual,
                first(&[r.equilibrium, r.penetration, r.complementarity]),
            ),
        ]
        .into_iter()
        .find_map(|(quantity, v)| v.map(|v| (quantity, v)))
    }

    /// Marks a state that holds a NaN or an infinity [`Termination::NonFinite`], naming the
    /// field, so that no non-finite value passes for a solution: the data overflowed f64 (a
    /// load near 10³⁰⁸ N, a modulus near 10⁻³⁰⁰) or the method broke down.
    pub fn stop_if_not_finite(&mut self) {
        if let Some((quantity, _)) = self.non_finite() {
            self.termination = Termination::NonFinite { quantity };
        }
    }

    /// Largest contact pressure p_max \[MPa\].
    pub fn p_max(&self) -> f64 {
        self.pressure.iter().fold(0.0, |m, &p| m.max(p))
    }
}
