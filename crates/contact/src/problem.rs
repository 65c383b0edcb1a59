//! The contact interface problem that two bodies define (§2.1), held as operators.

use std::sync::{Arc, OnceLock};

use contopt_core::observe::Method;
use contopt_core::{
    check, ContactState, ElasticBody, Error, GapShape, InfluenceShape, Interface, Residuals,
    Result, RigidBody, Spares, Termination,
};
use faer::linalg::solvers::{Llt, Solve};
use faer::{Mat, Side};

/// The memory the dense matrices of one solve may take unless the caller says otherwise
/// ([`InterfaceProblem::with_dense_limit`]): 2 GB, a twelfth of the 24 GB machine we plan for,
/// enough for the dense solvers up to about 8 000 interface points.
pub const DEFAULT_DENSE_LIMIT_BYTES: u64 = 2_000_000_000;

/// Relative tolerance to which two interfaces must agree in weight.
const WEIGHT_MATCH: f64 = 1e-9;
/// Largest component of n¹ + n² for normals that count as opposite.
const NORMAL_MATCH: f64 = 1e-6;

/// The elastic displacement, as a multiple of the interface's size, past which a solution is
/// refused ([`InterfaceProblem::verify`]): loose on purpose, it catches data in the wrong units
/// or overflowing, not a mildly nonlinear contact.
pub const SMALL_STRAIN: f64 = 1.0;

/// A body the problem borrows from its caller or owns (a restricted part).
enum Body<'a> {
    Borrowed(&'a dyn ElasticBody),
    Owned(Box<dyn ElasticBody + 'a>),
}

impl Body<'_> {
    fn get(&self) -> &dyn ElasticBody {
        match self {
            Body::Borrowed(b) => *b,
            Body::Owned(b) => b.as_ref(),
        }
    }
}

/// A body's influence as a multiple of a fixed operator ([`ElasticBody::influence_shape`]).
type Shape = Option<(InfluenceShape, f64)>;

/// How the summed operator A = A¹ + P A² Pᵀ is applied.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Product {
    /// A = factor·Aᵏ: the other body is rigid (factor 1), or both bodies' operators are
    /// multiples of one, paired point for point ([`ElasticBody::influence_shape`]); one product.
    One { body: usize, factor: f64 },
    /// A = Aᵏ + `added`·A₀: the other body's operator is `added` times the fixed one A₀ that
    /// body k's contains ([`ElasticBody::base_shape`]), paired point for point; body k adds it
    /// inside its own product ([`ElasticBody::apply_influence_adding`]), one product.
    Adding { body: usize, added: f64 },
    /// Both bodies' products, summed.
    Both,
}

impl Product {
    /// The product that two bodies' shapes and base shapes allow (`identity`: paired point
    /// for point).
    fn of(shapes: [Shape; 2], bases: [Shape; 2], identity: bool) -> Self {
        // Body k's base holds the other's whole operator: the shape it names, a positive scale.
        let adding = |k: usize| match (bases[k], shapes[1 - k]) {
            (Some((base, scale)), Some((shape, added)))
                if identity && base == shape && scale > 0.0 && added > 0.0 =>
            {
                Some(Product::Adding { body: k, added })
            }
            _ => None,
        };
        let pure = Product::pure(shapes, identity);
        match pure {
            Product::Both => adding(1).or_else(|| adding(0)).unwrap_or(Product::Both),
            _ => pure,
        }
    }

    /// The product that two bodies' shapes allow: one when a body is rigid or both are
    /// multiples of one operator.
    fn pure(shapes: [Shape; 2], identity: bool) -> Self {
        match shapes {
            [_, Some((_, 0.0))] => Product::One {
                body: 0,
                factor: 1.0,
            },
            [Some((_, 0.0)), _] => Product::One {
                body: 1,
                factor: 1.0,
            },
            [Some((shape1, c1)), Some((shape2, c2))]
                if identity && shape1 == shape2 && c1 > 0.0 =>
            {
                Product::One {
                    body: 0,
                    factor: (c1 + c2) / c1,
                }
            }
            _ => Product::Both,
        }
    }
}

/// The second body's vectors in its own numbering.
struct Scratch {
    input: Vec<f64>,
    output: Vec<f64>,
    contact: Vec<bool>,
}

