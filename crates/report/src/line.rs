//! Line charts: labelled series on round axes, with dashed reference curves (a closed form
//! beside the computed values) and the legend to the right of the plot.

use std::io;

use plotters::chart::ChartBuilder;
use plotters::series::{DashedLineSeries, LineSeries};
use plotters::style::{Color, RGBColor, BLACK, TRANSPARENT};

use crate::figure::{self, Area, Drawn, Entry, Figure, Margins};
use crate::scale::Scale;
use crate::style::{self, LABEL_SIZE, TICK_LENGTH, TICK_SIZE};
use crate::ticks::Axis;

/// A reference curve's colour: its line's, this much as bright.
const REFERENCE_SHADE: f64 = 0.5;

/// The plot's size inside its axes \[px\].
const PLOT: (f64, f64) = (600.0, 380.0);

/// A line chart: a title, the axes' descriptions with their units, and the lines.
#[derive(Clone, Debug)]
pub struct LineChart {
    title: String,
    x_label: String,
    y_label: String,
    lines: Vec<Line>,
    /// The top of the y axis, when the lines reach past it (they are cut there).
    y_limit: Option<f64>,
}

#[derive(Clone, Debug)]
struct Line {
    label: String,
    points: Vec<(f64, f64)>,
    /// For a reference curve: the line it accompanies.
    reference_of: Option<usize>,
}

impl LineChart {
    /// A chart without lines; the axis labels carry their units (`p [MPa]`).
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            lines: vec![],
            y_limit: None,
        }
    }

    /// Adds a line in the next colour. Points with a coordinate that is not finite are left
    /// out.
    pub fn line(mut self, label: &str, points: &[(f64, f64)]) -> Self {
        self.lines.push(Line {
            label: label.into(),
            points: finite(points),
            reference_of: None,
        });
        self
    }

    /// Adds a dashed reference curve (a closed form) beside the last line added: in black when
    /// the chart has one line, else in a darker shade of that line's colour (visible where the
    /// two agree).
    pub fn reference(mut self, label: &str, points: &[(f64, f64)]) -> Self {
        let of = self.lines.iter().rposition(|l| l.reference_of.is_none());
        self.lines.push(Line {
            label: label.into(),
            points: finite(points),
            reference_of: Some(of.unwrap_or(0)),
        });
        self
    }

    /// Ends the y axis at `limit`: the lines are cut where they cross it. For a value that grows
    /// without bound, such as the pressure at a flat punch's rim.
    pub fn clip_above(mut self, limit: f64) -> Self {
        self.y_limit = limit.is_finite().then_some(limit);
        self
    }

    /// Whether the chart has a point to draw.
    pub fn is_empty(&self) -> bool {
        self.lines.iter().all(|l| l.points.is_empty())
    }

    /// The chart, drawn.
    pub fn draw(&self) -> io::Result<Figure> {
        let points = || self.lines.iter().flat_map(|l| l.points.iter());
        let x = Axis::over(points().map(|p| p.0));
        let y = match self.y_limit {
            Some(top) => Axis::over(points().map(|p| p.1.min(top)).chain([top])),
            None => Axis::over(points().map(|p| p.1)),
        };
        let labels = |a: &Axis| a.ticks().iter().map(|&v| a.label(v)).collect::<Vec<_>>();
        let margins = Margins::fit(&labels(&x), &labels(&y), &self.x_label, &self.y_label);
        let entries = self.entries();
        let (legend_w, legend_h) = figure::legend_size(&entries);
        let title_h = figure::title_height(self.title.lines().count());
        let plot_w = margins.left + PLOT.0 + margins.right;
        let plot_h = margins.top + PLOT.1 + margins.bottom;
        let width = (plot_w + legend_w).max(figure::title_width(&self.title));
        let height = title_h + plot_h.max(margins.top + legend_h);
        Figure::draw(width, height, |root| {
            figure::draw_title(root, &self.title)?;
            let (_, body) = root.split_vertically(title_h as u32);
            let (plot, legend) = body.split_horizontally(plot_w as u32);
            self.plot(&plot, &x, &y, &margins)?;
            figure::draw_legend(&legend, &entries, 0.0, margins.top)
        })
    }

    /// The colour of line `k`.
    fn colour(&self, k: usize) -> RGBColor {
        let solid = self
            .lines
            .iter()
            .filter(|l| l.reference_of.is_none())
            .count();
        match self.lines[k].reference_of {
            Some(_) if solid <= 1 => BLACK,
            Some(of) => {
                let RGBColor(r, g, b) = self.colour(of);
                let dark = |c: u8| (f64::from(c) * REFERENCE_SHADE).round() as u8;
                RGBColor(dark(r), dark(g), dark(b))
            }
            None => {
                let index = self.lines[..k]
                    .iter()
                    .filter(|l| l.reference_of.is_none())
                    .count();
                style::colour(index)
            }
        }
    }

    fn entries(&self) -> Vec<Entry> {
        (0..self.lines.len())
            .filter(|&k| !self.lines[k].label.is_empty())
            .map(|k| Entry {
                label: self.lines[k].label.clone(),
                colour: self.colour(k),
                dashed: self.lines[k].reference_of.is_some(),
                marker: None,
            })
            .collect()
    }

    /// The axes and the lines on `area`.
    fn plot(&self, area: &Area, x: &Axis, y: &Axis, m: &Margins) -> Drawn {
        let mut chart = ChartBuilder::on(area)
            .margin_top(m.top as u32)
            .margin_right(m.right as u32)
            .x_label_area_size(m.bottom as u32)
            .y_label_area_size(m.left as u32)
            .build_cartesian_2d(Scale::of(x), Scale::of(y))?;
        chart
            .configure_mesh()
            .x_desc(self.x_label.as_str())
            .y_desc(self.y_label.as_str())
            .x_label_formatter(&|v| x.label(*v))
            .y_label_formatter(&|v| y.label(*v))
            .label_style(style::text(TICK_SIZE))
            .axis_desc_style(style::text(LABEL_SIZE))
            .bold_line_style(style::GRID.stroke_width(1))
            .light_line_style(TRANSPARENT)
            .set_all_tick_mark_size(TICK_LENGTH)
            .draw()?;
        for (k, line) in self.lines.iter().enumerate() {
            let colour = self.colour(k);
            for piece in below(&line.points, y.hi) {
                if line.reference_of.is_some() {
                    let (dash, gap) = style::DASH;
                    let stroke = style::stroke(colour, 2);
                    chart.draw_series(DashedLineSeries::new(piece, dash, gap, stroke))?;
                } else {
                    chart.draw_series(LineSeries::new(piece, style::stroke(colour, 2)))?;
                }
            }
        }
        Ok(())
    }
}

