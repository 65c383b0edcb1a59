//! Kalker's active-set iteration, the one loop behind every method that solves on a contact
//! set C: the penalty method and the active-set QP solver on the condensed interface, each
//! Uzawa step of the augmented Lagrangian, and the penalty method on the full finite-element
//! system (2.22, [`FullPenalty`](crate::FullPenalty)).

use contopt_core::drive::Step;
use contopt_core::observe::Method;
use contopt_core::{ContactState, Error, Result, Stall, Termination};
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::llt;
use faer::linalg::evd::{self, ComputeEigenvectors as Eigenvectors};
use faer::linalg::matmul::matmul;
use faer::reborrow::{Reborrow, ReborrowMut};
use faer::{Accum, Conj, Mat, MatMut, Par};

use crate::watch::{self, Watch};
use crate::workspace::refill;
use crate::{problem, InterfaceProblem};

/// The n × n matrices a Kalker solve may hold at once, counted at its worst (every point in
/// contact, a spectral step): A, and in its workspace the contact-set matrix, its eigenvectors
/// and the eigen-decomposition's copy of the matrix (faer's tridiagonal reduction), and the
/// two k × k blocks faer's divide and conquer takes while it runs (a contact set of 128 points
/// or more). A solve by Cholesky steps alone peaks near two.
pub(crate) const DENSE_COPIES: u64 = 6;

/// An eigenvalue of the contact-set matrix below this fraction of its eigenvector's own
/// diagonal scale counts as null: the direction does not move the interface (round-off).
const NULL_EIGENVALUE: f64 = 1e-9;
/// A pressure in C below −`TENSION` times the largest |pᵢ| is tension (round-off).
const TENSION: f64 = 1e-12;
/// A gap outside C below −`PENETRATION` times the gap's largest term is a penetration
/// (round-off).
const PENETRATION: f64 = 1e-11;
/// The round-off level of a solved gap, relative to its largest terms (the free gap and the
/// rigid motion).
const GAP_ROUND_OFF: f64 = 1e-13;
/// c_stiff·maxᵢ(Aᵢᵢ wᵢ): the largest penalty parameter solved from scratch, whose proximal
/// term 1/c is 10⁻⁶ of the stiffest compliance (conditioning of the Cholesky solve).
const STIFF_RATIO: f64 = 1e6;
/// Kalker's iteration gives up after `SOLVES_PER_POINT`·n + [`SOLVES_EXTRA`] solves
/// (cycling: the pivot rule is finite, but a stuck iteration must still end).
const SOLVES_PER_POINT: usize = 4;
/// See [`SOLVES_PER_POINT`]: the allowance of a very small interface.
const SOLVES_EXTRA: usize = 20;

/// A system that Kalker's iteration solves on a contact set C: the condensed interface
/// problem ([`Subproblem`]) or the full finite-element system with penalty springs.
pub(crate) trait ContactSet {
    /// Number of contact points.
    fn points(&self) -> usize;
    /// The point put in contact when C is empty and a floating body would not be held (the
    /// point of least gap); `None` when nothing floats.
    fn anchor(&self) -> Option<usize>;
    /// Solves with the points of `active` in contact and zero pressure elsewhere; `Ok(Err)`
    /// with the stall when the system is singular on C (the iterate then holds no solve).
    fn solve_on(&mut self, active: &[bool]) -> Result<std::result::Result<(), Stall>>;
    /// The pressure of the last solve.
    fn pressure(&self) -> &[f64];
    /// The gap of point i after the last solve less the proximal shift, dᵢ − ρ p̂ᵢ: negative
    /// when the point, outside C, penetrates.
    fn clearance(&self, i: usize) -> f64;
    /// The largest term of the gap after the last solve, against which round-off is judged.
    fn gap_scale(&self) -> f64;
}

/// How Kalker's iteration ended; the system holds its last iterate.
pub(crate) struct Sweep {
    /// Solves, each followed by the sign check of p (the paper's `iterp`).
    pub iterp: usize,
    /// Penetration checks: the solves whose pressure had no negative value (`iterd`).
    pub iterd: usize,
    /// Why it stopped short; `None` when solved.
    pub halt: Option<Termination>,
}

