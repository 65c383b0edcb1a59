//! Colours, dashes and markers shared by the charts, and the sizes of their text.

use plotters::style::{Color, IntoFont, RGBColor, ShapeStyle, TextStyle, BLACK};

/// Text sizes in plotters' units (the SVG's font size is 1/1.24 of them: 16, 13.7, 12.1 px).
pub(crate) const TITLE_SIZE: f64 = 20.0;
pub(crate) const LABEL_SIZE: f64 = 17.0;
pub(crate) const TICK_SIZE: f64 = 15.0;

/// A gap between pieces of text and the plot \[px\].
pub(crate) const GAP: f64 = 8.0;

/// Length of a tick mark \[px\]; plotters keeps tick labels twice that from the axis.
pub(crate) const TICK_LENGTH: i32 = 5;

/// Ten distinct colours (the Tableau palette), so that a study's series do not repeat.
const PALETTE: [RGBColor; 10] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// The grid lines at the ticks.
pub(crate) const GRID: RGBColor = RGBColor(221, 221, 221);

/// Colour `k` of the palette (repeating after ten).
pub(crate) fn colour(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// The dash of a dashed line: length and gap \[px\].
pub(crate) const DASH: (u32, u32) = (9, 5);

/// A stroke of `width` pixels in `colour`.
pub(crate) fn stroke(colour: RGBColor, width: u32) -> ShapeStyle {
    colour.stroke_width(width)
}

/// Text of plotters size `size` in the embedded font.
pub(crate) fn text(size: f64) -> TextStyle<'static> {
    TextStyle::from(("sans-serif", size).into_font()).color(&BLACK)
}

/// Radius of a marker \[px\].
const MARKER: f64 = 4.5;

/// The outline of marker `k` (circle, square, triangle, diamond, cross, inverted triangle, in
/// turn) around the origin \[px\], a closed path: drawn open, markers on one spot stay
/// distinguishable.
pub(crate) fn marker_outline(k: usize) -> Vec<(i32, i32)> {
    let r = MARKER;
    let corners: Vec<(f64, f64)> = match k % 6 {
        0 => (0..=16)
            .map(|i| {
                let t = std::f64::consts::TAU * i as f64 / 16.0;
                (t.cos(), t.sin())
            })
            .collect(),
        1 => vec![
            (-0.9, -0.9),
            (0.9, -0.9),
            (0.9, 0.9),
            (-0.9, 0.9),
            (-0.9, -0.9),
        ],
        2 => vec![(0.0, -1.2), (1.1, 0.8), (-1.1, 0.8), (0.0, -1.2)],
        3 => vec![
            (0.0, -1.25),
            (1.25, 0.0),
            (0.0, 1.25),
            (-1.25, 0.0),
            (0.0, -1.25),
        ],
        4 => vec![
            (-1.0, -1.0),
            (1.0, 1.0),
            (0.0, 0.0),
            (-1.0, 1.0),
            (1.0, -1.0),
        ],
        _ => vec![(0.0, 1.2), (1.1, -0.8), (-1.1, -0.8), (0.0, 1.2)],
    };
    corners
        .into_iter()
        .map(|(x, y)| ((x * r).round() as i32, (y * r).round() as i32))
        .collect()
}

/// Colour levels of a heat map: nearby values share a level, so a row of cells draws as a few
/// rectangles.
pub(crate) const HEAT_LEVELS: usize = 64;

/// Viridis at nine stops, interpolated: dark for zero, yellow for the largest value.
pub(crate) fn viridis(t: f64) -> RGBColor {
    const STOPS: [[f64; 3]; 9] = [
        [68.0, 1.0, 84.0],
        [71.0, 44.0, 122.0],
        [59.0, 81.0, 139.0],
        [44.0, 113.0, 142.0],
        [33.0, 144.0, 141.0],
        [39.0, 173.0, 129.0],
        [92.0, 200.0, 99.0],
        [170.0, 220.0, 50.0],
        [253.0, 231.0, 37.0],
    ];
    let s = t.clamp(0.0, 1.0) * (STOPS.len() - 1) as f64;
    let k = (s.floor() as usize).min(STOPS.len() - 2);
    let f = s - k as f64;
    let c = |i: usize| (STOPS[k][i] + f * (STOPS[k + 1][i] - STOPS[k][i])).round() as u8;
    RGBColor(c(0), c(1), c(2))
}
