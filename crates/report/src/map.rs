//! Maps of a value over a regular grid of cells: the contact pressure over a two-dimensional
//! region, a stress on a vertical section below the surface; with a colour bar.

use std::io;

use plotters::chart::ChartBuilder;
use plotters::element::Rectangle;
use plotters::style::{Color, TRANSPARENT};

use crate::figure::{self, Area, Drawn, Figure, Margins};
use crate::scale::Scale;
use crate::style::{self, GAP, HEAT_LEVELS, LABEL_SIZE, TICK_LENGTH, TICK_SIZE};
use crate::ticks::Axis;

/// The map's size inside its axes \[px\] when the region's aspect cannot be kept (a roller's
/// contact is fifty times longer than wide).
const PLOT: (f64, f64) = (640.0, 320.0);

/// The smallest and largest map \[px\] that keeps the region's aspect (one mm as long across
/// as down).
const KEPT_MIN: (f64, f64) = (320.0, 200.0);
const KEPT_MAX: (f64, f64) = (800.0, 520.0);

/// The map's size inside its axes for a region `width` × `height` \[mm\]: to scale when that
/// fits between [`KEPT_MIN`] and [`KEPT_MAX`], else [`PLOT`].
fn plot_size(width: f64, height: f64) -> (f64, f64) {
    let aspect = height / width;
    let fits = |(w, h): (f64, f64)| {
        (KEPT_MIN.0..=KEPT_MAX.0).contains(&w) && (KEPT_MIN.1..=KEPT_MAX.1).contains(&h)
    };
    [
        (PLOT.0, PLOT.0 * aspect),
        (KEPT_MAX.1 / aspect, KEPT_MAX.1),
        (KEPT_MIN.1 / aspect, KEPT_MIN.1),
    ]
    .into_iter()
    .find(|&size| fits(size))
    .unwrap_or(PLOT)
}

/// The colour bar's width \[px\].
const BAR: f64 = 18.0;

/// Significant digits of the colour bar's largest value.
const BAR_DIGITS: usize = 4;

/// Coordinates closer than this \[mm\] are one row or column of cells.
const SAME: f64 = 1e-9;

/// A heat map of `points` (x, y, value) at the centres of a regular grid of cells: cropped to
/// the rows where some value is positive (with one row of margin), to scale where the region's
/// aspect allows, cells of one colour level merged along x, and a colour bar from 0 to the
/// largest value, whose description is `unit`. Points with a coordinate that is not finite are
/// left out.
pub fn heat_map(
    title: &str,
    x_label: &str,
    y_label: &str,
    unit: &str,
    points: &[(f64, f64, f64)],
) -> io::Result<Figure> {
    Grid::new(points).draw(title, x_label, y_label, unit, false)
}

/// A map of a vertical section below a surface, `points` (position along the surface, depth,
/// value): the surface at the top, depth growing downwards.
pub fn section_map(
    title: &str,
    x_label: &str,
    unit: &str,
    points: &[(f64, f64, f64)],
) -> io::Result<Figure> {
    let below: Vec<(f64, f64, f64)> = points.iter().map(|&(x, d, v)| (x, -d, v)).collect();
    Grid::new(&below).draw(title, x_label, "depth below the surface [mm]", unit, true)
}

/// The values on their grid: `values[row][column]`, rows along y.
struct Grid {
    xs: Vec<f64>,
    ys: Vec<f64>,
    values: Vec<Vec<f64>>,
    top: f64,
}

impl Grid {
    fn new(points: &[(f64, f64, f64)]) -> Self {
        let finite: Vec<_> = points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
            .collect();
        let distinct = |pick: fn(&(f64, f64, f64)) -> f64| {
            let mut v: Vec<f64> = finite.iter().map(|p| pick(p)).collect();
            v.sort_by(f64::total_cmp);
            v.dedup_by(|a, b| (*a - *b).abs() < SAME);
            v
        };
        let (xs, ys) = (distinct(|p| p.0), distinct(|p| p.1));
        let index = |v: &[f64], c: f64| v.partition_point(|&t| t < c - SAME).min(v.len() - 1);
        let mut values = vec![vec![0.0; xs.len()]; ys.len()];
        for p in &finite {
            values[index(&ys, p.1)][index(&xs, p.0)] = p.2;
        }
        let top = finite.iter().map(|p| p.2).fold(0.0, f64::max);
        Self {
            xs,
            ys,
            values,
            top,
        }
    }

    /// The rows to draw: those with a positive value, and one more on either side.
    fn rows(&self) -> (usize, usize) {
        let used: Vec<usize> = (0..self.ys.len())
            .filter(|&j| self.values[j].iter().any(|&v| v > 0.0))
            .collect();
        let last = self.ys.len().saturating_sub(1);
        match (used.first(), used.last()) {
            (Some(&a), Some(&b)) => (a.saturating_sub(1), (b + 1).min(last)),
            _ => (0, last),
        }
    }

