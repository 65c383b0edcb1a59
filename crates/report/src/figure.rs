//! A drawn chart: its SVG text, rasterised to PNG on demand; and the layout pieces every chart
//! shares (title, margins that fit the tick labels and axis descriptions, legend).

use std::io;
use std::sync::{Arc, OnceLock};

use plotters::coord::Shift;
use plotters::drawing::{DrawingArea, DrawingAreaErrorKind, IntoDrawingArea};
use plotters::element::{DashedPathElement, PathElement, Text};
use plotters::prelude::SVGBackend;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{RGBColor, WHITE};

use crate::font::text_size;
use crate::style::{self, GAP, LABEL_SIZE, TICK_LENGTH, TICK_SIZE, TITLE_SIZE};

/// The PNG's pixels per SVG unit: sharp on a high-density screen and in print.
pub const PNG_SCALE: f32 = 2.0;

/// The area charts draw on.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// What drawing on an [`Area`] may fail with.
pub(crate) type Drawn = Result<(), DrawingAreaErrorKind<io::Error>>;

/// A chart, drawn once as SVG; the PNG is that SVG rasterised with the same embedded font.
#[derive(Clone, Debug)]
pub struct Figure {
    svg: String,
}

impl Figure {
    /// A `width` × `height` figure on white, painted by `paint`.
    pub(crate) fn draw(
        width: f64,
        height: f64,
        paint: impl FnOnce(&Area) -> Drawn,
    ) -> io::Result<Self> {
        let mut svg = String::new();
        {
            let size = (width.ceil() as u32, height.ceil() as u32);
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            root.fill(&WHITE)
                .and_then(|()| paint(&root))
                .and_then(|()| root.present())
                .map_err(|e| io::Error::other(format!("drawing a chart: {e}")))?;
        }
        svg.push('\n');
        Ok(Self { svg })
    }

    /// The figure with its shapes drawn without anti-aliasing (`shape-rendering="crispEdges"`):
    /// for maps of abutting cells, whose anti-aliased edges otherwise leave light seams between
    /// the rows when rendered. Text keeps its smoothing.
    pub(crate) fn crisp(mut self) -> Self {
        if let Some(at) = self.svg.find("<svg ") {
            self.svg
                .insert_str(at + 5, "shape-rendering=\"crispEdges\" ");
        }
        self
    }

    /// The SVG document.
    pub fn svg(&self) -> &str {
        &self.svg
    }

    /// The figure as PNG, [`PNG_SCALE`] pixels per SVG unit.
    pub fn png(&self) -> io::Result<Vec<u8>> {
        let tree = resvg::usvg::Tree::from_str(&self.svg, options())
            .map_err(|e| io::Error::other(format!("reading the chart's SVG: {e}")))?;
        let size = tree.size().to_int_size().scale_by(PNG_SCALE);
        let mut pixmap = size
            .and_then(|s| resvg::tiny_skia::Pixmap::new(s.width(), s.height()))
            .ok_or_else(|| io::Error::other("the chart has no area to rasterise"))?;
        pixmap.fill(resvg::tiny_skia::Color::WHITE);
        let scale = resvg::tiny_skia::Transform::from_scale(PNG_SCALE, PNG_SCALE);
        resvg::render(&tree, scale, &mut pixmap.as_mut());
        pixmap
            .encode_png()
            .map_err(|e| io::Error::other(format!("encoding the chart as PNG: {e}")))
    }

    /// The files of the figure: `<stem>.svg` and `<stem>.png`.
    pub fn files(&self, stem: &str) -> io::Result<[(String, Vec<u8>); 2]> {
        Ok([
            (format!("{stem}.svg"), self.svg.clone().into_bytes()),
            (format!("{stem}.png"), self.png()?),
        ])
    }
}

/// The SVG reader's options: only the embedded font, as the family of `sans-serif`.
fn options() -> &'static resvg::usvg::Options<'static> {
    static OPTIONS: OnceLock<resvg::usvg::Options<'static>> = OnceLock::new();
    OPTIONS.get_or_init(|| {
        let mut fonts = resvg::usvg::fontdb::Database::new();
        fonts.load_font_data(crate::font::FONT.to_vec());
        fonts.set_sans_serif_family(crate::font::FAMILY);
        resvg::usvg::Options {
            font_family: crate::font::FAMILY.into(),
            fontdb: Arc::new(fonts),
            ..Default::default()
        }
    })
}

/// The height of a title of `lines` lines.
pub(crate) fn title_height(lines: usize) -> f64 {
    lines as f64 * 1.4 * text_size("", TITLE_SIZE).1 + GAP
}

