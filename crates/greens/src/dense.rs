//! A body given by its dense compliance matrix: the influence operator A of eq. (2.5) as a
//! matrix of numbers made elsewhere (a finite-element code's condensed compliance, a kernel
//! tabulated in numpy), checked before it is used.

use contopt_core::{block_among, check, memory, ElasticBody, Error, Interface, Result, RigidMode};
use faer::Mat;

/// How far A may be from symmetric, relative to its largest entry: |A_ij − A_ji| ≤
/// `SYMMETRY_TOLERANCE`·max|A|. A Betti–Maxwell reciprocal compliance is symmetric up to the
/// round-off of whatever made it (quadrature, a factorisation); more than this is a matrix
/// of something else (a transposed block, a stiffness).
pub const SYMMETRY_TOLERANCE: f64 = 1e-8;

/// The smallest Cholesky pivot a positive definite A may have, relative to its largest
/// diagonal entry: below it the matrix is singular to working precision (a body with a free
/// rigid motion, two points at one place) and the solvers' products would not be unique.
pub const PIVOT_TOLERANCE: f64 = 1e-12;

/// A body whose influence operator is a given dense matrix A \[mm/N\], `A[(i, j)]` the normal
/// displacement into the body at point i under a unit compressive force at point j (the
/// library's convention, [`ElasticBody::influence_matrix`]). It is held: no rigid mode, no
/// load of its own. A is checked square, of the interface's size, finite, symmetric within
/// [`SYMMETRY_TOLERANCE`] and positive definite (a Cholesky factor with every pivot above
/// [`PIVOT_TOLERANCE`]); its Cholesky factor is kept as the exact inverse that preconditions
/// the matrix-free solvers.
#[derive(Clone, Debug)]
pub struct DenseCompliance {
    name: String,
    interface: Interface,
    /// The symmetric part of the given A \[mm/N\].
    compliance: Mat<f64>,
    /// L of A = L Lᵀ.
    factor: Mat<f64>,
}

/// The memory a dense compliance body of `n` points takes to build \[bytes\]: A and its
/// Cholesky factor; `None` when the count overflows.
pub fn dense_compliance_bytes(n: usize) -> Option<u64> {
    memory::bytes(&[n, n], 2 * 8)
}

impl DenseCompliance {
    /// The body on `interface` (n points) whose compliance A \[mm/N\] has `shape` (rows,
    /// columns) and the `entries` in row-major order. Refused with the field named
    /// `compliance`: a matrix that is not square, not n × n, past the memory limit (estimated
    /// before anything is allocated), with an entry not finite, not symmetric or not positive
    /// definite (the failing pivot named).
    pub fn new(
        name: impl Into<String>,
        interface: Interface,
        shape: [usize; 2],
        entries: &[f64],
    ) -> Result<Self> {
        let [rows, columns] = shape;
        let n = interface.len();
        let size = format!("{rows} × {columns}");
        if rows.checked_mul(columns) != Some(entries.len()) {
            let given = format!("{} entries", entries.len());
            return Err(Error::invalid(
                "compliance",
                given,
                format!("{size} entries"),
            ));
        }
        if rows != columns {
            return Err(Error::invalid("compliance", size, "a square matrix"));
        }
        if rows != n {
            let allowed = format!("{n} × {n}, one row and column per contact point");
            return Err(Error::invalid("compliance", size, allowed));
        }
        memory::require(
            format!("the dense compliance {n} × {n} and its Cholesky factor"),
            dense_compliance_bytes(n),
            memory::BODY_LIMIT_BYTES,
            "use fewer contact points",
        )?;
        if let Some(k) = entries.iter().position(|v| !v.is_finite()) {
            let field = format!("compliance[{}, {}]", k / n, k % n);
            check::finite(&field, entries[k])?;
        }
        let at = |i: usize, j: usize| entries[i * n + j];
        let largest = entries.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        check_symmetric(n, &at, largest)?;
        let compliance = Mat::from_fn(n, n, |i, j| 0.5 * at(i, j) + 0.5 * at(j, i));
        let factor = cholesky(&compliance)?;
        Ok(Self {
            name: name.into(),
            interface,
            compliance,
            factor,
        })
    }
}

/// A's worst asymmetry within [`SYMMETRY_TOLERANCE`]·`largest`, else an error naming it.
fn check_symmetric(n: usize, at: &impl Fn(usize, usize) -> f64, largest: f64) -> Result<()> {
    let mut worst = (0.0, 0, 0);
    for i in 0..n {
        for j in i + 1..n {
            let gap = (at(i, j) - at(j, i)).abs();
            if gap > worst.0 {
                worst = (gap, i, j);
            }
        }
    }
    let (gap, i, j) = worst;
    if gap > SYMMETRY_TOLERANCE * largest {
        return Err(Error::invalid(
            format!("compliance[{i}, {j}]"),
            at(i, j),
            format!(
                "equal to compliance[{j}, {i}] = {} within {SYMMETRY_TOLERANCE:e} of the \
                 largest entry {largest:e} (a compliance is symmetric)",
                at(j, i)
            ),
        ));
    }
    Ok(())
}

