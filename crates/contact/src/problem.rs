//! The contact interface problem that two bodies define (§2.1).

use contopt_core::{ContactState, ElasticBody, Error, GapShape, Interface, Residuals, Result};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

/// Frictionless normal contact of two bodies, condensed to their common interface points.
///
/// With W = diag(wᵢ) the point weights, A = A¹ + A² the summed influence matrices of the
/// bodies (displacement into the body per unit force, [`ElasticBody::influence_matrix`]) and
/// g = h + f¹ + f² the initial gap plus the displacements under the given loads, the gap after
/// deformation is (2.7)
///
/// d = g + A W p + R λ,
///
/// where the columns of R are the interface displacements of the free rigid modes and λ their
/// amplitudes. Equilibrium of each free mode (2.10) reads Rᵀ W p = −q. In the paper's notation
/// (2.12)–(2.14): H = W A W, t = −W g, G_R = W R, and its q is our −q.
#[derive(Clone, Debug)]
pub struct InterfaceProblem {
    interface: Interface,
    influence: Mat<f64>,
    initial_gap: Vec<f64>,
    load_gap: Vec<f64>,
    rigid: Mat<f64>,
    load: Vec<f64>,
    mode_names: Vec<String>,
    pressure_basis: Option<GapShape>,
}

impl InterfaceProblem {
    /// The problem of `body1` and `body2` touching over their common points with initial
    /// gap `initial_gap` \[mm\] (h of eq. 2.1, one value per point of `body1`). The two
    /// interfaces must hold the same points (in any order: they are paired by position), with
    /// the same weights and opposite normals; the first mismatch is reported.
    pub fn new(
        body1: &dyn ElasticBody,
        body2: &dyn ElasticBody,
        initial_gap: &[f64],
    ) -> Result<Self> {
        let (s1, s2) = (body1.interface(), body2.interface());
        let pair = s1.partners(s2, body1.name(), body2.name())?;
        for (i, &j) in pair.iter().enumerate() {
            let (wa, wb) = (s1.weights[i], s2.weights[j]);
            if (wa - wb).abs() > 1e-9 * wa.abs().max(wb.abs()) {
                return Err(Error::InterfaceMismatch {
                    index: i,
                    detail: format!(
                        "weight {wa} of `{}` against {wb} of `{}`",
                        body1.name(),
                        body2.name()
                    ),
                });
            }
            let (na, nb) = (s1.normals[i], s2.normals[j]);
            if (0..3).map(|c| (na[c] + nb[c]).abs()).fold(0.0, f64::max) > 1e-6 {
                return Err(Error::InterfaceMismatch {
                    index: i,
                    detail: format!("normals {na:?} and {nb:?} are not opposite"),
                });
            }
        }
        let n = s1.len();
        check_gap(initial_gap, n)?;
        let a2 = body2.influence_matrix();
        let influence =
            body1.influence_matrix() + Mat::from_fn(n, n, |i, j| a2[(pair[i], pair[j])]);
        let f1 = body1.load_displacement()?;
        let f2 = body2.load_displacement()?;
        let load_gap = (0..n).map(|i| f1[i] + f2[pair[i]]).collect();
        let identity: Vec<usize> = (0..n).collect();
        let modes: Vec<(String, Vec<f64>, f64)> = [(body1, &identity), (body2, &pair)]
            .iter()
            .flat_map(|(b, order)| {
                b.rigid_modes().iter().map(move |m| {
                    let r = order.iter().map(|&j| m.interface_displacement[j]).collect();
                    (format!("{} of `{}`", m.name, b.name()), r, m.load)
                })
            })
            .collect();
        let mut kept = vec![];
        for (name, r, q) in modes {
            let span = r.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let total = r
                .iter()
                .zip(&s1.weights)
                .map(|(v, w)| (v * w).abs())
                .sum::<f64>();
            if span < 1e-12 {
                // A mode that does not move the interface normally cannot be loaded.
                if q.abs() > 1e-9 * total.max(1.0) {
                    return Err(Error::invalid(format!("load on {name}"), q, "cannot be equilibrated by normal contact: the mode does not move the interface"));
                }
                continue;
            }
            let all_pos = r.iter().all(|v| *v >= -1e-12 * span);
            let all_neg = r.iter().all(|v| *v <= 1e-12 * span);
            if (all_pos && q > 0.0) || (all_neg && q < 0.0) {
                return Err(Error::invalid(
                    format!("load on {name}"),
                    q,
                    "pulls the bodies apart: compressive contact cannot carry it",
                ));
            }
            if q == 0.0 && (all_pos || all_neg) {
                return Err(Error::invalid(
                    format!("load on {name}"),
                    q,
                    "is zero: the floating body is not pressed into contact",
                ));
            }
            kept.push((name, r, q));
        }
        let m = kept.len();
        let rigid = Mat::from_fn(n, m, |i, k| kept[k].1[i]);
        // Two modes that move the interface alike leave λ undetermined.
        if m > 1 {
            let gram = Mat::from_fn(m, m, |a, b| {
                (0..n)
                    .map(|i| rigid[(i, a)] * rigid[(i, b)] * s1.weights[i])
                    .sum::<f64>()
            });
            let independent = faer::linalg::solvers::Llt::new(gram.as_ref(), faer::Side::Lower)
                .is_ok_and(|l| (0..m).all(|k| l.L()[(k, k)].powi(2) > 1e-10 * gram[(k, k)]));
            if !independent {
                let names: Vec<&str> = kept.iter().map(|k| k.0.as_str()).collect();
                return Err(Error::invalid(
                    "rigid modes",
                    names.join(", "),
                    "move the interface alike: support one of the bodies",
                ));
            }
        }
        let pressure_basis = match (body1.pressure_basis(), body2.pressure_basis()) {
            (Some(b), _) => Some(b.clone()),
            (None, Some(b)) => Some(GapShape::new(
                b.nodes().to_vec(),
                pair.iter().map(|&j| b.row(j).to_vec()).collect(),
            )?),
            (None, None) => None,
        };
        Ok(Self {
            interface: s1.clone(),
            pressure_basis,
            influence,
            initial_gap: initial_gap.to_vec(),
            load_gap,
            mode_names: kept.iter().map(|k| k.0.clone()).collect(),
            load: kept.into_iter().map(|k| k.2).collect(),
            rigid,
        })
    }

