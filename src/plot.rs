//! Plots written as SVG text, with no dependency: enough for the examples' figures.

use std::fmt::Write;

/// Text made safe for XML.
fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Ten distinct colours (the Tableau palette), so that a study's series do not repeat.
const PALETTE: [&str; 10] = [
    "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f",
    "#bcbd22", "#17becf",
];

/// The range of `values`, widened to a unit around a single value and to (0, 1) when there is
/// none, so that scaling by it never divides by zero.
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo > hi {
        (0.0, 1.0)
    } else if lo == hi {
        (lo - 0.5, hi + 0.5)
    } else {
        (lo, hi)
    }
}

/// A line chart as a stand-alone SVG document: each series is a name and its (x, y) points,
/// drawn in its own colour with its name as the legend.
pub fn line_plot(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    series: &[(&str, &[(f64, f64)])],
) -> String {
    let (title, xlabel, ylabel) = (escape(title), escape(xlabel), escape(ylabel));
    let (w, h, m) = (640.0, 400.0, 60.0);
    let finite = |p: &&(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let pts = series.iter().flat_map(|s| s.1.iter()).filter(finite);
    let (x0, x1) = span(pts.clone().map(|p| p.0));
    let (y0, y1) = span(pts.map(|p| p.1));
    let sx = |x: f64| m + (x - x0) / (x1 - x0) * (w - 2.0 * m);
    let sy = |y: f64| h - m - (y - y0) / (y1 - y0) * (h - 2.0 * m);
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"14\">{title}</text>",
        w / 2.0
    );
    let _ = writeln!(s, "<line x1=\"{m}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"black\"/><line x1=\"{m}\" y1=\"{m}\" x2=\"{m}\" y2=\"{}\" stroke=\"black\"/>", h - m, w - m, h - m, h - m);
    for i in 0..=5 {
        let (x, y) = (
            x0 + (x1 - x0) * i as f64 / 5.0,
            y0 + (y1 - y0) * i as f64 / 5.0,
        );
        let _ = writeln!(
            s,
            "<text x=\"{:.1}\" y=\"{}\" text-anchor=\"middle\">{x:.3}</text>",
            sx(x),
            h - m + 16.0
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{y:.3}</text>",
            m - 6.0,
            sy(y) + 4.0
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{xlabel}</text>",
        w / 2.0,
        h - 18.0
    );
    let _ = writeln!(s, "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{ylabel}</text>", h / 2.0, h / 2.0);
    for (k, (name, data)) in series.iter().enumerate() {
        let colour = PALETTE[k % PALETTE.len()];
        let dash = dash(k);
        let path: Vec<String> = data
            .iter()
            .filter(finite)
            .map(|p| format!("{:.2},{:.2}", sx(p.0), sy(p.1)))
            .collect();
        let _ = writeln!(
            s,
            "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"{dash} points=\"{}\"/>",
            path.join(" ")
        );
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" fill=\"{colour}\">{}</text>",
            m + 12.0,
            m + 16.0 * k as f64,
            escape(name)
        );
    }
    s.push_str("</svg>\n");
    s
}

/// One panel of a [`log_log_plot`]: its title, axis labels and series, each a name and its
/// (x, y) points.
pub struct Panel<'a> {
    /// Title above the panel.
    pub title: &'a str,
    /// Label of the x axis.
    pub xlabel: &'a str,
    /// Label of the y axis.
    pub ylabel: &'a str,
    /// The series: name and points.
    pub series: &'a [(&'a str, &'a [(f64, f64)])],
}

/// `10ⁿ` with the exponent in superscript digits.
fn power_of_ten(n: i32) -> String {
    const DIGITS: [char; 10] = ['⁰', '¹', '²', '³', '⁴', '⁵', '⁶', '⁷', '⁸', '⁹'];
    let exponent: String = n
        .to_string()
        .chars()
        .map(|c| c.to_digit(10).map_or('⁻', |d| DIGITS[d as usize]))
        .collect();
    format!("10{exponent}")
}

/// The decades that hold `values`: (⌊log₁₀ min⌋, ⌈log₁₀ max⌉), at least one apart.
fn decades(values: impl Iterator<Item = f64>) -> (i32, i32) {
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    if lo > hi {
        return (0, 1);
    }
    let (lo, hi) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
    (lo, hi.max(lo + 1))
}

