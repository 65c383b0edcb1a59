//! The files a scene's [`Report`] becomes: `result.json`, `interface.csv`, the charts of p
//! and Δh along x (with the closed form dashed beside a validation case), a map of the
//! pressure over a two-dimensional region, a roller envelope's centre lines, and the
//! stresses on each vertical section below the surface (CSV and von Mises maps), and a
//! finite-element case's fields as VTK files. Every chart is written as SVG and PNG.
//!
//! Units are those of `result.json`, one per kind of quantity and written in the CSV columns'
//! names as in its fields': pressures and stresses in MPa (`_mpa`), positions and sizes in mm
//! (`_mm`), gaps and gap changes in µm (`_um`). A case is named by its `label` everywhere.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::io;

use contopt_core::{SectionAxis, SectionField};
use contopt_results::words::number;
use contopt_results::{BodyStresses, CaseReport, CaseStatus, CurvePoint, Point, Report};

use crate::{heat_map, section_map, BarChart, Figure, LineChart};

/// Where a report's files go: a results folder, or memory.
pub trait Sink {
    /// Writes `contents` as the file `name` (a plain file name).
    fn put(&mut self, name: &str, contents: &[u8]) -> io::Result<()>;

    /// Writes the file `name` as `write` writes it: a sink that writes files streams it, so a
    /// large file (a 2048² grid's `result.json`, about 1 GB) is not held in memory whole. By
    /// default, into memory and then [`Sink::put`].
    fn put_with(
        &mut self,
        name: &str,
        write: &mut dyn FnMut(&mut dyn io::Write) -> io::Result<()>,
    ) -> io::Result<()> {
        let mut contents = vec![];
        write(&mut contents)?;
        self.put(name, &contents)
    }
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
/// The resolution of a tilt in a chart's legend \[′\]: the bearing table's 0.001′.
const TILT_STEP_ARCMIN: f64 = 1e-3;

/// Writes every file of `report` to `sink`, in order: `result.json`, `interface.csv`,
/// `p.{svg,png}`, when some case changes the gap `dh.{svg,png}`, and for bearing cases
/// `lives.{svg,png}` (the duty cycle's lives per case); per case `p_map_<case>` (a
/// two-dimensional region), `envelope_<case>` (a roller's envelope), `load_zone_<case>` (a
/// bearing's load zone around the ring), `bearing_loads_<case>`
/// (a bearing's roller loads per load case), `subsurface_<case>.csv`
/// and `mises_<case>_<section>` (stresses below the surface), `fields_<case>.vtu` and
/// `contact_<case>.vtu` (a finite-element case's fields for ParaView: [`crate::vtu`]); cases
/// and sections numbered from 1.
///
/// The charts draw the cases whose methods converged, those outside the model's limits too
/// (their legend says so); `interface.csv` holds every case's points.
pub fn write(report: &Report, sink: &mut dyn Sink) -> io::Result<()> {
    write_scene(report, sink)?;
    write_cases(report, 1, sink)
}

/// Writes the files of `report` drawn from all its cases together: `result.json`,
/// `interface.csv`, `p.{svg,png}`, `dh.{svg,png}` and a bearing's `lives.{svg,png}` — the first
/// part of [`write()`], which a merge of job-array shards writes from their joined report.
pub fn write_scene(report: &Report, sink: &mut dyn Sink) -> io::Result<()> {
    sink.put_with("result.json", &mut |w| {
        serde_json::to_writer_pretty(w, report).map_err(io::Error::other)
    })?;
    sink.put_with("interface.csv", &mut |w| interface_csv(report, w))?;
    if let Some(chart) = pressure_chart(report) {
        put(sink, "p", &chart.draw()?)?;
    }
    if let Some(chart) = gap_change_chart(report) {
        put(sink, "dh", &chart.draw()?)?;
    }
    if let Some(chart) = lives_chart(report) {
        put(sink, "lives", &chart.draw()?)?;
    }
    Ok(())
}

/// Writes the files of each case of `report` on its own (the second part of [`write()`]),
/// numbering the cases from `first`: a job-array shard that holds cases 5 to 8 of its scene
/// writes them as one run of the whole scene would, `p_map_5` to `p_map_8`.
pub fn write_cases(report: &Report, first: usize, sink: &mut dyn Sink) -> io::Result<()> {
    for (k, case) in report.cases.iter().enumerate() {
        let number = first + k;
        if let Some(map) = pressure_map(report, case)? {
            put(sink, &format!("p_map_{number}"), &map)?;
        }
        if let Some(chart) = envelope_chart(report, case) {
            put(sink, &format!("envelope_{number}"), &chart.draw()?)?;
        }
        if let Some(chart) = bearing_loads_chart(case) {
            put(sink, &format!("bearing_loads_{number}"), &chart.draw()?)?;
        }
        if let Some(zone) = crate::polar::load_zone(case) {
            put(sink, &format!("load_zone_{number}"), &zone?)?;
        }
        sections(report, case, number, sink)?;
        if let Some(vtu) = crate::vtu::fields_vtu(case)? {
            sink.put(&format!("fields_{number}.vtu"), &vtu)?;
        }
        if let Some(vtu) = crate::vtu::contact_vtu(case)? {
            sink.put(&format!("contact_{number}.vtu"), &vtu)?;
        }
    }
    Ok(())
}

/// A bearing case's roller loads over their angle from the load, one line per load case.
fn bearing_loads_chart(case: &CaseReport) -> Option<LineChart> {
    let b = case.bearing.as_ref()?;
    let title = format!("{}: roller loads", case.label);
    let mut chart = LineChart::new(&title, "ψ [°] from the load", "Q [N]");
    for c in &b.load_cases {
        let mut points: Vec<(f64, f64)> = c
            .rollers
            .iter()
            .map(|r| {
                let psi = (r.angle_deg + 180.0).rem_euclid(360.0) - 180.0;
                (psi, r.load_n)
            })
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart = chart.line(&c.label, &points);
    }
    (!chart.is_empty()).then_some(chart)
}

/// The duty cycle's lives of every bearing case, one group of bars per case: ISO/TS 16281's
/// from the half-space contacts (their peak pressures' Hertzian slice loads, and their slice
/// loads) and from the slice model, and ISO 281's.
fn lives_chart(report: &Report) -> Option<BarChart> {
    let title = format!("{}: rating lives over the duty cycle", report.scene);
    let series = [
        "L10r, peak pressures",
        "L10r, half-space slice loads",
        "L10r, slice model",
        "L10, ISO 281",
    ];
    let mut chart = BarChart::new(&title, "life [10⁶ revolutions]", &series);
    for c in report.cases.iter().filter(|c| converged(c)) {
        if let Some(b) = &c.bearing {
            let l = &b.duty_cycle;
            let lives = [
                l.peak_pressure_mrev,
                l.half_space_mrev,
                l.slice_model_mrev,
                l.iso_281_mrev,
            ];
            chart = chart.group(&legend(c), &lives);
        }
    }
    (!chart.is_empty()).then_some(chart)
}

/// Writes `figure` as `<stem>.svg` and `<stem>.png`.
fn put(sink: &mut dyn Sink, stem: &str, figure: &Figure) -> io::Result<()> {
    for (name, bytes) in figure.files(stem)? {
        sink.put(&name, &bytes)?;
    }
    Ok(())
}

/// The header of `interface.csv`: the fields of `result.json`'s interface points, the
/// coordinates `x_mm` spread over three columns.
const INTERFACE_HEADER: &str = "case,x_mm,y_mm,z_mm,p_mpa,d_um,dh_um,h_um\n";

/// The fields at every interface point of every case.
fn interface_csv(report: &Report, csv: &mut dyn io::Write) -> io::Result<()> {
    csv.write_all(INTERFACE_HEADER.as_bytes())?;
    for c in &report.cases {
        let label = csv_field(&c.label);
        for q in &c.interface {
            let [x, y, z] = q.x_mm;
            writeln!(
                csv,
                "{label},{x},{y},{z},{},{},{},{}",
                q.p_mpa, q.d_um, q.dh_um, q.h_um
            )?;
        }
    }
    Ok(())
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

/// Whether the case's methods converged: solved, or outside the model's limits (an answer
/// that the zone cuts short, still worth seeing).
fn converged(case: &CaseReport) -> bool {
    case.status != CaseStatus::NotConverged
}

/// A case's name in a chart's legend: its label, and whether it lies outside the model.
fn legend(case: &CaseReport) -> String {
    match case.status {
        CaseStatus::OutsideModel => format!("{} (outside the model)", case.label),
        _ => case.label.clone(),
    }
}

/// `field` along the row of a case's interface points nearest the x axis (all of them on an
/// axisymmetric or plane body), sorted by x.
fn along_x(case: &CaseReport, field: impl Fn(&Point) -> f64) -> Vec<(f64, f64)> {
    let near = case
        .interface
        .iter()
        .map(|q| q.x_mm[1].abs())
        .fold(f64::INFINITY, f64::min);
    let mut line: Vec<(f64, f64)> = case
        .interface
        .iter()
        .filter(|q| q.x_mm[1].abs() <= near + SAME_ROW)
        .map(|q| (q.x_mm[0], field(q)))
        .collect();
    line.sort_by(|a, b| a.0.total_cmp(&b.0));
    line
}

/// A pressure curve as (x, p).
fn curve(points: &[CurvePoint]) -> Vec<(f64, f64)> {
    points.iter().map(|c| (c.x_mm, c.p_mpa)).collect()
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
    for c in report.cases.iter().filter(|c| converged(c)) {
        chart = chart.line(&legend(c), &along_x(c, |q| q.p_mpa));
        if let Some(r) = &c.reference {
            let label = if report.cases.len() > 1 {
                format!("{} ({})", r.label, c.label)
            } else {
                r.label.clone()
            };
            chart = chart.reference(&label, &curve(&r.points));
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
        .filter(|c| converged(c))
        .flat_map(|c| along_x(c, |q| q.p_mpa))
        .map(|p| p.1)
        .filter(|&p| p > 0.0 && p.is_finite())
        .collect();
    positive.sort_by(f64::total_cmp);
    let median = *positive.get(positive.len() / 2)?;
    let largest = *positive.last()?;
    (largest > SPIKE * median).then(|| crate::ticks::Axis::between(0.0, SPIKE * median).hi)
}

/// The gap change Δh \[µm\] along x of every converged case, when one of them changes the
/// gap.
fn gap_change_chart(report: &Report) -> Option<LineChart> {
    let changes = |c: &&CaseReport| converged(c) && c.interface.iter().any(|q| q.dh_um != 0.0);
    report.cases.iter().find(changes)?;
    let title = format!("{}: gap change", report.scene);
    let mut chart = LineChart::new(&title, "x [mm]", "Δh [µm]");
    for c in report.cases.iter().filter(|c| converged(c)) {
        chart = chart.line(&legend(c), &along_x(c, |q| q.dh_um));
    }
    (!chart.is_empty()).then_some(chart)
}

/// A map of the pressure over a case's two-dimensional region (its points off one row);
/// none for a line of points or a case that did not converge.
fn pressure_map(report: &Report, case: &CaseReport) -> io::Result<Option<Figure>> {
    let first_y = case.interface.first().map_or(0.0, |q| q.x_mm[1]);
    let flat = case
        .interface
        .iter()
        .all(|q| (q.x_mm[1] - first_y).abs() < SAME_ROW);
    if !converged(case) || flat {
        return Ok(None);
    }
    let points: Vec<(f64, f64, f64)> = case
        .interface
        .iter()
        .map(|q| (q.x_mm[0], q.x_mm[1], q.p_mpa))
        .collect();
    let peak = case.p_max_mpa.map_or(String::new(), |p| {
        format!(", largest {} MPa", number(p.round()))
    });
    let title = format!(
        "{}: contact pressure{}{peak}",
        report.scene,
        of_case(report, case)
    );
    // Only a roller's x runs along an axis of the bodies.
    let x = match case.roller {
        Some(_) => "x [mm] (along the axis)",
        None => "x [mm]",
    };
    heat_map(&title, x, "y [mm]", "p [MPa]", &points).map(Some)
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
            number(to_the_table(e.tilt_arcmin))
        );
        chart = chart.line(&label, &curve(&e.centre_line));
    }
    Some(chart)
}

/// A tilt \[′\] to the table's 0.001′ (a bearing's aligned rollers come out of their
/// equilibrium solve at 10⁻¹⁶′, not 0), without a negative zero.
fn to_the_table(arcmin: f64) -> f64 {
    (arcmin / TILT_STEP_ARCMIN).round() * TILT_STEP_ARCMIN + 0.0
}

/// `, <case>` in a title, or nothing when the case is the scene itself.
fn of_case(report: &Report, case: &CaseReport) -> String {
    if case.label == report.scene {
        String::new()
    } else {
        format!(", {}", legend(case))
    }
}

/// The header of `subsurface_<case>.csv`: the case, the body, the section (its name, as the
/// title of its map says it), the point (x, y along the surface, as `result.json`'s peaks
/// write them; r and 0 on an axisymmetric body) and its depth, then the stresses.
const SECTION_HEADER: &str = "case,body,section,x_mm,y_mm,depth_mm,sxx_mpa,syy_mpa,szz_mpa,\
sxy_mpa,sxz_mpa,syz_mpa,von_mises_mpa,tresca_mpa,s1_mpa,s3_mpa\n";

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
        let map = section(report, case, body, field, &mut csv)?;
        put(sink, &format!("mises_{number}_{}", n + 1), &map)?;
    }
    if sub.bodies.iter().any(|b| !b.sections.is_empty()) {
        sink.put(&format!("subsurface_{number}.csv"), csv.as_bytes())?;
    }
    Ok(())
}

