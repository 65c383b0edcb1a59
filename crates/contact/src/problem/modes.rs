//! The free rigid-body modes of the interface problem: the columns of R (eq. 2.6), G_R = W R
//! with the equilibrium rows G_Rᵀ p = q (2.10–2.11), and how they follow a restriction or a
//! coarsening of the interface.

use std::sync::Arc;

use contopt_core::{check, ElasticBody, Error, Result};
use faer::linalg::solvers::Llt;
use faer::{Mat, Side};

use super::WEIGHT_MATCH;

/// Relative size below which a mode's interface displacement counts as zero (it does not move
/// the interface) or of one sign.
const MODE_ZERO: f64 = 1e-12;
/// A load on a mode that does not move the interface counts as zero below this fraction of
/// the mode's weighted size (at least 1 N): round-off of the load's work.
const UNCARRIED_LOAD: f64 = 1e-9;
/// Two modes move the interface alike when the Gram matrix's pivot falls below this fraction
/// of its diagonal (round-off: the modes are numerically dependent).
const MODE_INDEPENDENCE: f64 = 1e-10;

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

    /// Checks that it moves points of an interface of `n` points, one finite displacement
    /// per point, under a finite load.
    fn check(&self, n: usize) -> Result<()> {
        let name = &self.name;
        if self.points.len() != self.displacement.len() {
            return Err(Error::invalid(
                format!("mode `{name}`"),
                format!(
                    "{} points, {} values",
                    self.points.len(),
                    self.displacement.len()
                ),
                "one displacement per point",
            ));
        }
        if let Some(k) = self.points.iter().position(|&i| i >= n) {
            return Err(Error::invalid(
                format!("mode `{name}`.points[{k}]"),
                self.points[k],
                format!("an interface point below {n}"),
            ));
        }
        check::finite(&format!("mode `{name}`.load"), self.load)?;
        check::all_finite(&format!("mode `{name}`.displacement"), &self.displacement)
    }
}

/// The free rigid modes of a problem, R and q of eqs. (2.6)–(2.10) (G_R = W R), shared by the
/// problems derived from one, with whose each is when they are the bodies' own.
#[derive(Clone)]
pub(super) struct Modes {
    list: Arc<Vec<FreeMode>>,
    /// Whose each mode is: (body, its index among the body's rigid modes); `None` for modes
    /// given in their place ([`Modes::given`]) or carried to a part of the interface.
    owners: Option<Arc<Vec<[usize; 2]>>>,
}

