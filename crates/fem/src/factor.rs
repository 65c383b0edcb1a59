//! Sparse Cholesky factorisation K = L Lᵀ with the contact-face unknowns ordered last, so that
//! the face block of K⁻¹ (the condensed compliance) comes from the trailing supernodes alone.

use contopt_core::{memory, Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::{
    solve_lower_triangular_in_place, solve_upper_triangular_in_place,
};
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, CholeskySymbolicParams, LltRef,
    SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, MatRef, Par, Side};

thread_local! {
    /// The numeric factorisations made on this thread so far.
    static FACTORISATIONS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The numeric factorisations of stiffness matrices made on the calling thread so far: what a
/// test counts to prove that a step built nothing (a check that factorises no body), or that
/// cases sharing their bodies share one factorisation. Counted per thread, so that tests running
/// side by side do not see each other's.
pub fn factorisations() -> u64 {
    FACTORISATIONS.with(std::cell::Cell::get)
}

/// The fill-reducing ordering of the unknowns ahead of the contact face's.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (faer's AMD).
    #[default]
    Amd,
    /// The unknowns as numbered (no reordering): the baseline AMD is measured against.
    Natural,
    /// Nested dissection of the mesh's nodes by their coordinates: solids only, where the
    /// nodes are known; a factor given a matrix alone orders it by AMD.
    Dissection,
}

/// A numeric Cholesky factor with its symbolic analysis kept for reuse.
pub(crate) struct Factor {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    /// Where the trailing unknowns (the last of the matrix: the contact face) sit in the
    /// factor, from the symbolic analysis.
    tail: Tail,
}

/// The trailing supernodes of a factor: the first that holds a trailing unknown, the first
/// trailing unknown's row in the factor's order (`offset`), and each trailing unknown's row
/// counted from it.
struct Tail {
    first_supernode: usize,
    offset: usize,
    positions: Vec<usize>,
}

impl Tail {
    fn of(symbolic: &SymbolicCholesky<usize>, n_tail: usize) -> Self {
        let SymbolicCholeskyRaw::Supernodal(sn) = symbolic.raw() else {
            unreachable!("the factorisation is forced supernodal")
        };
        let n = symbolic.nrows();
        let inv = symbolic.perm().map(|p| p.arrays().1);
        // Positions of the trailing unknowns in the factor's order.
        let position = |i: usize| inv.map_or(i, |inv| inv[i]);
        let offset = (n - n_tail..n).map(position).min().unwrap_or(n);
        let first_supernode = (0..sn.n_supernodes())
            .find(|&s| sn.supernode_end()[s] > offset)
            .unwrap_or(sn.n_supernodes());
        Self {
            first_supernode,
            offset,
            positions: (n - n_tail..n).map(|i| position(i) - offset).collect(),
        }
    }
}

/// The work buffers of products through the trailing block
/// ([`Factor::tail_solve_in_place`]): the right-hand side over the trailing rows and a
/// supernode's rows below its diagonal block. Sized by the first product, reused after it.
#[derive(Debug)]
pub(crate) struct TailWork {
    y: Mat<f64>,
    below: Mat<f64>,
}

impl Default for TailWork {
    /// Empty: the first product sizes it.
    fn default() -> Self {
        Self {
            y: Mat::zeros(0, 0),
            below: Mat::zeros(0, 0),
        }
    }
}

impl Factor {
    /// Symbolic analysis of the upper triangle `a` (n × n): AMD on the leading
    /// n − `n_tail` unknowns, the trailing `n_tail` kept last; then the numeric factorisation.
    pub fn new(a: SparseColMatRef<'_, usize, f64>, n_tail: usize, body: &str) -> Result<Self> {
        Self::ordered(a, n_tail, body, Ordering::Amd, memory::BODY_LIMIT_BYTES)
    }

    /// As [`Factor::new`] with the leading unknowns ordered by `ordering`. The factor's size is
    /// known after the symbolic analysis: it is checked against `limit` \[bytes\] before its
    /// values are allocated.
    pub fn ordered(
        a: SparseColMatRef<'_, usize, f64>,
        n_tail: usize,
        body: &str,
        ordering: Ordering,
        limit: u64,
    ) -> Result<Self> {
        let n = a.nrows();
        let mut fwd: Vec<usize> = (0..n).collect();
        if ordering != Ordering::Natural {
            let n_int = n - n_tail;
            let sym = a.symbolic();
            let col_ptr = sym.col_ptr();
            let interior = SymbolicSparseColMatRef::new_checked(
                n_int,
                n_int,
                &col_ptr[..=n_int],
                None,
                &sym.row_idx()[..col_ptr[n_int]],
            );
            let mut inv: Vec<usize> = (0..n).collect();
            let mut mem =
                MemBuffer::new(amd::order_scratch::<usize>(n_int, interior.compute_nnz()));
            amd::order(
                &mut fwd[..n_int],
                &mut inv[..n_int],
                interior,
                Default::default(),
                MemStack::new(&mut mem),
            )
            .map_err(|e| Error::Singular {
                body: body.into(),
                detail: format!("ordering failed: {e:?}"),
            })?;
        }
        Self::permuted(a, n_tail, body, fwd, limit)
    }

