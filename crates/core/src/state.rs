use serde::{Deserialize, Serialize};

use crate::{Error, Result};

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
    pub fn new(equilibrium: f64, pressure: &[f64], gap: &[f64]) -> Self {
        Self {
            equilibrium,
            penetration: gap.iter().fold(0.0, |m, &d| m.max(-d)),
            complementarity: pressure
                .iter()
                .zip(gap)
                .fold(0.0, |m, (p, d)| m.max((p * d).abs())),
        }
    }
}

/// How a solve ended: clarabel's way, a status rather than an error (errors are for bad input).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub enum Status {
    /// The method met its tolerance.
    #[default]
    Solved,
    /// The method stopped before its tolerance; the text says where and how far it got. The
    /// state holds its last iterate and that iterate's residuals.
    Stopped(String),
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
    /// Whether the method met its tolerance.
    pub status: Status,
}

impl ContactState {
    /// The state itself when its method met its tolerance; otherwise
    /// [`Error::NotConverged`] naming `method`, the reason and the residuals reached.
    pub fn solved(self, method: &str) -> Result<Self> {
        match &self.status {
            Status::Solved => Ok(self),
            Status::Stopped(reason) => Err(Error::NotConverged {
                method: method.into(),
                iterations: self.iterations,
                detail: format!(
                    "{reason}; reached: equilibrium {:.3e} N, penetration {:.3e} mm, |p·d| {:.3e} MPa·mm",
                    self.residuals.equilibrium,
                    self.residuals.penetration,
                    self.residuals.complementarity
                ),
            }),
        }
    }

    /// Largest contact pressure p_max \[MPa\].
    pub fn p_max(&self) -> f64 {
        self.pressure.iter().fold(0.0, |m, &p| m.max(p))
    }
}
