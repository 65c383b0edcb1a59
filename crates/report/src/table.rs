//! The tables printed after a run: per case p_max, the bound, Δh_max, passes and time; a
//! roller study's figures and its envelope; the largest stresses below the surface. A case is
//! named by its label; under its row, how it ended when it did not converge or lies outside
//! the model, and Hertz's nominal contact where Hertz applies. Warnings are not part of the
//! table (`contopt run` prints them on their own).

use std::fmt::Write;

use contopt_results::words::significant;
use contopt_results::{CaseReport, CaseStatus, Report};

/// The table of a report: the cases (a roller study's own columns when it has rollers), then
/// the stresses below the surface when some case computed them.
pub fn table(report: &Report) -> String {
    let cases = if report.cases.iter().any(|c| c.bearing.is_some()) {
        bearing_table(report)
    } else if report.cases.iter().any(|c| c.roller.is_some()) {
        roller_table(report)
    } else {
        case_table(report)
    };
    cases + &subsurface_table(report)
}

/// The table of a bearing study: per case the worst contact's p_max and the duty cycle's
/// lives, with the worst contact, each load case's distribution, pressure and lives, and the
/// tuned crown's parameters under it; then the [`notes`].
fn bearing_table(report: &Report) -> String {
    let width = label_width(report);
    let mut s = format!(
        "{:<width$} {:>10} {:>11} {:>11} {:>11} {:>11} {:>9}\n",
        "case", "p_max MPa", "L10", "L10r", "L10r", "L10r", "time ms"
    );
    let _ = writeln!(
        s,
        "{:<width$} {:>10} {:>11} {:>11} {:>11} {:>11}",
        "", "(worst)", "ISO 281", "slices", "half-space", "peaks"
    );
    for c in &report.cases {
        let Some(b) = &c.bearing else {
            let _ = writeln!(s, "{:<width$} {:>10}", c.label, figure(c.p_max_mpa));
            s += &notes(c);
            continue;
        };
        let l = &b.duty_cycle;
        let _ = writeln!(
            s,
            "{:<width$} {:>10.1} {:>11.2} {:>11.2} {:>11.2} {:>11.2} {:>9.0}",
            c.label,
            b.worst.p_max_mpa,
            l.iso_281_mrev,
            l.slice_model_mrev,
            l.half_space_mrev,
            l.peak_pressure_mrev,
            total_ms(c)
        );
        s += &bearing_lines(b);
        if let Some(levels) = &b.pressure_levels {
            let levels: Vec<String> = levels.iter().map(|s| format!("{s:.3}")).collect();
            let _ = writeln!(
                s,
                "  the load cases' pressure levels for the life: {}",
                levels.join(", ")
            );
        }
        if let Some(t) = c.roller.as_ref().and_then(|r| r.tuned.as_ref()) {
            s += &format!("  {}", tuned_line("tuned", t));
        }
        s += &notes(c);
    }
    s + "(lives over the duty cycle by Palmgren–Miner, 10⁶ revolutions: ISO 281's L10, ISO/TS \
         16281's L10r from the slice model, from the half-space contacts' slice loads, and \
         with those raised to their peak pressures' Hertzian loads)\n"
}

/// A bearing case's worst contact and its load cases, indented under its row.
fn bearing_lines(b: &contopt_results::BearingReport) -> String {
    let w = &b.worst;
    let case = &b.load_cases[w.load_case.min(b.load_cases.len().saturating_sub(1))];
    let mut s = format!(
        "  worst contact: {}, roller {}: Q = {:.1} N, γ = {:+.3}′, band {:+.1} µm, at x = {:.3} mm{}\n",
        case.label,
        w.roller,
        w.load_n,
        w.tilt_arcmin,
        w.deviation_um,
        w.p_max_at_mm[0],
        if w.edge_loading { ", edge loaded" } else { "" }
    );
    let _ = writeln!(
        s,
        "  {:<18} {:>8} {:>7} {:>6} {:>8} {:>6} {:>9} {:>9} {:>9} {:>9} {:>9}",
        "load case",
        "fraction",
        "F_r N",
        "γ ′",
        "Q_max N",
        "zone °",
        "p_max MPa",
        "L10",
        "L10r sl.",
        "h.-s.",
        "peaks"
    );
    for c in &b.load_cases {
        let q_max = c.rollers.iter().map(|r| r.load_n).fold(0.0, f64::max);
        let l = &c.lives;
        let _ = writeln!(
            s,
            "  {:<18} {:>8.3} {:>7.0} {:>6.2} {:>8.1} {:>6.1} {:>9.1} {:>9.2} {:>9.2} {:>9.2} {:>9.2}",
            c.label,
            c.fraction,
            c.radial_n,
            c.misalignment_arcmin,
            q_max,
            c.loaded_zone_deg,
            c.p_max_mpa,
            l.iso_281_mrev,
            l.slice_model_mrev,
            l.half_space_mrev,
            l.peak_pressure_mrev
        );
    }
    s
}