/// L of A = L Lᵀ, refused at the first pivot L_kk² not above [`PIVOT_TOLERANCE`]·max A_ii
/// (named with its value): A not positive definite.
fn cholesky(a: &Mat<f64>) -> Result<Mat<f64>> {
    let n = a.nrows();
    let largest = (0..n).fold(0.0f64, |m, i| m.max(a[(i, i)]));
    let floor = PIVOT_TOLERANCE * largest;
    let mut l = Mat::<f64>::zeros(n, n);
    for j in 0..n {
        let pivot = a[(j, j)] - (0..j).map(|k| l[(j, k)] * l[(j, k)]).sum::<f64>();
        if pivot.is_nan() || pivot <= floor {
            return Err(Error::invalid(
                "compliance",
                format!("a matrix whose Cholesky pivot {j} is {pivot:e}"),
                format!(
                    "positive definite: every pivot above {PIVOT_TOLERANCE:e} × the largest \
                     diagonal entry {largest:e}"
                ),
            ));
        }
        let d = pivot.sqrt();
        l[(j, j)] = d;
        for i in j + 1..n {
            let s = a[(i, j)] - (0..j).map(|k| l[(i, k)] * l[(j, k)]).sum::<f64>();
            l[(i, j)] = s / d;
        }
    }
    Ok(l)
}

impl ElasticBody for DenseCompliance {
    fn name(&self) -> &str {
        &self.name
    }

    fn interface(&self) -> &Interface {
        &self.interface
    }

    /// u = A F (eq. 2.5).
    fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        let a = &self.compliance;
        for (i, u) in displacement.iter_mut().enumerate() {
            *u = force.iter().enumerate().map(|(j, f)| a[(i, j)] * f).sum();
        }
    }

    fn influence_matrix(&self) -> Mat<f64> {
        self.compliance.clone()
    }

    fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        block_among(&self.compliance, points)
    }

    /// The exact inverse: F = A⁻¹ u by the two triangular solves of L Lᵀ.
    fn precondition(&self, displacement: &[f64], force: &mut [f64]) -> bool {
        let l = &self.factor;
        let n = displacement.len();
        for i in 0..n {
            let s: f64 = (0..i).map(|k| l[(i, k)] * force[k]).sum();
            force[i] = (displacement[i] - s) / l[(i, i)];
        }
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|k| l[(k, i)] * force[k]).sum();
            force[i] = (force[i] - s) / l[(i, i)];
        }
        true
    }

    /// It carries no load of its own.
    fn load_displacement(&self) -> Result<Vec<f64>> {
        Ok(vec![0.0; self.interface.len()])
    }

    /// It is held: none.
    fn rigid_modes(&self) -> &[RigidMode] {
        &[]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contopt_core::Geometry;

    fn line(n: usize) -> Interface {
        let points = (0..n).map(|i| [i as f64, 0.0, 0.0]).collect();
        Interface::new(
            Geometry::Surface,
            points,
            vec![1.0; n],
            vec![[0.0, 0.0, 1.0]; n],
        )
        .unwrap()
    }

    fn refused(shape: [usize; 2], entries: &[f64]) -> String {
        DenseCompliance::new("d", line(2), shape, entries)
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn bad_matrices_are_refused_by_name() {
        let e = refused([2, 2], &[1.0, 0.0, 0.0]);
        assert_eq!(e, "invalid compliance = 3 entries: 2 × 2 entries");
        let e = refused([1, 4], &[1.0; 4]);
        assert_eq!(e, "invalid compliance = 1 × 4: a square matrix");
        let e = refused([1, 1], &[1.0]);
        assert!(
            e.starts_with("invalid compliance = 1 × 1: 2 × 2, one row"),
            "{e}"
        );
        let e = refused([2, 2], &[1.0, f64::NAN, 0.0, 1.0]);
        assert_eq!(e, "invalid compliance[0, 1] = NaN: must be finite");
        let e = refused([2, 2], &[1.0, 0.5, 0.4, 1.0]);
        assert!(e.starts_with("invalid compliance[0, 1] = 0.5: equal to compliance[1, 0] = 0.4"));
        // Eigenvalues 3 and −1: the second pivot is 1 − 4 = −3.
        let e = refused([2, 2], &[1.0, 2.0, 2.0, 1.0]);
        assert!(e.contains("Cholesky pivot 1 is -3e0"), "{e}");
        let e = refused([2, 2], &[1.0, 1.0, 1.0, 1.0]);
        assert!(e.contains("Cholesky pivot 1 is 0e0"), "{e}");
    }

    #[test]
    fn products_and_the_inverse_agree() {
        let a = [4.0, 1.0, 0.5, 1.0, 3.0, 0.2, 0.5, 0.2, 2.0];
        let body = DenseCompliance::new("d", line(3), [3, 3], &a).unwrap();
        let force = [1.0, -2.0, 0.5];
        let mut u = [0.0; 3];
        body.apply_influence(&force, &mut u);
        assert_eq!(u, [4.0 - 2.0 + 0.25, 1.0 - 6.0 + 0.1, 0.5 - 0.4 + 1.0]);
        let mut back = [0.0; 3];
        assert!(body.precondition(&u, &mut back));
        for (b, f) in back.iter().zip(force) {
            assert!((b - f).abs() < 1e-14, "{back:?}");
        }
    }
}
