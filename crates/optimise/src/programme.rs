//! A restricted programme of the linear programme (3.5), solved by eliminating its equalities.
//!
//! The programme is written as rows, each a value `a·x + b` that must be zero (an equality)
//! or non-negative (an inequality), over variables of order one. The equalities E x = e (the
//! closed gaps, equilibrium) are eliminated by a column-pivoted QR of Eᵀ: x = x₀ + N u, with
//! x₀ the least-norm solution and N an orthonormal basis of E's null space. The QR reveals
//! E's rank, so redundant equalities (the gaps at the Gauss points of quadratic faces, which
//! depend on fewer nodal values) drop out, and equalities that contradict each other are
//! found before any interior point starts. What is left is a small dense programme in u,
//! min cᵀu subject to the inequalities, which clarabel solves; on the bearing roller, whose
//! Ω_v closes every design column, u is empty and the programme is its one point.

use contopt_contact::conic::{self, CscMatrix, Outcome};
use contopt_core::{Result, Termination};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::householder;
use faer::{Conj, Mat, Par};

/// Relative size of a diagonal entry of R (to the largest) below which the QR counts the
/// equalities as dependent (round-off of rows scaled to one).
const RANK: f64 = 1e-9;

/// How far a row scaled to one may miss its constraint and still count as met (round-off of
/// the elimination, in the programme's units of order one).
const FEASIBILITY: f64 = 1e-9;

/// What a row of a restricted programme says, to name it when the programme is infeasible.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Kind {
    /// Equilibrium of rigid mode m, Rᵀ W p = −q.
    Equilibrium(usize),
    /// The gap at point i: d = 0 (closed) or d ≥ 0.
    Gap(usize),
    /// χ = v·p_max − p ≥ 0 at point i of Ω_nv.
    Chi(usize),
    /// p ≥ 0 at point i.
    Pressure(usize),
    /// p_max ≥ 0 (p ≥ 0 on Ω_v).
    Level,
    /// Δh ≥ 0 at design node k.
    Change(usize),
}

/// The rows of a restricted programme: the equalities and the inequalities.
pub(crate) struct Rows {
    pub equal: Vec<Kind>,
    pub at_least: Vec<Kind>,
}

/// Writes the row of a kind as `a·x + b`: the entries of a into `entries` (cleared first),
/// returning b.
pub(crate) trait RowSource {
    /// The number of variables.
    fn variables(&self) -> usize;
    /// The index of the variable the objective minimises (p_max).
    fn objective(&self) -> usize;
    /// Row `kind` into `entries`; its constant.
    fn row(&self, kind: Kind, entries: &mut Vec<(usize, f64)>) -> f64;
}

/// How a restricted programme ended.
pub(crate) enum Solved {
    /// Its optimum x, the interior point's iterations (0 when nothing was left to choose) and
    /// its accuracy ([`Termination::Converged`] or [`Termination::ReducedAccuracy`]).
    Optimal(Vec<f64>, usize, Termination),
    /// No x meets the rows; the rows that conflict, most to blame first (every row x₀ misses
    /// when nothing is left to choose, else those of the infeasibility certificate).
    Infeasible(Vec<Kind>),
    /// The objective is unbounded below.
    Unbounded,
    /// The interior point stopped short.
    Stopped(Termination),
}

/// The equalities' solution set x₀ + N u.
struct Affine {
    x0: Vec<f64>,
    /// n × dim, orthonormal columns.
    null: Mat<f64>,
}

