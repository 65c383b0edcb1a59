//! Panels side by side on log–log axes: a benchmark's error against run time, a run time
//! against the problem's size.

use std::io;

use plotters::chart::ChartBuilder;
use plotters::element::{EmptyElement, PathElement};
use plotters::series::{DashedLineSeries, LineSeries};
use plotters::style::{Color, RGBColor};

use crate::figure::{self, Area, Drawn, Entry, Figure, Margins};
use crate::scale::Scale;
use crate::style::{self, LABEL_SIZE, TICK_LENGTH, TICK_SIZE};
use contopt_results::words::power_of_ten;

use crate::ticks::decades;

/// A panel's size inside its axes \[px\].
const PLOT: (f64, f64) = (380.0, 300.0);

/// The faint grid at 2…9 times each decade.
const MINOR_GRID: RGBColor = RGBColor(240, 240, 240);

/// One panel of a [`log_log`] figure: its title, axis descriptions and series, each a name and
/// its (x, y) points.
#[derive(Clone, Copy, Debug)]
pub struct Panel<'a> {
    /// Title above the panel.
    pub title: &'a str,
    /// Description of the x axis, with its unit.
    pub x_label: &'a str,
    /// Description of the y axis, with its unit.
    pub y_label: &'a str,
    /// The series: name and points.
    pub series: &'a [(&'a str, &'a [(f64, f64)])],
}

/// Panels side by side on log–log axes under `title`: grid lines and ticks labelled 10ⁿ at the
/// decades, a faint grid at 2…9 times each, each series a line (every other one dashed) with an
/// open marker at every point. A series name keeps its colour, dash and marker in every panel,
/// and the legend lists each name once, to the right of the panels. Points with a coordinate
/// that is not positive and finite cannot be drawn and are left out.
pub fn log_log(title: &str, panels: &[Panel]) -> io::Result<Figure> {
    let mut names: Vec<&str> = vec![];
    for (name, _) in panels.iter().flat_map(|p| p.series.iter()) {
        if !names.contains(name) {
            names.push(name);
        }
    }
    let entries: Vec<Entry> = names
        .iter()
        .enumerate()
        .map(|(k, name)| Entry {
            label: name.to_string(),
            colour: style::colour(k),
            dashed: k % 2 == 1,
            marker: Some(k),
        })
        .collect();
    let layouts: Vec<Layout> = panels.iter().map(Layout::new).collect();
    let panel_w = |l: &Layout| l.margins.left + PLOT.0 + l.margins.right;
    let panel_h = |l: &Layout| l.margins.top + PLOT.1 + l.margins.bottom;
    let heading = figure::title_height(1);
    let (legend_w, legend_h) = figure::legend_size(&entries);
    let panels_w: f64 = layouts.iter().map(panel_w).sum();
    let tallest = layouts.iter().map(panel_h).fold(0.0, f64::max);
    let title_h = figure::title_height(title.lines().count());
    let width = (panels_w + legend_w).max(figure::title_width(title));
    let height = title_h + heading + tallest.max(legend_h);
    Figure::draw(width, height, |root| {
        figure::draw_title(root, title)?;
        let (_, mut rest) = root.split_vertically(title_h as u32);
        for ((panel, layout), w) in panels.iter().zip(&layouts).zip(layouts.iter().map(panel_w)) {
            let (area, right) = rest.split_horizontally(w as u32);
            figure::draw_title(&area, panel.title)?;
            let (_, plot) = area.split_vertically(heading as u32);
            layout.draw(&plot, panel, &names)?;
            rest = right;
        }
        figure::draw_legend(&rest, &entries, 0.0, heading)
    })
}

/// A panel's decades and margins.
struct Layout {
    x: (i32, i32),
    y: (i32, i32),
    margins: Margins,
}

