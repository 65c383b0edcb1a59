//! Sparse Cholesky factorisation K = L Lᵀ with the contact-face unknowns ordered last, so that
//! the face block of K⁻¹ (the condensed compliance) comes from the trailing supernodes alone.

use contopt_core::{memory, Error, Result};
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_lower_triangular_in_place;
use faer::sparse::linalg::amd;
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, CholeskySymbolicParams, LltRef,
    SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Accum, Conj, Mat, MatMut, Par, Side};

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
    /// The last `n_tail` unknowns of the matrix are the contact face.
    n_tail: usize,
}

impl Factor {
    /// Symbolic analysis of the upper triangle `a` (n × n): AMD on the leading
    /// n − `n_tail` unknowns, the trailing `n_tail` kept last; then the numeric factorisation.
    pub fn new(a: SparseColMatRef<'_, usize, f64>, n_tail: usize, body: &str) -> Result<Self> {
        Self::ordered(a, n_tail, body, Ordering::Amd)
    }

    /// As [`Factor::new`] with the leading unknowns ordered by `ordering`. The factor's size is
    /// known after the symbolic analysis: it is checked against
    /// [`memory::BODY_LIMIT_BYTES`] before its values are allocated.
    pub fn ordered(
        a: SparseColMatRef<'_, usize, f64>,
        n_tail: usize,
        body: &str,
        ordering: Ordering,
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
        Self::permuted(a, n_tail, body, fwd)
    }

    /// As [`Factor::new`] with the leading unknowns eliminated in the order `fwd` (position →
    /// unknown; its last `n_tail` entries the trailing unknowns in place).
    pub fn permuted(
        a: SparseColMatRef<'_, usize, f64>,
        n_tail: usize,
        body: &str,
        fwd: Vec<usize>,
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
            memory::BODY_LIMIT_BYTES,
            "use fewer elements (coarser away from the contact)",
        )?;
        let values = vec![0.0; symbolic.len_val()];
        let mut factor = Self {
            symbolic,
            values,
            n_tail,
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
        let SymbolicCholeskyRaw::Supernodal(sn) = self.symbolic.raw() else {
            unreachable!("the factorisation is forced supernodal")
        };
        let n = self.symbolic.nrows();
        let n_tail = self.n_tail;
        let inv = self
            .symbolic
            .perm()
            .map(|p| p.arrays().1.to_vec())
            .unwrap_or_else(|| (0..n).collect());
        // Positions of the trailing unknowns in the factor's order.
        let pos: Vec<usize> = (n - n_tail..n).map(|i| inv[i]).collect();
        let first = pos.iter().copied().min().unwrap_or(n);
        let llt = SupernodalLltRef::new(sn, &self.values);
        let begin = sn.supernode_begin();
        let s0 = (0..sn.n_supernodes())
            .find(|&s| sn.supernode_end()[s] > first)
            .unwrap_or(sn.n_supernodes());
        let offset = if s0 < sn.n_supernodes() { begin[s0] } else { n };
        let mut y = Mat::<f64>::zeros(n - offset, n_tail);
        for (k, &p) in pos.iter().enumerate() {
            y[(p - offset, k)] = 1.0;
        }
        let mut tmp = Mat::<f64>::zeros(0, 0);
        for s in s0..sn.n_supernodes() {
            let node = llt.supernode(s);
            let ls = node.val();
            let size = ls.ncols();
            let (top, bottom) = ls.split_at_row(size);
            let start = node.start() - offset;
            solve_lower_triangular_in_place(top, y.as_mut().subrows_mut(start, size), Par::Seq);
            let pattern = node.pattern();
            if pattern.is_empty() {
                continue;
            }
            tmp.resize_with(pattern.len(), n_tail, |_, _| 0.0);
            matmul(
                tmp.as_mut(),
                Accum::Replace,
                bottom,
                y.as_ref().subrows(start, size),
                1.0,
                Par::Seq,
            );
            for j in 0..n_tail {
                for (r, &i) in pattern.iter().enumerate() {
                    y[(i - offset, j)] -= tmp[(r, j)];
                }
            }
        }
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
}