/// p_max (the largest pressure), the optimisation's bound p̂ and Δh_max, its passes and the
/// time of each case, with the [`notes`] under it.
fn case_table(report: &Report) -> String {
    let width = label_width(report);
    let mut s = format!(
        "{:<width$} {:>12} {:>12} {:>12} {:>6} {:>10}\n",
        "case", "p_max MPa", "bound MPa", "Δh_max µm", "passes", "time ms"
    );
    for c in &report.cases {
        let _ = writeln!(
            s,
            "{:<width$} {:>12} {:>12} {:>12} {:>6} {:>10.0}",
            c.label,
            figure(c.p_max_mpa),
            figure(c.bound_p_max_mpa),
            figure(c.dh_max_um),
            c.passes.len(),
            total_ms(c)
        );
        s += &notes(c);
    }
    s
}

/// The lines under a case's row: how it ended when it did not converge or stands at a reduced
/// accuracy (the termination's words) or lies outside the model (the limit's message), and
/// Hertz's nominal contact.
fn notes(case: &CaseReport) -> String {
    let mut s = String::new();
    match case.status {
        CaseStatus::Solved => {}
        CaseStatus::NotConverged => {
            let _ = writeln!(s, "  not converged: {}", case.termination);
        }
        CaseStatus::OutsideModel => {
            let why = case.limit.as_ref().map_or("", |l| l.message.as_str());
            let _ = writeln!(s, "  outside the model: {why}");
        }
    }
    if case.status != CaseStatus::NotConverged && !case.termination.is_converged() {
        let _ = writeln!(s, "  {}", case.termination);
    }
    if let Some(h) = &case.hertz {
        let half_width = if h.contact == "line" { "b" } else { "a" };
        // A bearing's rollers carry many loads: its Hertz is the design load's, not the worst's.
        let at = case.bearing.as_ref().map_or(String::new(), |b| {
            format!(" at the design load {} N", significant(b.design_load_n, 5))
        });
        let _ = writeln!(
            s,
            "  Hertz{at}: p₀ = {} MPa, {half_width} = {} mm",
            significant(h.p0_mpa, 4),
            significant(h.half_width_mm, 4)
        );
    }
    s
}

/// The wall time of a case's stages \[ms\].
fn total_ms(case: &CaseReport) -> f64 {
    case.timings_ms.values().sum()
}

/// A value to six significant digits, in scientific notation outside 10⁻³…10⁶; `-` for none.
fn figure(v: Option<f64>) -> String {
    match v {
        None => "-".into(),
        Some(0.0) => "0".into(),
        Some(v) if (1e-3..1e6).contains(&v.abs()) => {
            let decimals = |x: f64| (5 - x.abs().log10().floor() as i32).clamp(0, 8) as usize;
            // Rounding may carry into the next power of ten (99.999996 to 100.0000): the
            // decimals of the rounded value keep six digits.
            let d = decimals(v);
            let rounded: f64 = format!("{v:.d$}").parse().unwrap_or(v);
            let d = d.min(decimals(rounded));
            format!("{v:.d$}")
        }
        Some(v) => format!("{v:.5e}"),
    }
}