/// The width a title needs.
pub(crate) fn title_width(title: &str) -> f64 {
    title
        .lines()
        .map(|l| text_size(l, TITLE_SIZE).0)
        .fold(0.0, f64::max)
        + 4.0 * GAP
}

/// Draws the lines of `title` centred across `area`, from its top.
pub(crate) fn draw_title(area: &Area, title: &str) -> Drawn {
    let (width, _) = area.dim_in_pixel();
    let line = 1.4 * text_size("", TITLE_SIZE).1;
    let style = style::text(TITLE_SIZE).pos(Pos::new(HPos::Center, VPos::Top));
    for (k, text) in title.lines().enumerate() {
        let at = ((width / 2) as i32, (GAP / 2.0 + k as f64 * line) as i32);
        area.draw(&Text::new(text.to_string(), at, style.clone()))?;
    }
    Ok(())
}

/// The space around a plot that its tick labels and axis descriptions need \[px\]: the left
/// area holds the y description, a gap and the widest y label; the bottom area the x labels
/// and, below them, the x description; the right and top margins the halves of the outermost
/// labels that overhang the plot.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Margins {
    pub left: f64,
    pub bottom: f64,
    pub right: f64,
    pub top: f64,
}

impl Margins {
    /// The margins for these labels (a y description drawn across the left area).
    pub fn fit(x_labels: &[String], y_labels: &[String], x_desc: &str, y_desc: &str) -> Self {
        let tick = |l: &String| text_size(l, TICK_SIZE).0;
        let widest = y_labels.iter().map(tick).fold(0.0, f64::max);
        let (_, tick_height) = text_size("", TICK_SIZE);
        let (_, desc_height) = text_size("", LABEL_SIZE);
        let label_distance = f64::from(2 * TICK_LENGTH);
        let y_desc_width = if y_desc.is_empty() {
            0.0
        } else {
            1.3 * desc_height + GAP
        };
        let x_desc_height = if x_desc.is_empty() {
            0.0
        } else {
            1.3 * desc_height + GAP
        };
        let last_x = x_labels.last().map_or(0.0, tick);
        Self {
            left: y_desc_width + widest + label_distance + GAP / 2.0,
            bottom: label_distance + 1.3 * tick_height + x_desc_height,
            right: (last_x / 2.0 + GAP).max(2.0 * GAP),
            top: tick_height + GAP,
        }
    }
}

/// One entry of a legend: a line (dashed or not, with a marker or not) and its text.
#[derive(Clone, Debug)]
pub(crate) struct Entry {
    pub label: String,
    pub colour: RGBColor,
    pub dashed: bool,
    pub marker: Option<usize>,
}

/// The length of the line sample in a legend \[px\].
const SAMPLE: f64 = 30.0;

/// The size of a legend of `entries` in one column.
pub(crate) fn legend_size(entries: &[Entry]) -> (f64, f64) {
    let (_, height) = text_size("", TICK_SIZE);
    let widest = entries
        .iter()
        .map(|e| text_size(&e.label, TICK_SIZE).0)
        .fold(0.0, f64::max);
    let rows = entries.len() as f64;
    (SAMPLE + 4.0 * GAP + widest, rows * 1.6 * height + GAP)
}