impl Scratch {
    /// The vectors of `n` points.
    fn new(n: usize) -> Self {
        Self {
            input: vec![0.0; n],
            output: vec![0.0; n],
            contact: vec![false; n],
        }
    }
}

/// The summed influence operator A = A¹ + P A² Pᵀ of the two bodies through their point
/// pairing P, with the buffers its products reuse and the dense matrix once it is asked for.
struct Operator<'a> {
    bodies: [Body<'a>; 2],
    /// `pair[i]`: the index of point i among the second body's points; `None` for the identity.
    pair: Option<Vec<usize>>,
    /// The second body's input and output, and the contact set, in its own numbering (only
    /// with a pairing), a set per product running at once.
    scratch: Option<Spares<Scratch>>,
    dense: OnceLock<Mat<f64>>,
    /// Each body's share of the compliance at the first point, (Aᵏ)₀₀ / A₀₀ (a uniform load
    /// moves a periodic grid not at all), for the preconditioner.
    shares: OnceLock<[f64; 2]>,
    product: Product,
}

impl Operator<'_> {
    /// `map(body, input, output)` in the body's own numbering, with `input` and `output` in the
    /// first body's: the second body's points are permuted through the pairing P.
    /// `map(body, input, contact, output)` in the body's own numbering, with `input`,
    /// `contact` and `output` in the first body's: the second body's points are permuted
    /// through the pairing P.
    fn in_own_numbering<T>(
        &self,
        body: usize,
        input: &[f64],
        contact: &[bool],
        output: &mut [f64],
        map: impl FnOnce(&dyn ElasticBody, &[f64], &[bool], &mut [f64]) -> T,
    ) -> T {
        let b = self.bodies[body].get();
        match (&self.pair, &self.scratch, body) {
            (Some(pair), Some(scratch), 1) => scratch.with(
                || Scratch::new(pair.len()),
                |scratch| {
                    let Scratch {
                        input: own_in,
                        output: own_out,
                        contact: own_contact,
                    } = scratch;
                    for (i, &j) in pair.iter().enumerate() {
                        own_in[j] = input[i];
                    }
                    if !contact.is_empty() {
                        for (i, &j) in pair.iter().enumerate() {
                            own_contact[j] = contact[i];
                        }
                    }
                    let result = map(b, own_in, own_contact, own_out);
                    for (i, &j) in pair.iter().enumerate() {
                        output[i] = own_out[j];
                    }
                    result
                },
            ),
            _ => map(b, input, contact, output),
        }
    }

    /// `out = A¹ force` (first body) or `out = P A² Pᵀ force` (second).
    fn apply_one(&self, body: usize, force: &[f64], out: &mut [f64]) {
        self.in_own_numbering(body, force, &[], out, |b, f, _, o| b.apply_influence(f, o));
    }

    fn apply(&self, force: &[f64], out: &mut [f64], spare: &mut [f64]) {
        match self.product {
            Product::One { body, factor } => {
                self.apply_one(body, force, out);
                if factor != 1.0 {
                    out.iter_mut().for_each(|u| *u *= factor);
                }
            }
            Product::Adding { body, added } => {
                self.in_own_numbering(body, force, &[], out, |b, f, _, o| {
                    b.apply_influence_adding(f, added, o)
                });
            }
            Product::Both => {
                self.apply_one(0, force, out);
                self.apply_one(1, force, spare);
                for (o, s) in out.iter_mut().zip(spare.iter()) {
                    *o += s;
                }
            }
        }
    }

    fn shares(&self, n: usize) -> [f64; 2] {
        if let Product::One { body, factor } = self.product {
            let mut shares = [0.0; 2];
            shares[body] = 1.0 / factor;
            return shares;
        }
        *self.shares.get_or_init(|| {
            let (mut unit, mut u) = (vec![0.0; n], vec![0.0; n]);
            unit[0] = 1.0;
            let mut total = [0.0; 2];
            for (body, t) in total.iter_mut().enumerate() {
                self.apply_one(body, &unit, &mut u);
                *t = u[0].max(0.0);
            }
            let sum = total[0] + total[1];
            if sum > 0.0 {
                total.map(|t| t / sum)
            } else {
                [0.0; 2]
            }
        })
    }

    /// Approximate inverse on the set `contact`: the first body's (or else the second's)
    /// scaled by its share of the compliance, exact when the kernels are proportional (two
    /// half-spaces on one grid, or a half-space against a rigid body).
    fn precondition(&self, displacement: &[f64], contact: &[bool], force: &mut [f64]) -> bool {
        let shares = self.shares(displacement.len());
        for (body, &share) in shares.iter().enumerate() {
            if share <= 0.0 {
                continue;
            }
            let done = self.in_own_numbering(body, displacement, contact, force, |b, d, c, f| {
                b.precondition_on(d, c, f)
            });
            if done {
                if share != 1.0 {
                    force.iter_mut().for_each(|f| *f *= share);
                }
                return true;
            }
        }
        false
    }
}

