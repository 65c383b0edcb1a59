//! Maxwell–Betti reciprocity of a body's influence operator, probed before a problem is built:
//! the solvers minimise the complementary energy (2.12), a quadratic form in the pressure only
//! when A is symmetric and, pressed, the body gives way (Aⱼⱼ > 0). A body of one's own whose
//! `apply_influence` is neither (a coupling written one way only, a sign turned) would
//! otherwise be solved to a different "converged" answer by each solver.

use contopt_core::{ElasticBody, Error, Result};

/// The largest |Aᵢⱼ − Aⱼᵢ| accepted, relative to the larger of Aᵢᵢ and Aⱼⱼ: far above the
/// round-off of a factorised stiffness (condition 10¹², the thinnest layers the finite
/// elements are used with, loses about 10⁻⁴), and an asymmetry this small moves an answer by
/// about as much.
const RECIPROCITY: f64 = 1e-3;

/// Refuses `body` when its influence is not symmetric or not positive at a probe: the column
/// of the middle point j (a unit force there) and that of the point i it moves most besides
/// itself must agree, Aᵢⱼ = Aⱼᵢ, and Aⱼⱼ must be positive. Two products: a probe, not a proof
/// (an asymmetry far from the middle point passes). A body that says its operator is a
/// multiple of a fixed one ([`ElasticBody::influence_shape`]: the library's grids, a rigid
/// body) is symmetric by construction and not probed; a body without compliance there (a
/// rigid body) passes.
pub(super) fn check(body: &dyn ElasticBody) -> Result<()> {
    if body.influence_shape().is_some() {
        return Ok(());
    }
    let n = body.interface().len();
    let j = n / 2;
    let column_j = column(body, j);
    let diagonal = column_j[j];
    if diagonal == 0.0 {
        return Ok(());
    }
    let field = || format!("influence of `{}`", body.name());
    if diagonal.is_nan() || diagonal < 0.0 {
        return Err(Error::invalid(
            field(),
            format!("A[{j}, {j}] = {diagonal:e}"),
            "positive: a body gives way where it is pressed (displacements into the body)",
        ));
    }
    let Some(i) = (0..n)
        .filter(|&i| i != j)
        .max_by(|&a, &b| column_j[a].abs().total_cmp(&column_j[b].abs()))
    else {
        return Ok(());
    };
    let column_i = column(body, i);
    let scale = diagonal.max(column_i[i].abs());
    if (column_j[i] - column_i[j]).abs() > RECIPROCITY * scale {
        return Err(Error::invalid(
            field(),
            format!(
                "A[{i}, {j}] = {:e} against A[{j}, {i}] = {:e}",
                column_j[i], column_i[j]
            ),
            format!(
                "symmetric within {RECIPROCITY} of the diagonal (Maxwell–Betti: the \
                 displacement at i under a unit force at j equals that at j under the force at i)"
            ),
        ));
    }
    Ok(())
}

/// Column `j` of the influence matrix: the displacements under a unit force at point j.
fn column(body: &dyn ElasticBody, j: usize) -> Vec<f64> {
    let n = body.interface().len();
    let mut force = vec![0.0; n];
    force[j] = 1.0;
    let mut displacement = vec![0.0; n];
    body.apply_influence(&force, &mut displacement);
    displacement
}