/// Kalker's iteration: solve with the points of `active` in contact (one `iterp`); drop the
/// points whose pressure came out negative, else check the gap (one `iterd`) and add the
/// points that penetrate; repeat until neither occurs. Changes follow [`PivotRule`], so the
/// iteration cannot cycle. Each solve is reported to `watch` with the number of points that
/// break a sign condition as the measure (tolerance 0). The lists of such points are kept in
/// `lists` (of capacity n: the loop allocates nothing of its own).
pub(crate) fn iterate(
    system: &mut impl ContactSet,
    active: &mut [bool],
    watch: Watch,
    lists: &mut Infeasible,
) -> Result<Sweep> {
    let max_solves = SOLVES_PER_POINT * system.points() + SOLVES_EXTRA;
    let mut driver = watch.driver(0.0, max_solves);
    let mut pivot = PivotRule::new();
    let Infeasible {
        negative,
        penetrating,
    } = lists;
    let mut iterd = 0;
    let end = driver.run(|solve, _| {
        if solve > 1 {
            // The last solve left points that break a sign condition, and the iteration goes
            // on: change the set.
            match pivot.next(negative, penetrating) {
                Pivot::Drop(points) => points.iter().for_each(|&i| active[i] = false),
                Pivot::Add(points) => points.iter().for_each(|&i| active[i] = true),
            }
        }
        if !active.contains(&true) {
            if let Some(i) = system.anchor() {
                active[i] = true;
            }
        }
        if let Err(cause) = system.solve_on(active)? {
            return Ok(Step::Ended(Termination::Stalled { cause }));
        }
        infeasible(system, active, negative, penetrating);
        if negative.is_empty() {
            iterd += 1;
        }
        // The measure: the points that still break a sign condition (negative pressure or
        // penetration).
        let infeasible = negative.len() + penetrating.len();
        Ok::<_, Error>(Step::converged_below(infeasible as f64, 0.0))
    })?;
    Ok(Sweep {
        iterp: driver.steps(),
        iterd,
        halt: (end != Termination::Converged).then_some(end),
    })
}

/// The points of C in tension and the points outside C that penetrate, after the last solve.
fn infeasible(
    system: &impl ContactSet,
    active: &[bool],
    negative: &mut Vec<usize>,
    penetrating: &mut Vec<usize>,
) {
    let p = system.pressure();
    let p_scale = p.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    negative.clear();
    negative.extend((0..p.len()).filter(|&i| active[i] && p[i] < -TENSION * p_scale));
    let tol = PENETRATION * system.gap_scale();
    penetrating.clear();
    penetrating.extend((0..p.len()).filter(|&i| !active[i] && system.clearance(i) < -tol));
}

/// A pressure and rigid-mode amplitudes: an iterate, or the reference a solve starts from.
#[derive(Clone, Debug)]
pub(crate) struct Iterate {
    pub(crate) pressure: Vec<f64>,
    pub(crate) rigid: Vec<f64>,
}

impl Iterate {
    pub(crate) fn zero(n: usize, m: usize) -> Self {
        Self {
            pressure: vec![0.0; n],
            rigid: vec![0.0; m],
        }
    }
}

/// The points that break a sign condition after a solve, the lists Kalker's iteration pivots
/// on (capacity n: filling them never allocates).
#[derive(Default)]
pub(crate) struct Infeasible {
    /// Points of C in tension.
    negative: Vec<usize>,
    /// Points outside C that penetrate.
    penetrating: Vec<usize>,
}

impl Infeasible {
    pub(crate) fn new(n: usize) -> Self {
        Self {
            negative: Vec::with_capacity(n),
            penetrating: Vec::with_capacity(n),
        }
    }

    /// Room for n points in each list.
    fn reserve(&mut self, n: usize) {
        for list in [&mut self.negative, &mut self.penetrating] {
            list.clear();
            list.reserve(n);
        }
    }
}

/// The parallelism of faer's dense kernels: the global one, as faer's own `Llt::new` and
/// `self_adjoint_eigen` use.
fn par() -> Par {
    faer::get_global_parallelism()
}

/// Makes `mat` exactly `rows` × `cols`, zeroed; reallocated only when its size differs.
fn exactly(mat: &mut Mat<f64>, rows: usize, cols: usize) {
    if (mat.nrows(), mat.ncols()) == (rows, cols) {
        mat.fill(0.0);
    } else {
        *mat = Mat::zeros(rows, cols);
    }
}

/// Makes `mat` at least `rows` × `cols`; its leading block is then used as that size. It is
/// reallocated (zeroed) only when it is too small: once per solve for each contact set larger
/// than any before.
fn reserve(mat: &mut Mat<f64>, rows: usize, cols: usize) {
    if mat.nrows() < rows || mat.ncols() < cols {
        *mat = Mat::zeros(rows.max(mat.nrows()), cols.max(mat.ncols()));
    }
}

/// The contact-set matrix M = W_C A_CC W_C + ρ W_C on the k points of C, factorised in place
/// by faer on the leading k × k block of buffers that every solve reuses. They grow with the
/// largest contact set solved on (not to n: a spectral solve's set is often half the points),
/// so a solve on a set no larger than an earlier one allocates nothing.
struct ContactMatrix {
    /// The leading k × k block holds L of M = L Lᵀ (lower triangle), or T = W^½ A W^½ on C.
    storage: Mat<f64>,
    /// The eigenvectors U of T (a spectral solve's).
    eigenvectors: Mat<f64>,
    /// The eigenvalues Λ of T (k × 1).
    eigenvalues: Mat<f64>,
    /// (Λ + ρ)⁺: with T = U Λ Uᵀ, M⁺ = W^-½ U (Λ + ρ)⁺ Uᵀ W^-½, where an eigenvector u counts
    /// as null when its eigenvalue is below [`NULL_EIGENVALUE`] of its own diagonal scale
    /// Σᵢ uᵢ² Tᵢᵢ (scale-invariant: points of small weight near an axis are not null): no
    /// correction is made along the directions that do not move the interface, so
    /// c·(round-off) never enters.
    inverse: Vec<f64>,
    /// √wᵢ on C.
    root_w: Vec<f64>,
    /// Uᵀ b of a spectral solve (k × 1 or k × m).
    product: Mat<f64>,
    /// faer's scratch space (the Cholesky factorisations', the eigen-decomposition's).
    scratch: MemBuffer,
    /// What `scratch` was sized for.
    scratch_size: StackReq,
    /// Size of C, and whether M was factorised spectrally.
    k: usize,
    spectral: bool,
}

