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
