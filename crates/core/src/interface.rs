use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::{check, Error, Result};

/// How the surface measure of an interface point was formed.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub enum Geometry {
    /// Axisymmetric: points are (r, z); weights carry the ring length 2πr.
    Axisymmetric,
    /// Plane stress or plane strain: points are (x, y); weights carry the thickness.
    Plane {
        /// Out-of-plane thickness b \[mm\].
        thickness: f64,
    },
    /// A surface in 3-D (half-space grids): points are (x₁, x₂, x₃); weights are areas.
    Surface,
}

/// Relative round-off below which two coordinates or lengths count as equal (geometry): points
/// of an interface within 10⁻⁹ of its size are one place, a normal within 10⁻⁹ of unit
/// length is a unit vector. Far above f64's ε, far below any mesh or grid spacing.
pub const GEOMETRY_TOLERANCE: f64 = 1e-9;

/// The points of a body's proposed contact zone Ω at which pressure and gap are evaluated.
///
/// For finite-element bodies these are the three Gauss points of every contact face (as in
/// the paper, §2.2); for Green's-function bodies the grid-cell centres. Stored as columns
/// (structure of arrays) because the solvers sweep them, and shared: a clone, or the partner's
/// surface ([`Interface::mirrored`]), holds the same columns, not a copy (a grid of 10⁶ cells
/// has 32 MB of points and weights). Normals that are all alike (a plane) are stored once.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(into = "Columns", try_from = "Columns")]
pub struct Interface {
    geometry: Geometry,
    points: Arc<[[f64; 3]]>,
    weights: Arc<[f64]>,
    normals: Normals,
}

/// The outward normals of an interface: one for all points, or one each.
#[derive(Clone, Debug, PartialEq)]
enum Normals {
    Uniform([f64; 3]),
    Each(Arc<[[f64; 3]]>),
}

impl Normals {
    /// One normal when all are equal, else each.
    fn new(normals: Vec<[f64; 3]>) -> Self {
        match normals.first() {
            Some(&first) if normals.iter().all(|&n| n == first) => Normals::Uniform(first),
            _ => Normals::Each(normals.into()),
        }
    }

    fn reversed(&self) -> Self {
        match self {
            Normals::Uniform(n) => Normals::Uniform(n.map(|c| -c)),
            Normals::Each(each) => Normals::Each(each.iter().map(|n| n.map(|c| -c)).collect()),
        }
    }
}

/// The unit outward normals of an interface's points, by index or in order
/// ([`Interface::normals`]).
#[derive(Clone, Copy, Debug)]
pub struct NormalsView<'a> {
    normals: &'a Normals,
    len: usize,
}

impl<'a> NormalsView<'a> {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there are none (never for a constructed interface).
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The normals in order of the points.
    pub fn iter(&self) -> impl Iterator<Item = &'a [f64; 3]> + 'a {
        let (normals, len) = (self.normals, self.len);
        (0..len).map(move |i| match normals {
            Normals::Uniform(n) => n,
            Normals::Each(each) => &each[i],
        })
    }
}

impl std::ops::Index<usize> for NormalsView<'_> {
    type Output = [f64; 3];

    fn index(&self, i: usize) -> &[f64; 3] {
        assert!(i < self.len, "normal {i} of {} points", self.len);
        match self.normals {
            Normals::Uniform(n) => n,
            Normals::Each(each) => &each[i],
        }
    }
}

impl<'a> IntoIterator for NormalsView<'a> {
    type Item = &'a [f64; 3];
    type IntoIter = Box<dyn Iterator<Item = &'a [f64; 3]> + 'a>;

    fn into_iter(self) -> Self::IntoIter {
        Box::new(self.iter())
    }
}

/// An interface as its columns, for files: read back through [`Interface::new`]'s checks.
#[derive(Serialize, Deserialize)]
struct Columns {
    geometry: Geometry,
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    normals: Vec<[f64; 3]>,
}

impl From<Interface> for Columns {
    fn from(s: Interface) -> Self {
        Columns {
            geometry: s.geometry,
            points: s.points.to_vec(),
            weights: s.weights.to_vec(),
            normals: s.normals().iter().copied().collect(),
        }
    }
}

