//! The penalty method on the full finite-element system of two bodies (eq. 2.22), without
//! condensation: the cross-check of the condensed interface problem.

use contopt_core::{ContactState, ElasticBody, Error, Residuals, Result, Status};
use faer::sparse::{Pair, SparseColMat, SymbolicSparseColMat};
use faer::Mat;
use nalgebra::{DMatrix, DVector};

use crate::factor::Factor;
use crate::system::{assemble, Dof, Numbering};
use crate::FeBody;

/// Solves the contact of `body1` and `body2` with initial gap `initial_gap` (at body 1's
/// points) by the penalty method on their joint stiffness system (2.22):
///
/// (K¹ ⊕ K² + Σ_{i ∈ C} c wᵢ Lᵢᵀ Lᵢ) u = b − Σ_{i ∈ C} c wᵢ hᵢ Lᵢᵀ,
///
/// with Lᵢ u the closing of the gap at point i, and Kalker's loop over the contact set C
/// (`iterp`, `iterd`). Neither body is condensed or pinned: the springs hold a floating body.
/// The pattern holds every candidate spring, so the symbolic factorisation is done once and
/// each change of C costs one numeric refactorisation.
///
/// The returned pressure is pᵢ = c⟨−dᵢ⟩; `rigid` holds each body's free-mode amplitudes
/// (body 1's, then body 2's) relative to the reference that [`FeBody`] pins, as the condensed
/// problem reports them.
pub fn penalty_full(
    body1: &FeBody,
    body2: &FeBody,
    initial_gap: &[f64],
    c: f64,
) -> Result<ContactState> {
    if !(c.is_finite() && c > 0.0) {
        return Err(Error::invalid(
            "solver.c",
            c,
            "the penalty parameter must be positive and finite [MPa/mm]",
        ));
    }
    let pair = body1
        .interface()
        .partners(body2.interface(), body1.name(), body2.name())?;
    let n = pair.len();
    if initial_gap.len() != n {
        return Err(Error::invalid(
            "initial_gap",
            initial_gap.len(),
            format!("one value per interface point ({n})"),
        ));
    }
    let bodies = [body1, body2];
    let numbering = [
        Numbering::new(&body1.model, &[], false)?,
        Numbering::new(&body2.model, &[], false)?,
    ];
    let offset = [0, numbering[0].n_free];
    let n_total = numbering[0].n_free + numbering[1].n_free;

    // Each point's gap: d = h + closing·u + fixed part from prescribed displacements.
    let mut springs: Vec<Vec<(usize, f64)>> = Vec::with_capacity(n);
    let mut fixed = vec![0.0; n];
    for i in 0..n {
        let mut entries = vec![];
        for (b, &point) in [i, pair[i]].iter().enumerate() {
            let row = &bodies[b].rows[point];
            for (&g, &coef) in row.dofs.iter().zip(&row.coef) {
                match numbering[b].dofs[g] {
                    Dof::Free(j) => entries.push((offset[b] + j, -coef)),
                    Dof::Prescribed(v) => fixed[i] -= coef * v,
                    Dof::Pinned => unreachable!("no pins in the joint system"),
                }
            }
        }
        springs.push(entries);
    }

    let mut idx = vec![];
    let mut base_values = vec![];
    let mut rhs_base = vec![0.0; n_total];
    for b in 0..2 {
        let t = assemble(&bodies[b].model, &numbering[b].dofs, offset[b])?;
        idx.extend(t.idx);
        base_values.extend(t.val);
        for (g, d) in numbering[b].dofs.iter().enumerate() {
            if let Dof::Free(j) = d {
                rhs_base[offset[b] + j] = bodies[b].model.forces[g] - t.prescribed_load[*j];
            }
        }
    }
    for entries in &springs {
        for &(a, _) in entries {
            for &(b, _) in entries {
                if a <= b {
                    idx.push(Pair::new(a, b));
                }
            }
        }
    }
    let (pattern, order) = SymbolicSparseColMat::try_new_from_indices(n_total, n_total, &idx)
        .map_err(|e| Error::Mesh(format!("joint sparse pattern: {e:?}")))?;
    let w = &body1.interface().weights;
    let h: Vec<f64> = (0..n).map(|i| initial_gap[i] + fixed[i]).collect();
    let system = |active: &[bool]| -> Result<(SparseColMat<usize, f64>, Mat<f64>)> {
        let mut values = base_values.clone();
        let mut rhs = Mat::from_fn(n_total, 1, |j, _| rhs_base[j]);
        for (i, entries) in springs.iter().enumerate() {
            let k = if active[i] { c * w[i] } else { 0.0 };
            for &(a, ca) in entries {
                for &(b, cb) in entries {
                    if a <= b {
                        values.push(k * ca * cb);
                    }
                }
                rhs[(a, 0)] -= k * h[i] * ca;
            }
        }
        debug_assert_eq!(values.len(), idx.len());
        let matrix = SparseColMat::new_from_argsort(pattern.clone(), &order, &values)
            .map_err(|e| Error::Mesh(format!("joint sparse values: {e:?}")))?;
        Ok((matrix, rhs))
    };

    let mut active = vec![true; n];
    let (matrix, mut rhs) = system(&active)?;
    let mut factor = Factor::new(matrix.as_ref(), 0, "joint system")?;
    let (mut iterp, mut iterd, mut solves) = (0, 0, 0);
    loop {
        factor.solve_in_place(rhs.as_mut());
        solves += 1;
        let gap: Vec<f64> = (0..n)
            .map(|i| {
                h[i] + springs[i]
                    .iter()
                    .map(|&(j, cj)| cj * rhs[(j, 0)])
                    .sum::<f64>()
            })
            .collect();
        let scale = gap.iter().fold(0.0f64, |m, d| m.max(d.abs())).max(1e-300);
        let opening: Vec<usize> = (0..n)
            .filter(|&i| active[i] && gap[i] > 1e-12 * scale)
            .collect();
        let changed = if !opening.is_empty() {
            for i in opening {
                active[i] = false;
            }
            iterp += 1;
            true
        } else {
            let closing: Vec<usize> = (0..n)
                .filter(|&i| !active[i] && gap[i] < -1e-12 * scale)
                .collect();
            for &i in &closing {
                active[i] = true;
            }
            iterd += usize::from(!closing.is_empty());
            !closing.is_empty()
        };
        if !changed {
            let pressure: Vec<f64> = (0..n)
                .map(|i| {
                    if active[i] {
                        c * (-gap[i]).max(0.0)
                    } else {
                        0.0
                    }
                })
                .collect();
            let u: Vec<Vec<f64>> = (0..2)
                .map(|b| {
                    numbering[b]
                        .dofs
                        .iter()
                        .map(|d| match *d {
                            Dof::Free(j) => rhs[(offset[b] + j, 0)],
                            Dof::Prescribed(v) => v,
                            Dof::Pinned => 0.0,
                        })
                        .collect()
                })
                .collect();
            let rigid = (0..2)
                .flat_map(|b| pinned_amplitudes(bodies[b], &u[b]))
                .collect();
            let residuals = residuals(bodies, &pair, &pressure, &gap);
            let mut state = ContactState {
                pressure,
                gap,
                rigid,
                active,
                iterations: solves,
                iterp,
                iterd,
                residuals,
                status: Status::Solved,
            };
            state.stop_if_not_finite();
            return Ok(state);
        }
        if iterp + iterd > 4 * n + 20 {
            return Err(Error::NotConverged {
                method: "penalty on the joint system (2.22)".into(),
                iterations: solves,
                detail: format!("the contact set kept changing ({iterp} for negative pressure, {iterd} for penetration)"),
            });
        }
        let (matrix, new_rhs) = system(&active)?;
        factor.refactor(matrix.as_ref(), "joint system")?;
        rhs = new_rhs;
    }
}