    /// As [`Factor::ordered`] with the leading unknowns eliminated in the order `fwd` (position
    /// → unknown; its last `n_tail` entries the trailing unknowns in place).
    pub fn permuted(
        a: SparseColMatRef<'_, usize, f64>,
        n_tail: usize,
        body: &str,
        fwd: Vec<usize>,
        limit: u64,
    ) -> Result<Self> {
        let n = a.nrows();
        let sym = a.symbolic();
        let mut inv = vec![0; n];
        for (position, &unknown) in fwd.iter().enumerate() {
            inv[unknown] = position;
        }
        let perm = faer::perm::PermRef::new_checked(&fwd, &inv, n);
        let symbolic = factorize_symbolic_cholesky(
            sym,
            Side::Upper,
            SymmetricOrdering::Custom(perm),
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .map_err(|e| Error::Singular {
            body: body.into(),
            detail: format!("symbolic analysis failed: {e:?}"),
        })?;
        memory::require(
            format!(
                "{body}: the Cholesky factor of {n} unknowns ({} nonzeros)",
                symbolic.len_val()
            ),
            memory::bytes(&[symbolic.len_val()], 8),
            limit,
            "use fewer elements (coarser away from the contact)",
        )?;
        let values = vec![0.0; symbolic.len_val()];
        let tail = Tail::of(&symbolic, n_tail);
        let mut factor = Self {
            symbolic,
            values,
            tail,
        };
        factor.refactor(a, body)?;
        Ok(factor)
    }

    /// Numeric refactorisation of a matrix with the pattern of the first, reusing the
    /// symbolic analysis (ordering, elimination tree, supernodes).
    pub fn refactor(&mut self, a: SparseColMatRef<'_, usize, f64>, body: &str) -> Result<()> {
        FACTORISATIONS.with(|count| count.set(count.get() + 1));
        let mut mem = MemBuffer::new(
            self.symbolic
                .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        );
        self.symbolic
            .factorize_numeric_llt(
                &mut self.values,
                a,
                Side::Upper,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut mem),
                Default::default(),
            )
            .map_err(|e| Error::Singular {
                body: body.into(),
                detail: format!(
                    "{e:?}; check that the supports leave no mechanism, and that no element is \
                     stretched past about 1:1000 (a slender body loses a digit per decade of \
                     aspect ratio in bending, and double precision runs out near 1:10000)"
                ),
            })?;
        Ok(())
    }

    /// Number of nonzeros of L.
    pub fn factor_nnz(&self) -> usize {
        self.values.len()
    }

    /// Floating-point operations of the numeric factorisation: per supernode of k columns
    /// and p rows below them, k³/3 (its diagonal block) + p k² (the rows below) + p² k (its
    /// update of the later columns). What an ordering costs, apart from the kernels' speed.
    pub fn flops(&self) -> f64 {
        let SymbolicCholeskyRaw::Supernodal(sn) = self.symbolic.raw() else {
            unreachable!("the factorisation is forced supernodal")
        };
        (0..sn.n_supernodes())
            .map(|s| {
                let k = (sn.supernode_end()[s] - sn.supernode_begin()[s]) as f64;
                let p = (sn.col_ptr_for_row_idx()[s + 1] - sn.col_ptr_for_row_idx()[s]) as f64;
                k * k * k / 3.0 + p * k * k + p * p * k
            })
            .sum()
    }

