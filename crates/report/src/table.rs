//! The tables printed after a run: per case p_max, the bound, Δh_max, steps and time; a
//! roller study's figures and its envelope; the largest stresses below the surface.

use std::fmt::Write;

use contopt_scene::Report;

use crate::words::case_legend;

/// The table of a report: the cases (a roller study's own columns when it has rollers), then
/// the stresses below the surface when some case computed them.
pub fn table(report: &Report) -> String {
    let cases = if report.cases.iter().any(|c| c.roller.is_some()) {
        roller_table(report)
    } else {
        case_table(report)
    };
    cases + &subsurface_table(report)
}

/// p_max (the largest pressure), the optimisation's bound p̂ and Δh_max, its steps and the
/// time of each case.
fn case_table(report: &Report) -> String {
    let width = label_width(report);
    let mut s = format!(
        "{:<width$} {:>12} {:>12} {:>12} {:>6} {:>10}\n",
        "case", "p_max MPa", "bound MPa", "Δh_max µm", "steps", "time ms"
    );
    for c in &report.cases {
        let total: f64 = c.timings_ms.values().sum();
        let _ = writeln!(
            s,
            "{:<width$} {:>12} {:>12} {:>12} {:>6} {:>10.0}",
            case_legend(c),
            significant(c.p_max),
            significant(c.bound_p_max),
            significant(c.dh_max_um),
            c.iterations.len(),
            total
        );
        if let Some(e) = &c.error {
            let _ = writeln!(s, "  not converged: {e}");
        }
    }
    s
}

/// A value to six significant digits, in scientific notation outside 10⁻³…10⁶; `-` for none.
fn significant(v: Option<f64>) -> String {
    match v {
        None => "-".into(),
        Some(0.0) => "0".into(),
        Some(v) if (1e-3..1e6).contains(&v.abs()) => {
            let decimals = (5 - v.abs().log10().floor() as i32).clamp(0, 8) as usize;
            format!("{v:.decimals$}")
        }
        Some(v) => format!("{v:.5e}"),
    }
}

/// The width of the case column: the longest label, at least 4.
fn label_width(report: &Report) -> usize {
    report
        .cases
        .iter()
        .map(|c| case_legend(c).chars().count())
        .max()
        .unwrap_or(4)
        .max(4)
}

/// The table of a roller study: per case p_max and where it sits, edge loading, the approach,
/// the contact half-widths at mid-length and at the ends, and the crown's drop at the ends.
fn roller_table(report: &Report) -> String {
    let width = label_width(report);
    let mut s = format!(
        "{:<width$} {:>10} {:>14} {:>5} {:>12} {:>16} {:>12} {:>8}\n",
        "case",
        "p_max MPa",
        "at x, y mm",
        "edge",
        "approach µm",
        "half-width mm",
        "end drop µm",
        "time ms"
    );
    let _ = writeln!(
        s,
        "{:<width$} {:>10} {:>14} {:>5} {:>12} {:>16}",
        "", "", "", "", "", "mid / ends"
    );
    for c in &report.cases {
        let total: f64 = c.timings_ms.values().sum();
        match (&c.roller, c.p_max) {
            (Some(r), Some(p)) => {
                let _ = writeln!(
                    s,
                    "{:<width$} {:>10.1} {:>14} {:>5} {:>12} {:>16} {:>12.3} {:>8.0}",
                    case_legend(c),
                    p,
                    format!("{:.2}, {:.3}", r.p_max_at_mm[0], r.p_max_at_mm[1]),
                    if r.edge_loading { "yes" } else { "no" },
                    c.approach_um.map_or("-".into(), |a| format!("{a:.3}")),
                    format!("{:.4} / {:.4}", r.half_width_mm[0], r.half_width_mm[1]),
                    r.crown_drop_end_um,
                    total
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "{:<width$} not converged: {}",
                    case_legend(c),
                    c.error.as_deref().unwrap_or("?")
                );
            }
        }
    }
    s + &envelope_table(report, width)
}