    fn draw(
        &self,
        title: &str,
        x_label: &str,
        y_label: &str,
        unit: &str,
        depth: bool,
    ) -> io::Result<Figure> {
        if self.xs.is_empty() {
            let text = format!(
                "{}\nno finite values to draw",
                title.lines().next().unwrap_or("")
            );
            let width = figure::title_width(&text);
            return Figure::draw(width, figure::title_height(2), |area| {
                figure::draw_title(area, &text)
            });
        }
        let (j0, j1) = self.rows();
        let (x_lo, x_hi) = edges(&self.xs, 0, self.xs.len() - 1);
        let (y_lo, y_hi) = edges(&self.ys, j0, j1);
        let x = Axis::between(x_lo, x_hi);
        let y = Axis::between(y_lo, y_hi);
        let (xs, ys) = (Scale::within(x_lo, x_hi, &x), Scale::within(y_lo, y_hi, &y));
        let sign = if depth { -1.0 } else { 1.0 };
        let x_labels: Vec<String> = xs.ticks().iter().map(|&v| x.label(v)).collect();
        let y_labels: Vec<String> = ys.ticks().iter().map(|&v| y.label(sign * v)).collect();
        let m = Margins::fit(&x_labels, &y_labels, x_label, y_label);
        let bar = ColourBar::new(self.top, unit);
        let title_h = figure::title_height(title.lines().count());
        let plot = plot_size(x_hi - x_lo, y_hi - y_lo);
        let map_w = m.left + plot.0 + m.right;
        let width = (map_w + bar.width()).max(figure::title_width(title));
        let height = title_h + m.top + plot.1 + m.bottom;
        Figure::draw(width, height, |root| {
            figure::draw_title(root, title)?;
            let (_, body) = root.split_vertically(title_h as u32);
            let (map, right) = body.split_horizontally(map_w as u32);
            let mut chart = ChartBuilder::on(&map)
                .margin_top(m.top as u32)
                .margin_right(m.right as u32)
                .x_label_area_size(m.bottom as u32)
                .y_label_area_size(m.left as u32)
                .build_cartesian_2d(xs, ys)?;
            chart
                .configure_mesh()
                .disable_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .x_label_formatter(&|v| x.label(*v))
                .y_label_formatter(&|v| y.label(sign * *v))
                .label_style(style::text(TICK_SIZE))
                .axis_desc_style(style::text(LABEL_SIZE))
                .set_all_tick_mark_size(TICK_LENGTH)
                .draw()?;
            chart.draw_series(self.cells(j0, j1))?;
            bar.draw(&right, m.top, m.bottom)
        })
        .map(Figure::crisp)
    }

    /// The cells of rows `j0..=j1` as rectangles, runs of one colour level merged along x.
    fn cells(&self, j0: usize, j1: usize) -> Vec<Rectangle<(f64, f64)>> {
        let level = |v: f64| {
            if self.top > 0.0 {
                ((v / self.top).max(0.0) * (HEAT_LEVELS - 1) as f64).round() as usize
            } else {
                0
            }
        };
        let mut cells = vec![];
        for j in j0..=j1 {
            let (y0, y1) = edges(&self.ys, j, j);
            let row = &self.values[j];
            let mut i = 0;
            while i < row.len() {
                let (start, l) = (i, level(row[i]));
                while i < row.len() && level(row[i]) == l {
                    i += 1;
                }
                let (x0, x1) = edges(&self.xs, start, i - 1);
                let colour = style::viridis(l as f64 / (HEAT_LEVELS - 1) as f64);
                cells.push(Rectangle::new([(x0, y0), (x1, y1)], colour.filled()));
            }
        }
        cells
    }
}

/// The outer edges of cells `a..=b` of centres `c`: halfway to the neighbours, and as far
/// beyond the outermost centres as the neighbour inside (a single cell is one unit wide).
fn edges(c: &[f64], a: usize, b: usize) -> (f64, f64) {
    let half = |k: usize, l: usize| (c[l] - c[k]) / 2.0;
    let lo = match (a, c.len()) {
        (_, 1) => c[a] - 0.5,
        (0, _) => c[0] - half(0, 1),
        _ => c[a] - half(a - 1, a),
    };
    let hi = match (b + 1 == c.len(), c.len()) {
        (_, 1) => c[b] + 0.5,
        (true, n) => c[b] + half(n - 2, n - 1),
        (false, _) => c[b] + half(b, b + 1),
    };
    (lo, hi)
}

/// A vertical colour bar from 0 to `top`, labelled at round values and at `top`.
struct ColourBar {
    axis: Axis,
    top: f64,
    unit: String,
}

impl ColourBar {
    fn new(top: f64, unit: &str) -> Self {
        let top = if top > 0.0 { top } else { 1.0 };
        Self {
            axis: Axis::between(0.0, top),
            top,
            unit: unit.into(),
        }
    }

    /// The round ticks below the top, and the top itself unless a tick is near it.
    fn ticks(&self) -> Vec<f64> {
        let mut ticks: Vec<f64> = self
            .axis
            .ticks()
            .into_iter()
            .filter(|&t| t <= self.top)
            .collect();
        if ticks
            .last()
            .is_none_or(|&t| self.top - t > 0.3 * self.axis.step)
        {
            ticks.push(self.top);
        }
        ticks
    }