/// Panels side by side on log–log axes, one stand-alone SVG document under `title`: grid lines
/// and ticks labelled 10ⁿ at the decades, short ticks at 2…9 times each, each series a line
/// (every other one dashed) with an open marker at every point. A series name keeps its colour
/// and marker in every panel, and the legend is a row below the panels, clear of the curves.
/// Points with a coordinate that is not positive and finite cannot be drawn and are left out.
pub fn log_log_plot(title: &str, panels: &[Panel]) -> String {
    let (pw, ph) = (440.0, 340.0);
    let (left, right, top, bottom) = (70.0, 20.0, 56.0, 52.0);
    let (iw, ih) = (pw - left - right, ph - top - bottom);
    let width = pw * panels.len().max(1) as f64;
    let mut names: Vec<&str> = vec![];
    for (name, _) in panels.iter().flat_map(|p| p.series.iter()) {
        if !names.contains(name) {
            names.push(name);
        }
    }
    // The legend: entries of a marker, a line and the name, wrapped to the width.
    let (mut x, mut y, mut legend) = (left, ph + 8.0, String::new());
    for (k, name) in names.iter().enumerate() {
        let span = 48.0 + 6.5 * name.chars().count() as f64;
        if x + span > width - right && x > left {
            (x, y) = (left, y + 20.0);
        }
        let colour = PALETTE[k % PALETTE.len()];
        let _ = writeln!(
            legend,
            "<line x1=\"{x}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" stroke=\"{colour}\" stroke-width=\"1.5\"{}/>{}<text x=\"{}\" y=\"{}\">{}</text>",
            x + 24.0,
            dash(k),
            marker(k, x + 12.0, y, colour),
            x + 30.0,
            y + 4.0,
            escape(name)
        );
        x += span;
    }
    let height = y + 16.0;
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"20\" text-anchor=\"middle\" font-size=\"15\">{}</text>",
        width / 2.0,
        escape(title)
    );
    let usable = |p: &&(f64, f64)| p.0 > 0.0 && p.1 > 0.0 && p.0.is_finite() && p.1.is_finite();
    for (j, panel) in panels.iter().enumerate() {
        let x0 = j as f64 * pw + left;
        let pts = || panel.series.iter().flat_map(|s| s.1.iter()).filter(usable);
        let (xa, xb) = decades(pts().map(|p| p.0));
        let (ya, yb) = decades(pts().map(|p| p.1));
        let sx = |v: f64| x0 + (v.log10() - xa as f64) / (xb - xa) as f64 * iw;
        let sy = |v: f64| top + ih - (v.log10() - ya as f64) / (yb - ya) as f64 * ih;
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"42\" text-anchor=\"middle\" font-size=\"13\">{}</text>",
            x0 + iw / 2.0,
            escape(panel.title)
        );
        // Decades: a grid line and a label; between them, short ticks at 2…9 times each.
        let minor = |a: i32, b: i32| {
            (a..b).flat_map(|d| (2..10).map(move |m| f64::from(m) * 10f64.powi(d)))
        };
        for d in xa..=xb {
            let x = sx(10f64.powi(d));
            let _ = writeln!(s, "<line x1=\"{x:.1}\" y1=\"{top}\" x2=\"{x:.1}\" y2=\"{}\" stroke=\"#ddd\"/><text x=\"{x:.1}\" y=\"{}\" text-anchor=\"middle\">{}</text>", top + ih, top + ih + 18.0, power_of_ten(d));
        }
        for x in minor(xa, xb).map(sx) {
            let _ = writeln!(
                s,
                "<line x1=\"{x:.1}\" y1=\"{}\" x2=\"{x:.1}\" y2=\"{}\" stroke=\"black\"/>",
                top + ih,
                top + ih - 4.0
            );
        }
        for d in ya..=yb {
            let y = sy(10f64.powi(d));
            let _ = writeln!(s, "<line x1=\"{x0}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"#ddd\"/><text x=\"{}\" y=\"{:.1}\" text-anchor=\"end\">{}</text>", x0 + iw, x0 - 6.0, y + 4.0, power_of_ten(d));
        }
        for y in minor(ya, yb).map(sy) {
            let _ = writeln!(
                s,
                "<line x1=\"{x0}\" y1=\"{y:.1}\" x2=\"{}\" y2=\"{y:.1}\" stroke=\"black\"/>",
                x0 + 4.0
            );
        }
        let _ = writeln!(s, "<rect x=\"{x0}\" y=\"{top}\" width=\"{iw}\" height=\"{ih}\" fill=\"none\" stroke=\"black\"/>");
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            x0 + iw / 2.0,
            top + ih + 38.0,
            escape(panel.xlabel)
        );
        let (lx, ly) = (x0 - 52.0, top + ih / 2.0);
        let _ = writeln!(s, "<text x=\"{lx}\" y=\"{ly}\" transform=\"rotate(-90 {lx} {ly})\" text-anchor=\"middle\">{}</text>", escape(panel.ylabel));
        for (name, data) in panel.series {
            let k = names.iter().position(|n| n == name).unwrap_or(0);
            let colour = PALETTE[k % PALETTE.len()];
            let at: Vec<(f64, f64)> = data
                .iter()
                .filter(usable)
                .map(|p| (sx(p.0), sy(p.1)))
                .collect();
            let path: Vec<String> = at
                .iter()
                .map(|p| format!("{:.2},{:.2}", p.0, p.1))
                .collect();
            let _ = writeln!(
                s,
                "<polyline fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"{} points=\"{}\"/>",
                dash(k),
                path.join(" ")
            );
            for &(x, y) in &at {
                s.push_str(&marker(k, x, y, colour));
            }
            s.push('\n');
        }
    }
    s.push_str(&legend);
    s.push_str("</svg>\n");
    s
}