/// The two-dimensional model a case's bodies are, which has one section, its own plane.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Model {
    /// Axisymmetric: the section runs along r.
    Axisymmetric,
    /// Plane stress or strain: the section runs along x.
    Plane,
}

/// The two-dimensional model of a case's bodies, from the zone of its resolved inputs
/// (`contact.zone`: rings are axisymmetric, strips plane, finite-element faces as their
/// `analysis` says); `None` for a grid on a surface, and when the inputs do not say.
fn model(case: &CaseReport) -> Option<Model> {
    let zone = case.input.pointer("/contact/zone")?.as_object()?;
    // `{"rings": {…}}` as the scene writes it, or `{"kind": "rings", …}` as a scene file does.
    let (kind, content) = match zone.get("kind").and_then(|k| k.as_str()) {
        Some(kind) => (kind, zone),
        None => {
            let (kind, content) = zone.iter().next().filter(|_| zone.len() == 1)?;
            (kind.as_str(), content.as_object()?)
        }
    };
    match kind {
        "rings" => Some(Model::Axisymmetric),
        "strips" => Some(Model::Plane),
        "faces" => match content.get("analysis").and_then(|a| a.as_str()) {
            Some("axisymmetric") => Some(Model::Axisymmetric),
            _ => Some(Model::Plane),
        },
        _ => None,
    }
}

