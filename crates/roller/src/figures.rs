//! The figures of a roller's contact that a report shows: where p_max sits, edge loading,
//! the contact half-width at mid-length and at the ends, the crown's drop at the ends and the
//! pressure along the centre line. Plain data, computed from the grid's points, the pressure,
//! the crown's drop per point and the cell size across.

use contopt_core::stress::peak_index;
use serde::Serialize;

/// Ends that carry more than this over the peak pressure at mid-length are edge loaded.
pub const EDGE_LOADING: f64 = 1.1;

/// Points closer than this along the axis \[mm\] are one column (geometry: far below any
/// cell).
const SAME_COLUMN: f64 = 1e-9;

/// The columns of a roller grid: the distinct x of its points, the first, the last and the
/// one nearest mid-length.
struct Columns<'a> {
    points: &'a [[f64; 3]],
    first: f64,
    last: f64,
    middle: f64,
}

impl<'a> Columns<'a> {
    fn new(points: &'a [[f64; 3]]) -> Self {
        let mut xs: Vec<f64> = points.iter().map(|x| x[0]).collect();
        xs.sort_by(f64::total_cmp);
        xs.dedup_by(|a, b| (*a - *b).abs() < SAME_COLUMN);
        let middle = xs
            .iter()
            .copied()
            .min_by(|a, b| a.abs().total_cmp(&b.abs()))
            .unwrap_or(0.0);
        Self {
            points,
            first: xs.first().copied().unwrap_or(0.0),
            last: xs.last().copied().unwrap_or(0.0),
            middle,
        }
    }

    /// The points of the column at `c`.
    fn column(&self, c: f64) -> impl Iterator<Item = usize> + '_ {
        (0..self.points.len()).filter(move |&i| (self.points[i][0] - c).abs() < SAME_COLUMN)
    }

    fn peak(&self, c: f64, pressure: &[f64]) -> f64 {
        self.column(c).map(|i| pressure[i]).fold(0.0, f64::max)
    }

    /// The larger end's peak over the peak at mid-length (infinite when mid-length is open).
    fn end_ratio(&self, pressure: &[f64]) -> f64 {
        let end = self
            .peak(self.first, pressure)
            .max(self.peak(self.last, pressure));
        match self.peak(self.middle, pressure) {
            mid if mid > 0.0 => end / mid,
            _ if end > 0.0 => f64::INFINITY,
            _ => 0.0,
        }
    }
}

/// The larger end's peak pressure over the peak at mid-length of a roller grid's `points`
/// under `pressure`: above [`EDGE_LOADING`], the ends are edge loaded.
pub fn end_ratio(points: &[[f64; 3]], pressure: &[f64]) -> f64 {
    Columns::new(points).end_ratio(pressure)
}

/// The figures of one load case's contact.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct CaseFigures {
    /// The case's load \[N\].
    pub load_n: f64,
    /// The case's tilt \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// The largest pressure \[MPa\].
    pub p_max: f64,
    /// Where it sits: x along the axis, y across \[mm\].
    pub p_max_at_mm: [f64; 2],
    /// The larger end's peak over the peak at mid-length ([`end_ratio`]).
    pub end_ratio: f64,
    /// Whether the ends are edge loaded (the ratio above [`EDGE_LOADING`]).
    pub edge_loading: bool,
    /// The contact half-width at mid-length and the mean of the two ends' \[mm\]: half the
    /// cells in contact across times the cell size.
    pub half_width_mm: [f64; 2],
    /// Cells across the contact's half-width through its peak: half the cells that carry
    /// pressure in the peak's column (a case far lighter than the load the grid was sized for
    /// spans few).
    pub cells_across: f64,
    /// The largest pressure on the grid's outermost rows across \[MPa\]: a contact that
    /// carries pressure there reaches the grid's edge across (a case far heavier than the load
    /// the grid was sized for), where the grid, not the roller, ends it.
    pub edge_across_mpa: f64,
    /// The crown's largest drop at the end columns \[µm\].
    pub crown_drop_end_um: f64,
    /// The roller's approach \[µm\].
    pub approach_um: f64,
    /// The pressure along the centre line, (x \[mm\], p \[MPa\]) per cell.
    pub centre_line: Vec<[f64; 2]>,
}

/// What one case's contact is: its load and tilt, its pressure and approach.
#[derive(Clone, Copy, Debug)]
pub struct CaseContact<'a> {
    /// The case's load \[N\].
    pub load_n: f64,
    /// The case's tilt \[arc-minutes\].
    pub tilt_arcmin: f64,
    /// The pressure at the grid's points \[MPa\].
    pub pressure: &'a [f64],
    /// The roller's approach \[mm\].
    pub approach_mm: f64,
}