    /// The same problem with another initial gap h (the optimisation changes it).
    pub fn with_initial_gap(&self, initial_gap: &[f64]) -> Result<Self> {
        check_gap(initial_gap, self.len())?;
        Ok(Self {
            initial_gap: initial_gap.to_vec(),
            ..self.clone()
        })
    }

    /// Number of interface points.
    pub fn len(&self) -> usize {
        self.interface.len()
    }

    /// Never true for a constructed problem.
    pub fn is_empty(&self) -> bool {
        self.interface.is_empty()
    }

    /// The interface points (of the first body, whose normal n¹ is the reference).
    pub fn interface(&self) -> &Interface {
        &self.interface
    }

    /// Point weights wᵢ \[mm²\].
    pub fn weights(&self) -> &[f64] {
        &self.interface.weights
    }

    /// Summed influence matrix A = A¹ + A² \[mm/N\].
    pub fn influence(&self) -> &Mat<f64> {
        &self.influence
    }

    /// Initial gap h \[mm\].
    pub fn initial_gap(&self) -> &[f64] {
        &self.initial_gap
    }

    /// g = h + f¹ + f²: the gap before any contact pressure, rigid modes held \[mm\].
    pub fn free_gap(&self) -> Vec<f64> {
        self.initial_gap
            .iter()
            .zip(&self.load_gap)
            .map(|(h, f)| h + f)
            .collect()
    }

    /// Interface displacements of the free rigid modes, R (n × m).
    pub fn rigid(&self) -> &Mat<f64> {
        &self.rigid
    }

    /// Load resultant q of each free rigid mode \[N\].
    pub fn load(&self) -> &[f64] {
        &self.load
    }

    /// Names of the free rigid modes.
    pub fn mode_names(&self) -> &[String] {
        &self.mode_names
    }