/// A coordinate \[mm\] in a section's name: four decimals, never `-0.0000`.
fn mm(v: f64) -> String {
    let v = if v.abs() < 5e-5 { 0.0 } else { v };
    format!("{v:.4}")
}

/// A section's name in the CSV and in its map's title (`along x at y = 0.0000 mm`; the
/// body's own plane on a plane or axisymmetric body), and the coordinate along it.
fn name(field: &SectionField, model: Option<Model>) -> (String, &'static str) {
    let at = mm(field.section.at);
    match (model, field.section.axis) {
        (Some(Model::Axisymmetric), _) => ("the body's plane along r (axisymmetric)".into(), "r"),
        (Some(Model::Plane), _) => ("the body's plane along x (plane model)".into(), "x"),
        (None, SectionAxis::X) => (format!("along x at y = {at} mm"), "x"),
        (None, SectionAxis::Y) => (format!("along y at x = {at} mm"), "y"),
    }
}

/// Where `position` along a section lies on the surface, (x, y) \[mm\]: on a plane or
/// axisymmetric body (x or r, 0), as `result.json`'s peaks write it.
fn on_surface(field: &SectionField, model: Option<Model>, position: f64) -> (f64, f64) {
    match (model, field.section.axis) {
        (Some(_), _) => (position, 0.0),
        (None, SectionAxis::X) => (position, field.section.at),
        (None, SectionAxis::Y) => (field.section.at, position),
    }
}

