//! Where the bodies face each other: a design changes the gap there only. Beyond a flat
//! punch's rim the gap is open for good — no face is there to change, nor a pressure to
//! prescribe — so those points move with the nearest point of the face, and Ω_v leaves them
//! out.

use contopt_core::{GapShape, Interface, Result};

use super::CaseView;

/// Which of `points` the bodies face each other at — where the case's gap is finite — when
/// some do not (`None`: all do).
pub(super) fn facing(case: &CaseView, points: &[[f64; 3]]) -> Option<Vec<bool>> {
    let facing: Vec<bool> = (points.iter())
        .map(|&x| case.gap.finite_at(case.zone, x))
        .collect();
    facing.contains(&false).then_some(facing)
}

/// One design value per point where the bodies face each other (`facing`); each other point
/// follows the nearest of them, so that a uniform Δh stays a uniform gap change.
pub(super) fn tied(iface: &Interface, facing: &[bool]) -> Result<GapShape> {
    let points = iface.points();
    let faced: Vec<usize> = (0..points.len()).filter(|&i| facing[i]).collect();
    let mut node = vec![usize::MAX; points.len()];
    for (k, &i) in faced.iter().enumerate() {
        node[i] = k;
    }
    let buckets = Buckets::new(points, &faced);
    let rows = (0..points.len())
        .map(|i| match facing[i] {
            true => vec![(node[i], 1.0)],
            false => buckets
                .nearest(points, points[i])
                .map_or(vec![], |j| vec![(node[j], 1.0)]),
        })
        .collect();
    GapShape::new(faced.iter().map(|&i| points[i]).collect(), rows)
}

/// The facing points in a grid of buckets over their bounding box (x and y), about one point
/// per bucket (a row of them where the points lie on a line: rings, strips, faces), for
/// nearest-point queries.
struct Buckets {
    low: [f64; 2],
    size: [f64; 2],
    sides: [usize; 2],
    members: Vec<Vec<usize>>,
}

impl Buckets {
    fn new(points: &[[f64; 3]], faced: &[usize]) -> Self {
        let (mut low, mut high) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &i in faced {
            for c in 0..2 {
                low[c] = low[c].min(points[i][c]);
                high[c] = high[c].max(points[i][c]);
            }
        }
        let spans = [0, 1].map(|c| high[c] - low[c] > 0.0);
        let n = faced.len().max(1) as f64;
        let per_axis = match spans {
            [true, true] => n.sqrt().ceil(),
            _ => n,
        };
        let sides = spans.map(|spans| if spans { per_axis as usize } else { 1 });
        let size = [0, 1].map(|c| match spans[c] {
            true => (high[c] - low[c]) / sides[c] as f64,
            false => f64::INFINITY,
        });
        let mut buckets = Self {
            low,
            size,
            sides,
            members: vec![vec![]; sides[0] * sides[1]],
        };
        for &i in faced {
            let [bx, by] = buckets.of(points[i]);
            buckets.members[by * sides[0] + bx].push(i);
        }
        buckets
    }

    /// The bucket of `x`, clamped to the grid.
    fn of(&self, x: [f64; 3]) -> [usize; 2] {
        [0, 1].map(|c| {
            let k = ((x[c] - self.low[c]) / self.size[c]).floor();
            k.clamp(0.0, (self.sides[c] - 1) as f64) as usize
        })
    }

    /// The facing point nearest `x` (`None` without any). A point in a bucket r rings from
    /// `x`'s clamped bucket lies at least (r − 1) bucket sizes from the projection of `x` on
    /// the box, and so from `x`: the search stops there.
    fn nearest(&self, points: &[[f64; 3]], x: [f64; 3]) -> Option<usize> {
        let [bx, by] = self.of(x).map(|k| k as isize);
        let step = self.size[0].min(self.size[1]);
        let [sx, sy] = self.sides.map(|s| s as isize);
        let mut best: Option<(f64, usize)> = None;
        for ring in 0..=sx.max(sy) {
            if best.is_some_and(|(d, _)| ((ring - 1) as f64 * step).powi(2) >= d) {
                break;
            }
            for (i, j) in ring_cells(bx, by, ring) {
                if i < 0 || j < 0 || i >= sx || j >= sy {
                    continue;
                }
                for &p in &self.members[(j * sx + i) as usize] {
                    let d = (points[p][0] - x[0]).powi(2) + (points[p][1] - x[1]).powi(2);
                    if best.is_none_or(|(b, _)| d < b) {
                        best = Some((d, p));
                    }
                }
            }
        }
        best.map(|(_, p)| p)
    }
}

/// The buckets at Chebyshev distance `ring` from (`bx`, `by`).
fn ring_cells(bx: isize, by: isize, ring: isize) -> impl Iterator<Item = (isize, isize)> {
    (-ring..=ring)
        .flat_map(move |di| (-ring..=ring).map(move |dj| (di, dj)))
        .filter(move |&(di, dj)| di.abs().max(dj.abs()) == ring)
        .map(move |(di, dj)| (bx + di, by + dj))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The buckets find the nearest facing point, as a search over all of them does, for
    /// points inside and outside their box.
    #[test]
    fn buckets_find_the_nearest_point() {
        let points: Vec<[f64; 3]> = (0..400)
            .map(|k| {
                [
                    (k % 20) as f64 * 0.1 - 1.0,
                    (k / 20) as f64 * 0.07 - 0.7,
                    0.0,
                ]
            })
            .collect();
        let faced: Vec<usize> = (0..400)
            .filter(|&k| points[k][0].hypot(points[k][1]) < 0.5)
            .collect();
        let buckets = Buckets::new(&points, &faced);
        let check = |points: &[[f64; 3]], faced: &[usize], buckets: &Buckets, x: [f64; 3]| {
            let d = |p: usize| (points[p][0] - x[0]).hypot(points[p][1] - x[1]);
            let brute = faced.iter().map(|&p| d(p)).fold(f64::INFINITY, f64::min);
            let found = buckets.nearest(points, x).unwrap();
            assert_eq!(d(found), brute, "{x:?}");
        };
        for x in points.iter().chain(&[[3.0, -2.0, 0.0], [0.01, 0.02, 0.0]]) {
            check(&points, &faced, &buckets, *x);
        }
        // Points on a line (rings): one row of buckets.
        let line: Vec<[f64; 3]> = (0..50).map(|k| [0.1 * k as f64, 0.0, 0.0]).collect();
        let under: Vec<usize> = (0..30).collect();
        let buckets = Buckets::new(&line, &under);
        assert_eq!(buckets.sides, [30, 1]);
        for x in &line {
            check(&line, &under, &buckets, *x);
        }
    }
}
