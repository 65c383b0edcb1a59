//! The files a scene's [`Report`] becomes: `result.json`, `interface.csv`, the charts of p
//! and Δh along x (with the closed form dashed beside a validation case), a map of the
//! pressure over a two-dimensional region, a roller envelope's centre lines, and the
//! stresses on each vertical section below the surface (CSV and von Mises maps). Every chart
//! is written as SVG and PNG.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io;

use contopt_core::SectionAxis;
use contopt_scene::{BodyStresses, CaseReport, PointReport, Report};

use crate::words::{case_legend, number};
use crate::{heat_map, section_map, Figure, LineChart};

/// Where a report's files go: a results folder, or memory.
pub trait Sink {
    /// Writes `contents` as the file `name` (a plain file name).
    fn put(&mut self, name: &str, contents: &[u8]) -> io::Result<()>;
}

/// Files in memory, by name.
impl Sink for BTreeMap<String, Vec<u8>> {
    fn put(&mut self, name: &str, contents: &[u8]) -> io::Result<()> {
        self.insert(name.to_string(), contents.to_vec());
        Ok(())
    }
}

/// Points whose second coordinate is within this of the smallest \[mm\] lie on the plotted
/// row (round-off of the grid's coordinates).
const SAME_ROW: f64 = 1e-9;

/// Writes every file of `report` to `sink`, in order: `result.json`, `interface.csv`,
/// `p.{svg,png}` and, when some case changes the gap, `dh.{svg,png}`; per case `p_map_<case>`
/// (a two-dimensional region), `envelope_<case>` (a roller's envelope), `subsurface_<case>.csv`
/// and `mises_<case>_<section>` (stresses below the surface); cases and sections numbered
/// from 1.
pub fn write(report: &Report, sink: &mut dyn Sink) -> io::Result<()> {
    let json = serde_json::to_string_pretty(report).map_err(io::Error::other)?;
    sink.put("result.json", json.as_bytes())?;
    sink.put("interface.csv", interface_csv(report).as_bytes())?;
    if let Some(chart) = pressure_chart(report) {
        put(sink, "p", &chart.draw()?)?;
    }
    if let Some(chart) = gap_change_chart(report) {
        put(sink, "dh", &chart.draw()?)?;
    }
    for (k, case) in report.cases.iter().enumerate() {
        let number = k + 1;
        if let Some(map) = pressure_map(report, case)? {
            put(sink, &format!("p_map_{number}"), &map)?;
        }
        if let Some(chart) = envelope_chart(report, case) {
            put(sink, &format!("envelope_{number}"), &chart.draw()?)?;
        }
        sections(report, case, number, sink)?;
    }
    Ok(())
}

/// Writes `figure` as `<stem>.svg` and `<stem>.png`.
fn put(sink: &mut dyn Sink, stem: &str, figure: &Figure) -> io::Result<()> {
    for (name, bytes) in figure.files(stem)? {
        sink.put(&name, &bytes)?;
    }
    Ok(())
}

/// The fields at every interface point of every case.
fn interface_csv(report: &Report) -> String {
    let mut csv = String::from("case,x,y,z,p_mpa,d_mm,dh_mm\n");
    for c in &report.cases {
        let label = csv_field(&c.label);
        for q in &c.interface {
            let [x, y, z] = q.x;
            let _ = writeln!(csv, "{label},{x},{y},{z},{},{},{}", q.p, q.d, q.dh);
        }
    }
    csv
}

/// A CSV field (RFC 4180): quoted, with quotes doubled, when it holds a comma, a quote or a
/// line break; as it is otherwise.
pub fn csv_field(text: &str) -> std::borrow::Cow<'_, str> {
    if text.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", text.replace('"', "\"\"")).into()
    } else {
        text.into()
    }
}