impl ContactMatrix {
    /// Empty buffers for n points and m rigid modes.
    fn new(n: usize, m: usize) -> Self {
        let scratch_size = Self::cholesky_scratch(n, m);
        Self {
            storage: Mat::new(),
            eigenvectors: Mat::new(),
            eigenvalues: Mat::new(),
            inverse: Vec::with_capacity(n),
            root_w: Vec::with_capacity(n),
            product: Mat::new(),
            scratch: MemBuffer::new(scratch_size),
            scratch_size,
            k: 0,
            spectral: false,
        }
    }

    /// The Cholesky factorisations' scratch (of M and of the modes' Gram matrix): n values.
    fn cholesky_scratch(n: usize, m: usize) -> StackReq {
        StackReq::any_of(&[
            llt::factor::cholesky_in_place_scratch::<f64>(n, par(), Default::default()),
            llt::factor::cholesky_in_place_scratch::<f64>(m, par(), Default::default()),
        ])
    }

    /// Makes room for a problem of n points and m modes, with no contact set factorised.
    fn prepare(&mut self, n: usize, m: usize) {
        self.reserve_scratch(Self::cholesky_scratch(n, m));
        self.inverse.reserve(n);
        self.root_w.reserve(n);
        (self.k, self.spectral) = (0, false);
    }

    /// Makes the scratch space hold `req`.
    fn reserve_scratch(&mut self, req: StackReq) {
        if !MemStack::new(&mut self.scratch).can_hold(req) {
            self.scratch_size = StackReq::any_of(&[self.scratch_size, req]);
            self.scratch = MemBuffer::new(self.scratch_size);
        }
    }

