//! The joint finite-element system of two bodies with a penalty spring at each contact point
//! (eq. 2.22), without condensation: the cross-check of the condensed interface problem.
//! This module builds the system; `contopt_contact::FullPenalty` runs Kalker's iteration
//! on it, the loop the condensed penalty method shares.

use contopt_core::FullSystem;
use contopt_core::{ElasticBody, Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};
use faer::Mat;

use crate::factor::Factor;
use crate::system::{assemble, Dof, Numbering};
use crate::FeBody;

/// The joint stiffness system of two finite-element bodies with a penalty spring at each
/// contact point (2.22):
///
/// (K¹ ⊕ K² + Σ_{i ∈ C} c wᵢ Lᵢᵀ Lᵢ) u = b − Σ_{i ∈ C} c wᵢ hᵢ Lᵢᵀ,
///
/// with Lᵢ u the closing of the gap at point i, dᵢ = hᵢ + Lᵢ u. Neither body is condensed or
/// pinned: the springs hold a floating body. The pattern holds every candidate spring, so the
/// symbolic factorisation is done at the first solve and each change of the contact set C
/// costs one numeric refactorisation.
///
/// Solve it with `contopt_contact::FullPenalty`: its pressure is pᵢ = c⟨−dᵢ⟩, and its
/// `rigid` holds each body's free-mode amplitudes (body 1's, then body 2's) relative to the
/// reference that [`FeBody`] pins, as the condensed problem reports them.
pub struct JointSystem<'a> {
    bodies: [&'a FeBody; 2],
    /// `pair[i]`: point i of the first body is point `pair[i]` of the second.
    pair: Vec<usize>,
    /// Each body's numbering of its free unknowns, nothing pinned.
    numbering: [Numbering; 2],
    /// Each point's row of L: (joint unknown, coefficient) pairs, dᵢ = hᵢ + Σ coef·u.
    springs: Vec<Vec<(usize, f64)>>,
    /// hᵢ: the initial gap plus the share of prescribed displacements.
    rest_gap: Vec<f64>,
    /// The pattern of K¹ ⊕ K² and every spring (upper triangle), with the order that sums
    /// the triplets into it.
    pattern: SymbolicSparseColMat<usize>,
    order: Argsort<usize>,
    /// The bodies' stiffness triplets' values; the springs' follow them in the pattern.
    stiffness: Vec<f64>,
    /// b: the given loads less the prescribed displacements' share.
    load: Vec<f64>,
    factor: Option<Factor>,
    /// The joint displacement u of the last solve.
    solution: Mat<f64>,
}

impl<'a> JointSystem<'a> {
    /// The joint system of `body1` and `body2` (their interfaces paired by position) with
    /// initial gap `initial_gap` \[mm\] at body 1's points. Bodies of a
    /// [`crate::ContactPairing`], which read their point values at the first body's face
    /// nodes, are refused: their springs would couple every point.
    pub fn new(body1: &'a FeBody, body2: &'a FeBody, initial_gap: &[f64]) -> Result<Self> {
        if let Some(b) = [body1, body2].iter().find(|b| b.mortar.is_some()) {
            return Err(Error::invalid(
                "joint system",
                b.name(),
                "is a body of a contact pairing, which the joint system does not couple: \
                 solve its condensed InterfaceProblem",
            ));
        }
        let pair = body1
            .interface()
            .partners(body2.interface(), body1.name(), body2.name())?;
        let n = pair.len();
        contopt_core::check::gap(initial_gap, n)?;
        let bodies = [body1, body2];
        let numbering = [
            Numbering::new(&body1.model, &[], false)?,
            Numbering::new(&body2.model, &[], false)?,
        ];
        let offset = [0, numbering[0].n_free];
        let (springs, fixed) = closing_rows(bodies, &pair, &numbering, offset);
        let rest_gap = initial_gap.iter().zip(&fixed).map(|(h, f)| h + f).collect();
        let Assembled {
            mut idx,
            values: stiffness,
            load,
        } = assemble_joint(bodies, &numbering, offset)?;
        for entries in &springs {
            for &(a, _) in entries {
                for &(b, _) in entries {
                    if a <= b {
                        idx.push(Pair::new(a, b));
                    }
                }
            }
        }
        let n_total = load.len();
        let (pattern, order) = SymbolicSparseColMat::try_new_from_indices(n_total, n_total, &idx)
            .map_err(|e| Error::Mesh(format!("joint sparse pattern: {e:?}")))?;
        Ok(Self {
            bodies,
            pair,
            numbering,
            springs,
            rest_gap,
            pattern,
            order,
            stiffness,
            load,
            factor: None,
            solution: Mat::zeros(n_total, 1),
        })
    }

    /// The matrix and right-hand side of (2.22) with springs c·wᵢ at the points of `active`.
    fn springs_system(
        &self,
        active: &[bool],
        c: f64,
    ) -> Result<(SparseColMat<usize, f64>, Mat<f64>)> {
        let w = self.weights();
        let mut values = self.stiffness.clone();
        let mut rhs = Mat::from_fn(self.load.len(), 1, |j, _| self.load[j]);
        for (i, entries) in self.springs.iter().enumerate() {
            let k = if active[i] { c * w[i] } else { 0.0 };
            for &(a, ca) in entries {
                for &(b, cb) in entries {
                    if a <= b {
                        values.push(k * ca * cb);
                    }
                }
                rhs[(a, 0)] -= k * self.rest_gap[i] * ca;
            }
        }
        let matrix = SparseColMat::new_from_argsort(self.pattern.clone(), &self.order, &values)
            .map_err(|e| Error::Mesh(format!("joint sparse values: {e:?}")))?;
        Ok((matrix, rhs))
    }

