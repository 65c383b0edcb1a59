use contopt_core::{check, Geometry, Result};
use serde::{Deserialize, Serialize};

use crate::Material;

/// The two-dimensional idealisation of a body.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Analysis {
    /// Axisymmetric about the y axis: coordinates (r, z) = (x, y), strains (ε_r, ε_z, ε_θ, γ_rz),
    /// volume element 2πr dA.
    Axisymmetric,
    /// Plane stress (σ_zz = 0) with thickness b \[mm\].
    PlaneStress {
        /// Thickness b \[mm\].
        #[serde(rename = "thickness_mm")]
        thickness: f64,
    },
    /// Plane strain (ε_zz = 0), with an out-of-plane length \[mm\] (1 for per-unit-length results).
    PlaneStrain {
        /// Out-of-plane length \[mm\].
        #[serde(rename = "thickness_mm")]
        thickness: f64,
    },
}

impl Analysis {
    pub(crate) fn validate(&self) -> Result<()> {
        match *self {
            Analysis::Axisymmetric => Ok(()),
            Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => {
                check::positive("analysis.thickness", thickness).map(|_| ())
            }
        }
    }

    /// Number of strain components: 4 for axisymmetric (with the hoop strain), else 3.
    pub fn n_strain(&self) -> usize {
        match self {
            Analysis::Axisymmetric => 4,
            _ => 3,
        }
    }

    /// Out-of-plane measure at radius/abscissa `x`: 2πr for axisymmetry, b otherwise.
    pub fn measure(&self, x: f64) -> f64 {
        match *self {
            Analysis::Axisymmetric => 2.0 * std::f64::consts::PI * x,
            Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => thickness,
        }
    }

    /// The interface geometry this analysis produces.
    pub fn geometry(&self) -> Geometry {
        match *self {
            Analysis::Axisymmetric => Geometry::Axisymmetric,
            Analysis::PlaneStress { thickness } | Analysis::PlaneStrain { thickness } => {
                Geometry::Plane { thickness }
            }
        }
    }

    /// Elasticity matrix D, row-major, for the strain order (ε_x, ε_y, γ_xy) in plane
    /// analyses and (ε_r, ε_z, ε_θ, γ_rz) in axisymmetry.
    pub fn elasticity(&self, m: &Material) -> [[f64; 4]; 4] {
        let (e, nu) = (m.e(), m.nu());
        let mut d = [[0.0; 4]; 4];
        match self {
            Analysis::PlaneStress { .. } => {
                let c = e / (1.0 - nu * nu);
                d[0][0] = c;
                d[1][1] = c;
                d[0][1] = c * nu;
                d[1][0] = c * nu;
                d[2][2] = c * (1.0 - nu) / 2.0;
            }
            Analysis::PlaneStrain { .. } | Analysis::Axisymmetric => {
                let c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
                let normal = if matches!(self, Analysis::Axisymmetric) {
                    [0, 1, 2]
                } else {
                    [0, 1, 1]
                };
                for &i in &normal {
                    for &j in &normal {
                        d[i][j] = if i == j { c * (1.0 - nu) } else { c * nu };
                    }
                }
                let shear = if matches!(self, Analysis::Axisymmetric) {
                    3
                } else {
                    2
                };
                d[shear][shear] = c * (1.0 - 2.0 * nu) / 2.0;
            }
        }
        d
    }
}