    /// Factorises M on the points `idx`; `false` when it is singular there.
    fn factor(&mut self, a: &Mat<f64>, w: &[f64], idx: &[usize], rho: f64, spectral: bool) -> bool {
        let k = idx.len();
        (self.k, self.spectral) = (k, spectral);
        if spectral && self.eigenvectors.nrows() == 0 {
            // The first spectral solve: the storage of the Cholesky solves before it (all n
            // points at their start) makes way for one of this set's size.
            self.storage = Mat::new();
        }
        reserve(&mut self.storage, k, k);
        if !spectral {
            let mut m = self.storage.as_mut().submatrix_mut(0, 0, k, k);
            for y in 0..k {
                for x in 0..k {
                    let (i, j) = (idx[x], idx[y]);
                    // Lower triangle only, as faer's `Llt::new` copies it.
                    m[(x, y)] = if x >= y {
                        w[i] * a[(i, j)] * w[j] + if x == y { rho * w[i] } else { 0.0 }
                    } else {
                        0.0
                    };
                }
            }
            let factored = llt::factor::cholesky_in_place(
                m.rb_mut(),
                Default::default(),
                par(),
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .is_ok();
            for y in 1..k {
                for x in 0..y {
                    m[(x, y)] = 0.0;
                }
            }
            return factored;
        }
        reserve(&mut self.eigenvectors, k, k);
        reserve(&mut self.eigenvalues, k, 1);
        self.reserve_scratch(evd::self_adjoint_evd_scratch::<f64>(
            k,
            Eigenvectors::Yes,
            par(),
            Default::default(),
        ));
        self.root_w.clear();
        self.root_w.extend(idx.iter().map(|&i| w[i].sqrt()));
        let root_w = &self.root_w;
        let mut t = self.storage.as_mut().submatrix_mut(0, 0, k, k);
        for y in 0..k {
            for x in 0..k {
                t[(x, y)] = root_w[x] * a[(idx[x], idx[y])] * root_w[y];
            }
        }
        let mut u = self.eigenvectors.as_mut().submatrix_mut(0, 0, k, k);
        u.fill(0.0);
        let mut s = self.eigenvalues.as_mut().col_mut(0).subrows_mut(0, k);
        s.fill(0.0);
        let solved = evd::self_adjoint_evd(
            t.rb(),
            s.rb_mut().as_diagonal_mut(),
            Some(u.rb_mut()),
            par(),
            MemStack::new(&mut self.scratch),
            Default::default(),
        );
        if solved.is_err() {
            return false;
        }
        self.inverse.clear();
        self.inverse.extend((0..k).map(|x| {
            let l = s[x];
            let scale: f64 = (0..k).map(|i| u[(i, x)] * u[(i, x)] * t[(i, i)]).sum();
            if l > NULL_EIGENVALUE * scale {
                1.0 / (l + rho)
            } else {
                0.0
            }
        }));
        true
    }

    /// Overwrites the k rows of `b` with M⁻¹ b (M⁺ b when spectral).
    fn solve_in_place(&mut self, mut b: MatMut<'_, f64>) {
        let k = self.k;
        if !self.spectral {
            llt::solve::solve_in_place_with_conj(
                self.storage.as_ref().submatrix(0, 0, k, k),
                Conj::No,
                b,
                par(),
                MemStack::new(&mut self.scratch),
            );
            return;
        }
        let (root_w, inverse) = (&self.root_w, &self.inverse);
        let u = self.eigenvectors.as_ref().submatrix(0, 0, k, k);
        let cols = b.ncols();
        reserve(&mut self.product, k, cols);
        for j in 0..cols {
            for i in 0..k {
                b[(i, j)] /= root_w[i];
            }
        }
        let mut coef = self.product.as_mut().submatrix_mut(0, 0, k, cols);
        matmul(
            coef.rb_mut(),
            Accum::Replace,
            u.transpose(),
            b.rb(),
            1.0,
            par(),
        );
        for (i, inv) in inverse.iter().enumerate() {
            for j in 0..cols {
                coef[(i, j)] *= inv;
            }
        }
        matmul(b.rb_mut(), Accum::Replace, u, coef.rb(), 1.0, par());
        for j in 0..cols {
            for i in 0..k {
                b[(i, j)] /= root_w[i];
            }
        }
    }
}

/// What Kalker's iteration holds (the active-set, penalty and augmented-Lagrangian solvers),
/// reused by every solve on a contact set and every subproblem of a solve (the Uzawa steps),
/// and kept by a caller across the solves of a design loop (faer's explicit scratch,
/// [`ContactSolver::solve_in`](crate::ContactSolver::solve_in)): the problem's free gap, R and
/// q, the index lists, the iterate and its gap, the products' buffers, sized for the number of
/// points n and of rigid modes m and grown for a larger problem; and the contact-set matrix's,
/// sized to the largest contact set solved on. A solve on C then allocates nothing of its
/// own, unless its set is the largest yet or it is the first spectral one; faer's kernels,
/// which factorise and multiply in these buffers, allocate nothing either at the sizes tested
/// (see the crate's `tests/allocations.rs`).
pub struct KalkerWorkspace {
    /// The free gap g and its largest |gᵢ|.
    free_gap: Vec<f64>,
    free_scale: f64,
    /// The rigid modes R (n × m) and their loads q.
    r: Mat<f64>,
    q: Vec<f64>,
    /// The points of C, in order.
    idx: Vec<usize>,
    infeasible: Infeasible,
    /// The last solve's iterate and its gap d.
    current: Iterate,
    gap: Vec<f64>,
    /// The gap of the reference restricted to C, and the buffers of the product A W p.
    reference_gap: Vec<f64>,
    force: Vec<f64>,
    spare: Vec<f64>,
    matrix: ContactMatrix,
    /// The right-hand side of a solve on C and its solution y (n × 1).
    rhs: Mat<f64>,
    /// W_C R_C and M⁻¹ W_C R_C (n × m each; their leading k rows are used).
    modes: Mat<f64>,
    solved_modes: Mat<f64>,
    /// The rigid modes' Gram matrix (W R)ᵀ M⁻¹ (W R) (m × m), its right-hand side and solution
    /// Δλ (m × 1), and M⁻¹ W R Δλ (n × 1).
    gram: Mat<f64>,
    lambda: Mat<f64>,
    mode_correction: Mat<f64>,
}

impl Default for KalkerWorkspace {
    /// An empty workspace: its first solve sizes it.
    fn default() -> Self {
        Self::new(0, 0)
    }
}

impl KalkerWorkspace {
    /// A workspace for problems of `points` points and `modes` free rigid modes (it grows
    /// for larger ones).
    pub fn new(points: usize, modes: usize) -> Self {
        let (n, m) = (points, modes);
        Self {
            free_gap: Vec::with_capacity(n),
            free_scale: 0.0,
            r: Mat::zeros(n, m),
            q: Vec::with_capacity(m),
            idx: Vec::with_capacity(n),
            infeasible: Infeasible::new(n),
            current: Iterate::zero(n, m),
            gap: Vec::with_capacity(n),
            reference_gap: Vec::with_capacity(n),
            force: Vec::with_capacity(n),
            spare: Vec::with_capacity(n),
            matrix: ContactMatrix::new(n, m),
            rhs: Mat::zeros(n, 1),
            modes: Mat::zeros(n, m),
            solved_modes: Mat::zeros(n, m),
            gram: Mat::zeros(m, m),
            lambda: Mat::zeros(m, 1),
            mode_correction: Mat::zeros(n, 1),
        }
    }