/// Appends a section's rows to `csv` and draws its von Mises map.
fn section(
    report: &Report,
    case: &CaseReport,
    body: &BodyStresses,
    field: &SectionField,
    csv: &mut String,
) -> io::Result<Figure> {
    let model = model(case);
    let (section, along) = name(field, model);
    let start = format!(
        "{},{},{}",
        csv_field(&case.label),
        csv_field(&body.body),
        csv_field(&section)
    );
    let mut points = Vec::with_capacity(field.tensors.len());
    for (kd, depth) in field.depths.iter().enumerate() {
        for (i, position) in field.positions.iter().enumerate() {
            let t = field.at(kd, i);
            let [s1, _, s3] = t.principal();
            let (mises, tresca) = (t.von_mises(), t.tresca());
            let (x, y) = on_surface(field, model, *position);
            let _ = writeln!(
                csv,
                "{start},{x},{y},{depth},{},{},{},{},{},{},{mises},{tresca},{s1},{s3}",
                t.xx, t.yy, t.zz, t.xy, t.xz, t.yz
            );
            points.push((*position, *depth, mises));
        }
    }
    let of_case = of_case(report, case);
    let (top, depth) = points
        .iter()
        .fold((0.0, 0.0), |m, p| if p.2 > m.0 { (p.2, p.1) } else { m });
    let within = if model.is_some() { "in " } else { "" };
    let title = format!(
        "von Mises stress below the {}{of_case}, {within}{}\n\
         largest {top:.0} MPa at depth {depth:.3} mm",
        body.body,
        section.replace('-', "−")
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
    use contopt_core::{Section, StressTensor, Termination};
    use contopt_results::{
        ModelLimit, Peak, Peaks, ReferenceCurve, SubsurfaceReport, SCHEMA_VERSION,
    };

    use super::*;

    /// A solved case along a line of 11 points, x from 0 to 1 mm: p = scale·(1 − x²) MPa,
    /// Δh = 2x µm, with a closed form.
    fn case(label: &str, l1: f64, scale: f64) -> CaseReport {
        let params = BTreeMap::from([("optimisation.controller.l1_mm".to_string(), l1)]);
        let mut c = CaseReport::new(label, &params, serde_json::Value::Null);
        c.status = CaseStatus::Solved;
        c.termination = Termination::Converged;
        c.dh_max_um = Some(2.0);
        c.interface = (0..11)
            .map(|i| {
                let x = 0.1 * i as f64;
                Point {
                    x_mm: [x, 0.0, 0.0],
                    p_mpa: scale * (1.0 - x * x).max(0.0),
                    d_um: 0.0,
                    dh_um: 2.0 * x,
                    h_um: 0.0,
                }
            })
            .collect();
        c.reference = Some(ReferenceCurve {
            label: "Hertz: p₀ = 100 MPa".into(),
            points: vec![
                CurvePoint {
                    x_mm: 0.0,
                    p_mpa: 100.0,
                },
                CurvePoint {
                    x_mm: 1.0,
                    p_mpa: 0.0,
                },
            ],
        });
        c.settle();
        c
    }

    /// A swept scene of two cases, labelled as the scene labels a sweep.
    fn report() -> Report {
        Report {
            schema_version: SCHEMA_VERSION,
            scene: "s".into(),
            description: "two cases".into(),
            cases: vec![
                case("L1 = 0 mm", 0.0, 100.0),
                case("L1 = 20 mm", 20.0, 80.0),
            ],
        }
    }

    fn text(files: &BTreeMap<String, Vec<u8>>, name: &str) -> String {
        String::from_utf8(files[name].clone()).unwrap()
    }

    /// The texts of a chart's SVG, apostrophes unescaped.
    fn texts(svg: &str) -> Vec<String> {
        crate::figure::check::text_boxes(svg)
            .into_iter()
            .map(|b| b.text.replace("&apos;", "'"))
            .collect()
    }

    /// The files of a line of points: the JSON, the CSV, p and Δh as SVG and PNG; the legend
    /// the cases' labels, the closed form beside its case; nothing non-finite.
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
        let p = text(&files, "p.svg");
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
        let json: Report = serde_json::from_slice(&files["result.json"]).unwrap();
        assert_eq!(json.schema_version, SCHEMA_VERSION);
        assert_eq!(json.cases[1].reference, report().cases[1].reference);
        let (read, wrote) = (&json.cases[1].interface, &report().cases[1].interface);
        assert_eq!(read.len(), wrote.len());
        for (a, b) in read.iter().zip(wrote) {
            assert!((a.p_mpa - b.p_mpa).abs() < 1e-12 && (a.dh_um - b.dh_um).abs() < 1e-12);
        }
    }

    /// The gap-change chart is in µm, as the JSON: Δh runs to 2 µm, so does its axis.
    #[test]
    fn the_gap_change_is_drawn_in_micrometres() {
        let mut files = BTreeMap::new();
        write(&report(), &mut files).unwrap();
        let dh = texts(&text(&files, "dh.svg"));
        assert!(dh.iter().any(|t| t == "Δh [µm]"), "{dh:?}");
        assert!(dh.iter().any(|t| t == "2.0"), "{dh:?}");
        assert!(!dh.iter().any(|t| t == "2000" || t == "0.002"), "{dh:?}");
    }

    /// `interface.csv`: units in the header, as the JSON's field names; the case's label in
    /// the first column, quoted when it holds a comma; gaps in µm.
    #[test]
    fn interface_csv_has_units_and_the_case_label() {
        let mut r = report();
        r.cases[1].label = "F = 1000 N, ν = 0.3".into();
        r.cases[1].interface[0].d_um = 3.5;
        let mut files = BTreeMap::new();
        write(&r, &mut files).unwrap();
        let csv = text(&files, "interface.csv");
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "case,x_mm,y_mm,z_mm,p_mpa,d_um,dh_um,h_um");
        assert_eq!(lines.len(), 1 + 2 * 11);
        assert_eq!(lines[1], "L1 = 0 mm,0,0,0,100,0,0,0");
        assert_eq!(lines[12], "\"F = 1000 N, ν = 0.3\",0,0,0,80,3.5,0,0");
        assert_eq!(lines[13], "\"F = 1000 N, ν = 0.3\",0.1,0,0,79.2,0,0.2,0");
    }

    /// A grid of points becomes a map per case; a case that did not converge draws nothing.
    #[test]
    fn a_region_is_mapped() {
        let mut r = report();
        r.cases[0].interface = (0..25)
            .map(|k| Point {
                x_mm: [(k % 5) as f64, (k / 5) as f64, 0.0],
                p_mpa: if k == 12 { 10.0 } else { 0.0 },
                d_um: 0.0,
                dh_um: 0.0,
                h_um: 0.0,
            })
            .collect();
        r.cases[1].status = CaseStatus::NotConverged;
        let mut files = BTreeMap::new();
        write(&r, &mut files).unwrap();
        assert!(files.contains_key("p_map_1.svg") && files.contains_key("p_map_1.png"));
        assert!(!files.contains_key("p_map_2.svg") && !files.contains_key("dh.svg"));
    }

    /// A case outside the model is drawn, its legend saying so; one that did not converge is
    /// not.
    #[test]
    fn charts_say_which_case_lies_outside_the_model() {
        let mut r = report();
        r.cases[0].status = CaseStatus::OutsideModel;
        r.cases[0].limit = Some(ModelLimit {
            edge: "x = +1 mm".into(),
            extent_mm: 1.0,
            needed_mm: 1.5,
            message: "the contact reaches the zone's edge".into(),
        });
        r.cases[1].status = CaseStatus::NotConverged;
        let mut files = BTreeMap::new();
        write(&r, &mut files).unwrap();
        let p = texts(&text(&files, "p.svg"));
        assert!(
            p.iter().any(|t| t == "L1 = 0 mm (outside the model)"),
            "{p:?}"
        );
        assert!(!p.iter().any(|t| t.contains("L1 = 20 mm")), "{p:?}");
    }

    /// One body's stresses on one section: a σ_zz of −(1 + k) at depth k, 2 positions × 2
    /// depths.
    fn stresses(section: Section) -> SubsurfaceReport {
        let peak = Peak {
            value_mpa: 1.0,
            x_mm: 0.0,
            y_mm: 0.0,
            depth_mm: 0.1,
        };
        let tensor = |k: usize| StressTensor {
            zz: -(1.0 + k as f64),
            ..Default::default()
        };
        SubsurfaceReport {
            depths_mm: vec![0.1, 0.2],
            bodies: vec![BodyStresses {
                body: "half-space".into(),
                peaks: Peaks {
                    von_mises: peak,
                    tresca: peak,
                    max_principal: peak,
                    min_principal: peak,
                    shear_xz: peak,
                    shear_yz: Some(peak),
                },
                sections: vec![SectionField {
                    section,
                    positions: vec![-0.1, 0.1],
                    depths: vec![0.1, 0.2],
                    tensors: vec![tensor(0), tensor(0), tensor(1), tensor(1)],
                }],
            }],
        }
    }

    /// The numbers of a CSV row after its first fields, `start`.
    fn numbers(row: &str, start: &str) -> Vec<f64> {
        let rest = row
            .strip_prefix(start)
            .unwrap_or_else(|| panic!("{row} does not start with {start}"));
        rest.split(',').map(|v| v.parse().unwrap()).collect()
    }

    /// A legend's tilt is the table's, to 0.001′: round-off of an aligned roller's
    /// equilibrium reads 0 (not −0 or 10⁻¹⁶).
    #[test]
    fn a_legends_tilt_is_read_to_the_tables_resolution() {
        assert_eq!(number(to_the_table(1.24648e-16)), "0");
        assert_eq!(number(to_the_table(-1.88598e-16)), "0");
        assert_eq!(number(to_the_table(0.900969)), "0.901");
        assert_eq!(number(to_the_table(-2.0)), number(-2.0));
    }

    /// `got` equals `want` to 10⁻⁷ (the principal stresses are solved for, to about 10⁻⁸
    /// where two are equal).
    fn assert_near(got: &[f64], want: &[f64]) {
        assert_eq!(got.len(), want.len(), "{got:?}");
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-7, "{got:?} against {want:?}");
        }
    }

    /// `subsurface_<case>.csv` names the case (quoted when it holds a comma), the body and
    /// the section of each row, with the surface point (x, y) of a section along y at x =
    /// 0.25 mm; its map's title names the same section.
    #[test]
    fn subsurface_rows_name_their_case_and_section() {
        let mut r = report();
        r.cases[1].label = "F = 1000 N, ν = 0.3".into();
        r.cases[1].subsurface = Some(stresses(Section {
            axis: SectionAxis::Y,
            at: 0.25,
        }));
        let mut files = BTreeMap::new();
        write(&r, &mut files).unwrap();
        assert!(!files.contains_key("subsurface_1.csv"));
        let csv = text(&files, "subsurface_2.csv");
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(
            lines[0],
            "case,body,section,x_mm,y_mm,depth_mm,sxx_mpa,syy_mpa,szz_mpa,sxy_mpa,sxz_mpa,\
             syz_mpa,von_mises_mpa,tresca_mpa,s1_mpa,s3_mpa"
        );
        assert_eq!(lines.len(), 1 + 4);
        let case = "\"F = 1000 N, ν = 0.3\",half-space,along y at x = 0.2500 mm,";
        assert_near(
            &numbers(lines[1], case),
            &[
                0.25, -0.1, 0.1, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0, 0.5, 0.0, -1.0,
            ],
        );
        assert_near(
            &numbers(lines[4], case),
            &[
                0.25, 0.1, 0.2, 0.0, 0.0, -2.0, 0.0, 0.0, 0.0, 2.0, 1.0, 0.0, -2.0,
            ],
        );
        let map = text(&files, "mises_2_1.svg");
        assert!(map.contains("along y at x = 0.2500 mm"), "{map}");
        assert!(files.contains_key("mises_2_1.png"));
    }

    /// On an axisymmetric body (rings, or finite-element faces so analysed) the one section
    /// is the body's plane, along r, at y = 0; on a plane one along x; on a grid the section
    /// is named by its line.
    #[test]
    fn a_two_dimensional_body_has_its_plane_as_section() {
        let along_x = Section {
            axis: SectionAxis::X,
            at: 0.0,
        };
        let zones = [
            (
                serde_json::json!({"rings": {"rings": 40, "radius_mm": 1.0}}),
                "the body's plane along r (axisymmetric)",
            ),
            (
                serde_json::json!({"faces": {"analysis": "axisymmetric", "radius_mm": 1.0}}),
                "the body's plane along r (axisymmetric)",
            ),
            (
                serde_json::json!({"faces": {"analysis": {"plane_strain": {"thickness_mm": 1.0}}}}),
                "the body's plane along x (plane model)",
            ),
            (
                serde_json::json!({"kind": "strips", "strips": 40}),
                "the body's plane along x (plane model)",
            ),
            (
                serde_json::json!({"grid": {"cells": [8, 8]}}),
                "along x at y = 0.0000 mm",
            ),
        ];
        for (zone, name) in zones {
            let mut r = report();
            r.cases[0].input = serde_json::json!({"contact": {"zone": zone}});
            r.cases[0].subsurface = Some(stresses(along_x));
            let mut files = BTreeMap::new();
            write(&r, &mut files).unwrap();
            let csv = text(&files, "subsurface_1.csv");
            let row = csv.lines().nth(1).unwrap();
            let start = format!("L1 = 0 mm,half-space,{name},");
            assert_near(&numbers(row, &start)[..3], &[-0.1, 0.0, 0.1]);
            let map = text(&files, "mises_1_1.svg");
            let title = if name.starts_with("the body's") {
                format!("L1 = 0 mm, in {name}")
            } else {
                format!("L1 = 0 mm, {name}")
            };
            let lines = texts(&map);
            assert!(
                lines.iter().any(|t| t.contains(&title)),
                "{title} in {lines:?}"
            );
            let axis = if name.contains("along r") {
                "r [mm] along the section"
            } else {
                "x [mm] along the section"
            };
            assert!(
                texts(&text(&files, "mises_1_1.svg"))
                    .iter()
                    .any(|t| t == axis),
                "{name}"
            );
        }
    }

    #[test]
    fn csv_fields_are_quoted_when_needed() {
        assert_eq!(csv_field("l1_mm = 20"), "l1_mm = 20");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
    }
}