/// `field` along the row of a case's interface points nearest the x axis (all of them on an
/// axisymmetric or plane body), sorted by x.
fn along_x(case: &CaseReport, field: impl Fn(&PointReport) -> f64) -> Vec<(f64, f64)> {
    let near = case
        .interface
        .iter()
        .map(|q| q.x[1].abs())
        .fold(f64::INFINITY, f64::min);
    let mut line: Vec<(f64, f64)> = case
        .interface
        .iter()
        .filter(|q| q.x[1].abs() <= near + SAME_ROW)
        .map(|q| (q.x[0], field(q)))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    line
}

/// The contact pressure along x of every converged case, each with its closed form dashed
/// beside it; the axis cut at an edge singularity ([`spike_limit`]); none when no case
/// converged.
fn pressure_chart(report: &Report) -> Option<LineChart> {
    let mut title = format!("{}: contact pressure", report.scene);
    let limit = spike_limit(report);
    if let Some(top) = limit {
        let top = number(top);
        title += &format!("\n(above {top} MPa not shown: p grows without bound at the rim)");
    }
    let mut chart = LineChart::new(&title, "x [mm]", "p [MPa]");
    if let Some(top) = limit {
        chart = chart.clip_above(top);
    }
    for c in report.cases.iter().filter(|c| c.converged) {
        chart = chart.line(&case_legend(c), &along_x(c, |q| q.p));
        if let Some(r) = &c.reference {
            let points: Vec<(f64, f64)> = r.points.iter().map(|p| (p[0], p[1])).collect();
            let label = if report.cases.len() > 1 {
                format!("{} ({})", r.label, case_legend(c))
            } else {
                r.label.clone()
            };
            chart = chart.reference(&label, &points);
        }
    }
    (!chart.is_empty()).then_some(chart)
}

/// A pressure this many times the median of the positive ones is an edge singularity (a flat
/// punch's rim, where p grows like 1/√(a − r)), not a value to scale the axis to.
const SPIKE: f64 = 8.0;

/// The top of the pressure axis when some pressure is an edge singularity: [`SPIKE`] times
/// the median positive pressure of the plotted rows, rounded up to a round value.
fn spike_limit(report: &Report) -> Option<f64> {
    let mut positive: Vec<f64> = report
        .cases
        .iter()
        .filter(|c| c.converged)
        .flat_map(|c| along_x(c, |q| q.p))
        .map(|p| p.1)
        .filter(|&p| p > 0.0 && p.is_finite())
        .collect();
    positive.sort_by(f64::total_cmp);
    let median = *positive.get(positive.len() / 2)?;
    let largest = *positive.last()?;
    (largest > SPIKE * median).then(|| crate::ticks::Axis::between(0.0, SPIKE * median).hi)
}

/// The gap change Δh along x of every converged case, when one of them changes the gap.
fn gap_change_chart(report: &Report) -> Option<LineChart> {
    let changes = |c: &&CaseReport| c.converged && c.interface.iter().any(|q| q.dh != 0.0);
    report.cases.iter().find(changes)?;
    let title = format!("{}: gap change", report.scene);
    let mut chart = LineChart::new(&title, "x [mm]", "Δh [µm]");
    for c in report.cases.iter().filter(|c| c.converged) {
        chart = chart.line(&case_legend(c), &along_x(c, |q| 1e3 * q.dh));
    }
    (!chart.is_empty()).then_some(chart)
}

/// A map of the pressure over a case's two-dimensional region (its points off one row);
/// none for a line of points or a case that did not converge.
fn pressure_map(report: &Report, case: &CaseReport) -> io::Result<Option<Figure>> {
    let first_y = case.interface.first().map_or(0.0, |q| q.x[1]);
    let flat = case
        .interface
        .iter()
        .all(|q| (q.x[1] - first_y).abs() < SAME_ROW);
    if !case.converged || flat {
        return Ok(None);
    }
    let points: Vec<(f64, f64, f64)> = case
        .interface
        .iter()
        .map(|q| (q.x[0], q.x[1], q.p))
        .collect();
    let peak = case.p_max.map_or(String::new(), |p| {
        format!(", largest {} MPa", number(p.round()))
    });
    let title = format!(
        "{}: contact pressure{}{peak}",
        report.scene,
        of_case(report, case)
    );
    heat_map(
        &title,
        "x [mm] (along the axis)",
        "y [mm]",
        "p [MPa]",
        &points,
    )
    .map(Some)
}