    /// Takes `problem`'s free gap, R and q, and sizes the buffers for its n points and m
    /// modes, reallocating only those too small.
    pub(crate) fn prepare(&mut self, problem: &InterfaceProblem) {
        let (n, modes) = (problem.len(), problem.modes());
        let m = modes.len();
        refill(&mut self.free_gap, n, 0.0);
        problem.add_free_gap(&mut self.free_gap);
        self.free_scale = self.free_gap.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        exactly(&mut self.r, n, m);
        for (k, mode) in modes.iter().enumerate() {
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                self.r[(i, k)] = v;
            }
        }
        self.q.clear();
        self.q.extend(modes.iter().map(|mode| mode.load));
        self.idx.clear();
        self.idx.reserve(n);
        self.infeasible.reserve(n);
        refill(&mut self.current.pressure, n, 0.0);
        refill(&mut self.current.rigid, m, 0.0);
        for v in [
            &mut self.gap,
            &mut self.reference_gap,
            &mut self.force,
            &mut self.spare,
        ] {
            refill(v, n, 0.0);
        }
        self.matrix.prepare(n, m);
        for (mat, cols) in [
            (&mut self.rhs, 1),
            (&mut self.modes, m),
            (&mut self.solved_modes, m),
            (&mut self.mode_correction, 1),
        ] {
            reserve(mat, n, cols);
        }
        exactly(&mut self.gram, m, m);
        exactly(&mut self.lambda, m, 1);
    }

    /// The last subproblem's solution (its last iterate when it stopped short).
    pub(crate) fn solution(&self) -> &Iterate {
        &self.current
    }

    /// Exchanges the last subproblem's solution with `other`, whose buffers the next
    /// subproblem overwrites.
    pub(crate) fn swap_solution(&mut self, other: &mut Iterate) {
        std::mem::swap(&mut self.current, other);
    }

    /// The largest |dᵢ| over the contact set `active` of the last subproblem's solution.
    pub(crate) fn open_on_contact(&self, active: &[bool]) -> f64 {
        (0..active.len())
            .filter(|&i| active[i])
            .fold(0.0f64, |s, i| s.max(self.gap[i].abs()))
    }
}

/// How one subproblem ended; its solution is the workspace's ([`KalkerWorkspace::solution`]).
pub(crate) struct Inner {
    /// Round-off level of the gap ([`GAP_ROUND_OFF`] of its largest terms); 0 when stopped.
    pub(crate) gap_floor: f64,
    /// Solves, each followed by the sign check of p (the paper's `iterp`).
    pub(crate) iterp: usize,
    /// Penetration checks: the solves whose pressure had no negative value (the paper's
    /// `iterd`).
    pub(crate) iterd: usize,
    /// Why the iteration stopped short, with the workspace's solution its last iterate; `None`
    /// when solved.
    pub(crate) stopped: Option<Termination>,
}

impl Inner {
    /// The contact set it started from was already the answer.
    pub(crate) fn unchanged(&self) -> bool {
        self.iterp == 1
    }
}

/// The proximal subproblem
///
/// min ½ pᵀ (H + ρW) p + pᵀ W (g − ρ p̂)  over  p ≥ 0,  Rᵀ W p = −q,
///
/// whose solution is p = ⟨p̂ − c d⟩ with c = 1/ρ: eq. (2.19) with the gap d of the new
/// state, i.e. one augmented-Lagrangian step (2.18)–(2.20); with p̂ = 0 it is the penalty
/// method.
///
/// Each solve on C is in residual form: the correction to `reference` (restricted to C) is
/// driven by the reference's own residual −W(d + ρ(p − p̂)). Round-off in the data along the
/// directions that do not move the interface (a semi-definite H) is amplified by c; in this
/// form it multiplies the reference's residual instead of the whole gap, so a reference close
/// to the answer keeps large c accurate.
///
/// It works in the solve's [`KalkerWorkspace`], where it leaves its solution.
pub(crate) struct Subproblem<'a> {
    problem: &'a InterfaceProblem<'a>,
    rho: f64,
    shift: &'a [f64],
    /// Solve spectrally (for ρ below the stiff level; see [`ContactMatrix`]).
    spectral: bool,
    reference: &'a Iterate,
    /// The dense influence matrix A.
    a: &'a Mat<f64>,
    ws: &'a mut KalkerWorkspace,
}

impl<'a> Subproblem<'a> {
    pub(crate) fn new(
        problem: &'a InterfaceProblem<'a>,
        rho: f64,
        shift: &'a [f64],
        spectral: bool,
        reference: &'a Iterate,
        ws: &'a mut KalkerWorkspace,
    ) -> Result<Self> {
        Ok(Self {
            a: problem.dense_influence(DENSE_COPIES)?,
            problem,
            rho,
            shift,
            spectral,
            reference,
            ws,
        })
    }

    /// Kalker's iteration ([`iterate`]) from the contact set `active`, which it updates.
    pub(crate) fn solve(mut self, active: &mut [bool], watch: Watch) -> Result<Inner> {
        let mut infeasible = std::mem::take(&mut self.ws.infeasible);
        let sweep = iterate(&mut self, active, watch, &mut infeasible);
        self.ws.infeasible = infeasible;
        let sweep = sweep?;
        let gap_floor = if sweep.halt.is_none() {
            for v in self.ws.current.pressure.iter_mut() {
                *v = v.max(0.0);
            }
            // d = g + A W p + R λ, with the elastic term balancing the others on C.
            GAP_ROUND_OFF * (self.ws.free_scale + self.rigid_motion())
        } else {
            0.0
        };
        Ok(Inner {
            gap_floor,
            iterp: sweep.iterp,
            iterd: sweep.iterd,
            stopped: sweep.halt,
        })
    }