    /// Gap after deformation d = g + A W p + R λ, eq. (2.7).
    pub fn gap(&self, pressure: &[f64], rigid: &[f64]) -> Vec<f64> {
        let n = self.len();
        let w = self.weights();
        let force: Vec<f64> = (0..n).map(|j| w[j] * pressure[j]).collect();
        let g = self.free_gap();
        (0..n)
            .map(|i| {
                let elastic: f64 = (0..n).map(|j| self.influence[(i, j)] * force[j]).sum();
                let motion: f64 = (0..rigid.len())
                    .map(|k| self.rigid[(i, k)] * rigid[k])
                    .sum();
                g[i] + elastic + motion
            })
            .collect()
    }

    /// The field the point pressures sample (see [`ElasticBody::pressure_basis`]), from the
    /// first body that has one.
    pub fn pressure_basis(&self) -> Option<&GapShape> {
        self.pressure_basis.as_ref()
    }

    /// The pressure read as a field: the W-weighted least-squares fit p̃ = B (BᵀWB)⁻¹ BᵀW p by
    /// the [`pressure basis`](Self::pressure_basis), which has the same nodal forces Bᵀ W p
    /// and so the same displacements, and drops the part of p that moves nothing (a sawtooth of
    /// Gauss-point values within each quadratic face). `p` itself without a basis.
    pub fn recovered_pressure(&self, pressure: &[f64]) -> Result<Vec<f64>> {
        let Some(basis) = &self.pressure_basis else {
            return Ok(pressure.to_vec());
        };
        let w = self.weights();
        let nb = basis.nodes().len();
        let (mut gram, mut rhs) = (Mat::<f64>::zeros(nb, nb), Mat::<f64>::zeros(nb, 1));
        for (i, (&wi, &pi)) in w.iter().zip(pressure).enumerate() {
            let row = basis.row(i);
            for &(a, ba) in row {
                rhs[(a, 0)] += ba * wi * pi;
                for &(b, bb) in row {
                    gram[(a, b)] += ba * wi * bb;
                }
            }
        }
        let nodal = Llt::new(gram.as_ref(), Side::Lower)
            .map_err(|_| {
                Error::invalid(
                    "pressure basis",
                    nb,
                    "its nodes are not all reached by the points (BᵀWB is singular)",
                )
            })?
            .solve(&rhs);
        Ok(basis.apply(&(0..nb).map(|a| nodal[(a, 0)]).collect::<Vec<_>>()))
    }

    /// Residuals of a pressure p with its gap d.
    pub fn residuals(&self, pressure: &[f64], gap: &[f64]) -> Residuals {
        let w = self.weights();
        let equilibrium = (0..self.load.len())
            .map(|k| {
                ((0..self.len())
                    .map(|i| w[i] * pressure[i] * self.rigid[(i, k)])
                    .sum::<f64>()
                    + self.load[k])
                    .abs()
            })
            .fold(0.0, f64::max);
        Residuals::new(equilibrium, pressure, gap)
    }

    /// Assembles a [`ContactState`] from a solution, with its gap and residuals.
    pub fn state(
        &self,
        pressure: Vec<f64>,
        rigid: Vec<f64>,
        active: Vec<bool>,
        counts: [usize; 3],
    ) -> ContactState {
        let gap = self.gap(&pressure, &rigid);
        let residuals = self.residuals(&pressure, &gap);
        ContactState {
            pressure,
            gap,
            rigid,
            active,
            iterations: counts[0],
            iterp: counts[1],
            iterd: counts[2],
            residuals,
        }
    }
}

/// Checks an initial gap: one finite value per interface point.
pub(crate) fn check_gap(initial_gap: &[f64], n: usize) -> Result<()> {
    if initial_gap.len() != n {
        return Err(Error::invalid(
            "initial_gap",
            initial_gap.len(),
            format!("one value per interface point ({n})"),
        ));
    }
    if let Some(i) = initial_gap.iter().position(|h| !h.is_finite()) {
        return Err(Error::invalid(
            format!("initial_gap[{i}]"),
            initial_gap[i],
            "must be finite",
        ));
    }
    Ok(())
}