/// The dash pattern of series `k`: every other one dashed.
fn dash(k: usize) -> &'static str {
    if k % 2 == 0 {
        ""
    } else {
        " stroke-dasharray=\"6 4\""
    }
}

/// Marker `k` (circle, square, triangle, diamond, cross, inverted triangle, in turn) at (x, y),
/// drawn open in `colour` so that markers on one spot stay distinguishable.
fn marker(k: usize, x: f64, y: f64, colour: &str) -> String {
    let r = 4.5;
    let style = format!("fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"");
    let polygon = |corners: &[(f64, f64)]| {
        let points: Vec<String> = corners
            .iter()
            .map(|(dx, dy)| format!("{:.2},{:.2}", x + dx * r, y + dy * r))
            .collect();
        format!("<polygon points=\"{}\" {style}/>", points.join(" "))
    };
    match k % 6 {
        0 => format!("<circle cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"{r}\" {style}/>"),
        1 => polygon(&[(-0.9, -0.9), (0.9, -0.9), (0.9, 0.9), (-0.9, 0.9)]),
        2 => polygon(&[(0.0, -1.2), (1.1, 0.8), (-1.1, 0.8)]),
        3 => polygon(&[(0.0, -1.25), (1.25, 0.0), (0.0, 1.25), (-1.25, 0.0)]),
        4 => format!(
            "<path d=\"M{:.2},{:.2}L{:.2},{:.2}M{:.2},{:.2}L{:.2},{:.2}\" {style}/>",
            x - r,
            y - r,
            x + r,
            y + r,
            x - r,
            y + r,
            x + r,
            y - r
        ),
        _ => polygon(&[(0.0, 1.2), (1.1, -0.8), (-1.1, -0.8)]),
    }
}

/// Colour levels of a heat map: nearby values share a level, so a row of cells draws as a few
/// rectangles.
const HEAT_LEVELS: usize = 64;

/// Viridis at nine stops, interpolated: dark for zero, yellow for the largest value.
fn viridis(t: f64) -> String {
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
    let c: Vec<u8> = (0..3)
        .map(|i| (STOPS[k][i] + f * (STOPS[k + 1][i] - STOPS[k][i])).round() as u8)
        .collect();
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// A heat map of `values` at the centres of a regular grid of cells, `points` (x, y, value),
/// as a stand-alone SVG document: cropped to the rows where some value is positive (with one
/// row of margin), cells of one colour level merged along x, and a colour bar from 0 to the
/// largest value in `unit`. The aspect is not kept: a roller's contact is 50 times longer
/// than wide.
pub fn heat_map(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    unit: &str,
    points: &[(f64, f64, f64)],
) -> String {
    map_svg(title, xlabel, ylabel, unit, points, false)
}

/// A heat map of a vertical section below a surface, `points` (position along the surface,
/// depth, value): the surface at the top, depth growing downwards and labelled as depth.
pub fn section_map(title: &str, xlabel: &str, unit: &str, points: &[(f64, f64, f64)]) -> String {
    let flipped: Vec<(f64, f64, f64)> = points.iter().map(|&(x, d, v)| (x, -d, v)).collect();
    map_svg(
        title,
        xlabel,
        "depth below the surface [mm]",
        unit,
        &flipped,
        true,
    )
}

/// [`heat_map`], with the y labels negated when `depth_down` (y is −depth).
fn map_svg(
    title: &str,
    xlabel: &str,
    ylabel: &str,
    unit: &str,
    points: &[(f64, f64, f64)],
    depth_down: bool,
) -> String {
    let finite: Vec<(f64, f64, f64)> = points
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite() && p.2.is_finite())
        .collect();
    if finite.is_empty() {
        return format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"720\" height=\"80\" font-family=\"sans-serif\" font-size=\"14\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"360\" y=\"30\" text-anchor=\"middle\">{}</text>\n<text x=\"360\" y=\"56\" text-anchor=\"middle\">no finite values to draw</text>\n</svg>\n",
            escape(title.lines().next().unwrap_or_default())
        );
    }
    let points = finite.as_slice();
    let distinct = |pick: fn(&(f64, f64, f64)) -> f64| {
        let mut v: Vec<f64> = points.iter().map(pick).collect();
        v.sort_by(f64::total_cmp);
        v.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
        v
    };
    let (xs, ys) = (distinct(|p| p.0), distinct(|p| p.1));
    let top = points.iter().map(|p| p.2).fold(0.0, f64::max);
    let index = |v: &[f64], c: f64| v.partition_point(|&t| t < c - 1e-9).min(v.len() - 1);
    let mut grid = vec![vec![0.0; xs.len()]; ys.len()];
    for p in points {
        grid[index(&ys, p.1)][index(&xs, p.0)] = p.2;
    }
    let used: Vec<usize> = (0..ys.len())
        .filter(|&j| grid[j].iter().any(|&v| v > 0.0))
        .collect();
    let (j0, j1) = match (used.first(), used.last()) {
        (Some(&a), Some(&b)) => (a.saturating_sub(1), (b + 1).min(ys.len() - 1)),
        _ => (0, ys.len() - 1),
    };
    let (w, h, m, bar) = (720.0, 360.0, 60.0, 70.0);
    let (cw, ch) = (
        (w - 2.0 * m - bar) / xs.len() as f64,
        (h - 2.0 * m) / (j1 - j0 + 1) as f64,
    );
    let mut s = format!("<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n");
    // A title of two lines (split at a newline) fits above the map.
    for (k, line) in title.lines().enumerate() {
        let _ = writeln!(
            s,
            "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-size=\"14\">{}</text>",
            w / 2.0,
            20 + 18 * k,
            escape(line)
        );
    }
    let level = |v: f64| {
        if top > 0.0 {
            ((v / top) * (HEAT_LEVELS - 1) as f64).round() as usize
        } else {
            0
        }
    };
    for (j, row) in grid.iter().enumerate().take(j1 + 1).skip(j0) {
        let y = m + (j1 - j) as f64 * ch;
        let mut i = 0;
        while i < xs.len() {
            let l = level(row[i]);
            let start = i;
            while i < xs.len() && level(row[i]) == l {
                i += 1;
            }
            let _ = writeln!(
                s,
                "<rect x=\"{:.2}\" y=\"{y:.2}\" width=\"{:.2}\" height=\"{:.2}\" fill=\"{}\"/>",
                m + start as f64 * cw,
                (i - start) as f64 * cw + 0.3,
                ch + 0.3,
                viridis(l as f64 / (HEAT_LEVELS - 1) as f64)
            );
        }
    }
    // Axes: the extremes of x and y of the drawn cells.
    let (x_lo, x_hi) = (xs[0], xs[xs.len() - 1]);
    let sign = if depth_down { -1.0 } else { 1.0 };
    let (y_lo, y_hi) = (sign * ys[j0], sign * ys[j1]);
    let right = w - m - bar;
    let _ = writeln!(s, "<text x=\"{m}\" y=\"{}\" text-anchor=\"start\">{x_lo:.3}</text><text x=\"{right}\" y=\"{}\" text-anchor=\"end\">{x_hi:.3}</text>", h - m + 16.0, h - m + 16.0);
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
        (m + right) / 2.0,
        h - m + 32.0,
        escape(xlabel)
    );
    let _ = writeln!(s, "<text x=\"{}\" y=\"{}\" text-anchor=\"end\">{y_hi:.3}</text><text x=\"{}\" y=\"{}\" text-anchor=\"end\">{y_lo:.3}</text>", m - 4.0, m + 10.0, m - 4.0, h - m);
    let _ = writeln!(
        s,
        "<text x=\"16\" y=\"{}\" transform=\"rotate(-90 16 {})\" text-anchor=\"middle\">{}</text>",
        h / 2.0,
        h / 2.0,
        escape(ylabel)
    );
    // The colour bar.
    let bx = w - m - bar + 20.0;
    for k in 0..HEAT_LEVELS {
        let t = k as f64 / (HEAT_LEVELS - 1) as f64;
        let _ = writeln!(
            s,
            "<rect x=\"{bx}\" y=\"{:.2}\" width=\"16\" height=\"{:.2}\" fill=\"{}\"/>",
            h - m - (k + 1) as f64 * (h - 2.0 * m) / HEAT_LEVELS as f64,
            (h - 2.0 * m) / HEAT_LEVELS as f64 + 0.3,
            viridis(t)
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\">{top:.1} {}</text><text x=\"{}\" y=\"{}\">0</text>",
        bx + 20.0,
        m + 10.0,
        escape(unit),
        bx + 20.0,
        h - m
    );
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Decades labelled in superscript over the data's range, a point at zero left out, and
    /// one legend entry per name across the panels.
    #[test]
    fn log_log_plot_labels_decades_and_shares_the_legend() {
        let a = [(1e-3, 0.5), (0.2, 2e-3), (3.0, 0.0)];
        let b = [(0.05, 0.01)];
        let svg = log_log_plot(
            "t",
            &[
                Panel {
                    title: "one",
                    xlabel: "x",
                    ylabel: "y",
                    series: &[("s", &a), ("r", &b)],
                },
                Panel {
                    title: "two",
                    xlabel: "x",
                    ylabel: "y",
                    series: &[("s", &b)],
                },
            ],
        );
        for label in [">10⁻³<", ">10⁻²<", ">10⁰<"] {
            assert!(svg.contains(label), "{label}: {svg}");
        }
        // The point at y = 0 neither extends the x axis to 10¹ nor is drawn.
        assert!(!svg.contains(">10¹<") && !svg.contains(">10⁻⁴<"), "{svg}");
        let first = svg.lines().find(|l| l.starts_with("<polyline")).unwrap();
        assert_eq!(first.matches(',').count(), 2, "{first}");
        assert_eq!(svg.matches(">s</text>").count(), 1);
        assert_eq!(svg.matches(">r</text>").count(), 1);
    }

    /// One loaded cell in a 5 × 5 grid: the map keeps its row and one row either side, colours
    /// it at the top of the scale and labels the bar with its value.
    #[test]
    fn heat_map_crops_to_the_contact_and_scales_to_the_peak() {
        let points: Vec<(f64, f64, f64)> = (0..25)
            .map(|k| {
                let (i, j) = (k % 5, k / 5);
                (
                    i as f64,
                    j as f64,
                    if (i, j) == (2, 2) { 10.0 } else { 0.0 },
                )
            })
            .collect();
        let svg = heat_map("t", "x", "y", "MPa", &points);
        assert!(svg.contains("10.0 MPa"), "{svg}");
        assert!(svg.contains(&viridis(1.0)) && viridis(1.0) == "#fde725");
        // Rows 1, 2 and 3 drawn: the loaded row as three runs, the others as one each.
        let cells = svg.matches("<rect x=").count() - HEAT_LEVELS;
        assert_eq!(cells, 5, "{svg}");
        assert!(svg.contains(">3.000<") && svg.contains(">1.000<"), "{svg}");
    }
}