    /// The largest rigid motion |(R λ)ᵢ| of the current iterate.
    fn rigid_motion(&self) -> f64 {
        let (r, lambda) = (&self.ws.r, &self.ws.current.rigid);
        (0..self.problem.len())
            .map(|i| {
                (0..lambda.len())
                    .map(|c| r[(i, c)] * lambda[c])
                    .sum::<f64>()
                    .abs()
            })
            .fold(0.0f64, f64::max)
    }

    /// Corrects the current iterate (the reference restricted to C, whose points are the
    /// workspace's `idx`) by the solve on C.
    fn correct(&mut self) -> std::result::Result<(), Stall> {
        let (problem, rho, shift) = (self.problem, self.rho, self.shift);
        let w = problem.weights();
        let ws = &mut *self.ws;
        let (idx, k) = (&ws.idx, ws.idx.len());
        if !ws.matrix.factor(self.a, w, idx, rho, self.spectral) {
            return Err(Stall::SingularOnContactSet { points: k, rho });
        }
        let p = &ws.current.pressure;
        let d_ref = &mut ws.reference_gap;
        problem.gap_with(p, &ws.current.rigid, d_ref, &mut ws.force, &mut ws.spare);
        let mut y = ws.rhs.as_mut().submatrix_mut(0, 0, k, 1);
        for (a, &i) in idx.iter().enumerate() {
            y[(a, 0)] = -w[i] * (d_ref[i] + rho * (p[i] - shift[i]));
        }
        ws.matrix.solve_in_place(y.rb_mut());
        if !ws.q.is_empty() {
            self.balance()?;
        }
        let ws = &mut *self.ws;
        for (a, &i) in ws.idx.iter().enumerate() {
            ws.current.pressure[i] += ws.rhs[(a, 0)];
        }
        Ok(())
    }

    /// Makes the correction y on C (the workspace's `rhs`) balance the rigid modes,
    /// Rᵀ W δ = −q − Rᵀ W p_ref (eq. 2.10), and updates their amplitudes.
    fn balance(&mut self) -> std::result::Result<(), Stall> {
        let w = self.problem.weights();
        let ws = &mut *self.ws;
        let (idx, q) = (&ws.idx, &ws.q);
        let (k, m) = (idx.len(), q.len());
        let mut bm = ws.modes.as_mut().submatrix_mut(0, 0, k, m);
        for c in 0..m {
            for (a, &i) in idx.iter().enumerate() {
                bm[(a, c)] = w[i] * ws.r[(i, c)];
            }
        }
        let bm = bm.rb();
        let mut z = ws.solved_modes.as_mut().submatrix_mut(0, 0, k, m);
        z.copy_from(bm);
        ws.matrix.solve_in_place(z.rb_mut());
        let mut s = ws.gram.as_mut();
        matmul(
            s.rb_mut(),
            Accum::Replace,
            bm.transpose(),
            z.rb(),
            1.0,
            par(),
        );
        let p = &ws.current.pressure;
        let y = ws.rhs.as_ref().submatrix(0, 0, k, 1);
        let mut lambda = ws.lambda.as_mut();
        for c in 0..m {
            let held: f64 = (0..k).map(|a| bm[(a, c)] * p[idx[a]]).sum();
            lambda[(c, 0)] = (0..k).map(|a| bm[(a, c)] * y[(a, 0)]).sum::<f64>() + q[c] + held;
        }
        // The lower triangle, as faer's `Llt::new` copies it.
        for c in 1..m {
            for r in 0..c {
                s[(r, c)] = 0.0;
            }
        }
        let scratch = MemStack::new(&mut ws.matrix.scratch);
        if llt::factor::cholesky_in_place(
            s.rb_mut(),
            Default::default(),
            par(),
            scratch,
            Default::default(),
        )
        .is_err()
        {
            return Err(Stall::RigidModesUnheld { points: k });
        }
        llt::solve::solve_in_place_with_conj(s.rb(), Conj::No, lambda.rb_mut(), par(), scratch);
        for (c, l) in ws.current.rigid.iter_mut().enumerate() {
            *l += lambda[(c, 0)];
        }
        let mut correction = ws.mode_correction.as_mut().submatrix_mut(0, 0, k, 1);
        matmul(
            correction.rb_mut(),
            Accum::Replace,
            z.rb(),
            lambda.rb(),
            1.0,
            par(),
        );
        let mut y = ws.rhs.as_mut().submatrix_mut(0, 0, k, 1);
        for a in 0..k {
            y[(a, 0)] -= correction[(a, 0)];
        }
        Ok(())
    }
}