/// The centre-line pressure of a roller under each load and tilt of its envelope.
fn envelope_chart(report: &Report, case: &CaseReport) -> Option<LineChart> {
    let roller = case.roller.as_ref().filter(|r| !r.envelope.is_empty())?;
    let nominal = roller.envelope[0].load_n;
    let title = format!(
        "{}: centre-line pressure{}",
        report.scene,
        of_case(report, case)
    );
    let mut chart = LineChart::new(&title, "x [mm] (along the axis)", "p [MPa]");
    for e in &roller.envelope {
        let label = format!(
            "{} Q, γ = {}′",
            number(e.load_n / nominal),
            number(e.tilt_arcmin)
        );
        let points: Vec<(f64, f64)> = e.centre_line.iter().map(|p| (p[0], p[1])).collect();
        chart = chart.line(&label, &points);
    }
    Some(chart)
}

/// `, <case>` in a title, or nothing when the case is the scene itself.
fn of_case(report: &Report, case: &CaseReport) -> String {
    if case.label == report.scene {
        String::new()
    } else {
        format!(", {}", case_legend(case))
    }
}

/// The header of `subsurface_<case>.csv`.
const SECTION_HEADER: &str = "body,section,along,at_mm,position_mm,depth_mm,sxx_mpa,syy_mpa,\
szz_mpa,sxy_mpa,sxz_mpa,syz_mpa,von_mises_mpa,tresca_mpa,s1_mpa,s3_mpa\n";

/// The stresses on each vertical section below each body of case `number`: one CSV,
/// `subsurface_<case>.csv`, and a von Mises map per section, `mises_<case>_<section>`
/// (sections numbered over the case's bodies).
fn sections(
    report: &Report,
    case: &CaseReport,
    number: usize,
    sink: &mut dyn Sink,
) -> io::Result<()> {
    let Some(sub) = &case.subsurface else {
        return Ok(());
    };
    let mut csv = String::from(SECTION_HEADER);
    let all = sub
        .bodies
        .iter()
        .flat_map(|b| b.sections.iter().map(move |f| (b, f)));
    for (n, (body, field)) in all.enumerate() {
        let map = section(report, case, body, field, n + 1, &mut csv)?;
        put(sink, &format!("mises_{number}_{}", n + 1), &map)?;
    }
    if sub.bodies.iter().any(|b| !b.sections.is_empty()) {
        sink.put(&format!("subsurface_{number}.csv"), csv.as_bytes())?;
    }
    Ok(())
}