impl TryFrom<Columns> for Interface {
    type Error = Error;

    fn try_from(c: Columns) -> Result<Self> {
        Interface::new(c.geometry, c.points, c.weights, c.normals)
    }
}

impl Interface {
    /// Builds an interface, checking that the columns have one length, the weights are
    /// positive and finite and the normals have unit length.
    pub fn new(
        geometry: Geometry,
        points: Vec<[f64; 3]>,
        weights: Vec<f64>,
        normals: Vec<[f64; 3]>,
    ) -> Result<Self> {
        let n = points.len();
        if n == 0 {
            return Err(Error::invalid("interface.points", 0, "at least one point"));
        }
        if weights.len() != n || normals.len() != n {
            return Err(Error::invalid(
                "interface",
                format!(
                    "{n} points, {} weights, {} normals",
                    weights.len(),
                    normals.len()
                ),
                "one weight and one normal per point",
            ));
        }
        if let Some(i) = points.iter().position(|x| x.iter().any(|c| !c.is_finite())) {
            check::all_finite(&format!("interface.points[{i}]"), &points[i])?;
        }
        check::all_positive("interface.weights", &weights)?;
        // The field's name is formatted for the first bad normal only: a grid has millions.
        if let Some(i) = normals
            .iter()
            .position(|&nrm| check::unit_vector("", nrm).is_err())
        {
            check::unit_vector(&format!("interface.normals[{i}]"), normals[i])?;
        }
        let interface = Self {
            geometry,
            points: points.into(),
            weights: weights.into(),
            normals: Normals::new(normals),
        };
        interface.check_sums()?;
        Ok(interface)
    }

    /// The extent and the area are finite: points spread, or weights summed, beyond f64 are
    /// refused (no non-finite size reaches a solver's tolerances).
    fn check_sums(&self) -> Result<()> {
        let (lo, hi) = self.bounds();
        let spread = format!("a box from {lo:?} to {hi:?}");
        check::derived("interface.points", spread, "the extent", self.extent())?;
        let weights = format!("{} weights", self.len());
        check::derived("interface.weights", weights, "their sum", self.area())?;
        Ok(())
    }

    /// How the weights were formed.
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// Coordinates of the points \[mm\].
    pub fn points(&self) -> &[[f64; 3]] {
        &self.points
    }

    /// Surface measure w_i attributed to each point \[mm²\]: the quadrature weight times
    /// the Jacobian and 2πr (axisymmetric) or b (plane), so that ∫_Ω p dS ≈ Σ w_i p_i.
    pub fn weights(&self) -> &[f64] {
        &self.weights
    }