impl CaseFigures {
    /// The figures of `contact` on a grid of `points` with the crown's `drop` per point
    /// \[mm\] and the cell size across `dy` \[mm\].
    pub fn new(contact: &CaseContact, points: &[[f64; 3]], drop: &[f64], dy: f64) -> Self {
        let pressure = contact.pressure;
        let columns = Columns::new(points);
        let end_drop = columns
            .column(columns.first)
            .chain(columns.column(columns.last))
            .map(|i| drop.get(i).copied().unwrap_or(0.0))
            .fold(0.0, f64::max);
        let top = peak_index(pressure).unwrap_or(0);
        let carrying = |c: f64| columns.column(c).filter(|&i| pressure[i] > 0.0).count() as f64;
        let end_ratio = columns.end_ratio(pressure);
        Self {
            load_n: contact.load_n,
            tilt_arcmin: contact.tilt_arcmin,
            p_max: pressure.iter().fold(0.0, |m: f64, p| m.max(*p)),
            p_max_at_mm: [points[top][0], points[top][1]],
            end_ratio,
            edge_loading: end_ratio > EDGE_LOADING,
            half_width_mm: [
                0.5 * dy * carrying(columns.middle),
                0.25 * dy * (carrying(columns.first) + carrying(columns.last)),
            ],
            cells_across: 0.5 * carrying(points[top][0]),
            edge_across_mpa: edge_across(points, pressure, dy),
            crown_drop_end_um: 1e3 * end_drop,
            approach_um: 1e3 * contact.approach_mm,
            centre_line: (0..points.len())
                .filter(|&i| points[i][1].abs() < 0.5 * dy)
                .map(|i| [points[i][0], pressure[i]])
                .collect(),
        }
    }
}

/// The largest pressure on the outermost rows across (the least and the largest y) of a grid
/// of `points` with cells `dy` across \[MPa\].
fn edge_across(points: &[[f64; 3]], pressure: &[f64], dy: f64) -> f64 {
    let (low, high) = points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x[1]), h.max(x[1]))
        });
    let outer = |y: f64| y < low + 0.5 * dy || y > high - 0.5 * dy;
    (points.iter().zip(pressure))
        .filter(|(x, _)| outer(x[1]))
        .map(|(_, &p)| p)
        .fold(0.0, f64::max)
}

/// The figures of every case of a roller under one crown, and the worst p_max over them.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RollerFigures {
    /// Each case's figures, in the cases' order (the scene's own first).
    pub cases: Vec<CaseFigures>,
    /// The largest p_max over the cases \[MPa\].
    pub worst_p_max: f64,
}

impl RollerFigures {
    /// The figures of `contacts` on a grid of `points` with the crown's `drop` per point and
    /// the cell size across `dy` \[mm\].
    pub fn new(contacts: &[CaseContact], points: &[[f64; 3]], drop: &[f64], dy: f64) -> Self {
        let cases: Vec<CaseFigures> = contacts
            .iter()
            .map(|c| CaseFigures::new(c, points, drop, dy))
            .collect();
        let worst_p_max = cases.iter().map(|c| c.p_max).fold(0.0, f64::max);
        Self { cases, worst_p_max }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 × 3 grid: the end ratio, the half-widths, the peak's place and the centre line.
    #[test]
    fn figures_of_a_small_grid() {
        let points: Vec<[f64; 3]> = (0..9)
            .map(|k| [(k % 3) as f64 - 1.0, 0.1 * ((k / 3) as f64 - 1.0), 0.0])
            .collect();
        // Columns x = −1, 0, 1; rows y = −0.1, 0, 0.1.
        let pressure = [0.0, 1.0, 0.0, 3.0, 2.0, 1.0, 0.0, 1.0, 0.0];
        assert_eq!(end_ratio(&points, &pressure), 1.5);
        let contact = CaseContact {
            load_n: 10.0,
            tilt_arcmin: 1.0,
            pressure: &pressure,
            approach_mm: 0.002,
        };
        let drop = [0.001, 0.0, 0.002, 0.001, 0.0, 0.002, 0.001, 0.0, 0.002];
        let f = CaseFigures::new(&contact, &points, &drop, 0.1);
        assert_eq!((f.p_max, f.p_max_at_mm), (3.0, [-1.0, 0.0]));
        assert!(f.edge_loading);
        assert!((f.half_width_mm[0] - 0.15).abs() < 1e-15 && f.half_width_mm[1] == 0.05);
        assert!((f.crown_drop_end_um - 2.0).abs() < 1e-12);
        // The peak's column x = −1 carries one cell of three.
        assert_eq!(f.cells_across, 0.5);
        // The rows y = ±0.1 carry 1 at x = 0.
        assert_eq!(f.edge_across_mpa, 1.0);
        assert_eq!(f.centre_line, vec![[-1.0, 3.0], [0.0, 2.0], [1.0, 1.0]]);
        let all = RollerFigures::new(&[contact], &points, &drop, 0.1);
        assert_eq!(all.worst_p_max, 3.0);
        assert!(serde_json::to_string(&all)
            .unwrap()
            .contains("\"edge_loading\":true"));
    }
}