/// Appends section `n`'s rows to `csv` and draws its von Mises map.
fn section(
    report: &Report,
    case: &CaseReport,
    body: &BodyStresses,
    field: &contopt_core::SectionField,
    n: usize,
    csv: &mut String,
) -> io::Result<Figure> {
    let (along, across) = match field.section.axis {
        SectionAxis::X => ("x", "y"),
        SectionAxis::Y => ("y", "x"),
    };
    let name = csv_field(&body.body);
    let at = field.section.at;
    let mut points = Vec::with_capacity(field.tensors.len());
    for (kd, depth) in field.depths.iter().enumerate() {
        for (i, position) in field.positions.iter().enumerate() {
            let t = field.at(kd, i);
            let [s1, _, s3] = t.principal();
            let (mises, tresca) = (t.von_mises(), t.tresca());
            let _ = writeln!(
                csv,
                "{name},{n},{along},{at},{position},{depth},{},{},{},{},{},{},{mises},{tresca},{s1},{s3}",
                t.xx, t.yy, t.zz, t.xy, t.xz, t.yz
            );
            points.push((*position, *depth, mises));
        }
    }
    let of_case = of_case(report, case);
    let shown = format!("{at:.3}").replace('-', "−");
    let (top, depth) = points
        .iter()
        .fold((0.0, 0.0), |m, p| if p.2 > m.0 { (p.2, p.1) } else { m });
    let title = format!(
        "von Mises stress below the {}{of_case}, along {along} at {across} = {shown} mm\n\
         largest {top:.0} MPa at depth {depth:.3} mm",
        body.body
    );
    section_map(
        &title,
        &format!("{along} [mm] along the section"),
        "von Mises stress [MPa]",
        &points,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A swept scene of two cases along a line of points, the first with a closed form.
    fn report() -> Report {
        let points = |scale: f64| -> Vec<serde_json::Value> {
            (0..11)
                .map(|i| {
                    let x = 0.1 * i as f64;
                    let p = scale * (1.0 - x * x).max(0.0);
                    serde_json::json!({"x": [x, 0.0, 0.0], "p": p, "d": 0.0, "dh": 1e-3 * x})
                })
                .collect()
        };
        let case = |l1: f64, scale: f64| {
            serde_json::json!({
                "label": format!("l1_mm = {l1}"), "params": {"l1_mm": l1}, "p_max": scale,
                "dh_max_um": 1.0, "converged": true, "error": null, "iterations": [],
                "interface": points(scale), "timings_ms": {},
                "reference": {"label": "Hertz: p₀ = 100 MPa", "points": [[0.0, 100.0], [1.0, 0.0]]},
            })
        };
        let cases = [case(0.0, 100.0), case(20.0, 80.0)];
        serde_json::from_value(serde_json::json!({"scene": "s", "cases": cases})).unwrap()
    }

    /// The files of a line of points: the JSON, the CSV, p and Δh as SVG and PNG; the legend
    /// in the paper's words, the closed form beside its case; nothing non-finite.
    #[test]
    fn writes_the_files_of_a_report() {
        let mut files = BTreeMap::new();
        write(&report(), &mut files).unwrap();
        let names: Vec<&str> = files.keys().map(String::as_str).collect();
        assert_eq!(
            names,
            [
                "dh.png",
                "dh.svg",
                "interface.csv",
                "p.png",
                "p.svg",
                "result.json"
            ]
        );
        let p = String::from_utf8(files["p.svg"].clone()).unwrap();
        for text in [
            "L1 = 0 mm",
            "L1 = 20 mm",
            "Hertz: p₀ = 100 MPa (L1 = 20 mm)",
            "p [MPa]",
        ] {
            assert!(p.contains(text), "{text}");
        }
        assert!(!p.contains("NaN") && !p.contains("inf"));
        assert_eq!(&files["p.png"][1..4], b"PNG");
        let csv = String::from_utf8(files["interface.csv"].clone()).unwrap();
        assert_eq!(csv.lines().count(), 1 + 2 * 11);
        assert!(csv
            .lines()
            .nth(1)
            .unwrap()
            .starts_with("l1_mm = 0,0,0,0,100,0,0"));
        let json: Report = serde_json::from_slice(&files["result.json"]).unwrap();
        assert_eq!(json.cases[1].reference, report().cases[1].reference);
    }

    /// A grid of points becomes a map per case; a case that did not converge draws nothing.
    #[test]
    fn a_region_is_mapped() {
        let mut r = report();
        r.cases[0].interface = (0..25)
            .map(|k| PointReport {
                x: [(k % 5) as f64, (k / 5) as f64, 0.0],
                p: if k == 12 { 10.0 } else { 0.0 },
                d: 0.0,
                dh: 0.0,
            })
            .collect();
        r.cases[1].converged = false;
        let mut files = BTreeMap::new();
        write(&r, &mut files).unwrap();
        assert!(files.contains_key("p_map_1.svg") && files.contains_key("p_map_1.png"));
        assert!(!files.contains_key("p_map_2.svg") && !files.contains_key("dh.svg"));
    }

    #[test]
    fn csv_fields_are_quoted_when_needed() {
        assert_eq!(csv_field("l1_mm = 20"), "l1_mm = 20");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
    }
}