    /// Solves K X = B in place for a block of right-hand sides.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) {
        let mut mem = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(rhs.ncols(), Par::Seq),
        );
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            rhs,
            Par::Seq,
            MemStack::new(&mut mem),
        );
    }

    /// The trailing `n_tail × n_tail` block of K⁻¹: with Y = L⁻¹ E (E the trailing columns of
    /// the identity, permuted), the block is Yᵀ Y. Y is zero above the first supernode that
    /// holds a trailing unknown, so only the trailing supernodes are visited.
    pub fn tail_inverse(&self) -> Mat<f64> {
        let sweep = self.tail_sweep();
        let n_tail = self.tail.positions.len();
        let mut y = Mat::<f64>::zeros(sweep.rows(), n_tail);
        for (k, &p) in sweep.tail.positions.iter().enumerate() {
            y[(p, k)] = 1.0;
        }
        sweep.forward(y.as_mut(), &mut Mat::zeros(0, 0));
        let mut a = Mat::<f64>::zeros(n_tail, n_tail);
        matmul(
            a.as_mut(),
            Accum::Replace,
            y.transpose(),
            y.as_ref(),
            1.0,
            Par::Seq,
        );
        a
    }

    /// Solves K x = b for a right-hand side `b` that is zero outside the trailing unknowns, and
    /// returns x on them in place of `b` (`n_tail` values: T b, T the trailing block of K⁻¹).
    /// Only the trailing supernodes are visited, forward and backward (eq. 2.22's product
    /// A f = L T Lᵀ f through the factor at the cost of its trailing block, not of all of L),
    /// in the buffers of `work`: after the first product with a `work`, none is allocated.
    pub fn tail_solve_in_place(&self, b: &mut [f64], work: &mut TailWork) {
        let sweep = self.tail_sweep();
        let TailWork { y, below } = work;
        y.resize_with(sweep.rows(), 1, |_, _| 0.0);
        y.fill(0.0);
        for (&p, &v) in sweep.tail.positions.iter().zip(b.iter()) {
            y[(p, 0)] = v;
        }
        sweep.forward(y.as_mut(), below);
        sweep.backward(y.as_mut(), below);
        for (&p, v) in sweep.tail.positions.iter().zip(b.iter_mut()) {
            *v = y[(p, 0)];
        }
    }

    /// The trailing supernodes and where the trailing unknowns sit among their rows.
    fn tail_sweep(&self) -> TailSweep<'_> {
        let SymbolicCholeskyRaw::Supernodal(sn) = self.symbolic.raw() else {
            unreachable!("the factorisation is forced supernodal")
        };
        TailSweep {
            llt: SupernodalLltRef::new(sn, &self.values),
            tail: &self.tail,
            n: self.symbolic.nrows(),
        }
    }
}

/// The factor L from the first trailing unknown's row (`offset`, factor order) on: where a
/// right-hand side of trailing unknowns is nonzero. The supernode that holds that row (a
/// relaxed supernode may reach back into the unknowns ahead) is entered at it.
struct TailSweep<'a> {
    llt: SupernodalLltRef<'a, usize, f64>,
    tail: &'a Tail,
    n: usize,
}

/// A supernode's columns from the sweep's offset on: its diagonal block, the rows below it,
/// its first row (counted from the offset) and the rows below's indices (factor order).
struct Columns<'a> {
    diagonal: MatRef<'a, f64>,
    below: MatRef<'a, f64>,
    start: usize,
    pattern: &'a [usize],
}

