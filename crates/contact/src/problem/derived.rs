//! The problems an iterative solve derives from the one it solves, a part of the interface
//! ([`InterfaceProblem::restrict`]) and a coarser version ([`InterfaceProblem::coarsen`]),
//! kept for the next solves of the same bodies ([`Derived`]): their bodies, with the FFT plans
//! and spectra of a grid, are built once; a later solve refills only their gaps.

use std::sync::Arc;

use contopt_core::InfluenceShape;

use super::modes::Modes;
use super::InterfaceProblem;

/// Problems derived from others kept at once: a solve on a grid derives about two per level
/// (a coarser grid, a part or two of each), so this holds a solve down to 2¹⁰ × 2¹⁰ cells.
const KEPT: usize = 24;

/// How a derived problem's points take the values of the problem it comes from.
#[derive(Clone, Copy)]
pub(crate) enum Mapping<'m> {
    /// A part's point a is the whole's point `index[a]`.
    Part(&'m [usize]),
    /// A coarse point c is the W-weighted mean of the fine points i with `parent[i]` = c,
    /// whose weights sum to `total[c]`.
    Coarse {
        parent: &'m [usize],
        total: &'m [f64],
    },
}

impl Mapping<'_> {
    /// Writes the mapped values of `v` (one per point of the problem of weights `w`) to `out`,
    /// resized to the derived problem's points.
    pub(super) fn apply(&self, v: &[f64], w: &[f64], out: &mut Vec<f64>) {
        out.clear();
        match *self {
            Mapping::Part(index) => out.extend(index.iter().map(|&i| v[i])),
            Mapping::Coarse { parent, total } => {
                out.resize(total.len(), 0.0);
                for (i, &c) in parent.iter().enumerate() {
                    out[c] += w[i] * v[i];
                }
                out.iter_mut().zip(total).for_each(|(s, t)| *s /= t);
            }
        }
    }
}

/// The typed identity of a problem's operator and modes, as far as derived problems depend
/// on them: both bodies' influence shapes and scales ([`ElasticBody::influence_shape`]), the
/// points, the first point's place and the modes (shared, [`Modes::same`]). Problems whose
/// bodies do not say their shape, that pair their points out of order or that carry a
/// pressure basis have none: what is derived from them is not kept.
///
/// [`ElasticBody::influence_shape`]: contopt_core::ElasticBody::influence_shape
struct Identity {
    shapes: [(InfluenceShape, f64); 2],
    points: usize,
    first: [f64; 3],
    modes: Modes,
}

impl Identity {
    fn of(problem: &InterfaceProblem) -> Option<Self> {
        let operator = &problem.operator;
        let shape = |k: usize| operator.body(k).influence_shape();
        let ordered = operator.pairs_in_order() && problem.pressure_basis.is_none();
        Some(Self {
            shapes: [shape(0)?, shape(1)?],
            points: problem.len(),
            first: *problem.interface.points().first()?,
            modes: problem.modes.clone(),
        })
        .filter(|_| ordered)
    }

    fn is(&self, other: &Identity) -> bool {
        self.shapes == other.shapes
            && self.points == other.points
            && self.first == other.first
            && self.modes.same(&other.modes)
    }
}

/// What a problem derives.
#[derive(PartialEq)]
enum Derivation {
    /// The part that holds the points marked here.
    Part(Vec<bool>),
    Coarse,
}

/// A derived problem with the map from the problem it comes from (a part's index, a coarse
/// problem's parents and their total weights).
pub(crate) struct Kept {
    /// Whence it was derived; `None` when it cannot be kept.
    from: Option<(Identity, Derivation)>,
    problem: InterfaceProblem<'static>,
    map: Vec<usize>,
    total: Vec<f64>,
}

impl Kept {
    /// The derived problem.
    pub(crate) fn problem(&self) -> &InterfaceProblem<'static> {
        &self.problem
    }

    /// A part's index of its points among the whole's, or a coarse problem's parent of each
    /// fine point.
    pub(crate) fn map(&self) -> &[usize] {
        &self.map
    }

    /// Refills its gaps from those of `from`, the problem it was derived from.
    fn refill(&mut self, from: &InterfaceProblem) {
        let mapping = match self.from {
            Some((_, Derivation::Coarse)) => Mapping::Coarse {
                parent: &self.map,
                total: &self.total,
            },
            _ => Mapping::Part(&self.map),
        };
        let (w, to) = (from.weights(), &mut self.problem);
        mapping.apply(&from.initial_gap, w, &mut to.initial_gap);
        let Some(f) = &from.load_gap else {
            to.load_gap = None;
            return;
        };
        match to.load_gap.as_mut().and_then(Arc::get_mut) {
            Some(load) => mapping.apply(f, w, load),
            None => {
                let mut mapped = vec![];
                mapping.apply(f, w, &mut mapped);
                to.load_gap = Some(Arc::new(mapped));
            }
        }
    }
}