/// Solves the programme `rows` of `source` to clarabel's `tolerance`.
pub(crate) fn solve(source: &dyn RowSource, rows: &Rows, tolerance: f64) -> Result<Solved> {
    let affine = match eliminate(source, &rows.equal) {
        Ok(affine) => affine,
        Err(conflict) => return Ok(Solved::Infeasible(conflict)),
    };
    let reduced = Reduced::new(source, &rows.at_least, &affine);
    if let Some(conflict) = reduced.conflict() {
        return Ok(Solved::Infeasible(conflict));
    }
    let dim = affine.null.ncols();
    let objective: Vec<f64> = (0..dim)
        .map(|c| affine.null[(source.objective(), c)])
        .collect();
    let steep = objective.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    if dim == 0 || (reduced.rows.is_empty() && steep <= RANK) {
        // Nothing left to choose, or nothing that changes p_max: x₀ is an optimum.
        return Ok(Solved::Optimal(affine.x0, 0, Termination::Converged));
    }
    if reduced.rows.is_empty() {
        return Ok(Solved::Unbounded);
    }
    let (mut ii, mut jj, mut vv, mut b) = (vec![], vec![], vec![], vec![]);
    for (r, (a, rhs)) in reduced.rows.iter().enumerate() {
        for (c, &v) in a.iter().enumerate() {
            if v != 0.0 {
                ii.push(r);
                jj.push(c);
                vv.push(-v);
            }
        }
        b.push(*rhs);
    }
    let constraints = CscMatrix::new_from_triplets(b.len(), dim, ii, jj, vv);
    let sol = conic::solve(
        &CscMatrix::zeros((dim, dim)),
        &objective,
        &constraints,
        &b,
        0,
        tolerance,
        "linear programme (3.5)",
    )?;
    let accuracy = match sol.outcome {
        Outcome::Solved => Termination::Converged,
        Outcome::ReducedAccuracy(reduced) => reduced,
        Outcome::Infeasible => return Ok(Solved::Infeasible(blame(&reduced.kinds, &sol.z))),
        Outcome::Unbounded => return Ok(Solved::Unbounded),
        Outcome::Stopped(end) => return Ok(Solved::Stopped(end)),
    };
    let mut x = affine.x0;
    for (c, u) in sol.x.iter().enumerate() {
        for (xi, k) in x.iter_mut().zip(affine.null.col(c).iter()) {
            *xi += k * u;
        }
    }
    Ok(Solved::Optimal(x, sol.iterations, accuracy))
}

/// The rows of `kinds` the certificate `z` blames, the largest multipliers first.
fn blame(kinds: &[Kind], z: &[f64]) -> Vec<Kind> {
    let mut order: Vec<usize> = (0..kinds.len()).filter(|&r| z[r] > 0.0).collect();
    order.sort_by(|&a, &b| z[b].total_cmp(&z[a]));
    order.into_iter().map(|r| kinds[r]).collect()
}