    /// Unit outward normal of this body at each point.
    pub fn normals(&self) -> NormalsView<'_> {
        NormalsView {
            normals: &self.normals,
            len: self.points.len(),
        }
    }

    /// The same points seen from the partner across the contact: the normals reversed (a
    /// rigid body's or a bed's surface facing this one). The points and weights are shared.
    pub fn mirrored(&self) -> Interface {
        Interface {
            normals: self.normals.reversed(),
            ..self.clone()
        }
    }

    /// Whether `other` holds the very same points and weights (a clone or a mirror of this
    /// one): then they pair point for point without a comparison.
    fn shares_points(&self, other: &Interface) -> bool {
        Arc::ptr_eq(&self.points, &other.points) && Arc::ptr_eq(&self.weights, &other.weights)
    }

    /// The points kept by `keep`, in order (one flag per point), with their weights and
    /// normals; `None` when none is kept.
    pub fn subset(&self, keep: &[bool]) -> Option<Interface> {
        let index: Vec<usize> = (0..self.len())
            .filter(|&i| keep.get(i) == Some(&true))
            .collect();
        if index.is_empty() {
            return None;
        }
        let normals = match &self.normals {
            Normals::Uniform(n) => Normals::Uniform(*n),
            Normals::Each(each) => Normals::Each(index.iter().map(|&i| each[i]).collect()),
        };
        Some(Interface {
            geometry: self.geometry,
            points: index.iter().map(|&i| self.points[i]).collect(),
            weights: index.iter().map(|&i| self.weights[i]).collect(),
            normals,
        })
    }

    /// For each point of `self`, the index of the point of `other` at the same place (within
    /// [`GEOMETRY_TOLERANCE`] of the interface's size): the identity when both list their points alike, else
    /// found through a spatial hash of `other`'s points. `name`/`other_name` label the error, which
    /// names the first point without a partner.
    pub fn partners(&self, other: &Interface, name: &str, other_name: &str) -> Result<Vec<usize>> {
        let n = self.len();
        if other.len() != n {
            return Err(Error::InterfaceMismatch {
                index: n.min(other.len()),
                detail: format!(
                    "`{name}` has {n} points, `{other_name}` has {}",
                    other.len()
                ),
            });
        }
        if self.shares_points(other) {
            return Ok((0..n).collect());
        }
        let scale = self
            .points
            .iter()
            .flatten()
            .fold(0.0f64, |m, c| m.max(c.abs()))
            .max(1.0);
        let tol = GEOMETRY_TOLERANCE * scale;
        let close = |a: [f64; 3], b: [f64; 3]| {
            (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>().sqrt() <= tol
        };
        if (0..n).all(|i| close(self.points[i], other.points[i])) {
            return Ok((0..n).collect());
        }
        // Hash `other`'s points into cells of side 4·tol and look for each point's partner
        // in its own and the neighbouring cells: a match is never split by a cell boundary.
        let cell = 4.0 * tol;
        let key = |p: [f64; 3]| p.map(|c| (c / cell).floor() as i64);
        let mut cells: std::collections::HashMap<[i64; 3], Vec<usize>> =
            std::collections::HashMap::new();
        for (j, &p) in other.points.iter().enumerate() {
            cells.entry(key(p)).or_default().push(j);
        }
        let mut taken = vec![false; n];
        let mut pair = vec![0; n];
        for (i, &p) in self.points.iter().enumerate() {
            let k = key(p);
            let found = (-1..=1)
                .flat_map(|a| {
                    (-1..=1)
                        .flat_map(move |b| (-1..=1).map(move |c| [k[0] + a, k[1] + b, k[2] + c]))
                })
                .filter_map(|neighbour| cells.get(&neighbour))
                .flatten()
                .copied()
                .find(|&j| !taken[j] && close(p, other.points[j]));
            match found {
                Some(j) => {
                    taken[j] = true;
                    pair[i] = j;
                }
                None => {
                    return Err(Error::InterfaceMismatch {
                        index: i,
                        detail: format!("point {p:?} of `{name}` has no partner in `{other_name}`"),
                    })
                }
            }
        }
        Ok(pair)
    }

    /// The size of the interface: the diagonal of its points' bounding box \[mm\] (zero for
    /// one point), by `hypot`, which does not overflow for spans up to f64's largest.
    pub fn extent(&self) -> f64 {
        let (lo, hi) = self.bounds();
        let span = |c: usize| hi[c] - lo[c];
        span(0).hypot(span(1)).hypot(span(2))
    }

    /// The corners of the points' bounding box, lowest and highest coordinates \[mm\].
    fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for x in self.points.iter() {
            for c in 0..3 {
                lo[c] = lo[c].min(x[c]);
                hi[c] = hi[c].max(x[c]);
            }
        }
        (lo, hi)
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.points.len()
    }

    /// Whether there are no points (never true for a constructed interface).
    pub fn is_empty(&self) -> bool {
        self.points.is_empty()
    }

    /// Total surface measure Σ w_i \[mm²\].
    pub fn area(&self) -> f64 {
        self.weights.iter().sum()
    }

    /// Resultant normal force Σ w_i p_i of a pressure at the points \[N\].
    pub fn resultant(&self, pressure: &[f64]) -> f64 {
        self.weights.iter().zip(pressure).map(|(w, p)| w * p).sum()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rejects_bad_columns() {
        let p = vec![[0.0; 3], [1.0, 0.0, 0.0]];
        let n = vec![[0.0, 1.0, 0.0]; 2];
        let err = Interface::new(Geometry::Surface, p.clone(), vec![1.0], n.clone()).unwrap_err();
        assert!(err.to_string().contains("one weight"), "{err}");
        let err = Interface::new(Geometry::Surface, p.clone(), vec![1.0, -2.0], n).unwrap_err();
        assert!(err.to_string().contains("weights[1] = -2"), "{err}");
        let err = Interface::new(
            Geometry::Surface,
            p.clone(),
            vec![1.0; 2],
            vec![[0.0, 2.0, 0.0]; 2],
        )
        .unwrap_err();
        assert!(err.to_string().contains("normals[0]"), "{err}");
        let second = vec![[0.0, 1.0, 0.0], [0.0, 0.0, 0.9]];
        let err = Interface::new(Geometry::Surface, p, vec![1.0; 2], second).unwrap_err();
        assert!(err.to_string().contains("interface.normals[1]"), "{err}");
    }

    /// A NaN normal is refused (its length passes no comparison); points 2·10²⁰⁰ mm apart
    /// have a finite extent (by `hypot`), points 2·f64::MAX apart are refused.
    #[test]
    fn refuses_nan_normals_and_spans_beyond_f64() {
        let one = |normal: [f64; 3]| {
            Interface::new(Geometry::Surface, vec![[0.0; 3]], vec![1.0], vec![normal])
        };
        let err = one([f64::NAN, 0.0, 0.0]).unwrap_err().to_string();
        assert!(err.contains("normals[0]"), "{err}");
        let two = |x: f64, w: f64| {
            let points = vec![[-x, 0.0, 0.0], [x, 0.0, 0.0]];
            Interface::new(
                Geometry::Surface,
                points,
                vec![w; 2],
                vec![[0.0, 0.0, 1.0]; 2],
            )
        };
        assert_eq!(two(1e200, 1.0).unwrap().extent(), 2e200);
        let err = two(f64::MAX, 1.0).unwrap_err().to_string();
        assert!(
            err.contains("interface.points") && err.contains("extent inf"),
            "{err}"
        );
        let err = two(1.0, f64::MAX).unwrap_err().to_string();
        assert!(
            err.contains("interface.weights") && err.contains("sum inf"),
            "{err}"
        );
    }

    #[test]
    fn partners_pair_points_listed_differently() {
        let make = |xs: &[f64]| {
            let points = xs.iter().map(|&x| [x, 0.0, 0.0]).collect();
            Interface::new(
                Geometry::Surface,
                points,
                vec![1.0; xs.len()],
                vec![[0.0, 0.0, 1.0]; xs.len()],
            )
            .unwrap()
        };
        // Points straddling the hash's cell boundaries by round-off still pair.
        let tol = GEOMETRY_TOLERANCE * 3.0;
        let a = make(&[0.0, 1.0, 2.0, 3.0, 4.0 * tol]);
        let b = make(&[3.0, 2.0 + 1e-13, 4.0 * tol - 1e-13, 0.0, 1.0]);
        assert_eq!(a.partners(&b, "a", "b").unwrap(), vec![3, 4, 1, 0, 2]);
        let c = make(&[3.0, 2.0, 0.5, 0.0, 1.0]);
        let err = a.partners(&c, "a", "c").unwrap_err().to_string();
        // a's last point (at 4·tol) has none: 0.0 went to a's first point.
        assert!(
            err.contains("at point 4") && err.contains("of `a` has no partner in `c`"),
            "{err}"
        );
    }

    #[test]
    fn resultant_is_weighted_sum() {
        let s = Interface::new(
            Geometry::Plane { thickness: 2.0 },
            vec![[0.0; 3], [1.0, 0.0, 0.0]],
            vec![0.5, 1.5],
            vec![[0.0, 1.0, 0.0]; 2],
        )
        .unwrap();
        assert_eq!(s.area(), 2.0);
        assert_eq!(s.resultant(&[2.0, 4.0]), 7.0);
    }
}
