//! The constrained conjugate-gradient method of Polonsky & Keer (Wear 231, 1999) for a rigid
//! indenter on an elastic body applied as an operator: for large half-space grids whose
//! influence product is an FFT convolution, never a dense matrix.

use contopt_core::{ContactState, ElasticBody, Error, Residuals, Result};

/// What drives the indenter into the body.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Indentation {
    /// A total force \[N\] > 0 (load control): the approach is found.
    Force(f64),
    /// An approach \[mm\] (displacement control): the force is found.
    Approach(f64),
}

/// Polonsky–Keer: conjugate gradients on the pressure restricted to the contact set, with
/// the set updated every step (points that leave get p = 0, penetrating points re-enter and
/// the conjugation restarts), and for load control the pressure rescaled to the force. When
/// the body offers an approximate inverse ([`ElasticBody::precondition`]; a half-space grid
/// uses its kernel's circulant inverse) the residual is preconditioned with it and the
/// directions conjugated by Polak–Ribière.
/// Inner products and means are weighted by the point weights, so unequal cells are allowed.
/// Each step costs two operator products: O(N log N) on an FFT half-space grid.
#[derive(Clone, Copy, Debug)]
pub struct PolonskyKeer {
    /// Stop when Σ wᵢ |Δpᵢ| falls below `tolerance` times the force.
    pub tolerance: f64,
    /// Largest number of steps.
    pub max_steps: usize,
}

impl Default for PolonskyKeer {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_steps: 10_000,
        }
    }
}