/// The pieces of the polyline `points` at or below `top`, each cut where it crosses it.
fn below(points: &[(f64, f64)], top: f64) -> Vec<Vec<(f64, f64)>> {
    let mut pieces = vec![];
    let mut piece: Vec<(f64, f64)> = vec![];
    let crossing = |a: (f64, f64), b: (f64, f64)| {
        let t = (top - a.1) / (b.1 - a.1);
        (a.0 + t * (b.0 - a.0), top)
    };
    for (k, &p) in points.iter().enumerate() {
        let previous = k.checked_sub(1).map(|j| points[j]);
        match (p.1 <= top, previous) {
            (true, Some(q)) if q.1 > top => piece.push(crossing(q, p)),
            (false, Some(q)) if q.1 <= top => {
                piece.push(crossing(q, p));
                pieces.push(std::mem::take(&mut piece));
            }
            _ => {}
        }
        if p.1 <= top {
            piece.push(p);
        }
    }
    pieces.push(piece);
    pieces.retain(|p| !p.is_empty());
    pieces
}

/// The points with both coordinates finite.
fn finite(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A line that leaves the top of the axis is cut where it crosses it and resumes where
    /// it comes back.
    #[test]
    fn lines_are_cut_at_the_top() {
        let points = [(0.0, 1.0), (1.0, 3.0), (2.0, 5.0), (3.0, 1.0)];
        let pieces = below(&points, 2.0);
        assert_eq!(
            pieces,
            vec![vec![(0.0, 1.0), (0.5, 2.0)], vec![(2.75, 2.0), (3.0, 1.0)]]
        );
        assert_eq!(below(&points, 10.0), vec![points.to_vec()]);
        assert!(below(&[(0.0, 5.0)], 1.0).is_empty());
    }

    /// Tick labels wide and narrow, a long legend, a reference and a point that is not
    /// finite: no text overlaps another or leaves the figure, the labels are round and the
    /// legend is in the given words.
    #[test]
    fn text_never_overlaps_nor_is_cut_off() {
        let p: Vec<(f64, f64)> = (0..50)
            .map(|k| (0.313 + k as f64, 93317.0 * (k as f64 / 49.0).sqrt()))
            .chain([(f64::NAN, 1.0), (3.0, f64::INFINITY)])
            .collect();
        let chart = LineChart::new("a title", "r [mm]", "p [MPa]")
            .line("L1 = 20 mm", &p)
            .reference(
                "Boussinesq–Sneddon, a long name for a closed form",
                &p[..10],
            );
        let svg = chart.draw().unwrap().svg().to_string();
        crate::figure::check::assert_text_clear(&svg);
        let texts: Vec<String> = crate::figure::check::text_boxes(&svg)
            .into_iter()
            .map(|b| b.text)
            .collect();
        for label in ["0", "10", "50", "20000", "100000", "L1 = 20 mm", "p [MPa]"] {
            assert!(texts.iter().any(|t| t == label), "{label} in {texts:?}");
        }
        assert!(!svg.contains("NaN") && !svg.contains("inf"));
        // One value only: a widened range, still clear.
        let flat = LineChart::new("t", "x [mm]", "p [MPa]").line("one", &[(1.0, 0.0)]);
        crate::figure::check::assert_text_clear(flat.draw().unwrap().svg());
    }
}