/// The width of the case column: the longest label, at least 4.
fn label_width(report: &Report) -> usize {
    report
        .cases
        .iter()
        .map(|c| c.label.chars().count())
        .max()
        .unwrap_or(4)
        .max(4)
}

/// The table of a roller study: per case p_max and where it sits, edge loading, the approach,
/// the contact half-widths at mid-length and at the ends, and the crown's drop at the ends,
/// with the [`notes`] under it.
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
        match (&c.roller, c.p_max_mpa) {
            (Some(r), Some(p)) => {
                let _ = writeln!(
                    s,
                    "{:<width$} {:>10.1} {:>14} {:>5} {:>12} {:>16} {:>12.3} {:>8.0}",
                    c.label,
                    p,
                    format!("{:.2}, {:.3}", r.p_max_at_mm[0], r.p_max_at_mm[1]),
                    if r.edge_loading { "yes" } else { "no" },
                    c.approach_um.map_or("-".into(), |a| format!("{a:.3}")),
                    format!("{:.4} / {:.4}", r.half_width_mm[0], r.half_width_mm[1]),
                    r.crown_drop_end_um,
                    total_ms(c)
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "{:<width$} {:>10} {:>14} {:>5} {:>12} {:>16} {:>12} {:>8.0}",
                    c.label,
                    "-",
                    "-",
                    "-",
                    "-",
                    "-",
                    "-",
                    total_ms(c)
                );
            }
        }
        s += &notes(c);
    }
    s + &envelope_table(report, width)
}

/// The table of a roller envelope: per case, p_max under each load and tilt (`*` marks edge
/// loading) and the worst; the tuned profiles' parameters below. Empty without an envelope.
/// A case whose envelope differs from the heading above it (other load factors or tilts, or
/// another number of them) gets a heading of its own, so that each figure stands under its
/// own load and tilt.
fn envelope_table(report: &Report, width: usize) -> String {
    let mut s = String::new();
    let mut heading: Option<Vec<String>> = None;
    let mut tuned = String::new();
    for c in &report.cases {
        let Some(r) = c.roller.as_ref().filter(|r| !r.envelope.is_empty()) else {
            continue;
        };
        let heads = envelope_heads(r);
        if heading.as_ref() != Some(&heads) {
            if heading.is_none() {
                s += "\np_max MPa over the envelope (* edge loading)\n";
            }
            let _ = write!(s, "{:<width$}", "case");
            for head in &heads {
                let _ = write!(s, " {head:>10}");
            }
            let _ = writeln!(s, " {:>10}", "worst");
            heading = Some(heads);
        }
        let _ = write!(s, "{:<width$}", c.label);
        for e in &r.envelope {
            let mark = if e.edge_loading { "*" } else { " " };
            let _ = write!(s, " {:>9.1}{mark}", e.p_max_mpa);
        }
        let worst = r.worst_p_max_mpa.map_or("-".into(), |p| format!("{p:.1}"));
        let _ = writeln!(s, " {worst:>10}");
        if let Some(t) = &r.tuned {
            tuned += &tuned_line(&c.label, t);
        }
    }
    s + &tuned
}

/// The column headings of a case's envelope: each load as a multiple of the case's own (its
/// first) and its tilt.
fn envelope_heads(r: &contopt_results::RollerReport) -> Vec<String> {
    let nominal = r.envelope[0].load_n;
    (r.envelope.iter())
        .map(|e| {
            format!(
                "{}Q {:+.0}′",
                load_factor(e.load_n / nominal),
                e.tilt_arcmin
            )
        })
        .collect()
}

/// A tuned crown's parameters: Fujiwara–Kawase's K1, K2 and z_m, or a circular crown's
/// crowned fraction, end drop and radius.
fn tuned_line(label: &str, t: &contopt_results::TunedProfile) -> String {
    match (t.k1, t.radius_mm) {
        (Some(k1), _) => format!(
            "{label}: K1 = {k1:.4}, K2 = {:.4}, z_m = {:.4} µm ({} crowns searched)\n",
            t.k2, t.z_m_um, t.evaluations
        ),
        (None, radius) => format!(
            "{label}: circular, crowned fraction {:.4}, z_m = {:.4} µm, R = {} mm ({} crowns searched)\n",
            t.k2,
            t.z_m_um,
            radius.map_or("-".into(), |r| format!("{r:.1}")),
            t.evaluations
        ),
    }
}