impl Modes {
    /// The bodies' rigid modes in the first body's numbering (`pair` maps its points to the
    /// second's), with the ones that do not move the interface dropped (and refused when
    /// loaded), loads that pull the bodies apart refused, and modes that move the interface
    /// alike refused.
    pub(super) fn of_bodies(
        b1: &dyn ElasticBody,
        b2: &dyn ElasticBody,
        pair: &[usize],
    ) -> Result<Self> {
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
                if let Some(mode) = free_mode(name, r, m.load, w)? {
                    kept.push(mode);
                    owners.push([k, j]);
                }
            }
        }
        check_independent(&kept, w)?;
        Ok(Self {
            list: Arc::new(kept),
            owners: Some(Arc::new(owners)),
        })
    }

    /// `modes` in place of the bodies', each checked against an interface of `n` points.
    pub(super) fn given(modes: Vec<FreeMode>, n: usize) -> Result<Self> {
        for mode in &modes {
            mode.check(n)?;
        }
        Ok(Self::carried(modes))
    }

    /// Modes that are no longer the bodies' own.
    fn carried(modes: Vec<FreeMode>) -> Self {
        Self {
            list: Arc::new(modes),
            owners: None,
        }
    }

    /// Whether `other` is these very modes (one list shared, as problems derived by
    /// [`InterfaceProblem::with_initial_gap`](super::InterfaceProblem::with_initial_gap)
    /// share it): then their points, displacements and loads are these.
    pub(super) fn same(&self, other: &Modes) -> bool {
        Arc::ptr_eq(&self.list, &other.list)
    }

    /// The modes.
    pub(super) fn list(&self) -> &[FreeMode] {
        &self.list
    }

    /// Each body's own rigid-mode amplitudes (of `counts[k]` modes each) in a solution's λ
    /// (`rigid`, one per mode); a mode dropped has amplitude 0.
    pub(super) fn body_rigid(&self, rigid: &[f64], counts: [usize; 2]) -> Result<[Vec<f64>; 2]> {
        let Some(owners) = &self.owners else {
            return Err(Error::invalid(
                "rigid",
                "the modes of with_modes",
                "the problem's modes are not its bodies' rigid modes",
            ));
        };
        if rigid.len() != self.list.len() {
            return Err(Error::invalid(
                "rigid.len()",
                rigid.len(),
                format!("one amplitude per free mode ({})", self.list.len()),
            ));
        }
        let mut own = counts.map(|m| vec![0.0; m]);
        for (&[body, mode], &lambda) in owners.iter().zip(rigid) {
            own[body][mode] = lambda;
        }
        Ok(own)
    }

    /// R as a dense n × m matrix.
    pub(super) fn matrix(&self, n: usize) -> Mat<f64> {
        let mut r = Mat::zeros(n, self.list.len());
        for (k, mode) in self.list.iter().enumerate() {
            for (&i, &v) in mode.points.iter().zip(&mode.displacement) {
                r[(i, k)] = v;
            }
        }
        r
    }

    /// Adds the rigid motion R λ to `gap`.
    pub(super) fn add_motion(&self, rigid: &[f64], gap: &mut [f64]) {
        for (mode, &l) in self.list.iter().zip(rigid) {
            for (&i, &r) in mode.points.iter().zip(&mode.displacement) {
                gap[i] += r * l;
            }
        }
    }

    /// The largest violation of the equilibrium rows, maxₖ |Σ wᵢ rᵢ pᵢ + qₖ| \[N\] (2.10).
    pub(super) fn equilibrium(&self, weights: &[f64], pressure: &[f64]) -> f64 {
        self.list
            .iter()
            .map(|m| (m.force(weights, pressure) + m.load).abs())
            .fold(0.0, f64::max)
    }

    /// The modes over the points `index` (renumbered), with their loads: the points left out
    /// carry no pressure. `None` when a loaded mode would lose all its points.
    pub(super) fn on(&self, index: &[usize]) -> Option<Self> {
        let sorted: Option<Vec<(usize, usize)>> = (!index.is_sorted()).then(|| {
            let mut s: Vec<(usize, usize)> = index.iter().copied().zip(0..).collect();
            s.sort_unstable();
            s
        });
        let position = |i: usize| match &sorted {
            None => index.binary_search(&i).ok(),
            Some(s) => s.binary_search_by_key(&i, |&(k, _)| k).ok().map(|k| s[k].1),
        };
        let mut modes = Vec::with_capacity(self.list.len());
        for mode in self.list.iter() {
            let pairs = mode.points.iter().zip(&mode.displacement);
            // A mode over as many points as the part or more, both lists in order (a grid's
            // box of its whole grid's translation): one walk along both, O(n), where a search
            // per point costs O(n log n) (about 20 ms at 1024²). A mode of a few points (a
            // design column) is searched for: a walk would cross the whole part for each.
            let dense = mode.points.len() >= index.len();
            let (points, displacement): (Vec<usize>, Vec<f64>) =
                if dense && sorted.is_none() && mode.points.is_sorted() {
                    let mut a = 0;
                    pairs
                        .filter_map(|(&i, &r)| {
                            while a < index.len() && index[a] < i {
                                a += 1;
                            }
                            (a < index.len() && index[a] == i).then_some((a, r))
                        })
                        .unzip()
                } else {
                    pairs
                        .filter_map(|(&i, &r)| position(i).map(|a| (a, r)))
                        .unzip()
                };
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
        Some(Self::carried(modes))
    }

    /// The modes on the coarse points of `parent` (of W-weights `total`; `weights` the fine
    /// points'): each moves a coarse point by the W-mean of its points' rᵢ. Modes that share a
    /// coarse point become one, carrying their loads' sum (the optimiser's design columns, two
    /// to a coarse column): the coarse solution is only a start, whose pressure the fine solve
    /// rescales to each mode's own load. `None` when a mode moves only some of a coarse
    /// point's points.
    pub(super) fn coarse(&self, parent: &[usize], total: &[f64], weights: &[f64]) -> Option<Self> {
        let m = total.len();
        let group = self.groups(parent, m);
        let mut merged: Vec<Option<FreeMode>> = vec![None; self.list.len()];
        let (mut moved, mut covered) = (vec![0.0; m], vec![0.0; m]);
        let mut seen = vec![false; m];
        for (k, mode) in self.list.iter().enumerate() {
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
                moved[c] += weights[i] * r;
                covered[c] += weights[i];
            }
        }
        let modes: Vec<FreeMode> = merged.into_iter().flatten().collect();
        let partial = |mode: &FreeMode| {
            mode.points
                .iter()
                .any(|&c| (covered[c] - total[c]).abs() > WEIGHT_MATCH * total[c])
        };
        if modes.iter().any(partial) {
            return None;
        }
        let modes = modes
            .into_iter()
            .map(|mode| FreeMode {
                displacement: mode.points.iter().map(|&c| moved[c] / covered[c]).collect(),
                ..mode
            })
            .collect();
        Some(Self::carried(modes))
    }

    /// The group of each mode: its first's index among the modes joined to it through shared
    /// coarse points (of `m`, by `parent`), a union–find.
    fn groups(&self, parent: &[usize], m: usize) -> Vec<usize> {
        fn root(group: &mut [usize], mut k: usize) -> usize {
            while group[k] != k {
                group[k] = group[group[k]];
                k = group[k];
            }
            k
        }
        let mut group: Vec<usize> = (0..self.list.len()).collect();
        let mut owner = vec![usize::MAX; m];
        for (k, mode) in self.list.iter().enumerate() {
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
}

/// A body's rigid mode `name` moving the interface by `r` under the load `q`, as a free mode:
/// `None` when it does not move the interface (refused when loaded); refused when its load
/// pulls the bodies apart, or is zero on a floating body.
fn free_mode(name: String, r: Vec<f64>, q: f64, w: &[f64]) -> Result<Option<FreeMode>> {
    let span = r.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    let total = r.iter().zip(w).map(|(v, w)| (v * w).abs()).sum::<f64>();
    if span < MODE_ZERO {
        if q.abs() > UNCARRIED_LOAD * total.max(1.0) {
            return Err(Error::invalid(
                format!("load on {name}"),
                q,
                "cannot be equilibrated by normal contact: the mode does not move the interface",
            ));
        }
        return Ok(None);
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
    Ok(Some(FreeMode {
        name,
        points,
        displacement,
        load: q,
    }))
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