impl PolonskyKeer {
    /// Presses a rigid indenter, whose shape is the initial gap `gap` \[mm\] at the body's
    /// points, into `body` as `indentation` says. The state's `rigid` holds the indenter's
    /// motion into itself (minus the approach), as for [`crate::InterfaceProblem`].
    ///
    /// When the body can be restricted ([`ElasticBody::restrict`]: a grid's bounding box), the
    /// solve runs where contact can occur: first the points within a quarter of the gap's
    /// range of its lowest point; the answer is then checked on the whole body with one
    /// product, and the region grows to take in any point that would penetrate, until none
    /// does. The result is that of the whole body.
    pub fn solve(
        &self,
        body: &dyn ElasticBody,
        gap: &[f64],
        indentation: Indentation,
    ) -> Result<ContactState> {
        let n = body.interface().len();
        crate::problem::check_gap(gap, n)?;
        let (lo, hi) = gap
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &h| {
                (a.min(h), b.max(h))
            });
        let mut keep: Vec<bool> = gap.iter().map(|&h| h <= lo + 0.25 * (hi - lo)).collect();
        let mut steps = 0;
        while let Some((part, index)) = body.restrict(&keep) {
            let part_gap: Vec<f64> = index.iter().map(|&k| gap[k]).collect();
            let state = self.solve_whole(part.as_ref(), &part_gap, indentation)?;
            drop((part, part_gap));
            steps += state.iterations;
            // The part's answer on the whole body: forces, then (in place) the gaps.
            let w = &body.interface().weights;
            let mut pressure = vec![0.0; n];
            for (a, &k) in index.iter().enumerate() {
                pressure[k] = state.pressure[a];
            }
            let shift = state.rigid[0];
            drop(state);
            let force: Vec<f64> = pressure.iter().zip(w).map(|(p, w)| p * w).collect();
            let carried: f64 = force.iter().sum();
            let mut d = vec![0.0; n];
            body.apply_influence(&force, &mut d);
            drop(force);
            let mut scale = 0.0f64;
            for (d, h) in d.iter_mut().zip(gap) {
                scale = scale.max(h.abs() + d.abs());
                *d += h + shift;
            }
            let mut inside = vec![false; n];
            for &k in &index {
                inside[k] = true;
            }
            let penetrating: Vec<usize> = (0..n)
                .filter(|&k| !inside[k] && d[k] < -1e-12 * scale)
                .collect();
            if penetrating.is_empty() {
                let active = pressure.iter().map(|&p| p > 0.0).collect();
                let equilibrium = match indentation {
                    Indentation::Force(f) => (carried - f).abs(),
                    Indentation::Approach(_) => 0.0,
                };
                let residuals = Residuals::new(equilibrium, &pressure, &d);
                return Ok(ContactState {
                    pressure,
                    gap: d,
                    rigid: vec![shift],
                    active,
                    iterations: steps,
                    iterp: 0,
                    iterd: 0,
                    residuals,
                });
            }
            for k in index.into_iter().chain(penetrating) {
                keep[k] = true;
            }
        }
        let mut state = self.solve_whole(body, gap, indentation)?;
        state.iterations += steps;
        Ok(state)
    }

    /// The iteration on the whole body (`gap` already checked by [`PolonskyKeer::solve`]).
    fn solve_whole(
        &self,
        body: &dyn ElasticBody,
        gap: &[f64],
        indentation: Indentation,
    ) -> Result<ContactState> {
        let w = &body.interface().weights;
        let n = w.len();
        let area: f64 = w.iter().sum();
        let (force, approach) = match indentation {
            Indentation::Force(f) if f.is_finite() && f > 0.0 => (Some(f), 0.0),
            Indentation::Approach(a) if a.is_finite() => (None, a),
            other => {
                return Err(Error::invalid(
                    "indentation",
                    format!("{other:?}"),
                    "a positive force or a finite approach",
                ))
            }
        };
        let dot = |a: &[f64], b: &[f64], set: &[bool]| {
            (0..n)
                .filter(|&i| set[i])
                .map(|i| w[i] * a[i] * b[i])
                .sum::<f64>()
        };
        let mean = |a: &[f64], set: &[bool]| {
            let total: f64 = (0..n).filter(|&i| set[i]).map(|i| w[i]).sum();
            if total > 0.0 {
                (0..n).filter(|&i| set[i]).map(|i| w[i] * a[i]).sum::<f64>() / total
            } else {
                0.0
            }
        };
        // Buffers for the whole iteration: the loop allocates nothing.
        let mut forces = vec![0.0; n];
        let mut apply = |p: &[f64], out: &mut [f64]| {
            for ((f, p), w) in forces.iter_mut().zip(p).zip(w) {
                *f = p * w;
            }
            body.apply_influence(&forces, out);
        };
        let mut contact = vec![false; n];
        let mut previous = vec![0.0; n];
        // Start: uniform pressure (load control) or the overlapped region (approach control).
        let mut p: Vec<f64> = match force {
            Some(f) => vec![f / area; n],
            None => gap
                .iter()
                .map(|h| if *h < approach { 1.0 } else { 0.0 })
                .collect(),
        };
        let (mut u, mut g, mut t, mut r) = (vec![0.0; n], vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let (mut masked, mut z, mut g_previous) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let (mut gz_old, mut conjugate) = (1.0, false);
        let mut shift = -approach;
        let mut change = f64::INFINITY;
        for step in 1..=self.max_steps {
            apply(&p, &mut u);
            for (c, &v) in contact.iter_mut().zip(&p) {
                *c = v > 0.0;
            }
            for i in 0..n {
                g[i] = gap[i] + u[i];
            }
            if force.is_some() {
                shift = -mean(&g, &contact);
            }
            for v in g.iter_mut() {
                *v += shift;
            }
            // Search direction: the residual on the contact set, preconditioned when the body
            // offers an approximate inverse (forces per point turned into pressures, with the
            // mean removed under load control so the force is kept), conjugated by
            // Polak–Ribière and restarted when points re-enter.
            for i in 0..n {
                masked[i] = if contact[i] { g[i] } else { 0.0 };
            }
            if body.precondition(&masked, &mut z) {
                for i in 0..n {
                    z[i] = if contact[i] { z[i] / w[i] } else { 0.0 };
                }
                if force.is_some() {
                    let z_mean = mean(&z, &contact);
                    for i in (0..n).filter(|&i| contact[i]) {
                        z[i] -= z_mean;
                    }
                }
            } else {
                z.copy_from_slice(&masked);
            }
            let gz = dot(&g, &z, &contact);
            let beta = if conjugate {
                ((gz - dot(&g_previous, &z, &contact)) / gz_old).max(0.0)
            } else {
                0.0
            };
            for i in 0..n {
                t[i] = if contact[i] { z[i] + beta * t[i] } else { 0.0 };
            }
            gz_old = gz;
            g_previous.copy_from_slice(&g);
            apply(&t, &mut r);
            if force.is_some() {
                let r_mean = mean(&r, &contact);
                for v in r.iter_mut() {
                    *v -= r_mean;
                }
            }
            let curvature = dot(&r, &t, &contact);
            let tau = if curvature > 0.0 {
                dot(&g, &t, &contact) / curvature
            } else {
                0.0
            };
            previous.copy_from_slice(&p);
            for i in 0..n {
                if contact[i] {
                    p[i] = (p[i] - tau * t[i]).max(0.0);
                }
            }
            // Penetrating points outside the contact set re-enter; conjugation restarts.
            let mut entered = false;
            for i in 0..n {
                if p[i] == 0.0 && !contact[i] && g[i] < 0.0 {
                    p[i] = -tau * g[i];
                    entered = true;
                }
            }
            conjugate = !entered;
            if let Some(f) = force {
                let total: f64 = p.iter().zip(w).map(|(p, w)| p * w).sum();
                if total > 0.0 {
                    for v in p.iter_mut() {
                        *v *= f / total;
                    }
                }
            }
            let scale = force
                .unwrap_or_else(|| p.iter().zip(w).map(|(p, w)| p * w).sum::<f64>())
                .max(f64::MIN_POSITIVE);
            change = p
                .iter()
                .zip(&previous)
                .zip(w)
                .map(|((a, b), w)| w * (a - b).abs())
                .sum::<f64>()
                / scale;
            if change < self.tolerance {
                apply(&p, &mut u);
                let active: Vec<bool> = p.iter().map(|&v| v > 0.0).collect();
                if force.is_some() {
                    let g_final: Vec<f64> = (0..n).map(|i| gap[i] + u[i]).collect();
                    shift = -mean(&g_final, &active);
                }
                let d: Vec<f64> = (0..n).map(|i| gap[i] + u[i] + shift).collect();
                let carried: f64 = p.iter().zip(w).map(|(p, w)| p * w).sum();
                let equilibrium = force.map_or(0.0, |f| (carried - f).abs());
                let residuals = Residuals::new(equilibrium, &p, &d);
                return Ok(ContactState {
                    pressure: p,
                    gap: d,
                    rigid: vec![shift],
                    active,
                    iterations: step,
                    iterp: 0,
                    iterd: 0,
                    residuals,
                });
            }
        }
        Err(Error::NotConverged {
            method: "Polonsky-Keer".into(),
            iterations: self.max_steps,
            detail: format!(
                "relative pressure change {change:.3e} (tolerance {:.1e})",
                self.tolerance
            ),
        })
    }
}
