//! Plots written as SVG text, with no dependency: enough for the examples' figures.

use std::fmt::Write;

/// Text made safe for XML.
fn escape(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
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
    let pts = series.iter().flat_map(|s| s.1.iter());
    let (x0, x1) = pts
        .clone()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.0), b.max(p.0))
        });
    let (y0, y1) = pts.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
        (a.min(p.1), b.max(p.1))
    });
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
        // Ten distinct colours (the Tableau palette), so that a study's series do not repeat.
        let colour = [
            "#d62728", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#e377c2", "#7f7f7f",
            "#bcbd22", "#17becf",
        ][k % 10];
        let dash = if k % 2 == 0 {
            ""
        } else {
            " stroke-dasharray=\"6 4\""
        };
        let path: Vec<String> = data
            .iter()
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
