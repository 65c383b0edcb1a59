//! Horizontal bar charts: a group of bars per row (a case), one bar per series (a kind of
//! value), each bar with its value at its end; the groups' labels to the left, the legend to
//! the right.

use std::io;

use plotters::element::{PathElement, Rectangle, Text};
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{Color, BLACK};

use contopt_results::words::significant;

use crate::figure::{self, Area, Drawn, Entry, Figure};
use crate::font::text_size;
use crate::style::{self, GAP, LABEL_SIZE, TICK_LENGTH, TICK_SIZE};
use crate::ticks::Axis;

/// The plot's width inside its axis \[px\].
const PLOT_WIDTH: f64 = 480.0;
/// A bar's height \[px\].
const BAR: f64 = 14.0;
/// The space between two groups \[px\].
const GROUP_GAP: f64 = 12.0;
/// The axis reaches this far past the longest bar, for its value.
const HEADROOM: f64 = 1.25;
/// Significant digits of a bar's value.
const DIGITS: usize = 4;

/// A horizontal bar chart: a title, the values' description with its unit, the series and
/// the groups.
#[derive(Clone, Debug)]
pub struct BarChart {
    title: String,
    x_label: String,
    series: Vec<String>,
    groups: Vec<(String, Vec<f64>)>,
}

impl BarChart {
    /// A chart of `series` without groups; `x_label` carries the unit (`L10r [10⁶ rev]`).
    pub fn new(title: &str, x_label: &str, series: &[&str]) -> Self {
        Self {
            title: title.into(),
            x_label: x_label.into(),
            series: series.iter().map(|s| s.to_string()).collect(),
            groups: vec![],
        }
    }

    /// Adds a group: its label and one value per series (a value that is not finite or is
    /// negative draws no bar).
    pub fn group(mut self, label: &str, values: &[f64]) -> Self {
        self.groups.push((label.into(), values.to_vec()));
        self
    }

    /// Whether the chart has a bar to draw.
    pub fn is_empty(&self) -> bool {
        !self
            .groups
            .iter()
            .flat_map(|g| &g.1)
            .any(|v| v.is_finite() && *v >= 0.0)
    }

    /// The chart, drawn.
    pub fn draw(&self) -> io::Result<Figure> {
        let values = self
            .groups
            .iter()
            .flat_map(|g| g.1.iter().copied())
            .filter(|v| v.is_finite() && *v >= 0.0);
        let top = values.fold(0.0f64, f64::max) * HEADROOM;
        let axis = Axis::between(0.0, top.max(f64::MIN_POSITIVE));
        let labels_w = self
            .groups
            .iter()
            .map(|g| text_size(&g.0, TICK_SIZE).0)
            .fold(0.0, f64::max)
            + 2.0 * GAP;
        let (_, tick_h) = text_size("", TICK_SIZE);
        let (_, desc_h) = text_size("", LABEL_SIZE);
        let row = self.series.len().max(1) as f64 * BAR + GROUP_GAP;
        let plot_h = self.groups.len() as f64 * row + GROUP_GAP;
        let bottom = f64::from(2 * TICK_LENGTH) + 1.3 * tick_h + 1.3 * desc_h + GAP;
        let last = axis.label(*axis.ticks().last().unwrap_or(&0.0));
        let right = text_size(&last, TICK_SIZE).0 / 2.0 + GAP;
        let entries = self.entries();
        let (legend_w, legend_h) = figure::legend_size(&entries);
        let title_h = figure::title_height(self.title.lines().count());
        let plot_w = labels_w + PLOT_WIDTH + right;
        let width = (plot_w + legend_w).max(figure::title_width(&self.title));
        let height = title_h + (GAP + plot_h + bottom).max(legend_h + GAP);
        Figure::draw(width, height, |root| {
            figure::draw_title(root, &self.title)?;
            let (_, body) = root.split_vertically(title_h as u32);
            let (plot, legend) = body.split_horizontally(plot_w as u32);
            let layout = Layout {
                left: labels_w,
                top: GAP,
                height: plot_h,
                row,
                axis,
            };
            self.plot(&plot, &layout)?;
            figure::draw_legend(&legend, &entries, 0.0, GAP)
        })
    }

    fn entries(&self) -> Vec<Entry> {
        self.series
            .iter()
            .enumerate()
            .map(|(k, s)| Entry {
                label: s.clone(),
                colour: style::colour(k),
                dashed: false,
                marker: None,
            })
            .collect()
    }