impl ContactSet for Subproblem<'_> {
    fn points(&self) -> usize {
        self.problem.len()
    }

    fn anchor(&self) -> Option<usize> {
        let g = &self.ws.free_gap;
        (!self.ws.q.is_empty()).then(|| (0..g.len()).min_by(|&i, &j| g[i].total_cmp(&g[j])))?
    }

    fn solve_on(&mut self, active: &[bool]) -> Result<std::result::Result<(), Stall>> {
        let ws = &mut *self.ws;
        ws.idx.clear();
        ws.idx.extend((0..active.len()).filter(|&i| active[i]));
        ws.current.pressure.fill(0.0);
        for &i in &ws.idx {
            ws.current.pressure[i] = self.reference.pressure[i];
        }
        ws.current.rigid.copy_from_slice(&self.reference.rigid);
        let outcome = if ws.idx.is_empty() {
            Ok(())
        } else {
            self.correct()
        };
        let ws = &mut *self.ws;
        let current = &ws.current;
        self.problem.gap_with(
            &current.pressure,
            &current.rigid,
            &mut ws.gap,
            &mut ws.force,
            &mut ws.spare,
        );
        Ok(outcome)
    }

    fn pressure(&self) -> &[f64] {
        &self.ws.current.pressure
    }

    fn clearance(&self, i: usize) -> f64 {
        self.ws.gap[i] - self.rho * self.shift[i]
    }

    fn gap_scale(&self) -> f64 {
        self.ws
            .gap
            .iter()
            .fold(self.ws.free_scale, |s, v| s.max(v.abs()))
    }
}