/// Problems derived by earlier solves, each with whence it came, for a caller that keeps
/// them across solves (a kept [`PolonskyKeerWorkspace`](crate::PolonskyKeerWorkspace)): a
/// derivation asked for again from a problem of the same identity hands back the kept
/// problem with its gaps refilled, and builds nothing; the same bits as a fresh derivation.
/// Without keeping ([`Derived::default`]), each derivation is built and dropped after use.
#[derive(Default)]
pub(crate) struct Derived {
    keeps: bool,
    kept: Vec<(u64, Kept)>,
    /// Derivations handed out so far, each entry stamped with the last that used it.
    uses: u64,
}

impl Derived {
    /// A store that keeps what it derives, up to [`KEPT`] problems (the least recently used
    /// dropped first).
    pub(crate) fn keeping() -> Self {
        Self {
            keeps: true,
            kept: Vec::with_capacity(KEPT),
            uses: 0,
        }
    }

    /// [`InterfaceProblem::restrict`] of `whole` to a part holding the points of `keep`.
    pub(crate) fn part(&mut self, whole: &InterfaceProblem, keep: &[bool]) -> Option<Kept> {
        let identity = self.identity(whole);
        let found = identity.as_ref().and_then(|id| {
            self.take(|(from, how)| from.is(id) && matches!(how, Derivation::Part(k) if k == keep))
        });
        if let Some(mut kept) = found {
            kept.refill(whole);
            return Some(kept);
        }
        let (problem, map) = whole.restrict(keep)?;
        let from = identity.map(|id| (id, Derivation::Part(keep.to_vec())));
        Some(Kept {
            from,
            problem,
            map,
            total: vec![],
        })
    }

    /// [`InterfaceProblem::coarsen`] of `fine`.
    pub(crate) fn coarse(&mut self, fine: &InterfaceProblem) -> Option<Kept> {
        let identity = self.identity(fine);
        let found = identity
            .as_ref()
            .and_then(|id| self.take(|(from, how)| from.is(id) && *how == Derivation::Coarse));
        if let Some(mut kept) = found {
            kept.refill(fine);
            return Some(kept);
        }
        let (problem, map, mut total) = fine.coarsened()?;
        let from = identity.map(|id| (id, Derivation::Coarse));
        if from.is_none() {
            // Needed only to refill a kept problem: not held through a one-off solve.
            total = vec![];
        }
        Some(Kept {
            from,
            problem,
            map,
            total,
        })
    }

    /// Takes back `kept` once its problem is solved, leaving its map in `map` (copied when
    /// the store keeps it, else moved and the problem dropped).
    pub(crate) fn give_back(&mut self, mut kept: Kept, map: &mut Vec<usize>) {
        if !self.keeps || kept.from.is_none() {
            std::mem::swap(map, &mut kept.map);
            return;
        }
        map.clear();
        map.extend_from_slice(&kept.map);
        if self.kept.len() == KEPT {
            let oldest = (0..KEPT).min_by_key(|&k| self.kept[k].0);
            oldest.map(|k| self.kept.swap_remove(k));
        }
        self.uses += 1;
        self.kept.push((self.uses, kept));
    }

    /// Done with a map that [`Derived::give_back`] left: freed unless the store keeps what it
    /// derives (then the next solve refills it), so that a one-off solve does not hold it.
    pub(crate) fn done_with(&self, map: &mut Vec<usize>) {
        if !self.keeps {
            *map = Vec::new();
        }
    }

    /// The identity of `problem` when this store keeps what it derives.
    fn identity(&self, problem: &InterfaceProblem) -> Option<Identity> {
        self.keeps.then(|| Identity::of(problem)).flatten()
    }

    /// The kept problem derived as `whence` says, taken out of the store.
    fn take(&mut self, whence: impl Fn(&(Identity, Derivation)) -> bool) -> Option<Kept> {
        let at = self
            .kept
            .iter()
            .position(|(_, k)| k.from.as_ref().is_some_and(&whence))?;
        Some(self.kept.swap_remove(at).1)
    }
}