/// Draws a legend of `entries` in one column from (`x`, `y`) of `area`.
pub(crate) fn draw_legend(area: &Area, entries: &[Entry], x: f64, y: f64) -> Drawn {
    let (_, height) = text_size("", TICK_SIZE);
    let style = style::text(TICK_SIZE).pos(Pos::new(HPos::Left, VPos::Center));
    for (k, e) in entries.iter().enumerate() {
        let row = (y + (k as f64 + 0.5) * 1.6 * height) as i32;
        let (x0, x1) = ((x + GAP) as i32, (x + GAP + SAMPLE) as i32);
        let line = style::stroke(e.colour, 2);
        if e.dashed {
            let (dash, gap) = style::DASH;
            area.draw(&DashedPathElement::new(
                [(x0, row), (x1, row)],
                dash,
                gap,
                line,
            ))?;
        } else {
            area.draw(&PathElement::new([(x0, row), (x1, row)], line))?;
        }
        if let Some(m) = e.marker {
            let centre = ((x0 + x1) / 2, row);
            let outline = style::marker_outline(m)
                .into_iter()
                .map(|(dx, dy)| (centre.0 + dx, centre.1 + dy));
            area.draw(&PathElement::new(outline.collect::<Vec<_>>(), line))?;
        }
        let at = ((x + 2.0 * GAP + SAMPLE) as i32, row);
        area.draw(&Text::new(e.label.clone(), at, style.clone()))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The PNG is the SVG's picture at twice its size, its text drawn with the embedded font
    /// (without a font the picture would stay white).
    #[test]
    fn png_has_the_svgs_size_and_its_text() {
        let figure = Figure::draw(200.0, 100.0, |area| draw_title(area, "Δh [µm]")).unwrap();
        assert!(figure.svg().starts_with("<svg") && figure.svg().contains("Δh [µm]"));
        let png = figure.png().unwrap();
        let pixmap = resvg::tiny_skia::Pixmap::decode_png(&png).unwrap();
        assert_eq!((pixmap.width(), pixmap.height()), (400, 200));
        let dark = pixmap.pixels().iter().filter(|p| p.red() < 128).count();
        assert!(dark > 200, "{dark} dark pixels");
        let blank = Figure::draw(200.0, 100.0, |_| Ok(()))
            .unwrap()
            .png()
            .unwrap();
        let blank = resvg::tiny_skia::Pixmap::decode_png(&blank).unwrap();
        assert!(blank.pixels().iter().all(|p| p.red() == 255));
    }
}

/// Checks of a drawn SVG's text, for the charts' tests.
#[cfg(test)]
pub(crate) mod check {
    use crate::font::text_size;

    /// A piece of text and the box it covers \[px\]: x from, x to, y from, y to.
    #[derive(Debug)]
    pub struct TextBox {
        pub text: String,
        pub x: (f64, f64),
        pub y: (f64, f64),
    }

    fn attribute(tag: &str, name: &str) -> Option<String> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_string())
    }

    /// The boxes of the SVG's `<text>` elements, measured with the embedded font, turned
    /// when the text is rotated by 270° or 90° (the descriptions of a left or right y axis).
    pub fn text_boxes(svg: &str) -> Vec<TextBox> {
        let mut boxes = vec![];
        for piece in svg.split("<text ").skip(1) {
            let (tag, rest) = piece.split_once('>').unwrap();
            let tag = &format!(" {tag}");
            let text = rest.split("</text>").next().unwrap().trim();
            let text = text
                .replace("&lt;", "<")
                .replace("&gt;", ">")
                .replace("&amp;", "&");
            let number = |name| attribute(tag, name).unwrap().parse::<f64>().unwrap();
            let (x, y, em) = (number("x"), number("y"), number("font-size"));
            let (w, _) = text_size(&text, 1.24 * em);
            let dx = match attribute(tag, "text-anchor").as_deref() {
                Some("middle") => (-w / 2.0, w / 2.0),
                Some("end") => (-w, 0.0),
                _ => (0.0, w),
            };
            let dy = match attribute(tag, "dy").as_deref() {
                Some("0.76em") => (0.0, em),
                Some("-0.5ex") => (-em, 0.0),
                _ => (-em / 2.0, em / 2.0),
            };
            let (bx, by) = match attribute(tag, "transform") {
                Some(t) if t.starts_with("rotate(270") => {
                    ((x + dy.0, x + dy.1), (y - dx.1, y - dx.0))
                }
                Some(t) if t.starts_with("rotate(90") => {
                    ((x - dy.1, x - dy.0), (y + dx.0, y + dx.1))
                }
                _ => ((x + dx.0, x + dx.1), (y + dy.0, y + dy.1)),
            };
            boxes.push(TextBox { text, x: bx, y: by });
        }
        boxes
    }

    /// The width and height of the SVG.
    pub fn size(svg: &str) -> (f64, f64) {
        let tag = svg.split('>').next().unwrap();
        let n = |name| attribute(tag, name).unwrap().parse::<f64>().unwrap();
        (n("width"), n("height"))
    }

    /// No text leaves the figure and no two pieces of text overlap (to a pixel).
    pub fn assert_text_clear(svg: &str) {
        let (width, height) = size(svg);
        let boxes = text_boxes(svg);
        assert!(!boxes.is_empty());
        for b in &boxes {
            let inside =
                b.x.0 >= -1.0 && b.x.1 <= width + 1.0 && b.y.0 >= -1.0 && b.y.1 <= height + 1.0;
            assert!(inside, "{b:?} leaves the {width} × {height} figure");
        }
        for (i, a) in boxes.iter().enumerate() {
            for b in &boxes[i + 1..] {
                let apart = a.x.1 <= b.x.0 + 1.0
                    || b.x.1 <= a.x.0 + 1.0
                    || a.y.1 <= b.y.0 + 1.0
                    || b.y.1 <= a.y.0 + 1.0;
                assert!(apart, "{a:?} overlaps {b:?}");
            }
        }
    }
}