/// A change of the contact set: points of the infeasible lists.
#[derive(Debug, PartialEq)]
enum Pivot<'a> {
    /// Points that leave the set (their pressure came out negative).
    Drop(&'a [usize]),
    /// Points that join it (they penetrate).
    Add(&'a [usize]),
}

/// The choice of the next contact set, after Júdice and Pires' safeguard for block principal
/// pivoting: Kalker's block changes (every negative-pressure point leaves, else every
/// penetrating point joins) while the number of infeasible points keeps reaching new lows, with
/// a few passes of grace; otherwise one point at a time, the lowest-numbered infeasible one
/// (Murty's rule, finite for the positive-definite matrix of a subproblem). Block changes alone
/// can cycle when the matrix is nearly singular on the set, as it is for three Gauss points per
/// quadratic face, where many points have p ≈ d ≈ 0 (an optimised gap).
struct PivotRule {
    /// Fewest infeasible points seen so far.
    best: usize,
    /// Block passes left without a new low.
    grace: usize,
}

impl PivotRule {
    /// Block passes allowed without a new low in the number of infeasible points.
    const GRACE: usize = 3;

    fn new() -> Self {
        Self {
            best: usize::MAX,
            grace: Self::GRACE,
        }
    }

    /// The change for `negative` points in the set and `penetrating` points outside it (not
    /// both empty).
    fn next<'a>(&mut self, negative: &'a [usize], penetrating: &'a [usize]) -> Pivot<'a> {
        let infeasible = negative.len() + penetrating.len();
        let block = if infeasible < self.best {
            self.best = infeasible;
            self.grace = Self::GRACE;
            true
        } else if self.grace > 0 {
            self.grace -= 1;
            true
        } else {
            false
        };
        if block {
            if negative.is_empty() {
                Pivot::Add(penetrating)
            } else {
                Pivot::Drop(negative)
            }
        } else {
            let (drop, add) = (negative.iter().min(), penetrating.iter().min());
            match drop.filter(|&d| add.is_none_or(|a| d < a)) {
                Some(d) => Pivot::Drop(std::slice::from_ref(d)),
                None => Pivot::Add(add.map_or(&[], std::slice::from_ref)),
            }
        }
    }
}

/// The contact state of a subproblem's solution (the workspace's), after
/// `steps` outer steps, with the set changes counted before it.
pub(crate) fn finish(
    problem: &InterfaceProblem,
    method: Method,
    inner: Inner,
    ws: &KalkerWorkspace,
    active: Vec<bool>,
    steps: usize,
    counts: [usize; 2],
) -> ContactState {
    let s = &ws.current;
    let mut state = problem.state(
        method,
        s.pressure.clone(),
        s.rigid.clone(),
        active,
        [steps, counts[0] + inner.iterp, counts[1] + inner.iterd],
    );
    if let Some(halt) = inner.stopped {
        watch::end(&mut state, halt);
    }
    state
}

/// The QP (2.14) on the contact set `active` (updated by Kalker's iteration), from
/// `reference`: ρ = 0 with the pseudo-inverse, so nothing changes along the directions that
/// do not move the interface.
pub(crate) fn solve_exact(
    problem: &InterfaceProblem,
    reference: &Iterate,
    active: &mut [bool],
    watch: Watch,
    ws: &mut KalkerWorkspace,
) -> Result<Inner> {
    let zeros = vec![0.0; problem.len()];
    Subproblem::new(problem, 0.0, &zeros, true, reference, ws)?.solve(active, watch)
}

/// The largest penalty parameter at which a subproblem is solved from scratch:
/// c_stiff = [`STIFF_RATIO`] / maxᵢ(Aᵢᵢ wᵢ). Larger parameters start from a c_stiff solution
/// (see [`Subproblem`]).
pub(crate) fn stiff_penalty(problem: &InterfaceProblem) -> Result<f64> {
    let a = problem.dense_influence(DENSE_COPIES)?;
    let scale = (0..problem.len())
        .map(|i| a[(i, i)] * problem.weights()[i])
        .fold(0.0, f64::max);
    Ok(STIFF_RATIO / problem::compliance(scale)?)
}

/// Makes `reference` (zero) a starting iterate for a subproblem with penalty `c`: zero, or for
/// c above c_stiff the penalty solution at c_stiff (whose small gap keeps the large-c solve
/// accurate), its solves added to `counts`; the stopped solve when it stopped short (its last
/// iterate the workspace's solution).
pub(crate) fn start(
    problem: &InterfaceProblem,
    c: f64,
    active: &mut [bool],
    counts: &mut [usize; 2],
    watch: Watch,
    reference: &mut Iterate,
    ws: &mut KalkerWorkspace,
) -> Result<Option<Inner>> {
    let c_stiff = stiff_penalty(problem)?;
    if c <= c_stiff {
        return Ok(None);
    }
    let zeros = vec![0.0; problem.len()];
    let pre = Subproblem::new(problem, 1.0 / c_stiff, &zeros, false, reference, ws)?
        .solve(active, watch.after(counts[0]))?;
    if pre.stopped.is_some() {
        return Ok(Some(pre));
    }
    counts[0] += pre.iterp;
    counts[1] += pre.iterd;
    ws.swap_solution(reference);
    Ok(None)
}

/// The penalty method: one subproblem with ρ = 1/c and p̂ = 0, so p = c⟨−d⟩.
pub(crate) fn penalty(
    problem: &InterfaceProblem,
    c: f64,
    watch: Watch,
    ws: &mut KalkerWorkspace,
) -> Result<ContactState> {
    let (n, m) = (problem.len(), problem.modes().len());
    ws.prepare(problem);
    let mut active = vec![true; n];
    let mut counts = [0, 0];
    let mut reference = Iterate::zero(n, m);
    let method = Method::Penalty;
    let started = start(
        problem,
        c,
        &mut active,
        &mut counts,
        watch,
        &mut reference,
        ws,
    )?;
    if let Some(stopped) = started {
        return Ok(finish(problem, method, stopped, ws, active, 1, counts));
    }
    let zeros = vec![0.0; n];
    let spectral = c > stiff_penalty(problem)?;
    let inner = Subproblem::new(problem, 1.0 / c, &zeros, spectral, &reference, ws)?
        .solve(&mut active, watch.after(counts[0]))?;
    Ok(finish(problem, method, inner, ws, active, 1, counts))
}

/// The QP (2.14) itself: Kalker's iteration with ρ = 0, solving on each contact set with the
/// pseudo-inverse (see [`ContactMatrix`]), which gives the pressure of least Σ wᵢpᵢ² exactly,
/// whatever the conditioning of H. Without `start_set`, one penalty solve at c_stiff (by
/// Cholesky) first finds the contact set and a reference pressure, so that the spectral solves
/// are few.
pub(crate) fn exact(
    problem: &InterfaceProblem,
    start_set: Option<&[bool]>,
) -> Result<ContactState> {
    let silent = contopt_core::observe::Silent;
    let watch = Watch::new(&silent, Method::ActiveSet);
    exact_observed(problem, start_set, watch, &mut KalkerWorkspace::default())
}

/// [`exact`], reporting each of Kalker's solves to `watch`, in the workspace `ws`.
pub(crate) fn exact_observed(
    problem: &InterfaceProblem,
    start_set: Option<&[bool]>,
    watch: Watch,
    ws: &mut KalkerWorkspace,
) -> Result<ContactState> {
    let (n, m) = (problem.len(), problem.modes().len());
    ws.prepare(problem);
    let mut reference = Iterate::zero(n, m);
    let mut counts = [0, 0];
    let method = Method::ActiveSet;
    let mut active = match start_set {
        Some(set) => set.to_vec(),
        None => {
            let mut active = vec![true; n];
            let zeros = vec![0.0; n];
            let rho = 1.0 / stiff_penalty(problem)?;
            let pre = Subproblem::new(problem, rho, &zeros, false, &reference, ws)?
                .solve(&mut active, watch)?;
            if pre.stopped.is_some() {
                return Ok(finish(problem, method, pre, ws, active, 1, counts));
            }
            counts = [pre.iterp, pre.iterd];
            ws.swap_solution(&mut reference);
            active
        }
    };
    let inner = solve_exact(problem, &reference, &mut active, watch.after(counts[0]), ws)?;
    Ok(finish(problem, method, inner, ws, active, 1, counts))
}

#[cfg(test)]
mod pivot_tests {
    use super::{Pivot, PivotRule};

    /// Block changes while the number of infeasible points reaches new lows, three more of
    /// grace, then one point at a time (the lowest index) until a new low.
    #[test]
    fn block_changes_fall_back_to_single_points() {
        let mut rule = PivotRule::new();
        assert_eq!(rule.next(&[4, 7], &[1]), Pivot::Drop(&[4, 7]));
        assert_eq!(rule.next(&[], &[5, 2]), Pivot::Add(&[5, 2]));
        for _ in 0..PivotRule::GRACE {
            assert_eq!(rule.next(&[9], &[3, 8]), Pivot::Drop(&[9]));
        }
        assert_eq!(rule.next(&[9], &[3, 8]), Pivot::Add(&[3]));
        assert_eq!(rule.next(&[6, 9], &[8]), Pivot::Drop(&[6]));
        assert_eq!(rule.next(&[], &[8]), Pivot::Add(&[8]));
    }
}
