//! The contact interface problem that two bodies define (§2.1), held as operators, in four
//! parts a reader can take one at a time: the influence operator and its products
//! ([`operator`]), the dense matrix on demand with its memory guard ([`dense`]), the free rigid
//! modes with their equilibrium rows ([`modes`]), and here the problem itself: its gaps, the
//! states of its solutions, and its restriction and coarsening.

mod dense;
mod derived;
mod modes;
mod operator;
mod reciprocity;

use std::sync::Arc;

use contopt_core::observe::Method;
use contopt_core::{
    check, ContactState, ElasticBody, Error, GapShape, InfluenceShape, Interface, Residuals,
    Result, Termination,
};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

pub use dense::DEFAULT_DENSE_LIMIT_BYTES;
pub use modes::FreeMode;

pub(crate) use derived::Derived;

use dense::Dense;
use derived::Mapping;
use modes::Modes;
use operator::{Body, Operator};

/// Relative tolerance to which two interfaces must agree in weight.
const WEIGHT_MATCH: f64 = 1e-9;
/// Largest component of n¹ + n² for normals that count as opposite.
const NORMAL_MATCH: f64 = 1e-6;

/// The elastic displacement, as a multiple of the interface's size, past which a solution is
/// refused ([`InterfaceProblem::verify`]): loose on purpose, it catches data in the wrong units
/// or overflowing, not a mildly nonlinear contact.
pub const SMALL_STRAIN: f64 = 1.0;

/// The gaps of a problem in the first body's numbering: the initial gap h and the bodies'
/// displacements under their own loads f¹ + f² (`None` when they are zero).
struct Gaps {
    initial: Vec<f64>,
    load: Option<Arc<Vec<f64>>>,
}

/// Frictionless normal contact of two bodies, condensed to their common interface points.
///
/// With W = diag(wᵢ) the point weights, A = A¹ + A² the summed influence operators of the
/// bodies (displacement into the body per unit force, [`ElasticBody::apply_influence`]) and
/// g = h + f¹ + f² the initial gap plus the displacements under the given loads, the gap after
/// deformation is (2.7)
///
/// d = g + A W p + R λ,
///
/// where the columns of R are the interface displacements of the free rigid modes and λ their
/// amplitudes. Equilibrium of each free mode (2.10) reads Rᵀ W p = −q. In the paper's notation
/// (2.12)–(2.14): H = W A W, t = −W g, G_R = W R, and its q is our −q.
///
/// The problem holds the bodies' operators, never a dense matrix of its own: a 2-D region of
/// 2·10⁴ points would need 3 GB for one. Solvers that work on the dense matrix ask for it
/// ([`InterfaceProblem::dense_influence`]); it is built once, shared by every problem derived
/// from this one ([`InterfaceProblem::with_initial_gap`] copies only the gap), and refused with
/// [`Error::TooLarge`] past the memory limit.
#[derive(Clone)]
pub struct InterfaceProblem<'a> {
    operator: Arc<Operator<'a>>,
    dense: Dense,
    modes: Modes,
    interface: Arc<Interface>,
    pressure_basis: Option<Arc<GapShape>>,
    /// h of eq. (2.1).
    initial_gap: Vec<f64>,
    /// f¹ + f², the displacements under the bodies' own loads; `None` when they are zero.
    load_gap: Option<Arc<Vec<f64>>>,
}

impl std::fmt::Debug for InterfaceProblem<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let names = [0, 1].map(|k| self.operator.body(k).name().to_string());
        f.debug_struct("InterfaceProblem")
            .field("points", &self.len())
            .field("bodies", &names)
            .field("modes", &self.modes())
            .finish()
    }
}