/// The largest stresses below the surface of each case's bodies: von Mises and the largest
/// shear (Tresca) with their depth and position, the largest tension and compression, and the
/// largest orthogonal shears |τ_xz| and |τ_yz| (the latter with its depth: a roller rolls
/// along y; "-" where there is none, on a plane or axisymmetric body). Empty when no case
/// asked for them.
fn subsurface_table(report: &Report) -> String {
    if report.cases.iter().all(|c| c.subsurface.is_none()) {
        return String::new();
    }
    let width = label_width(report);
    let mut s = format!(
        "\nbelow the surface (MPa; depth and position x, y in mm)\n{:<width$} {:<22} {:>10} {:>8} {:>16} {:>10} {:>8} {:>10} {:>10} {:>8} {:>8} {:>8}\n",
        "case", "body", "von Mises", "depth", "at x, y", "Tresca", "depth", "σ1 max", "σ3 min", "|τxz|", "|τyz|", "depth"
    );
    for c in &report.cases {
        for b in c.subsurface.iter().flat_map(|r| &r.bodies) {
            let p = &b.peaks;
            let _ = writeln!(
                s,
                "{:<width$} {:<22} {:>10.1} {:>8.4} {:>16} {:>10.1} {:>8.4} {:>10.1} {:>10.1} {:>8.1} {:>8} {:>8}",
                c.label,
                b.body,
                p.von_mises.value_mpa,
                p.von_mises.depth_mm,
                format!("{:.3}, {:.3}", p.von_mises.x_mm, p.von_mises.y_mm),
                p.tresca.value_mpa,
                p.tresca.depth_mm,
                p.max_principal.value_mpa,
                p.min_principal.value_mpa,
                p.shear_xz.value_mpa,
                p.shear_yz.map_or("-".into(), |q| format!("{:.1}", q.value_mpa)),
                p.shear_yz.map_or("-".into(), |q| format!("{:.4}", q.depth_mm)),
            );
        }
    }
    s
}