/// Amplitudes λ of a body's free modes such that u = u_pinned + Σ λₖ φₖ, read at the DOFs the
/// body pins (where u_pinned = 0).
fn pinned_amplitudes(body: &FeBody, u: &[f64]) -> Vec<f64> {
    let system = &body.system;
    let pins: Vec<usize> = (0..system.dofs.len())
        .filter(|&g| system.dofs[g] == Dof::Pinned)
        .collect();
    let m = system.modes.len();
    if m == 0 {
        return vec![];
    }
    let phi = DMatrix::from_fn(m, m, |r, k| system.modes[k].values[pins[r]]);
    let at_pins = DVector::from_fn(m, |r, _| u[pins[r]]);
    phi.lu()
        .solve(&at_pins)
        .map_or_else(|| vec![f64::NAN; m], |x| x.iter().copied().collect())
}

/// Residuals of the joint solution, with the equilibrium of each free rigid mode.
fn residuals(bodies: [&FeBody; 2], pair: &[usize], pressure: &[f64], gap: &[f64]) -> Residuals {
    let w = &bodies[0].interface().weights;
    let mut equilibrium: f64 = 0.0;
    for (b, body) in bodies.iter().enumerate() {
        for mode in body.rigid_modes() {
            let work: f64 = (0..pressure.len())
                .map(|i| {
                    w[i] * pressure[i]
                        * mode.interface_displacement[if b == 0 { i } else { pair[i] }]
                })
                .sum();
            equilibrium = equilibrium.max((work + mode.load).abs());
        }
    }
    Residuals::new(equilibrium, pressure, gap)
}