/// The table of a roller envelope: per case, p_max under each load and tilt (`*` marks edge
/// loading) and the worst; the tuned profiles' parameters below. Empty without an envelope.
fn envelope_table(report: &Report, width: usize) -> String {
    let Some(first) = report
        .cases
        .iter()
        .filter_map(|c| c.roller.as_ref())
        .find(|r| !r.envelope.is_empty())
    else {
        return String::new();
    };
    let nominal = first.envelope[0].load_n;
    let mut s = format!(
        "\np_max MPa over the envelope (* edge loading)\n{:<width$}",
        "case"
    );
    for e in &first.envelope {
        let head = format!("{:.1}Q {:+.0}′", e.load_n / nominal, e.tilt_arcmin);
        let _ = write!(s, " {head:>10}");
    }
    let _ = writeln!(s, " {:>10}", "worst");
    let mut tuned = String::new();
    for c in &report.cases {
        let Some(r) = c.roller.as_ref().filter(|r| !r.envelope.is_empty()) else {
            continue;
        };
        let _ = write!(s, "{:<width$}", case_legend(c));
        for e in &r.envelope {
            let mark = if e.edge_loading { "*" } else { " " };
            let _ = write!(s, " {:>9.1}{mark}", e.p_max);
        }
        let worst = r.worst_p_max.map_or("-".into(), |p| format!("{p:.1}"));
        let _ = writeln!(s, " {worst:>10}");
        if let Some(t) = &r.tuned {
            let _ = writeln!(
                tuned,
                "{}: K1 = {:.4}, K2 = {:.4}, z_m = {:.4} µm ({} crowns searched)",
                case_legend(c),
                t.k1,
                t.k2,
                1e3 * t.z_m_mm,
                t.evaluations
            );
        }
    }
    s + &tuned
}

/// The largest stresses below the surface of each case's bodies: von Mises and the largest
/// shear (Tresca) with their depth and position, the largest tension and compression. Empty
/// when no case asked for them.
fn subsurface_table(report: &Report) -> String {
    if report.cases.iter().all(|c| c.subsurface.is_none()) {
        return String::new();
    }
    let width = label_width(report);
    let mut s = format!(
        "\nbelow the surface (MPa; depth and position x, y in mm)\n{:<width$} {:<22} {:>10} {:>8} {:>16} {:>10} {:>8} {:>10} {:>10}\n",
        "case", "body", "von Mises", "depth", "at x, y", "Tresca", "depth", "σ1 max", "σ3 min"
    );
    for c in &report.cases {
        for b in c.subsurface.iter().flat_map(|r| &r.bodies) {
            let p = &b.peaks;
            let _ = writeln!(
                s,
                "{:<width$} {:<22} {:>10.1} {:>8.4} {:>16} {:>10.1} {:>8.4} {:>10.1} {:>10.1}",
                case_legend(c),
                b.body,
                p.von_mises.value,
                p.von_mises.depth,
                format!("{:.3}, {:.3}", p.von_mises.x, p.von_mises.y),
                p.tresca.value,
                p.tresca.depth,
                p.max_principal.value,
                p.min_principal.value
            );
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A case: its label, its swept parameter and its p_max (none: not converged).
    type Case<'a> = (&'a str, Option<(&'a str, f64)>, Option<f64>);

    /// A report of `cases` read from JSON, as `result.json` holds it.
    fn report(cases: &[Case]) -> Report {
        let cases: Vec<serde_json::Value> = cases
            .iter()
            .map(|(label, param, p_max)| {
                let params: serde_json::Map<String, serde_json::Value> = param
                    .iter()
                    .map(|(k, v)| (k.to_string(), (*v).into()))
                    .collect();
                serde_json::json!({
                    "label": label, "params": params, "p_max": p_max, "dh_max_um": null,
                    "converged": p_max.is_some(), "error": p_max.map_or(Some("diverged"), |_| None),
                    "iterations": [], "interface": [], "timings_ms": {"solve": 12.0},
                })
            })
            .collect();
        serde_json::from_value(serde_json::json!({"scene": "s", "cases": cases})).unwrap()
    }

    /// The case column names a sweep's cases in the paper's words and fits the longest; a
    /// case that did not converge says why.
    #[test]
    fn cases_in_the_papers_words() {
        let r = report(&[
            ("l1_mm = 20", Some(("l1_mm", 20.0)), Some(196.9)),
            ("l1_mm = 30", Some(("l1_mm", 30.0)), None),
        ]);
        let text = table(&r);
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].starts_with("case          p_max MPa"), "{text}");
        assert!(lines[1].starts_with("L1 = 20 mm"), "{text}");
        assert!(
            lines[1].contains("196.900") && lines[1].contains(" 12"),
            "{text}"
        );
        assert!(lines[2].starts_with("L1 = 30 mm") && lines[3].contains("not converged: diverged"));
        assert!(!text.contains("NaN"));
    }
}