    /// The bars, their values, the groups' labels and the axis on `area`.
    fn plot(&self, area: &Area, at: &Layout) -> Drawn {
        let x = |v: f64| at.left + PLOT_WIDTH * (v - at.axis.lo) / (at.axis.hi - at.axis.lo);
        let label_style = style::text(TICK_SIZE).pos(Pos::new(HPos::Right, VPos::Center));
        let value_style = style::text(TICK_SIZE).pos(Pos::new(HPos::Left, VPos::Center));
        for (g, (label, values)) in self.groups.iter().enumerate() {
            let y0 = at.top + GROUP_GAP + g as f64 * at.row;
            let middle = y0 + 0.5 * (at.row - GROUP_GAP);
            let anchor = ((at.left - GAP) as i32, middle as i32);
            area.draw(&Text::new(label.clone(), anchor, label_style.clone()))?;
            for (k, &v) in values.iter().enumerate() {
                if !(v.is_finite() && v >= 0.0) {
                    continue;
                }
                let (top, bottom) = (y0 + k as f64 * BAR, y0 + (k + 1) as f64 * BAR - 2.0);
                let corners = [(x(0.0) as i32, top as i32), (x(v) as i32, bottom as i32)];
                area.draw(&Rectangle::new(corners, style::colour(k).filled()))?;
                let at_end = ((x(v) + GAP / 2.0) as i32, (0.5 * (top + bottom)) as i32);
                let text = significant(v, DIGITS);
                area.draw(&Text::new(text, at_end, value_style.clone()))?;
            }
        }
        let base = (at.top + at.height) as i32;
        let line = style::stroke(BLACK, 1);
        let (from, to) = (x(at.axis.lo) as i32, x(at.axis.hi) as i32);
        area.draw(&PathElement::new([(from, base), (to, base)], line))?;
        area.draw(&PathElement::new(
            [(from, base), (from, at.top as i32)],
            line,
        ))?;
        let tick_style = style::text(TICK_SIZE).pos(Pos::new(HPos::Center, VPos::Top));
        for t in at.axis.ticks() {
            let tx = x(t) as i32;
            area.draw(&PathElement::new(
                [(tx, base), (tx, base + TICK_LENGTH)],
                line,
            ))?;
            let anchor = (tx, base + 2 * TICK_LENGTH);
            area.draw(&Text::new(at.axis.label(t), anchor, tick_style.clone()))?;
        }
        let (_, tick_h) = text_size("", TICK_SIZE);
        let desc = style::text(LABEL_SIZE).pos(Pos::new(HPos::Center, VPos::Top));
        let anchor = (
            x(0.5 * (at.axis.lo + at.axis.hi)) as i32,
            base + 2 * TICK_LENGTH + (1.3 * tick_h) as i32,
        );
        area.draw(&Text::new(self.x_label.clone(), anchor, desc))?;
        Ok(())
    }
}

/// Where a bar chart's plot lies in its area \[px\].
struct Layout {
    left: f64,
    top: f64,
    height: f64,
    /// A group's height with its gap.
    row: f64,
    axis: Axis,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Long labels, a value that is not finite and values of three magnitudes: no text
    /// overlaps another or leaves the figure; every finite value is written at its bar.
    #[test]
    fn bars_and_their_values_are_clear() {
        let chart = BarChart::new(
            "lives per profile",
            "L10r [10⁶ rev]",
            &["half-space", "slices", "ISO 281"],
        )
        .group("robust, L1 = 4.5 mm, a long label", &[612.0, 598.5, 217.6])
        .group("ISO/TS 16281", &[583.26, f64::NAN, 217.6])
        .group("circular", &[0.5, 1.0, 20.0]);
        assert!(!chart.is_empty());
        let svg = chart.draw().unwrap().svg().to_string();
        crate::figure::check::assert_text_clear(&svg);
        let texts: Vec<String> = crate::figure::check::text_boxes(&svg)
            .into_iter()
            .map(|b| b.text)
            .collect();
        for t in [
            "612",
            "598.5",
            "583.3",
            "ISO/TS 16281",
            "L10r [10⁶ rev]",
            "0",
        ] {
            assert!(texts.iter().any(|x| x == t), "{t} in {texts:?}");
        }
        assert!(!svg.contains("NaN"));
        assert!(BarChart::new("t", "x", &["a"])
            .group("g", &[f64::NAN])
            .is_empty());
    }
}