/// A free rigid-body mode of the interface problem: the normal displacement it gives the
/// points it moves per unit amplitude (a column of R, eq. 2.6, stored by its non-zeros) and the
/// load q it must balance, Σᵢ wᵢ rᵢ pᵢ = −q (2.10).
#[derive(Clone, Debug, PartialEq)]
pub struct FreeMode {
    /// A short name for messages.
    pub name: String,
    /// The points it moves.
    pub points: Vec<usize>,
    /// Their normal displacement into the body per unit amplitude, rᵢ.
    pub displacement: Vec<f64>,
    /// The work q of the given loads on the mode \[N\].
    pub load: f64,
}

impl FreeMode {
    /// Σᵢ wᵢ rᵢ pᵢ over the mode's points: the force the pressure `p` puts on it \[N\].
    pub fn force(&self, weights: &[f64], pressure: &[f64]) -> f64 {
        self.points
            .iter()
            .zip(&self.displacement)
            .map(|(&i, r)| weights[i] * r * pressure[i])
            .sum()
    }
}

/// What a problem holds besides its bodies and their pairing.
struct Parts {
    load_gap: Option<Arc<Vec<f64>>>,
    modes: Arc<Vec<FreeMode>>,
    owners: Option<Arc<Vec<[usize; 2]>>>,
    initial_gap: Vec<f64>,
    dense_limit: u64,
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
    interface: Arc<Interface>,
    /// f¹ + f², the displacements under the bodies' own loads; `None` when they are zero.
    load_gap: Option<Arc<Vec<f64>>>,
    modes: Arc<Vec<FreeMode>>,
    /// Whose each of `modes` is: (body, its index among the body's rigid modes); `None` once
    /// [`InterfaceProblem::with_modes`] replaced them.
    owners: Option<Arc<Vec<[usize; 2]>>>,
    pressure_basis: Option<Arc<GapShape>>,
    initial_gap: Vec<f64>,
    dense_limit: u64,
}