    /// Body `b`'s global nodal displacements in the last solve.
    fn displacement(&self, b: usize) -> Vec<f64> {
        let offset = if b == 0 { 0 } else { self.numbering[0].n_free };
        self.numbering[b]
            .dofs
            .iter()
            .map(|d| match *d {
                Dof::Free(j) => self.solution[(offset + j, 0)],
                Dof::Prescribed(v) => v,
                Dof::Pinned => 0.0,
            })
            .collect()
    }
}

impl FullSystem for JointSystem<'_> {
    fn points(&self) -> usize {
        self.pair.len()
    }

    fn weights(&self) -> &[f64] {
        self.bodies[0].interface().weights()
    }

    fn rest_gap(&self) -> &[f64] {
        &self.rest_gap
    }

    fn free_modes(&self) -> usize {
        self.bodies.iter().map(|b| b.rigid_modes().len()).sum()
    }

    fn solve_springs(&mut self, active: &[bool], c: f64, gap: &mut [f64]) -> Result<()> {
        let (matrix, mut rhs) = self.springs_system(active, c)?;
        match &mut self.factor {
            Some(factor) => factor.refactor(matrix.as_ref(), "joint system")?,
            None => self.factor = Some(Factor::new(matrix.as_ref(), 0, "joint system")?),
        }
        if let Some(factor) = &self.factor {
            factor.solve_in_place(rhs.as_mut());
        }
        self.solution = rhs;
        for ((d, h), entries) in gap.iter_mut().zip(&self.rest_gap).zip(&self.springs) {
            *d = h + entries
                .iter()
                .map(|&(j, cj)| cj * self.solution[(j, 0)])
                .sum::<f64>();
        }
        Ok(())
    }

    fn rigid(&self) -> Vec<f64> {
        (0..2)
            .flat_map(|b| pinned_amplitudes(self.bodies[b], &self.displacement(b)))
            .collect()
    }

    fn equilibrium(&self, pressure: &[f64]) -> f64 {
        let w = self.weights();
        let mut equilibrium: f64 = 0.0;
        for (b, body) in self.bodies.iter().enumerate() {
            let point = |i: usize| if b == 0 { i } else { self.pair[i] };
            for mode in body.rigid_modes() {
                let work: f64 = (0..pressure.len())
                    .map(|i| w[i] * pressure[i] * mode.interface_displacement[point(i)])
                    .sum();
                equilibrium = equilibrium.max((work + mode.load).abs());
            }
        }
        equilibrium
    }
}

/// Each point's row of L in the joint unknowns (the closing of its gap, −n·u of both bodies'
/// face nodes), and the part of its gap that prescribed displacements fix.
fn closing_rows(
    bodies: [&FeBody; 2],
    pair: &[usize],
    numbering: &[Numbering; 2],
    offset: [usize; 2],
) -> (Vec<Vec<(usize, f64)>>, Vec<f64>) {
    let n = pair.len();
    let mut springs = Vec::with_capacity(n);
    let mut fixed = vec![0.0; n];
    for (i, fixed) in fixed.iter_mut().enumerate() {
        let mut entries = vec![];
        for (b, &point) in [i, pair[i]].iter().enumerate() {
            let row = &bodies[b].rows[point];
            for (&g, &coef) in row.dofs.iter().zip(&row.coef) {
                match numbering[b].dofs[g] {
                    Dof::Free(j) => entries.push((offset[b] + j, -coef)),
                    Dof::Prescribed(v) => *fixed -= coef * v,
                    // Nothing is pinned in the joint system (`Numbering::new(.., false)`).
                    Dof::Pinned => {}
                }
            }
        }
        springs.push(entries);
    }
    (springs, fixed)
}

/// The bodies' stiffness K¹ ⊕ K² as triplets (upper triangle) in the joint unknowns, and the
/// joint load b: the given forces less the prescribed displacements' share.
struct Assembled {
    idx: Vec<Pair<usize, usize>>,
    values: Vec<f64>,
    load: Vec<f64>,
}

fn assemble_joint(
    bodies: [&FeBody; 2],
    numbering: &[Numbering; 2],
    offset: [usize; 2],
) -> Result<Assembled> {
    let mut joint = Assembled {
        idx: vec![],
        values: vec![],
        load: vec![0.0; numbering[0].n_free + numbering[1].n_free],
    };
    for b in 0..2 {
        let model = &bodies[b].model;
        let t = assemble(model, &numbering[b].dofs, offset[b])?;
        joint.idx.extend(t.idx);
        joint.values.extend(t.val);
        for (g, d) in numbering[b].dofs.iter().enumerate() {
            if let Dof::Free(j) = *d {
                joint.load[offset[b] + j] = model.forces[g] - t.prescribed_load[j];
            }
        }
    }
    Ok(joint)
}

/// Amplitudes λ of a body's free modes such that u = u_pinned + Σ λₖ φₖ, read at the DOFs the
/// body pins (where u_pinned = 0); NaN when the pins do not determine them.
fn pinned_amplitudes(body: &FeBody, u: &[f64]) -> Vec<f64> {
    let system = &body.system;
    let pins: Vec<usize> = (0..system.dofs.len())
        .filter(|&g| system.dofs[g] == Dof::Pinned)
        .collect();
    let m = system.modes.len();
    if m == 0 {
        return vec![];
    }
    if pins.len() != m {
        return vec![f64::NAN; m];
    }
    let phi = Mat::from_fn(m, m, |r, k| system.modes[k].values[pins[r]]);
    let at_pins = Mat::from_fn(m, 1, |r, _| u[pins[r]]);
    let lambda = phi.partial_piv_lu().solve(&at_pins);
    (0..m).map(|k| lambda[(k, 0)]).collect()
}
