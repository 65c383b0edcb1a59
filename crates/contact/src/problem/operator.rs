//! The summed influence operator of two bodies, A = A¹ + P A² Pᵀ through their point pairing
//! P (H = W A W of eqs. 2.8–2.15, with H = H¹ + H²), applied as products, never a matrix.

use contopt_core::{ElasticBody, InfluenceShape, Interface, RigidBody, Spares};
use faer::Mat;
use std::sync::OnceLock;

/// A body the operator borrows from its caller or owns (a restricted or coarser part).
pub(super) enum Body<'a> {
    Borrowed(&'a dyn ElasticBody),
    Owned(Box<dyn ElasticBody + 'a>),
}

impl Body<'_> {
    /// The body.
    pub(super) fn get(&self) -> &dyn ElasticBody {
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
        match Product::pure(shapes, identity) {
            Product::Both => adding(1).or_else(|| adding(0)).unwrap_or(Product::Both),
            pure => pure,
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

/// The summed influence operator A = A¹ + P A² Pᵀ \[mm/N\] of two bodies through their point
/// pairing P (eq. 2.7's A; the paper's H = W A W, 2.12), with the buffers its products reuse.
/// Two bodies whose operators are multiples of one ([`ElasticBody::influence_shape`], a typed
/// [`InfluenceShape`]) cost one product; a rigid body costs none.
///
/// An interface problem shares its operator with the problems derived from it (another gap,
/// other modes); a restricted or coarser problem has an operator of its own, over its bodies'
/// parts ([`Operator::restrict`], [`Operator::coarsen`]).
pub(super) struct Operator<'a> {
    bodies: [Body<'a>; 2],
    /// `pair[i]`: the index of point i among the second body's points; `None` for the identity.
    pair: Option<Vec<usize>>,
    /// The second body's input and output, and the contact set, in its own numbering (only
    /// with a pairing), a set per product running at once.
    scratch: Option<Spares<Scratch>>,
    /// Each body's share of the compliance at the first point, (Aᵏ)₀₀ / A₀₀ (a uniform load
    /// moves a periodic grid not at all), for the preconditioner.
    shares: OnceLock<[f64; 2]>,
    product: Product,
}

impl<'a> Operator<'a> {
    /// The operator of `bodies`, the second's points paired to the first's by `pair`.
    pub(super) fn new(bodies: [Body<'a>; 2], pair: Vec<usize>) -> Self {
        let identity = pair.iter().enumerate().all(|(i, &j)| i == j);
        let (b1, b2) = (bodies[0].get(), bodies[1].get());
        let product = Product::of(
            [b1.influence_shape(), b2.influence_shape()],
            [b1.base_shape(), b2.base_shape()],
            identity,
        );
        Self {
            product,
            scratch: (!identity).then(|| Spares::new(Scratch::new(pair.len()))),
            pair: (!identity).then_some(pair),
            bodies,
            shares: OnceLock::new(),
        }
    }

    /// Body k (0 or 1).
    pub(super) fn body(&self, k: usize) -> &dyn ElasticBody {
        self.bodies[k].get()
    }

    /// Whether the second body's points are the first's, in the same order.
    pub(super) fn pairs_in_order(&self) -> bool {
        self.pair.is_none()
    }

    /// The index among the second body's points of the first's point i.
    pub(super) fn to_second(&self, i: usize) -> usize {
        self.pair.as_ref().map_or(i, |p| p[i])
    }

    /// Whether a product sums two bodies' products (and so needs a `spare` buffer in
    /// [`Operator::apply`]).
    pub(super) fn sums_two_products(&self) -> bool {
        self.product == Product::Both
    }

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
        let b = self.body(body);
        let (Some(pair), Some(scratch), 1) = (&self.pair, &self.scratch, body) else {
            return map(b, input, contact, output);
        };
        scratch.with(
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
        )
    }

    /// `out = A¹ force` (first body) or `out = P A² Pᵀ force` (second).
    fn apply_one(&self, body: usize, force: &[f64], out: &mut [f64]) {
        self.in_own_numbering(body, force, &[], out, |b, f, _, o| b.apply_influence(f, o));
    }

    /// `out = A force`, with `spare` (of `force`'s length, or empty unless
    /// [`Operator::sums_two_products`]) for the second product.
    pub(super) fn apply(&self, force: &[f64], out: &mut [f64], spare: &mut [f64]) {
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
    /// half-spaces on one grid, or a half-space against a rigid body); `false` when neither
    /// body offers one ([`ElasticBody::precondition_on`]).
    pub(super) fn precondition(
        &self,
        displacement: &[f64],
        contact: &[bool],
        force: &mut [f64],
    ) -> bool {
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

    /// A among a few `points` from both bodies' [`ElasticBody::influence_block`]; `None` when
    /// a body gives none.
    pub(super) fn influence_block(&self, points: &[usize]) -> Option<Mat<f64>> {
        let first = self.body(0).influence_block(points)?;
        let own: Vec<usize> = points.iter().map(|&i| self.to_second(i)).collect();
        let second = self.body(1).influence_block(&own)?;
        Some(first + second)
    }

    /// The dense matrix A (n × n): both bodies' [`ElasticBody::influence_matrix`], summed
    /// through the pairing.
    pub(super) fn matrix(&self) -> Mat<f64> {
        let mut a = self.body(0).influence_matrix();
        let a2 = self.body(1).influence_matrix();
        let n = a.nrows();
        for j in 0..n {
            for i in 0..n {
                a[(i, j)] += a2[(self.to_second(i), self.to_second(j))];
            }
        }
        a
    }

    /// Whether the second body has no compliance (a scale of 0): it is then held on any
    /// surface of the first, its parts rigid bodies.
    fn second_is_rigid(&self) -> bool {
        matches!(self.body(1).influence_shape(), Some((_, c)) if c == 0.0)
    }

    /// The operator over a part of the interface that holds every point marked in `keep`
    /// and whose products are cheaper (the first body's [`ElasticBody::restrict`]), with the
    /// indices of its points; `None` when a body offers no such part or the two bodies' parts
    /// differ.
    pub(super) fn restrict(&self, keep: &[bool]) -> Option<(Operator<'static>, Vec<usize>)> {
        let (part1, index) = self.body(0).restrict(keep)?;
        let part2 = self.second_part(part1.interface(), &index)?;
        let pair = part1
            .interface()
            .partners(part2.interface(), part1.name(), part2.name())
            .ok()?;
        Some((
            Operator::new([Body::Owned(part1), Body::Owned(part2)], pair),
            index,
        ))
    }

    /// The second body over the points `index` of the first (whose part has the surface
    /// `surface`): a body without compliance is held there, on that surface (its modes are
    /// the problem's); another restricts itself to the same points, or `None`.
    fn second_part(&self, surface: &Interface, index: &[usize]) -> Option<Box<dyn ElasticBody>> {
        let second = self.body(1);
        if self.second_is_rigid() {
            return Some(Box::new(RigidBody::fixed(second.name(), surface)));
        }
        let mut keep2 = vec![false; second.interface().len()];
        for &i in index {
            keep2[self.to_second(i)] = true;
        }
        let (part2, mut index2) = second.restrict(&keep2)?;
        let mut wanted: Vec<usize> = index.iter().map(|&i| self.to_second(i)).collect();
        wanted.sort_unstable();
        index2.sort_unstable();
        (wanted == index2).then_some(part2)
    }

    /// The operator of the coarser bodies ([`ElasticBody::coarsen`]), with the coarse point
    /// of each point (`parent`): the first body coarsens itself, the second too (grouped
    /// alike) or, without compliance, is held on the coarse surface. `None` when a body offers
    /// no coarser version or the two group differently.
    pub(super) fn coarsen(&self) -> Option<(Operator<'static>, Vec<usize>)> {
        let (coarse1, parent) = self.body(0).coarsen()?;
        let second = self.body(1);
        let coarse2: Box<dyn ElasticBody> = if self.second_is_rigid() {
            Box::new(RigidBody::fixed(second.name(), coarse1.interface()))
        } else {
            let (coarse2, parent2) = second.coarsen()?;
            (self.pair.is_none() && parent2 == parent).then_some(coarse2)?
        };
        let pair = coarse1
            .interface()
            .partners(coarse2.interface(), coarse1.name(), coarse2.name())
            .ok()?;
        let coarse = Operator::new([Body::Owned(coarse1), Body::Owned(coarse2)], pair);
        Some((coarse, parent))
    }
}