impl std::fmt::Debug for InterfaceProblem<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("InterfaceProblem")
            .field("points", &self.len())
            .field(
                "bodies",
                &self
                    .operator
                    .bodies
                    .each_ref()
                    .map(|b| b.get().name().to_string()),
            )
            .field("modes", &self.modes)
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
        let n = s1.len();
        check::gap(initial_gap, n)?;
        let f1 = b1.load_displacement()?;
        let f2 = b2.load_displacement()?;
        let load_gap: Vec<f64> = (0..n).map(|i| f1[i] + f2[pair[i]]).collect();
        let load_gap = load_gap
            .iter()
            .any(|&f| f != 0.0)
            .then(|| Arc::new(load_gap));
        let (modes, owners) = free_modes(b1, b2, &pair)?;
        let parts = Parts {
            load_gap,
            modes: Arc::new(modes),
            owners: Some(Arc::new(owners)),
            initial_gap: initial_gap.to_vec(),
            dense_limit: DEFAULT_DENSE_LIMIT_BYTES,
        };
        Self::assemble(bodies, pair, parts)
    }

    /// The problem of `bodies`, paired by `pair`, with the rest given.
    fn assemble(bodies: [Body<'a>; 2], pair: Vec<usize>, parts: Parts) -> Result<Self> {
        let (b1, b2) = (bodies[0].get(), bodies[1].get());
        let n = pair.len();
        let pressure_basis = match (b1.pressure_basis(), b2.pressure_basis()) {
            (Some(b), _) => Some(b.clone()),
            (None, Some(b)) => Some(GapShape::new(
                b.nodes().to_vec(),
                pair.iter().map(|&j| b.row(j).to_vec()).collect(),
            )?),
            (None, None) => None,
        };
        let interface = Arc::new(b1.interface().clone());
        let identity = pair.iter().enumerate().all(|(i, &j)| i == j);
        let product = Product::of(
            [b1.influence_shape(), b2.influence_shape()],
            [b1.base_shape(), b2.base_shape()],
            identity,
        );
        let operator = Operator {
            product,
            scratch: (!identity).then(|| Spares::new(Scratch::new(n))),
            pair: (!identity).then_some(pair),
            bodies,
            dense: OnceLock::new(),
            shares: OnceLock::new(),
        };
        Ok(Self {
            interface,
            operator: Arc::new(operator),
            load_gap: parts.load_gap,
            modes: parts.modes,
            owners: parts.owners,
            pressure_basis: pressure_basis.map(Arc::new),
            initial_gap: parts.initial_gap,
            dense_limit: parts.dense_limit,
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
        self.dense_limit = bytes;
        self
    }

    /// The memory limit for dense matrices \[bytes\].
    pub fn dense_limit(&self) -> u64 {
        self.dense_limit
    }

    /// The same problem with other free modes: `modes` replace the bodies' rigid modes. The
    /// optimiser gives each design column of a gap shape its own translation and load this way
    /// (the column approaches are then the multipliers of a contact solve).
    pub fn with_modes(&self, modes: Vec<FreeMode>) -> Result<Self> {
        let n = self.len();
        for mode in &modes {
            if mode.points.len() != mode.displacement.len() {
                return Err(Error::invalid(
                    format!("mode `{}`", mode.name),
                    format!(
                        "{} points, {} values",
                        mode.points.len(),
                        mode.displacement.len()
                    ),
                    "one displacement per point",
                ));
            }
            if let Some(k) = mode.points.iter().position(|&i| i >= n) {
                return Err(Error::invalid(
                    format!("mode `{}`.points[{k}]", mode.name),
                    mode.points[k],
                    format!("an interface point below {n}"),
                ));
            }
            check::finite(&format!("mode `{}`.load", mode.name), mode.load)?;
            check::all_finite(
                &format!("mode `{}`.displacement", mode.name),
                &mode.displacement,
            )?;
        }
        Ok(Self {
            modes: Arc::new(modes),
            owners: None,
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
        let mut spare = if self.sums_two_products() {
            vec![0.0; force.len()]
        } else {
            vec![]
        };
        self.operator.apply(force, displacement, &mut spare);
    }

    /// As [`InterfaceProblem::apply_influence`] with a caller's buffer `spare` of the same
    /// length, for loops that must not allocate; it may be empty unless
    /// [`InterfaceProblem::sums_two_products`].
    pub fn apply_influence_with(&self, force: &[f64], displacement: &mut [f64], spare: &mut [f64]) {
        self.operator.apply(force, displacement, spare);
    }

    /// Whether the influence product sums two bodies' products (and so needs a `spare` buffer
    /// in [`InterfaceProblem::apply_influence_with`]): not when one body is rigid, nor when the
    /// two operators are multiples of one ([`ElasticBody::influence_shape`]).
    pub fn sums_two_products(&self) -> bool {
        self.operator.product == Product::Both
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
    pub fn offers_inverse(&self) -> bool {
        let n = self.len();
        self.precondition(&vec![0.0; n], &vec![true; n], &mut vec![0.0; n])
    }

    /// The dense summed influence matrix A = A¹ + P A² Pᵀ \[mm/N\], built on the first call and
    /// shared by every problem derived from this one. `copies` is how many n × n matrices the
    /// calling solver will hold at once, this one included; the call fails with
    /// [`Error::TooLarge`] before allocating anything when they would exceed the limit
    /// ([`InterfaceProblem::with_dense_limit`]).
    pub fn dense_influence(&self, copies: u64) -> Result<&Mat<f64>> {
        let n = self.len() as u64;
        // Building the matrix holds both bodies' matrices and their sum.
        let bytes = n
            .checked_mul(n)
            .and_then(|e| e.checked_mul(8 * copies.max(3)))
            .unwrap_or(u64::MAX);
        if bytes > self.dense_limit {
            return Err(Error::TooLarge {
                what: format!(
                    "a dense {n} × {n} influence matrix ({} copies)",
                    copies.max(3)
                ),
                bytes,
                limit: self.dense_limit,
                advice: "use the matrix-free solver (polonsky_keer) and the load split, or raise \
                         the limit (dense_limit_mb)"
                    .into(),
            });
        }
        Ok(self.operator.dense.get_or_init(|| self.build_dense()))
    }

    /// The summed influence among a few `points`, A = A¹ + P A² Pᵀ there \[mm/N\]
    /// (`block[(a, b)]` = `A[(points[a], points[b])]`): from the dense matrix once it is built,
    /// else from both bodies' [`ElasticBody::influence_block`]. `None` when a body gives none
    /// or a point is not on the interface.
    pub fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        if points.iter().any(|&i| i >= self.len()) {
            return None;
        }
        let op = &self.operator;
        if let Some(a) = op.dense.get() {
            return contopt_core::block_among(a, points);
        }
        let first = op.bodies[0].get().influence_block(points)?;
        let second = match &op.pair {
            None => op.bodies[1].get().influence_block(points)?,
            Some(pair) => {
                let own: Vec<usize> = points.iter().map(|&i| pair[i]).collect();
                op.bodies[1].get().influence_block(&own)?
            }
        };
        Some(first + second)
    }

    fn build_dense(&self) -> Mat<f64> {
        let op = &self.operator;
        let mut a = op.bodies[0].get().influence_matrix();
        let a2 = op.bodies[1].get().influence_matrix();
        let n = self.len();
        for j in 0..n {
            for i in 0..n {
                a[(i, j)] += match &op.pair {
                    None => a2[(i, j)],
                    Some(pair) => a2[(pair[i], pair[j])],
                };
            }
        }
        a
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

    /// Adds the free gap g = h + f¹ + f² to `gap` (one value per point), for loops that must
    /// not allocate.
    pub fn add_free_gap(&self, gap: &mut [f64]) {
        for (d, h) in gap.iter_mut().zip(&self.initial_gap) {
            *d += h;
        }
        if let Some(load_gap) = &self.load_gap {
            for (d, f) in gap.iter_mut().zip(load_gap.iter()) {
                *d += f;
            }
        }
    }

    /// The free rigid modes.
    pub fn modes(&self) -> &[FreeMode] {
        &self.modes
    }

    /// Each body's own rigid-mode amplitudes ([`ElasticBody::rigid_modes`], in the body's
    /// order) in a solution's λ (`rigid`, one per [`InterfaceProblem::modes`]): what a body
    /// needs to place its displacement field. A mode the problem dropped (it does not move the
    /// interface and carries no load, so that contact leaves it where it is) has amplitude 0.
    ///
    /// Errors: a `rigid` of the wrong length, or a problem whose modes are no longer the
    /// bodies' ([`InterfaceProblem::with_modes`]).
    pub fn body_rigid(&self, rigid: &[f64]) -> Result<[Vec<f64>; 2]> {
        let Some(owners) = &self.owners else {
            return Err(Error::invalid(
                "rigid",
                "the modes of with_modes",
                "the problem's modes are not its bodies' rigid modes",
            ));
        };
        if rigid.len() != self.modes.len() {
            return Err(Error::invalid(
                "rigid.len()",
                rigid.len(),
                format!("one amplitude per free mode ({})", self.modes.len()),
            ));
        }
        let mut own = self
            .operator
            .bodies
            .each_ref()
            .map(|b| vec![0.0; b.get().rigid_modes().len()]);
        for (&[body, mode], &lambda) in owners.iter().zip(rigid) {
            own[body][mode] = lambda;
        }
        Ok(own)
    }

    /// The interface displacements of the free rigid modes as a dense n × m matrix R, for the
    /// dense solvers.
    pub fn rigid(&self) -> Mat<f64> {
        let mut r = Mat::zeros(self.len(), self.modes.len());
        for (k, mode) in self.modes.iter().enumerate() {
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                r[(i, k)] = v;
            }
        }
        r
    }

    /// Load q of each free rigid mode \[N\].
    pub fn load(&self) -> Vec<f64> {
        self.modes.iter().map(|m| m.load).collect()
    }

    /// Names of the free rigid modes.
    pub fn mode_names(&self) -> Vec<String> {
        self.modes.iter().map(|m| m.name.clone()).collect()
    }

    /// Adds the rigid motion R λ to `gap`.
    pub fn add_rigid_motion(&self, rigid: &[f64], gap: &mut [f64]) {
        for (mode, &l) in self.modes.iter().zip(rigid) {
            for (&i, &r) in mode.points.iter().zip(&mode.displacement) {
                gap[i] += r * l;
            }
        }
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
        let w = self.weights();
        let equilibrium = self
            .modes
            .iter()
            .map(|m| (m.force(w, pressure) + m.load).abs())
            .fold(0.0, f64::max);
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
    pub fn restrict(&self, keep: &[bool]) -> Option<(InterfaceProblem<'a>, Vec<usize>)> {
        let op = &self.operator;
        let (part1, index) = op.bodies[0].get().restrict(keep)?;
        let part2 = self.second_part(part1.interface(), &index)?;
        let pair = part1
            .interface()
            .partners(part2.interface(), part1.name(), part2.name())
            .ok()?;
        let modes = self.modes_on(&index)?;
        let parts = Parts {
            load_gap: self
                .load_gap
                .as_ref()
                .map(|f| Arc::new(index.iter().map(|&i| f[i]).collect())),
            modes: Arc::new(modes),
            owners: None,
            initial_gap: index.iter().map(|&i| self.initial_gap[i]).collect(),
            dense_limit: self.dense_limit,
        };
        let part = Self::assemble([Body::Owned(part1), Body::Owned(part2)], pair, parts).ok()?;
        Some((part, index))
    }

    /// The problem on coarser bodies ([`ElasticBody::coarsen`]), with the coarse point of
    /// each point (`parent`): the first body coarsens itself, the second too (grouped alike)
    /// or, without compliance, is held on the coarse surface; the gaps are the W-weighted
    /// means over each coarse point's points, each mode moves the coarse points of its points
    /// by their mean and keeps its load (modes that share a coarse point are joined). `None`
    /// when a body offers no coarser version, the two group differently, or a mode moves only
    /// part of a coarse point.
    pub fn coarsen(&self) -> Option<(InterfaceProblem<'a>, Vec<usize>)> {
        let op = &self.operator;
        let (coarse1, parent) = op.bodies[0].get().coarsen()?;
        let second = op.bodies[1].get();
        let coarse2: Box<dyn ElasticBody + 'a> = if matches!(second.influence_shape(), Some((_, c)) if c == 0.0)
        {
            Box::new(RigidBody::fixed(second.name(), coarse1.interface()))
        } else {
            let (coarse2, parent2) = second.coarsen()?;
            (op.pair.is_none() && parent2 == parent).then_some(coarse2)?
        };
        let pair = coarse1
            .interface()
            .partners(coarse2.interface(), coarse1.name(), coarse2.name())
            .ok()?;
        let m = coarse1.interface().len();
        let w = self.weights();
        let mut total = vec![0.0; m];
        for (i, &c) in parent.iter().enumerate() {
            total[c] += w[i];
        }
        let mean = |v: &[f64]| {
            let mut sum = vec![0.0; m];
            for (i, &c) in parent.iter().enumerate() {
                sum[c] += w[i] * v[i];
            }
            sum.iter()
                .zip(&total)
                .map(|(s, t)| s / t)
                .collect::<Vec<f64>>()
        };
        let parts = Parts {
            load_gap: self.load_gap.as_ref().map(|f| Arc::new(mean(f))),
            modes: Arc::new(self.coarse_modes(&parent, &total)?),
            owners: None,
            initial_gap: mean(&self.initial_gap),
            dense_limit: self.dense_limit,
        };
        let coarse =
            Self::assemble([Body::Owned(coarse1), Body::Owned(coarse2)], pair, parts).ok()?;
        Some((coarse, parent))
    }

    /// The modes on the coarse points of `parent` (of W-weights `total`): each moves a coarse
    /// point by the W-mean of its points' rᵢ. Modes that share a coarse point become one,
    /// carrying their loads' sum (the optimiser's design columns, two to a coarse column):
    /// the coarse solution is only a start, whose pressure the fine solve rescales to each
    /// mode's own load. `None` when a mode moves only some of a coarse point's points.
    fn coarse_modes(&self, parent: &[usize], total: &[f64]) -> Option<Vec<FreeMode>> {
        let w = self.weights();
        let m = total.len();
        let group = self.mode_groups(parent, m);
        let mut merged: Vec<Option<FreeMode>> = vec![None; self.modes.len()];
        let (mut moved, mut covered) = (vec![0.0; m], vec![0.0; m]);
        let mut seen = vec![false; m];
        for (k, mode) in self.modes.iter().enumerate() {
            let into = merged[group[k]].get_or_insert_with(|| FreeMode {
                name: mode.name.clone(),
                points: vec![],
                displacement: vec![],
                load: 0.0,
            });
            into.load += mode.load;
            for (&i, &r) in mode.points.iter().zip(&mode.displacement) {
                let c = parent[i];
                if !seen[c] {
                    seen[c] = true;
                    into.points.push(c);
                }
                moved[c] += w[i] * r;
                covered[c] += w[i];
            }
        }
        let modes: Vec<FreeMode> = merged.into_iter().flatten().collect();
        for mode in &modes {
            if mode
                .points
                .iter()
                .any(|&c| (covered[c] - total[c]).abs() > WEIGHT_MATCH * total[c])
            {
                return None;
            }
        }
        Some(
            modes
                .into_iter()
                .map(|mode| FreeMode {
                    displacement: mode.points.iter().map(|&c| moved[c] / covered[c]).collect(),
                    ..mode
                })
                .collect(),
        )
    }

    /// The group of each mode: its first's index among the modes joined to it through shared
    /// coarse points (of `m`, by `parent`), a union–find.
    fn mode_groups(&self, parent: &[usize], m: usize) -> Vec<usize> {
        fn root(group: &mut [usize], mut k: usize) -> usize {
            while group[k] != k {
                group[k] = group[group[k]];
                k = group[k];
            }
            k
        }
        let mut group: Vec<usize> = (0..self.modes.len()).collect();
        let mut owner = vec![usize::MAX; m];
        for (k, mode) in self.modes.iter().enumerate() {
            for &i in &mode.points {
                let c = parent[i];
                if owner[c] == usize::MAX {
                    owner[c] = k;
                } else {
                    let (a, b) = (root(&mut group, owner[c]), root(&mut group, k));
                    group[a.max(b)] = a.min(b);
                }
            }
        }
        (0..group.len()).map(|k| root(&mut group, k)).collect()
    }

    /// The second body over the points `index` of the first (whose part has the surface
    /// `surface`): a body without compliance ([`ElasticBody::influence_shape`] of scale 0) is
    /// held there, on that surface (its modes are the problem's); another restricts itself to
    /// the same points, or `None`.
    fn second_part(
        &self,
        surface: &Interface,
        index: &[usize],
    ) -> Option<Box<dyn ElasticBody + 'a>> {
        let second = self.operator.bodies[1].get();
        if matches!(second.influence_shape(), Some((_, c)) if c == 0.0) {
            return Some(Box::new(RigidBody::fixed(second.name(), surface)));
        }
        let to_second = |i: usize| self.operator.pair.as_ref().map_or(i, |p| p[i]);
        let mut keep2 = vec![false; second.interface().len()];
        for &i in index {
            keep2[to_second(i)] = true;
        }
        let (part2, mut index2) = second.restrict(&keep2)?;
        let mut wanted: Vec<usize> = index.iter().map(|&i| to_second(i)).collect();
        wanted.sort_unstable();
        index2.sort_unstable();
        (wanted == index2).then_some(part2)
    }

    /// The free modes over the points `index` (renumbered), with their loads: the points left
    /// out carry no pressure. `None` when a loaded mode would lose all its points.
    fn modes_on(&self, index: &[usize]) -> Option<Vec<FreeMode>> {
        let sorted: Option<Vec<(usize, usize)>> = (!index.is_sorted()).then(|| {
            let mut s: Vec<(usize, usize)> = index.iter().copied().zip(0..).collect();
            s.sort_unstable();
            s
        });
        let position = |i: usize| match &sorted {
            None => index.binary_search(&i).ok(),
            Some(s) => s.binary_search_by_key(&i, |&(k, _)| k).ok().map(|k| s[k].1),
        };
        let mut modes = Vec::with_capacity(self.modes.len());
        for mode in self.modes.iter() {
            let (points, displacement): (Vec<usize>, Vec<f64>) = mode
                .points
                .iter()
                .zip(&mode.displacement)
                .filter_map(|(&i, &r)| position(i).map(|a| (a, r)))
                .unzip();
            if points.is_empty() && mode.load != 0.0 {
                return None;
            }
            modes.push(FreeMode {
                name: mode.name.clone(),
                points,
                displacement,
                load: mode.load,
            });
        }
        Some(modes)
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

/// Relative size below which a mode's interface displacement counts as zero (it does not move
/// the interface) or of one sign.
const MODE_ZERO: f64 = 1e-12;
/// A load on a mode that does not move the interface counts as zero below this fraction of
/// the mode's weighted size (at least 1 N): round-off of the load's work.
const UNCARRIED_LOAD: f64 = 1e-9;
/// Two modes move the interface alike when the Gram matrix's pivot falls below this fraction
/// of its diagonal (round-off: the modes are numerically dependent).
const MODE_INDEPENDENCE: f64 = 1e-10;

/// The bodies' rigid modes in the first body's numbering, with the ones that do not move the
/// interface dropped (and refused when loaded), loads that pull the bodies apart refused, and
/// modes that move the interface alike refused.
fn free_modes(
    b1: &dyn ElasticBody,
    b2: &dyn ElasticBody,
    pair: &[usize],
) -> Result<(Vec<FreeMode>, Vec<[usize; 2]>)> {
    let n = pair.len();
    let w = b1.interface().weights();
    let identity: Vec<usize> = (0..n).collect();
    let (mut kept, mut owners) = (vec![], vec![]);
    for (k, (b, order)) in [(b1, identity.as_slice()), (b2, pair)]
        .into_iter()
        .enumerate()
    {
        for (j, m) in b.rigid_modes().iter().enumerate() {
            let r: Vec<f64> = order.iter().map(|&j| m.interface_displacement[j]).collect();
            let name = format!("{} of `{}`", m.name, b.name());
            let q = m.load;
            let span = r.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            let total = r.iter().zip(w).map(|(v, w)| (v * w).abs()).sum::<f64>();
            if span < MODE_ZERO {
                if q.abs() > UNCARRIED_LOAD * total.max(1.0) {
                    return Err(Error::invalid(format!("load on {name}"), q, "cannot be equilibrated by normal contact: the mode does not move the interface"));
                }
                continue;
            }
            let all_pos = r.iter().all(|v| *v >= -MODE_ZERO * span);
            let all_neg = r.iter().all(|v| *v <= MODE_ZERO * span);
            if (all_pos && q > 0.0) || (all_neg && q < 0.0) {
                return Err(Error::invalid(
                    format!("load on {name}"),
                    q,
                    "pulls the bodies apart: compressive contact cannot carry it",
                ));
            }
            if q == 0.0 && (all_pos || all_neg) {
                return Err(Error::invalid(
                    format!("load on {name}"),
                    q,
                    "is zero: the floating body is not pressed into contact",
                ));
            }
            let (points, displacement) = r
                .iter()
                .enumerate()
                .filter(|(_, v)| **v != 0.0)
                .map(|(i, &v)| (i, v))
                .unzip();
            kept.push(FreeMode {
                name,
                points,
                displacement,
                load: q,
            });
            owners.push([k, j]);
        }
    }
    check_independent(&kept, w)?;
    Ok((kept, owners))
}

/// Two modes that move the interface alike leave λ undetermined.
fn check_independent(modes: &[FreeMode], w: &[f64]) -> Result<()> {
    let m = modes.len();
    if m < 2 {
        return Ok(());
    }
    let dense: Vec<Vec<f64>> = modes
        .iter()
        .map(|mode| {
            let mut r = vec![0.0; w.len()];
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                r[i] = v;
            }
            r
        })
        .collect();
    let gram = Mat::from_fn(m, m, |a, b| {
        (0..w.len())
            .map(|i| dense[a][i] * dense[b][i] * w[i])
            .sum::<f64>()
    });
    let independent = Llt::new(gram.as_ref(), Side::Lower)
        .is_ok_and(|l| (0..m).all(|k| l.L()[(k, k)].powi(2) > MODE_INDEPENDENCE * gram[(k, k)]));
    if !independent {
        let names: Vec<&str> = modes.iter().map(|k| k.name.as_str()).collect();
        return Err(Error::invalid(
            "rigid modes",
            names.join(", "),
            "move the interface alike: support one of the bodies",
        ));
    }
    Ok(())
}