impl Layout {
    fn new(panel: &Panel) -> Self {
        let points = || {
            panel
                .series
                .iter()
                .flat_map(|s| s.1.iter())
                .filter(|p| usable(p))
        };
        let x = decades(points().map(|p| p.0));
        let y = decades(points().map(|p| p.1));
        let labels = |(a, b): (i32, i32)| (a..=b).map(power_of_ten).collect::<Vec<_>>();
        let margins = Margins::fit(&labels(x), &labels(y), panel.x_label, panel.y_label);
        Self { x, y, margins }
    }

    fn draw(&self, area: &Area, panel: &Panel, names: &[&str]) -> Drawn {
        let m = &self.margins;
        let mut chart = ChartBuilder::on(area)
            .margin_top(m.top as u32)
            .margin_right(m.right as u32)
            .x_label_area_size(m.bottom as u32)
            .y_label_area_size(m.left as u32)
            .build_cartesian_2d(
                Scale::decades(self.x.0, self.x.1),
                Scale::decades(self.y.0, self.y.1),
            )?;
        let decade = |v: &f64| power_of_ten(v.round() as i32);
        chart
            .configure_mesh()
            .x_desc(panel.x_label)
            .y_desc(panel.y_label)
            .x_label_formatter(&decade)
            .y_label_formatter(&decade)
            .label_style(style::text(TICK_SIZE))
            .axis_desc_style(style::text(LABEL_SIZE))
            .bold_line_style(style::GRID.stroke_width(1))
            .light_line_style(MINOR_GRID.stroke_width(1))
            .set_all_tick_mark_size(TICK_LENGTH)
            .draw()?;
        for (name, data) in panel.series {
            let k = names.iter().position(|n| n == name).unwrap_or(0);
            let line = style::stroke(style::colour(k), 2);
            let at: Vec<(f64, f64)> = data
                .iter()
                .filter(|p| usable(p))
                .map(|p| (p.0.log10(), p.1.log10()))
                .collect();
            if k % 2 == 1 {
                let (dash, gap) = style::DASH;
                chart.draw_series(DashedLineSeries::new(at.clone(), dash, gap, line))?;
            } else {
                chart.draw_series(LineSeries::new(at.clone(), line))?;
            }
            let outline = style::marker_outline(k);
            chart.draw_series(
                at.into_iter()
                    .map(|p| EmptyElement::at(p) + PathElement::new(outline.clone(), line)),
            )?;
        }
        Ok(())
    }
}

/// Whether a point can be drawn on log–log axes.
fn usable(p: &(f64, f64)) -> bool {
    p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::figure::check::{assert_text_clear, text_boxes};

    /// Decades labelled in superscript over the data's range, a point at zero left out, and
    /// one legend entry per name across the panels.
    #[test]
    fn log_log_labels_decades_and_shares_the_legend() {
        let a = [(1e-3, 0.5), (0.2, 2e-3), (3.0, 0.0)];
        let b = [(0.05, 0.01)];
        let panel = |title, series| Panel {
            title,
            x_label: "run time [s]",
            y_label: "relative error",
            series,
        };
        let svg = log_log(
            "t",
            &[
                panel("one", &[("s", &a), ("r", &b)]),
                panel("two", &[("s", &b)]),
            ],
        )
        .unwrap()
        .svg()
        .to_string();
        assert_text_clear(&svg);
        let texts: Vec<String> = text_boxes(&svg).into_iter().map(|b| b.text).collect();
        for label in ["10⁻³", "10⁻²", "10⁰"] {
            assert!(texts.iter().any(|t| t == label), "{label}: {texts:?}");
        }
        // The point at y = 0 neither extends the x axis to 10¹ nor is drawn.
        assert!(
            !texts.iter().any(|t| t == "10¹" || t == "10⁻⁴"),
            "{texts:?}"
        );
        assert_eq!(texts.iter().filter(|t| *t == "s").count(), 1);
        assert_eq!(texts.iter().filter(|t| *t == "r").count(), 1);
        assert!(usable(&(1.0, 1.0)) && !usable(&(3.0, 0.0)) && !usable(&(f64::NAN, 1.0)));
    }
}
