//! A sharp edge: a contact whose pressure rises to its peak at the contact's own edge, as under
//! a flat punch's rim (Sneddon's p ∝ 1/√(a² − r²)) or a straight cylinder's end. The elastic
//! pressure there is singular, so the peak on a zone is the value on its cells, growing as they
//! shrink (by about √2 per halving), not a converged figure. A smooth contact (Hertz's) falls to
//! zero at its edge instead.

use contopt_core::stress::peak_index;
use contopt_greens::CARRIES;

use crate::zone::Layout;

/// The peak sits at a sharp edge when it stands this many times above the largest pressure a
/// cell inward (a 1/√ singularity gives 1.7–3 on cells of any size; an optimised, even pressure
/// stays within round-off of 1).
const RISE: f64 = 1.05;

/// A contact's peak at its own edge, with the pressure a cell inward.
#[derive(Debug, PartialEq)]
pub(super) struct SharpEdge {
    /// The surface axis along which the peak ends the contact, as named in the reports.
    pub along: &'static str,
    /// The peak's position along that axis, mm.
    pub at_mm: f64,
    /// On a grid, the peak's other surface coordinate, named: along x on a punch's rim the
    /// edge's x alone is no place (the rim's point at x = −0.21 mm is at y = ±0.77 mm).
    pub across: Option<(&'static str, f64)>,
    /// The peak, MPa.
    pub p_mpa: f64,
    /// The largest pressure a cell inward from the peak, MPa.
    pub inward_mpa: f64,
}

impl SharpEdge {
    /// The warning a case carries.
    pub fn warning(&self) -> String {
        let place = match self.across {
            Some((other, at)) => format!(
                "{} = {:+.4} mm, {other} = {at:+.4} mm, the edge across {}",
                self.along, self.at_mm, self.along
            ),
            None => format!("{} = {:+.4} mm", self.along, self.at_mm),
        };
        format!(
            "the pressure rises to its peak at the contact's edge ({place}: {:.1} MPa, \
             {:.2} times the {:.1} MPa a cell inward): the contact ends at a sharp edge (a \
             punch's rim, a body's end), where the elastic pressure is singular, so p_max is the \
             value on these cells and grows as they shrink; the load, the approach and the \
             pressure away from the edge do not; round the edge (a fillet, a crown or a profile) \
             for a peak that converges",
            self.p_mpa,
            self.p_mpa / self.inward_mpa,
            self.inward_mpa
        )
    }
}

/// The warning of a contact on `layout` whose pressure \[MPa\] at its `points` peaks at a
/// sharp edge — on the line of points through the peak, the peak in the last cell of its
/// carrying run (cells above [`CARRIES`] of the peak), standing 5 % above the cell inward — as
/// a scene's report says it: the scenes' own check, for a caller with a grid and a pressure of
/// its own (the Python package's solves and designs on a `HalfSpace` or `DenseBody` grid).
pub fn sharp_edge_warning(
    layout: &Layout,
    points: &[[f64; 3]],
    pressure: &[f64],
) -> Option<String> {
    let p_max = pressure.iter().fold(0.0f64, |m, &p| m.max(p));
    let carrying: Vec<bool> = pressure.iter().map(|&p| p > CARRIES * p_max).collect();
    sharp_edge(layout, points, &carrying, pressure).map(|edge| edge.warning())
}

/// Points of a layout that share one cell along a line: the three Gauss points of a face.
pub(super) fn points_per_cell(layout: &Layout) -> usize {
    match layout {
        Layout::Faces(_) => 3,
        _ => 1,
    }
}

/// The sharp edge where the pressure peaks, if it does: along each surface axis of the zone,
/// on the line of points through the peak, the peak lies in the last cell of its carrying run
/// and stands [`RISE`] times above the cell inward from it. The low end of rings and faces, and
/// of a grid along an axis of its `symmetry`, is the axis (or plane) of symmetry, not an edge;
/// an imported mesh's faces are not judged.
pub(super) fn sharp_edge(
    layout: &Layout,
    points: &[[f64; 3]],
    carrying: &[bool],
    pressure: &[f64],
) -> Option<SharpEdge> {
    let peak = peak_index(pressure)?;
    let (axes, symmetric_low): (&[(usize, &'static str)], [bool; 2]) = match layout {
        Layout::Grid { symmetric, .. } => (&[(0, "x"), (1, "y")], *symmetric),
        Layout::Strips { .. } => (&[(0, "x")], [false; 2]),
        Layout::Rings(_) => (&[(0, "r")], [true; 2]),
        Layout::Faces(f) if f.analysis == contopt_fem::Analysis::Axisymmetric => {
            (&[(0, "r")], [true; 2])
        }
        Layout::Faces(_) => (&[(0, "x")], [true; 2]),
        Layout::Mesh(_) => return None,
    };
    let m = points_per_cell(layout);
    axes.iter().find_map(|&(axis, along)| {
        let line = line_through(points, peak, axis);
        let k = line.iter().position(|&i| i == peak)?;
        let (start, end) = run(&line, carrying, k);
        // The cell inward from the peak's: below it at the run's high end, above it at its
        // low end (unless that is the axis).
        let (lo, hi) = if k + m > end {
            (k.saturating_sub(2 * m - 1).max(start), k.checked_sub(m)?)
        } else if k < start + m && !(symmetric_low[axis] && start == 0) {
            (k + m, (k + 2 * m - 1).min(end))
        } else {
            return None;
        };
        if lo > hi || lo < start || hi > end {
            return None;
        }
        let inward_mpa = (lo..=hi).map(|j| pressure[line[j]]).fold(0.0f64, f64::max);
        let across = match layout {
            Layout::Grid { .. } => Some((axes[1 - axis].1, points[peak][1 - axis])),
            _ => None,
        };
        (pressure[peak] > RISE * inward_mpa && inward_mpa > 0.0).then(|| SharpEdge {
            along,
            at_mm: points[peak][axis],
            across,
            p_mpa: pressure[peak],
            inward_mpa,
        })
    })
}

/// The points on the line through `peak` along `axis` (those sharing its other surface
/// coordinate), ordered along it.
pub(super) fn line_through(points: &[[f64; 3]], peak: usize, axis: usize) -> Vec<usize> {
    let other = 1 - axis;
    let mut line: Vec<usize> = (0..points.len())
        .filter(|&i| {
            let (a, b) = (points[i][other], points[peak][other]);
            (a - b).abs() < 1e-9 * (1.0 + b.abs())
        })
        .collect();
    line.sort_by(|&a, &b| points[a][axis].total_cmp(&points[b][axis]));
    line
}

/// The first and last positions on `line` of the carrying run holding position `k`.
fn run(line: &[usize], carrying: &[bool], k: usize) -> (usize, usize) {
    let mut start = k;
    while start > 0 && carrying[line[start - 1]] {
        start -= 1;
    }
    let mut end = k;
    while end + 1 < line.len() && carrying[line[end + 1]] {
        end += 1;
    }
    (start, end)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a grid the warning names the peak's point, not only its coordinate along the line
    /// it ends: a disc of radius 3 cells whose peak sits on the rim at (−2, 2), three times the
    /// cell inward along x, is said at x = −2 and y = +2, the edge across x.
    #[test]
    fn a_grids_sharp_edge_is_named_by_its_point() {
        let layout = Layout::Grid {
            nx: 7,
            ny: 7,
            dx: 1.0,
            dy: 1.0,
            origin: [-3.0, -3.0],
            symmetric: [false; 2],
        };
        let points: Vec<[f64; 3]> = (0..49)
            .map(|k| [(k % 7) as f64 - 3.0, (k / 7) as f64 - 3.0, 0.0])
            .collect();
        let carrying: Vec<bool> = points.iter().map(|x| x[0].hypot(x[1]) <= 3.0).collect();
        let mut pressure: Vec<f64> = carrying.iter().map(|&c| f64::from(u8::from(c))).collect();
        pressure[5 * 7 + 1] = 3.0;
        let edge = sharp_edge(&layout, &points, &carrying, &pressure).expect("a sharp edge");
        assert_eq!((edge.along, edge.at_mm), ("x", -2.0));
        assert_eq!(edge.across, Some(("y", 2.0)));
        let said = edge.warning();
        assert!(said.contains("x = -2.0000 mm, y = +2.0000 mm"), "{said}");
    }
}