/// A load as a multiple of the nominal: one decimal where that is exact (0.5, 1.0, 1.5), else
/// three significant digits (0.01, 0.125), so that a light case never reads as 0.0Q.
fn load_factor(f: f64) -> String {
    if ((10.0 * f).round() - 10.0 * f).abs() < 1e-9 {
        return format!("{f:.1}");
    }
    let digits = (2 - f.abs().log10().floor() as i32).clamp(0, 12) as usize;
    let text = format!("{f:.digits$}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use contopt_core::{Stall, Termination};
    use contopt_results::{
        EnvelopeCase, Hertz, ModelLimit, RollerReport, TunedProfile, SCHEMA_VERSION,
    };

    use super::*;

    /// A case labelled `label`: solved with `p_max` when given, else not converged, stalled.
    fn case(label: &str, p_max: Option<f64>) -> CaseReport {
        let params = BTreeMap::from([("optimisation.controller.l1_mm".to_string(), 20.0)]);
        let mut c = CaseReport::new(label, &params, serde_json::Value::Null);
        c.timings_ms.insert("solve".into(), 12.0);
        match p_max {
            Some(p) => {
                c.status = CaseStatus::Solved;
                c.termination = Termination::Converged;
                c.p_max_mpa = Some(p);
            }
            None => {
                c.termination = Termination::Stalled {
                    cause: Stall::WanderingReference { moves: 4 },
                };
            }
        }
        c
    }

    fn report(cases: Vec<CaseReport>) -> Report {
        Report {
            schema_version: SCHEMA_VERSION,
            scene: "s".into(),
            description: String::new(),
            cases,
        }
    }

    /// A case outside the model: converged, its contact at the zone's edge.
    fn outside(label: &str) -> CaseReport {
        let mut c = case(label, Some(950.0));
        c.status = CaseStatus::OutsideModel;
        c.limit = Some(ModelLimit {
            edge: "x = +1.25 mm".into(),
            extent_mm: 1.25,
            needed_mm: 1.6,
            message: "the contact reaches the zone's edge at x = +1.25 mm: make it reach \
                      1.6 mm at least"
                .into(),
        });
        c
    }

    /// The case column holds each case's label as it is and fits the longest; a case that
    /// did not converge says how it ended, one outside the model why; warnings stay out.
    #[test]
    fn cases_by_their_labels_and_how_they_ended() {
        let mut step_limit = case("F = 1000 N, ν = 0.3", None);
        step_limit.termination = Termination::StepLimit {
            steps: 200,
            measure: 3e-4,
            tolerance: 1e-6,
        };
        let mut solved = case("L1 = 20 mm", Some(196.9));
        solved.warnings = vec!["only 5 cells across the half-width".into()];
        solved.passes = vec![
            contopt_results::Pass {
                k: 1,
                bound_p_max_mpa: 200.0,
                dh_max_um: 1.0,
                tolh_mm2: 1e-6,
                iterp: 3,
                iterd: 4,
            };
            3
        ];
        let r = report(vec![
            solved,
            case("L1 = 30 mm", None),
            step_limit,
            outside("L1 = 40 mm"),
        ]);
        let text = table(&r);
        let lines: Vec<&str> = text.lines().collect();
        assert!(
            lines[0].starts_with("case                   p_max MPa"),
            "{text}"
        );
        assert!(lines[1].starts_with("L1 = 20 mm "), "{text}");
        assert!(
            lines[1].contains("196.900") && lines[1].contains(" 3 ") && lines[1].ends_with(" 12"),
            "{text}"
        );
        assert!(lines[2].starts_with("L1 = 30 mm ") && lines[2].contains(" - "));
        assert_eq!(
            lines[3],
            "  not converged: stalled: the node of least gap change moved 4 times between programmes"
        );
        assert!(lines[4].starts_with("F = 1000 N, ν = 0.3 "), "{text}");
        assert!(
            lines[5].starts_with("  not converged: stopped at its limit of 200 steps"),
            "{text}"
        );
        assert!(lines[6].starts_with("L1 = 40 mm ") && lines[6].contains("950.000"));
        assert_eq!(
            lines[7],
            "  outside the model: the contact reaches the zone's edge at x = +1.25 mm: make it \
             reach 1.6 mm at least"
        );
        assert_eq!(lines.len(), 8, "{text}");
        assert!(!text.contains("cells across") && !text.contains("NaN"));
    }

    /// Hertz's nominal p₀ and half-width under the case they belong to: a for a point
    /// contact, b for a line.
    #[test]
    fn hertz_beside_each_case() {
        let mut sphere = case("R = 10 mm", Some(4510.2));
        sphere.hertz = Some(Hertz {
            contact: "point".into(),
            p0_mpa: 4538.46,
            half_width_mm: 0.324371,
        });
        let mut cylinder = case("Q = 1000 N", Some(1200.0));
        cylinder.hertz = Some(Hertz {
            contact: "line".into(),
            p0_mpa: 1187.2,
            half_width_mm: 0.05361,
        });
        let text = table(&report(vec![sphere, case("plain", Some(1.0)), cylinder]));
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[1].starts_with("R = 10 mm "), "{text}");
        assert_eq!(lines[2], "  Hertz: p₀ = 4538 MPa, a = 0.3244 mm");
        assert!(lines[3].starts_with("plain "), "{text}");
        assert!(lines[4].starts_with("Q = 1000 N "), "{text}");
        assert_eq!(lines[5], "  Hertz: p₀ = 1187 MPa, b = 0.05361 mm");
        assert_eq!(lines.len(), 6, "{text}");
    }

    /// Load factors read as written: one decimal where exact, else three significant digits.
    #[test]
    fn six_digits_also_when_rounding_carries() {
        let shown: Vec<String> = [99.999996, 99.99994, 0.009999996, 123.4564]
            .map(|v| figure(Some(v)))
            .to_vec();
        assert_eq!(shown, ["100.000", "99.9999", "0.0100000", "123.456"]);
    }

    #[test]
    fn load_factors_keep_a_light_case_apart() {
        let shown: Vec<String> = [0.5, 1.0, 1.5, 0.01, 0.125, 0.0333, 12.34]
            .map(super::load_factor)
            .into();
        assert_eq!(
            shown,
            ["0.5", "1.0", "1.5", "0.01", "0.125", "0.0333", "12.3"]
        );
    }

    /// A roller study: its own columns, Hertz's figures and a case that did not converge
    /// under their rows, the envelope in MPa and the tuned profile's drop in µm.
    #[test]
    fn a_roller_study() {
        let envelope = |p: f64, edge: bool| EnvelopeCase {
            load_n: 1000.0,
            tilt_arcmin: 0.0,
            p_max_mpa: p,
            p_max_at_mm: [0.0, 0.0],
            edge_loading: edge,
            approach_um: 5.0,
            cells_across: 20.0,
            edge_across_mpa: 0.0,
            centre_line: vec![],
        };
        let mut roller = case("ISO/TS 16281", Some(1500.0));
        roller.approach_um = Some(4.25);
        roller.hertz = Some(Hertz {
            contact: "line".into(),
            p0_mpa: 1412.0,
            half_width_mm: 0.1123,
        });
        roller.roller = Some(RollerReport {
            p_max_at_mm: [4.95, 0.0],
            edge_loading: true,
            half_width_mm: [0.11, 0.13],
            crown_drop_end_um: 2.5,
            envelope: vec![envelope(1500.0, true), envelope(1600.5, false)],
            worst_p_max_mpa: Some(1600.5),
            tuned: Some(TunedProfile {
                family: "fujiwara_kawase".into(),
                k1: Some(1.1),
                k2: 0.5,
                z_m_um: 7.25,
                radius_mm: None,
                evaluations: 40,
            }),
        });
        let text = table(&report(vec![roller, case("Fujiwara–Kawase", None)]));
        let lines: Vec<&str> = text.lines().collect();
        assert!(lines[0].contains("approach µm") && lines[0].contains("end drop µm"));
        assert!(lines[2].starts_with("ISO/TS 16281 "), "{text}");
        for figure in [
            "1500.0",
            "4.95, 0.000",
            "yes",
            "4.250",
            "0.1100 / 0.1300",
            "2.500",
        ] {
            assert!(lines[2].contains(figure), "{figure} in {text}");
        }
        assert_eq!(lines[3], "  Hertz: p₀ = 1412 MPa, b = 0.1123 mm");
        assert!(lines[4].starts_with("Fujiwara–Kawase ") && lines[4].contains(" - "));
        assert_eq!(
            lines[5],
            "  not converged: stalled: the node of least gap change moved 4 times between programmes"
        );
        let envelope = lines
            .iter()
            .position(|l| l.starts_with("p_max MPa over"))
            .unwrap();
        let row = lines[envelope + 2];
        assert!(row.starts_with("ISO/TS 16281 "), "{text}");
        assert!(row.contains("1500.0*") && row.contains("1600.5 ") && row.ends_with("1600.5"));
        assert_eq!(
            lines[envelope + 3],
            "ISO/TS 16281: K1 = 1.1000, K2 = 0.5000, z_m = 7.2500 µm (40 crowns searched)"
        );
    }

    /// Cases whose envelopes differ (a case that sets its own `[envelope]`, or another
    /// load's factors) each get their envelope's heading: a case of one load under a heading
    /// of two put its worst under the second load's column (`1.0Q +0′  0.05Q +0′` over
    /// `455.4  455.4`, the second the worst), and a case of other loads under another case's
    /// factors.
    #[test]
    fn each_envelope_has_its_own_heading() {
        let envelope = |load_n: f64, p_max_mpa: f64| EnvelopeCase {
            load_n,
            tilt_arcmin: 0.0,
            p_max_mpa,
            p_max_at_mm: [0.0, 0.0],
            edge_loading: false,
            approach_um: 5.0,
            cells_across: 20.0,
            edge_across_mpa: 0.0,
            centre_line: vec![],
        };
        let roller = |label: &str, envelope: Vec<EnvelopeCase>| {
            let mut c = case(label, Some(envelope[0].p_max_mpa));
            let worst = envelope.iter().map(|e| e.p_max_mpa).fold(0.0, f64::max);
            c.roller = Some(RollerReport {
                p_max_at_mm: [0.0, 0.0],
                edge_loading: false,
                half_width_mm: [0.1, 0.1],
                crown_drop_end_um: 1.0,
                envelope,
                worst_p_max_mpa: Some(worst),
                tuned: None,
            });
            c
        };
        let text = table(&report(vec![
            roller(
                "two",
                vec![envelope(8000.0, 2104.4), envelope(400.0, 607.1)],
            ),
            roller("alone", vec![envelope(400.0, 455.4)]),
            roller(
                "three",
                vec![
                    envelope(400.0, 455.4),
                    envelope(200.0, 300.0),
                    envelope(600.0, 520.0),
                ],
            ),
            roller(
                "two again",
                vec![envelope(4000.0, 1500.0), envelope(200.0, 400.0)],
            ),
        ]));
        let lines: Vec<&str> = text
            .lines()
            .skip_while(|l| !l.starts_with("p_max MPa over the envelope"))
            .collect();
        let at = |label: &str| lines.iter().position(|l| l.starts_with(label)).unwrap();
        let heading = |row: usize| {
            let above = lines[..row].iter().rev().find(|l| l.starts_with("case"));
            above
                .unwrap()
                .split_whitespace()
                .skip(1)
                .collect::<Vec<_>>()
                .join(" ")
        };
        let last = at("two again");
        assert_eq!(heading(at("two ")), "1.0Q +0′ 0.05Q +0′ worst", "{text}");
        assert_eq!(heading(at("alone")), "1.0Q +0′ worst", "{text}");
        assert_eq!(
            heading(at("three")),
            "1.0Q +0′ 0.5Q +0′ 1.5Q +0′ worst",
            "{text}"
        );
        assert_eq!(heading(last), "1.0Q +0′ 0.05Q +0′ worst", "{text}");
        // Every figure of a row stands under its heading's column.
        for row in [at("two "), at("alone"), at("three"), last] {
            let head = lines[..row]
                .iter()
                .rev()
                .find(|l| l.starts_with("case"))
                .unwrap();
            assert_eq!(head.chars().count(), lines[row].chars().count(), "{text}");
        }
    }

    /// The largest stresses below the surface by case and body, in MPa and mm.
    #[test]
    fn stresses_below_the_surface() {
        use contopt_results::{BodyStresses, Peak, Peaks, SubsurfaceReport};
        let peak = |value_mpa: f64, depth_mm: f64| Peak {
            value_mpa,
            x_mm: 0.5,
            y_mm: -0.25,
            depth_mm,
        };
        let below = |shear_yz: Option<Peak>| {
            let mut c = case("L1 = 20 mm", Some(4500.0));
            c.subsurface = Some(SubsurfaceReport {
                depths_mm: vec![0.1, 0.2],
                bodies: vec![BodyStresses {
                    body: "half-space".into(),
                    peaks: Peaks {
                        von_mises: peak(2814.04, 0.156),
                        tresca: peak(1407.0, 0.1561),
                        max_principal: peak(120.0, 0.0),
                        min_principal: peak(-4538.0, 0.0),
                        shear_xz: peak(10.0, 0.2),
                        shear_yz,
                    },
                    sections: vec![],
                }],
            });
            table(&report(vec![c]))
        };
        let text = below(Some(peak(1134.5, 0.0867)));
        let row = text.lines().last().unwrap();
        assert!(row.starts_with("L1 = 20 mm half-space "), "{text}");
        for figure in [
            "2814.0",
            "0.1560",
            "0.500, -0.250",
            "1407.0",
            "0.1561",
            "120.0",
            "-4538.0",
            "1134.5",
            "0.0867",
        ] {
            assert!(row.contains(figure), "{figure} in {text}");
        }
        // A plane or axisymmetric body has no τ_yz: no peak, no depth.
        let text = below(None);
        let row = text.lines().last().unwrap();
        assert!(row.ends_with(" 10.0        -        -"), "{text}");
    }
}