impl TailSweep<'_> {
    fn rows(&self) -> usize {
        self.n - self.tail.offset
    }

    /// The supernodes of the sweep, first to last, each from the offset on.
    fn columns(&self) -> impl DoubleEndedIterator<Item = Columns<'_>> {
        let n_supernodes = self.llt.symbolic().n_supernodes();
        let offset = self.tail.offset;
        (self.tail.first_supernode..n_supernodes).map(move |s| {
            let node = self.llt.supernode(s);
            let size = node.val().ncols();
            let skip = offset.saturating_sub(node.start());
            let (top, bottom) = node.val().split_at_row(size);
            Columns {
                diagonal: top.submatrix(skip, skip, size - skip, size - skip),
                below: bottom.subcols(skip, size - skip),
                start: node.start() + skip - offset,
                pattern: node.pattern(),
            }
        })
    }

    /// Y ← L⁻¹ Y over the trailing rows (Y zero above them); `update` holds a supernode's
    /// update of the rows below it.
    fn forward(&self, mut y: MatMut<'_, f64>, update: &mut Mat<f64>) {
        let offset = self.tail.offset;
        for c in self.columns() {
            let size = c.diagonal.ncols();
            let mut ys = y.as_mut().subrows_mut(c.start, size);
            solve_lower_triangular_in_place(c.diagonal, ys.as_mut(), Par::Seq);
            update.resize_with(c.pattern.len(), y.ncols(), |_, _| 0.0);
            matmul(
                update.as_mut(),
                Accum::Replace,
                c.below,
                y.as_ref().subrows(c.start, size),
                1.0,
                Par::Seq,
            );
            for j in 0..y.ncols() {
                for (r, &i) in c.pattern.iter().enumerate() {
                    y[(i - offset, j)] -= update[(r, j)];
                }
            }
        }
    }

    /// Y ← L⁻ᵀ Y over the trailing rows: exact there, as the rows above never enter them;
    /// `below` holds Y on a supernode's rows below it.
    fn backward(&self, mut y: MatMut<'_, f64>, below: &mut Mat<f64>) {
        let offset = self.tail.offset;
        for c in self.columns().rev() {
            let size = c.diagonal.ncols();
            below.resize_with(c.pattern.len(), y.ncols(), |_, _| 0.0);
            for j in 0..y.ncols() {
                for (r, &i) in c.pattern.iter().enumerate() {
                    below[(r, j)] = y[(i - offset, j)];
                }
            }
            matmul(
                y.as_mut().subrows_mut(c.start, size),
                Accum::Add,
                c.below.transpose(),
                below.as_ref(),
                -1.0,
                Par::Seq,
            );
            solve_upper_triangular_in_place(
                c.diagonal.transpose(),
                y.as_mut().subrows_mut(c.start, size),
                Par::Seq,
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::sparse::{SparseColMat, Triplet};

    /// The upper triangle of the 5-point Laplacian of an m × m grid plus the identity: sparse,
    /// positive definite, and with a dense Schur complement on any set of its unknowns.
    fn laplacian(m: usize) -> SparseColMat<usize, f64> {
        let mut entries = Vec::new();
        for i in 0..m {
            for j in 0..m {
                let k = i * m + j;
                entries.push(Triplet::new(k, k, 5.0));
                if j + 1 < m {
                    entries.push(Triplet::new(k, k + 1, -1.0));
                }
                if i + 1 < m {
                    entries.push(Triplet::new(k, k + m, -1.0));
                }
            }
        }
        SparseColMat::try_new_from_triplets(m * m, m * m, &entries).unwrap()
    }

    /// The product through the trailing block alone is the full solve read on the trailing
    /// unknowns (to round-off), for tails that fill a supernode, share one with the unknowns
    /// ahead, or are a single unknown, in one work set reused from product to product; and
    /// its block of K⁻¹ is the full solve's too.
    #[test]
    fn the_trailing_product_is_the_full_solve_on_the_tail() {
        let a = laplacian(12);
        let n = a.nrows();
        // One work set for every tail, largest first: what a product leaves in it must not
        // reach the next.
        let mut work = TailWork::default();
        for n_tail in [30, 12, 5, 1] {
            let factor = Factor::new(a.as_ref(), n_tail, "grid").unwrap();
            let b: Vec<f64> = (0..n_tail).map(|k| 1.0 + (k % 7) as f64).collect();
            let mut full = Mat::<f64>::zeros(n, 1);
            for (k, v) in b.iter().enumerate() {
                full[(n - n_tail + k, 0)] = *v;
            }
            factor.solve_in_place(full.as_mut());
            let mut tail = b.clone();
            factor.tail_solve_in_place(&mut tail, &mut work);
            let mut again = b.clone();
            factor.tail_solve_in_place(&mut again, &mut work);
            assert_eq!(
                tail, again,
                "{n_tail}: a reused work set changed the product"
            );
            let t = factor.tail_inverse();
            for k in 0..n_tail {
                let x = full[(n - n_tail + k, 0)];
                assert!((tail[k] - x).abs() < 1e-13 * x.abs(), "{n_tail}: {k}");
                let tb: f64 = (0..n_tail).map(|j| t[(k, j)] * b[j]).sum();
                assert!((tb - x).abs() < 1e-13 * x.abs(), "{n_tail}: {k}");
            }
        }
    }

    /// A factor past its limit is refused after the symbolic analysis, before a numeric
    /// factorisation, with its size and the limit named.
    #[test]
    fn a_factor_past_its_limit_is_refused_before_it_is_computed() {
        let a = laplacian(12);
        let before = factorisations();
        let refused = Factor::ordered(a.as_ref(), 3, "grid", Ordering::Amd, 1000);
        let Err(Error::TooLarge {
            what, bytes, limit, ..
        }) = refused
        else {
            panic!("not refused");
        };
        assert_eq!(factorisations(), before);
        assert_eq!(limit, 1000);
        let nnz = Factor::new(a.as_ref(), 3, "grid").unwrap().factor_nnz();
        assert_eq!(bytes, 8 * nnz as u64);
        assert!(what.contains(&format!("({nnz} nonzeros)")), "{what}");
    }
}