    fn label(&self, v: f64) -> String {
        if v == self.top {
            contopt_results::words::significant(v, BAR_DIGITS)
        } else {
            self.axis.label(v)
        }
    }

    fn labels(&self) -> Vec<String> {
        self.ticks().iter().map(|&v| self.label(v)).collect()
    }

    /// The width the bar takes with its labels and description.
    fn width(&self) -> f64 {
        let m = Margins::fit(&[], &self.labels(), "", &self.unit);
        2.0 * GAP + BAR + m.left + GAP
    }

    /// The bar at the left of `area`, as tall as the map (`top` and `bottom` its margins).
    fn draw(&self, area: &Area, top: f64, bottom: f64) -> Drawn {
        let m = Margins::fit(&[], &self.labels(), "", &self.unit);
        let scale = Scale::with_ticks(0.0, self.top, self.ticks());
        let mut chart = ChartBuilder::on(area)
            .margin_top(top as u32)
            .margin_bottom(bottom as u32)
            .margin_left((2.0 * GAP) as u32)
            .margin_right(GAP as u32)
            .right_y_label_area_size(m.left as u32)
            .build_cartesian_2d(Scale::with_ticks(0.0, 1.0, vec![]), scale)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .disable_x_axis()
            .bold_line_style(TRANSPARENT)
            .light_line_style(TRANSPARENT)
            .y_desc(self.unit.as_str())
            .y_label_formatter(&|v| self.label(*v))
            .label_style(style::text(TICK_SIZE))
            .axis_desc_style(style::text(LABEL_SIZE))
            .set_all_tick_mark_size(TICK_LENGTH)
            .draw()?;
        let step = self.top / HEAT_LEVELS as f64;
        chart.draw_series((0..HEAT_LEVELS).map(|k| {
            let colour = style::viridis(k as f64 / (HEAT_LEVELS - 1) as f64);
            let (y0, y1) = (k as f64 * step, (k + 1) as f64 * step);
            Rectangle::new([(0.0, y0), (1.0, y1)], colour.filled())
        }))?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::check::{assert_text_clear, text_boxes};

    /// One loaded cell in a 5 × 5 grid: the map keeps its row and one row either side, colours
    /// it at the top of the scale, labels the bar with its value, and keeps the aspect.
    #[test]
    fn heat_map_crops_to_the_contact_and_scales_to_the_peak() {
        let points: Vec<(f64, f64, f64)> = (0..25)
            .map(|k| {
                let (i, j) = (k % 5, k / 5);
                let p = if (i, j) == (2, 2) { 10.0 } else { 0.0 };
                (i as f64, j as f64, p)
            })
            .chain([(f64::NAN, 0.0, 1.0)])
            .collect();
        let svg = heat_map("t", "x [mm]", "y [mm]", "p [MPa]", &points)
            .unwrap()
            .svg()
            .to_string();
        assert_text_clear(&svg);
        let grid = Grid::new(&points);
        assert_eq!(grid.rows(), (1, 3));
        // Rows 1, 2 and 3 drawn: the loaded row as three runs, the others as one each.
        assert_eq!(grid.cells(1, 3).len(), 5);
        let top = style::viridis(1.0);
        assert_eq!((top.0, top.1, top.2), (253, 231, 37));
        assert!(svg.contains("#FDE725"), "the loaded cell at the top colour");
        let texts: Vec<String> = text_boxes(&svg).into_iter().map(|b| b.text).collect();
        assert!(texts.contains(&"10".to_string()) && texts.contains(&"p [MPa]".to_string()));
        assert!(!svg.contains("NaN"));
        // Five columns by three rows of 1 mm: drawn to scale.
        assert_eq!(plot_size(5.0, 3.0), (640.0, 384.0));
        assert_eq!(plot_size(10.0, 0.35), PLOT);
    }

    /// A section's depth grows downwards and is labelled positive; nothing finite says so.
    #[test]
    fn section_map_is_labelled_in_depth() {
        let points: Vec<(f64, f64, f64)> = (0..40)
            .map(|k| ((k % 8) as f64 * 0.1, 0.1 * (1 + k / 8) as f64, k as f64))
            .collect();
        let svg = section_map("two\nlines", "x [mm]", "von Mises stress [MPa]", &points)
            .unwrap()
            .svg()
            .to_string();
        assert_text_clear(&svg);
        let texts: Vec<String> = text_boxes(&svg).into_iter().map(|b| b.text).collect();
        assert!(texts.contains(&"depth below the surface [mm]".to_string()));
        assert!(texts.contains(&"0.4".to_string()) && !texts.iter().any(|t| t.starts_with('−')));
        let empty = section_map("t", "x", "u", &[(f64::NAN, 1.0, 1.0)]).unwrap();
        assert!(empty.svg().contains("no finite values to draw"));
    }
}