/// The solution set of the equalities `equal`: a column-pivoted QR of Eᵀ (its rows scaled to
/// one), Eᵀ P = Q R, gives the rank k, the least-norm solution x₀ = Q₁ R₁₁⁻ᵀ (Pᵀe)₁ and
/// the null space N = Q₂. The equalities that x₀ misses conflict: they are returned.
fn eliminate(source: &dyn RowSource, equal: &[Kind]) -> std::result::Result<Affine, Vec<Kind>> {
    let n = source.variables();
    let m = equal.len();
    let mut et = Mat::<f64>::zeros(n, m);
    let mut e = vec![0.0; m];
    let mut entries = vec![];
    for (r, &kind) in equal.iter().enumerate() {
        let b = source.row(kind, &mut entries);
        let scale = entries.iter().fold(0.0f64, |s, (_, v)| s.max(v.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        for &(j, v) in &entries {
            et[(j, r)] += v / scale;
        }
        e[r] = -b / scale;
    }
    if m == 0 {
        return Ok(Affine {
            x0: vec![0.0; n],
            null: Mat::identity(n, n),
        });
    }
    let qr = et.col_piv_qr();
    let r = qr.R();
    let size = n.min(m);
    let top = (0..size).fold(0.0f64, |t, i| t.max(r[(i, i)].abs()));
    let rank = (0..size)
        .take_while(|&i| r[(i, i)].abs() > RANK * top)
        .count();
    // Eᵀ P = Q R: the j-th column of Eᵀ P is the equality perm[j].
    let (perm, _) = qr.P().arrays();
    let mut y = vec![0.0; n];
    for i in 0..rank {
        let s: f64 = (0..i).map(|j| r[(j, i)] * y[j]).sum();
        y[i] = (e[perm[i]] - s) / r[(i, i)];
    }
    let mut basis = Mat::<f64>::zeros(n, 1 + n - rank);
    for i in 0..rank {
        basis[(i, 0)] = y[i];
    }
    for c in 0..n - rank {
        basis[(rank + c, 1 + c)] = 1.0;
    }
    apply_q(&qr, &mut basis);
    let x0: Vec<f64> = (0..n).map(|i| basis[(i, 0)]).collect();
    let null = basis.subcols(1, n - rank).to_owned();
    let conflict: Vec<Kind> = (0..m)
        .filter(|&r| {
            let miss: f64 = (0..n).map(|j| et[(j, r)] * x0[j]).sum::<f64>() - e[r];
            miss.abs() > FEASIBILITY
        })
        .map(|r| equal[r])
        .collect();
    match conflict.is_empty() {
        true => Ok(Affine { x0, null }),
        false => Err(conflict),
    }
}

/// `matrix` ← Q `matrix`, with Q of the QR's Householder reflections.
fn apply_q(qr: &faer::linalg::solvers::ColPivQr<f64>, matrix: &mut Mat<f64>) {
    let (basis, factor) = (qr.Q_basis(), qr.Q_coeff());
    let scratch = householder::apply_block_householder_sequence_on_the_left_in_place_scratch::<f64>(
        basis.nrows(),
        factor.nrows(),
        matrix.ncols(),
    );
    householder::apply_block_householder_sequence_on_the_left_in_place_with_conj(
        basis,
        factor,
        Conj::No,
        matrix.as_mut(),
        Par::Seq,
        MemStack::new(&mut MemBuffer::new(scratch)),
    );
}

/// The inequalities in u: each row a·N u ≥ −(a·x₀ + b), scaled to one, kept with its kind;
/// rows that do not depend on u are met or not by x₀ alone.
struct Reduced {
    /// (a·N, a·x₀ + b) per row that depends on u, scaled so that max |a·N| = 1.
    rows: Vec<(Vec<f64>, f64)>,
    kinds: Vec<Kind>,
    /// The rows x₀ misses that u cannot change, most missed first.
    missed: Vec<(f64, Kind)>,
}

impl Reduced {
    fn new(source: &dyn RowSource, at_least: &[Kind], affine: &Affine) -> Self {
        let dim = affine.null.ncols();
        let (mut rows, mut kinds, mut missed) = (vec![], vec![], vec![]);
        let mut entries = vec![];
        for &kind in at_least {
            let b = source.row(kind, &mut entries);
            let scale = entries.iter().fold(0.0f64, |s, (_, v)| s.max(v.abs()));
            let scale = if scale > 0.0 { scale } else { 1.0 };
            let value = b + entries.iter().map(|&(j, v)| v * affine.x0[j]).sum::<f64>();
            let a: Vec<f64> = (0..dim)
                .map(|c| {
                    let col = affine.null.col(c);
                    entries.iter().map(|&(j, v)| v * col[j]).sum::<f64>() / scale
                })
                .collect();
            let reach = a.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            if reach > RANK {
                rows.push((a.iter().map(|v| v / reach).collect(), value / scale / reach));
                kinds.push(kind);
            } else if value / scale < -FEASIBILITY {
                missed.push((value / scale, kind));
            }
        }
        missed.sort_by(|a, b| a.0.total_cmp(&b.0));
        Self {
            rows,
            kinds,
            missed,
        }
    }

    /// The rows no u can change that x₀ misses, most missed first, when there are any.
    fn conflict(&self) -> Option<Vec<Kind>> {
        (!self.missed.is_empty()).then(|| self.missed.iter().map(|m| m.1).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A row given by its kind, entries and constant.
    type GivenRow = (Kind, Vec<(usize, f64)>, f64);

    /// A programme given by its rows, min x₀.
    struct Given {
        n: usize,
        rows: Vec<GivenRow>,
    }

    impl RowSource for Given {
        fn variables(&self) -> usize {
            self.n
        }

        fn objective(&self) -> usize {
            0
        }

        fn row(&self, kind: Kind, entries: &mut Vec<(usize, f64)>) -> f64 {
            let (_, e, b) = self.rows.iter().find(|r| r.0 == kind).unwrap();
            entries.clear();
            entries.extend_from_slice(e);
            *b
        }
    }

    fn run(given: &Given, equal: &[Kind], at_least: &[Kind]) -> Solved {
        let rows = Rows {
            equal: equal.to_vec(),
            at_least: at_least.to_vec(),
        };
        solve(given, &rows, conic::TOLERANCE).unwrap()
    }

    /// min x₀ with x₀ + x₁ = 1 written three times (twice scaled), x₀ ≥ ¼, x₁ ≥ 0: the QR
    /// drops the two redundant equalities and the optimum is (¼, ¾).
    #[test]
    fn redundant_equalities_drop_out() {
        use Kind::*;
        let given = Given {
            n: 2,
            rows: vec![
                (Gap(0), vec![(0, 1.0), (1, 1.0)], -1.0),
                (Gap(1), vec![(0, 2.0), (1, 2.0)], -2.0),
                (Gap(2), vec![(1, -3.0), (0, -3.0)], 3.0),
                (Pressure(0), vec![(0, 1.0)], -0.25),
                (Pressure(1), vec![(1, 1.0)], 0.0),
            ],
        };
        match run(
            &given,
            &[Gap(0), Gap(1), Gap(2)],
            &[Pressure(0), Pressure(1)],
        ) {
            Solved::Optimal(x, ..) => {
                assert!(
                    (x[0] - 0.25).abs() < 1e-8 && (x[1] - 0.75).abs() < 1e-8,
                    "{x:?}"
                )
            }
            _ => panic!("not solved"),
        }
    }

    /// Equalities that contradict each other (x₀ + x₁ = 1 and = 2), inequalities that do (x₀ +
    /// x₁ = 1 with x₀ ≥ 0.8 and x₁ ≥ 0.5, by the certificate; x₀ = 1 with x₀ ≥ 1.5, where
    /// nothing is left to choose) are named; a direction that lowers p_max without a bound is
    /// unbounded.
    #[test]
    fn conflicts_are_named_and_unbounded_found() {
        use Kind::*;
        let given = Given {
            n: 2,
            rows: vec![
                (Gap(0), vec![(0, 1.0), (1, 1.0)], -1.0),
                (Gap(1), vec![(0, 1.0), (1, 1.0)], -2.0),
                (Gap(2), vec![(0, 1.0)], -1.0),
                (Equilibrium(0), vec![(1, 1.0)], -2.0),
                (Pressure(0), vec![(0, 1.0)], -0.8),
                (Pressure(1), vec![(1, 1.0)], -0.5),
                (Chi(0), vec![(0, 1.0)], -1.5),
                (Level, vec![(1, 1.0)], 0.0),
            ],
        };
        let named = |s: Solved| match s {
            Solved::Infeasible(kinds) => kinds,
            _ => panic!("not infeasible"),
        };
        assert!(named(run(&given, &[Gap(0), Gap(1)], &[])).contains(&Gap(1)));
        let both = named(run(&given, &[Gap(0)], &[Pressure(0), Pressure(1)]));
        assert!(
            both.contains(&Pressure(0)) && both.contains(&Pressure(1)),
            "{both:?}"
        );
        let point = named(run(&given, &[Gap(2), Equilibrium(0)], &[Chi(0), Level]));
        assert_eq!(point, vec![Chi(0)]);
        assert!(matches!(run(&given, &[], &[Level]), Solved::Unbounded));
    }
}