impl<'a> InterfaceProblem<'a> {
    /// The problem of `body1` and `body2` touching over their common points with initial
    /// gap `initial_gap` \[mm\] (h of eq. 2.1, one value per point of `body1`). The two
    /// interfaces must hold the same points (in any order: they are paired by position), with
    /// the same weights and opposite normals; the first mismatch is reported.
    pub fn new(
        body1: &'a dyn ElasticBody,
        body2: &'a dyn ElasticBody,
        initial_gap: &[f64],
    ) -> Result<Self> {
        Self::from_bodies([Body::Borrowed(body1), Body::Borrowed(body2)], initial_gap)
    }

    /// As [`InterfaceProblem::new`], with the problem owning its bodies.
    pub fn owned(
        body1: Box<dyn ElasticBody + 'a>,
        body2: Box<dyn ElasticBody + 'a>,
        initial_gap: &[f64],
    ) -> Result<Self> {
        Self::from_bodies([Body::Owned(body1), Body::Owned(body2)], initial_gap)
    }

    fn from_bodies(bodies: [Body<'a>; 2], initial_gap: &[f64]) -> Result<Self> {
        let (b1, b2) = (bodies[0].get(), bodies[1].get());
        let (s1, s2) = (b1.interface(), b2.interface());
        let pair = s1.partners(s2, b1.name(), b2.name())?;
        check_partners(b1, b2, &pair)?;
        reciprocity::check(b1)?;
        reciprocity::check(b2)?;
        check::gap(initial_gap, s1.len())?;
        let (f1, f2) = (b1.load_displacement()?, b2.load_displacement()?);
        let load_gap: Vec<f64> = pair
            .iter()
            .enumerate()
            .map(|(i, &j)| f1[i] + f2[j])
            .collect();
        let gaps = Gaps {
            initial: initial_gap.to_vec(),
            load: load_gap
                .iter()
                .any(|&f| f != 0.0)
                .then(|| Arc::new(load_gap)),
        };
        let modes = Modes::of_bodies(b1, b2, &pair)?;
        let dense = Dense::new(DEFAULT_DENSE_LIMIT_BYTES);
        Self::assemble(Operator::new(bodies, pair), modes, gaps, dense)
    }

    /// The problem of `operator` with the rest given: the first body's interface, and the
    /// field its pressures sample from the first body that has one.
    fn assemble(operator: Operator<'a>, modes: Modes, gaps: Gaps, dense: Dense) -> Result<Self> {
        let (b1, b2) = (operator.body(0), operator.body(1));
        let pressure_basis = match (b1.pressure_basis(), b2.pressure_basis()) {
            (Some(b), _) => Some(b.clone()),
            (None, Some(b)) => {
                let rows = (0..b1.interface().len()).map(|i| b.row(operator.to_second(i)).to_vec());
                Some(GapShape::new(b.nodes().to_vec(), rows.collect())?)
            }
            (None, None) => None,
        };
        Ok(Self {
            interface: Arc::new(b1.interface().clone()),
            operator: Arc::new(operator),
            dense,
            modes,
            pressure_basis: pressure_basis.map(Arc::new),
            initial_gap: gaps.initial,
            load_gap: gaps.load,
        })
    }

    /// The same problem with another initial gap h (the optimisation changes it): the
    /// operators, the interface and the dense matrix, once built, are shared, not copied.
    pub fn with_initial_gap(&self, initial_gap: &[f64]) -> Result<Self> {
        check::gap(initial_gap, self.len())?;
        Ok(Self {
            initial_gap: initial_gap.to_vec(),
            ..self.clone()
        })
    }

    /// The same problem with the memory its solvers' dense matrices may take set to `bytes`.
    pub fn with_dense_limit(mut self, bytes: u64) -> Self {
        self.dense = self.dense.with_limit(bytes);
        self
    }

    /// The memory limit for dense matrices \[bytes\].
    pub fn dense_limit(&self) -> u64 {
        self.dense.limit()
    }

    /// The same problem with other free modes: `modes` replace the bodies' rigid modes. The
    /// optimiser gives each design column of a gap shape its own translation and load this way
    /// (the column approaches are then the multipliers of a contact solve).
    pub fn with_modes(&self, modes: Vec<FreeMode>) -> Result<Self> {
        Ok(Self {
            modes: Modes::given(modes, self.len())?,
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
        self.interface.weights()
    }

    /// The influence product `displacement = A force`, A = A¹ + A² \[mm/N\], through the
    /// bodies' operators (an FFT convolution on a half-space grid).
    pub fn apply_influence(&self, force: &[f64], displacement: &mut [f64]) {
        let mut spare = vec![
            0.0;
            if self.sums_two_products() {
                force.len()
            } else {
                0
            }
        ];
        self.operator.apply(force, displacement, &mut spare);
    }

    /// As [`InterfaceProblem::apply_influence`] with a caller's buffer `spare` of the same
    /// length, for loops that must not allocate; it may be empty unless
    /// [`InterfaceProblem::sums_two_products`].
    pub(crate) fn apply_influence_with(
        &self,
        force: &[f64],
        displacement: &mut [f64],
        spare: &mut [f64],
    ) {
        self.operator.apply(force, displacement, spare);
    }

    /// Whether the influence product sums two bodies' products (and so needs a `spare` buffer
    /// in the loops that must not allocate): not when one body is rigid, nor when the two
    /// operators are multiples of one ([`ElasticBody::influence_shape`]).
    pub fn sums_two_products(&self) -> bool {
        self.operator.sums_two_products()
    }

    /// An approximate inverse of A on the points marked in `contact` (the others unloaded),
    /// for preconditioning: writes forces on those points that roughly produce `displacement`
    /// there (zero elsewhere) and returns `true`, or `false` when neither body offers one
    /// ([`ElasticBody::precondition_on`]).
    pub fn precondition(&self, displacement: &[f64], contact: &[bool], force: &mut [f64]) -> bool {
        self.operator.precondition(displacement, contact, force)
    }

    /// Whether a body offers an approximate inverse of A ([`InterfaceProblem::precondition`]):
    /// found by applying it once to zero displacements on every point (one FFT pair on a
    /// half-space grid, nothing for a body without one).
    pub(crate) fn offers_inverse(&self) -> bool {
        let n = self.len();
        self.precondition(&vec![0.0; n], &vec![true; n], &mut vec![0.0; n])
    }

    /// The dense summed influence matrix A = A¹ + P A² Pᵀ \[mm/N\], built on the first call and
    /// shared by every problem derived from this one. `copies` is how many n × n matrices the
    /// calling solver will hold at once, this one included; the call fails with
    /// [`Error::TooLarge`] before allocating anything when they would exceed the limit
    /// ([`InterfaceProblem::with_dense_limit`]).
    pub fn dense_influence(&self, copies: u64) -> Result<&Mat<f64>> {
        self.dense
            .get_or_build(self.len(), copies, || self.operator.matrix())
    }

    /// The summed influence among a few `points`, A = A¹ + P A² Pᵀ there \[mm/N\]
    /// (`block[(a, b)]` = `A[(points[a], points[b])]`): from the dense matrix once it is built,
    /// else from both bodies' [`ElasticBody::influence_block`]. `None` when a body gives none
    /// or a point is not on the interface.
    pub fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        if points.iter().any(|&i| i >= self.len()) {
            return None;
        }
        match self.dense.built() {
            Some(a) => contopt_core::block_among(a, points),
            None => self.operator.influence_block(points),
        }
    }

    /// Initial gap h \[mm\].
    pub fn initial_gap(&self) -> &[f64] {
        &self.initial_gap
    }

    /// g = h + f¹ + f²: the gap before any contact pressure, rigid modes held \[mm\].
    pub fn free_gap(&self) -> Vec<f64> {
        let mut g = vec![0.0; self.len()];
        self.add_free_gap(&mut g);
        g
    }

    /// The free gap g = h + f¹ + f² point by point, for reading it without a buffer.
    pub(crate) fn free_gaps(&self) -> impl Iterator<Item = f64> + '_ {
        let load = self.load_gap.as_deref();
        self.initial_gap
            .iter()
            .enumerate()
            .map(move |(i, h)| h + load.map_or(0.0, |f| f[i]))
    }

    /// Adds the free gap g = h + f¹ + f² to `gap` (one value per point), for loops that must
    /// not allocate.
    pub(crate) fn add_free_gap(&self, gap: &mut [f64]) {
        for (d, h) in gap.iter_mut().zip(&self.initial_gap) {
            *d += h;
        }
        if let Some(load_gap) = &self.load_gap {
            for (d, f) in gap.iter_mut().zip(load_gap.iter()) {
                *d += f;
            }
        }
    }

    /// The free rigid modes: the columns of R (eq. 2.6) and their loads q (2.10).
    pub fn modes(&self) -> &[FreeMode] {
        self.modes.list()
    }

    /// Each body's own rigid-mode amplitudes ([`ElasticBody::rigid_modes`], in the body's
    /// order) in a solution's λ (`rigid`, one per [`InterfaceProblem::modes`]): what a body
    /// needs to place its displacement field. A mode the problem dropped (it does not move the
    /// interface and carries no load, so that contact leaves it where it is) has amplitude 0.
    ///
    /// Errors: a `rigid` of the wrong length, or a problem whose modes are no longer the
    /// bodies' ([`InterfaceProblem::with_modes`]).
    pub fn body_rigid(&self, rigid: &[f64]) -> Result<[Vec<f64>; 2]> {
        let counts = [0, 1].map(|k| self.operator.body(k).rigid_modes().len());
        self.modes.body_rigid(rigid, counts)
    }

    /// The interface displacements of the free rigid modes as a dense n × m matrix R, for the
    /// dense solvers (G_R = W R, eq. 2.10).
    pub fn rigid(&self) -> Mat<f64> {
        self.modes.matrix(self.len())
    }

    /// Load q of each free rigid mode \[N\].
    pub fn load(&self) -> Vec<f64> {
        self.modes().iter().map(|m| m.load).collect()
    }

    /// Names of the free rigid modes.
    pub fn mode_names(&self) -> Vec<String> {
        self.modes().iter().map(|m| m.name.clone()).collect()
    }

    /// Adds the rigid motion R λ to `gap`.
    pub(crate) fn add_rigid_motion(&self, rigid: &[f64], gap: &mut [f64]) {
        self.modes.add_motion(rigid, gap);
    }

    /// Gap after deformation d = g + A W p + R λ, eq. (2.7).
    pub fn gap(&self, pressure: &[f64], rigid: &[f64]) -> Vec<f64> {
        let n = self.len();
        let (mut d, mut force, mut spare) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        self.gap_with(pressure, rigid, &mut d, &mut force, &mut spare);
        d
    }

    /// [`InterfaceProblem::gap`] written to `gap`, with the caller's buffers `force` and
    /// `spare` (of n values each), for loops that must not allocate.
    pub(crate) fn gap_with(
        &self,
        pressure: &[f64],
        rigid: &[f64],
        gap: &mut [f64],
        force: &mut [f64],
        spare: &mut [f64],
    ) {
        for ((f, p), w) in force.iter_mut().zip(pressure).zip(self.weights()) {
            *f = p * w;
        }
        gap.fill(0.0);
        self.apply_influence_with(force, gap, spare);
        self.add_free_gap(gap);
        self.add_rigid_motion(rigid, gap);
    }

    /// The field the point pressures sample (see [`ElasticBody::pressure_basis`]), from the
    /// first body that has one.
    pub fn pressure_basis(&self) -> Option<&GapShape> {
        self.pressure_basis.as_deref()
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
        let equilibrium = self.modes.equilibrium(self.weights(), pressure);
        Residuals::new(equilibrium, pressure, gap)
    }
    /// Assembles a [`ContactState`] of `method` from a solution, with its gap and residuals,
    /// converged unless [`InterfaceProblem::verify`] finds it out of bounds.
    pub fn state(
        &self,
        method: Method,
        pressure: Vec<f64>,
        rigid: Vec<f64>,
        active: Vec<bool>,
        counts: [usize; 3],
    ) -> ContactState {
        let gap = self.gap(&pressure, &rigid);
        let residuals = self.residuals(&pressure, &gap);
        let mut state = ContactState {
            pressure,
            gap,
            rigid,
            active,
            iterations: counts[0],
            iterp: counts[1],
            iterd: counts[2],
            residuals,
            method,
            termination: Termination::Converged,
        };
        self.verify(&mut state);
        state
    }

    /// The largest elastic displacement of a solution, maxᵢ |dᵢ − hᵢ − (Rλ)ᵢ| \[mm\]: the
    /// scale against which its penetration is judged. `gap` is d less any gap change Δh.
    pub fn elastic_displacement(&self, gap: &[f64], rigid: &[f64]) -> f64 {
        self.elastic_displacement_in(gap, rigid, &mut vec![])
    }

    /// [`InterfaceProblem::elastic_displacement`] with the caller's buffer `scratch` (grown to
    /// n values when shorter), for solves that must not allocate.
    fn elastic_displacement_in(&self, gap: &[f64], rigid: &[f64], scratch: &mut Vec<f64>) -> f64 {
        scratch.clear();
        scratch.resize(self.len(), 0.0);
        self.add_free_gap(scratch);
        self.add_rigid_motion(rigid, scratch);
        gap.iter()
            .zip(scratch.iter())
            .fold(0.0f64, |m, (d, h)| m.max((d - h).abs()))
    }

    /// Ends (see [`ContactState::stop_if_not_finite`]) a state that holds a NaN or an
    /// infinity, or whose elastic displacement, d − h − Rλ, exceeds [`SMALL_STRAIN`] times the
    /// size of the interface (the diagonal of its points' bounding box): no linear-elastic
    /// answer, but data in the wrong units or overflowing (a modulus of 10⁻³⁰⁰ MPa). Every
    /// solver passes its result through it.
    pub fn verify(&self, state: &mut ContactState) {
        self.verify_in(state, &mut vec![]);
    }

    /// [`InterfaceProblem::verify`] with the caller's buffer `scratch` (of n values, grown
    /// when shorter), for solves that must not allocate.
    pub(crate) fn verify_in(&self, state: &mut ContactState, scratch: &mut Vec<f64>) {
        state.stop_if_not_finite();
        if !state.is_converged() || state.gap.len() != self.len() {
            return;
        }
        let elastic = self.elastic_displacement_in(&state.gap, &state.rigid, scratch);
        let size = self.interface().extent();
        if size > 0.0 && elastic > SMALL_STRAIN * size {
            state.termination = Termination::LargeDisplacement {
                displacement_mm: elastic,
                size_mm: size,
            };
        }
    }

    /// The problem over a part of the interface that holds every point marked in `keep` and
    /// whose products are cheaper (a grid's bounding box), with the indices of its points among
    /// this problem's; `None` when a body offers no such part, when the two bodies' parts differ,
    /// or when a loaded mode would lose all its points. Modes keep their loads: the points left
    /// out carry no pressure.
    pub fn restrict(&self, keep: &[bool]) -> Option<(InterfaceProblem<'static>, Vec<usize>)> {
        let (operator, index) = self.operator.restrict(keep)?;
        let modes = self.modes.on(&index)?;
        let gaps = self.gaps_mapped(Mapping::Part(&index));
        let dense = Dense::new(self.dense_limit());
        let part = InterfaceProblem::assemble(operator, modes, gaps, dense).ok()?;
        Some((part, index))
    }

    /// The cells (nx, ny) of the grid whose cells are the problem's points, x fastest: a
    /// body's that is a cell grid ([`InfluenceShape::CellGrid`]) when the bodies pair their
    /// points in order and no pressure basis stands between; else `None`.
    pub(crate) fn cell_grid(&self) -> Option<[usize; 2]> {
        if !self.operator.pairs_in_order() || self.pressure_basis.is_some() {
            return None;
        }
        (0..2)
            .find_map(|k| match self.operator.body(k).influence_shape()? {
                (InfluenceShape::CellGrid { cells, .. }, _) => Some(cells),
                _ => None,
            })
            .filter(|[nx, ny]| nx * ny == self.len())
    }

    /// The problem on coarser bodies ([`ElasticBody::coarsen`]), with the coarse point of
    /// each point (`parent`): the first body coarsens itself, the second too (grouped alike)
    /// or, without compliance, is held on the coarse surface; the gaps are the W-weighted
    /// means over each coarse point's points, each mode moves the coarse points of its points
    /// by their mean and keeps its load (modes that share a coarse point are joined). `None`
    /// when a body offers no coarser version, the two group differently, or a mode moves only
    /// part of a coarse point.
    pub fn coarsen(&self) -> Option<(InterfaceProblem<'static>, Vec<usize>)> {
        self.coarsened().map(|(coarse, parent, _)| (coarse, parent))
    }

    /// [`InterfaceProblem::coarsen`], with the total weight of each coarse point's points.
    fn coarsened(&self) -> Option<(InterfaceProblem<'static>, Vec<usize>, Vec<f64>)> {
        let (operator, parent) = self.operator.coarsen()?;
        let m = operator.body(0).interface().len();
        let w = self.weights();
        let mut total = vec![0.0; m];
        for (i, &c) in parent.iter().enumerate() {
            total[c] += w[i];
        }
        let modes = self.modes.coarse(&parent, &total, w)?;
        let gaps = self.gaps_mapped(Mapping::Coarse {
            parent: &parent,
            total: &total,
        });
        let dense = Dense::new(self.dense_limit());
        let coarse = InterfaceProblem::assemble(operator, modes, gaps, dense).ok()?;
        Some((coarse, parent, total))
    }

    /// Its gaps h and f¹ + f² at the points of another numbering, given by `mapping` (a
    /// part's, or a coarser one's means).
    fn gaps_mapped(&self, mapping: Mapping) -> Gaps {
        let w = self.weights();
        let map = |v: &[f64]| {
            let mut out = vec![];
            mapping.apply(v, w, &mut out);
            out
        };
        Gaps {
            initial: map(&self.initial_gap),
            load: self.load_gap.as_ref().map(|f| Arc::new(map(f))),
        }
    }
}

/// `scale`, a diagonal term of the influence matrix (a point's compliance), when it is
/// positive and finite; else the bodies have no compliance at the interface (or it overflowed).
pub(crate) fn compliance(scale: f64) -> Result<f64> {
    check::positive("influence", scale).map_err(|_| {
        Error::invalid(
            "influence",
            scale,
            "the bodies have no compliance at the interface (two rigid bodies?)",
        )
    })
}

/// The paired points have equal weights and opposite normals.
fn check_partners(b1: &dyn ElasticBody, b2: &dyn ElasticBody, pair: &[usize]) -> Result<()> {
    let (s1, s2) = (b1.interface(), b2.interface());
    for (i, &j) in pair.iter().enumerate() {
        let (wa, wb) = (s1.weights()[i], s2.weights()[j]);
        if (wa - wb).abs() > WEIGHT_MATCH * wa.abs().max(wb.abs()) {
            return Err(Error::InterfaceMismatch {
                index: i,
                detail: format!(
                    "weight {wa} of `{}` against {wb} of `{}`",
                    b1.name(),
                    b2.name()
                ),
            });
        }
        let (na, nb) = (s1.normals()[i], s2.normals()[j]);
        if (0..3).map(|c| (na[c] + nb[c]).abs()).fold(0.0, f64::max) > NORMAL_MATCH {
            return Err(Error::InterfaceMismatch {
                index: i,
                detail: format!("normals {na:?} and {nb:?} are not opposite"),
            });
        }
    }
    Ok(())
}
