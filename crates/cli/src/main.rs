//! `contopt`: runs scene files (TOML or JSON) and writes their results.
//!
//! - `contopt run <scene> [--json] [--out DIR]`: solves every case and writes
//!   `DIR/<name>/result.json`, `interface.csv`, `p.svg` (and `dh.svg` when a case changes the
//!   gap; with `[output.subsurface]` also `subsurface_<case>.csv` and
//!   `mises_<case>_<section>.svg`), then prints a table (or, with `--json`, the report as one
//!   JSON document on stdout). Files go only into `DIR/<name>/`, never through a symbolic link.
//! - `contopt check <scene>`: reads and checks the scene without solving;
//! - `contopt list`: the bundled scenes, which `run` and `check` also take by name.
//!
//! Exit status: see [`EXIT_CODES`].

mod files;

use std::io::{IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use clap::{Parser, Subcommand};
use contopt_scene::{CaseReport, Format, Report, Scene, SceneError, BUNDLED};
use files::{csv_field, ResultsDir};

/// A bad scene: unreadable, unknown or missing keys, values out of range, too large.
const EXIT_BAD_INPUT: u8 = 1;
/// A usage error: an unknown option or a missing argument (clap's code).
const EXIT_USAGE: u8 = 2;
/// Some case did not converge (its report says how far it got).
const EXIT_NOT_CONVERGED: u8 = 3;
/// The results could not be written.
const EXIT_WRITE: u8 = 4;

/// The exit codes, as `--help` shows them.
const EXIT_CODES: &str = "Exit status: 0 success; 1 bad scene (unreadable, invalid or too large); \
2 usage error; 3 some case did not converge; 4 the results could not be written.";

#[derive(Parser)]
#[command(
    name = "contopt",
    version,
    about = "Elastic contact and contact-pressure optimisation (Páczelt 1994)",
    after_help = EXIT_CODES
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a scene (a file, or a bundled scene's name) and write its results.
    Run {
        /// Scene file (.toml or .json) or bundled name.
        scene: String,
        /// Print the report as JSON on stdout (and nothing else there).
        #[arg(long)]
        json: bool,
        /// Folder for the results (a subfolder per scene).
        #[arg(long, default_value = "results")]
        out: PathBuf,
    },
    /// Read and check a scene without solving.
    Check {
        /// Scene file or bundled name.
        scene: String,
    },
    /// List the bundled scenes.
    List,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let _ = e.print();
            return ExitCode::from(if e.use_stderr() { EXIT_USAGE } else { 0 });
        }
    };
    match cli.command {
        Command::List => {
            let mut text = String::new();
            for (name, scene) in BUNDLED {
                let description = Scene::parse(scene, Format::Toml, Path::new(name))
                    .map(|s| s.spec.description)
                    .unwrap_or_default();
                text += &format!("{name:<16} {description}\n");
            }
            emit(&text);
            ExitCode::SUCCESS
        }
        Command::Check { scene } => match load(&scene) {
            Ok(s) => {
                let cases = s.cases().map(|c| c.len()).unwrap_or(0);
                emit(&format!("{}: ok ({cases} case(s))\n", s.file.display()));
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        Command::Run { scene, json, out } => match load(&scene).and_then(|s| run(&s, json, &out)) {
            Ok(code) => ExitCode::from(code),
            Err(e) => fail(&e),
        },
    }
}

fn fail(e: &SceneError) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(EXIT_BAD_INPUT)
}

/// Prints `text` on stdout; a reader that has gone (`contopt run … | head`) ends the output
/// quietly instead of a panic.
fn emit(text: &str) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        if e.kind() != std::io::ErrorKind::BrokenPipe {
            eprintln!("could not print the results: {e}");
        }
    }
}

/// A scene file, or a bundled scene by name.
fn load(scene: &str) -> Result<Scene, SceneError> {
    let path = Path::new(scene);
    if path.exists() {
        return Scene::load(path);
    }
    match BUNDLED.iter().find(|(name, _)| *name == scene) {
        Some((name, text)) => Scene::parse(
            text,
            Format::Toml,
            &Path::new("scenes").join(format!("{name}.toml")),
        ),
        None => Scene::load(path),
    }
}

/// Runs every case, writes the results and prints them; the exit code.
fn run(scene: &Scene, json: bool, out: &Path) -> Result<u8, SceneError> {
    let cases = scene.cases()?;
    let progress = std::io::stderr().is_terminal();
    let start = Instant::now();
    let mut reports = vec![];
    for (k, case) in cases.iter().enumerate() {
        if progress && start.elapsed().as_secs_f64() > 1.5 {
            eprint!("\r[{}/{}] {} … ", k + 1, cases.len(), case.label);
        }
        reports.push(case.run()?);
    }
    if progress && start.elapsed().as_secs_f64() > 1.5 {
        eprintln!("\rdone in {:.1} s{:20}", start.elapsed().as_secs_f64(), "");
    }
    let report = Report {
        scene: scene.spec.name.clone(),
        cases: reports,
    };
    for c in &report.cases {
        for w in &c.warnings {
            eprintln!("warning: {}: {w}", c.label);
        }
    }
    let written = ResultsDir::create(out, &scene.spec.name).and_then(|mut dir| {
        write(&report, &mut dir)?;
        dir.finish()
    });
    if json {
        emit(&(serde_json::to_string_pretty(&report).unwrap_or_default() + "\n"));
    } else {
        emit(&table(&report));
    }
    match written {
        Ok(dir) => {
            if !json {
                emit(&format!(
                    "results: {}/{{{}}}\n",
                    dir.path().display(),
                    dir.written().join(",")
                ));
            }
        }
        Err(e) => {
            eprintln!(
                "error: could not write the results to {}: {e}",
                out.join(&scene.spec.name).display()
            );
            return Ok(EXIT_WRITE);
        }
    }
    let converged = report.cases.iter().all(|c| c.converged);
    Ok(if converged { 0 } else { EXIT_NOT_CONVERGED })
}

fn table(report: &Report) -> String {
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
    use std::fmt::Write;
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
            c.label,
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
        .map(|c| c.label.len())
        .max()
        .unwrap_or(4)
        .max(4)
}

/// The table of a roller study: per case p_max and where it sits, edge loading, the approach,
/// the contact half-widths at mid-length and at the ends, and the crown's drop at the ends.
fn roller_table(report: &Report) -> String {
    use std::fmt::Write;
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
                    "{:<width$} {:>10.1} {:>14} {:>5} {:>12.3} {:>16} {:>12.3} {:>8.0}",
                    c.label,
                    p,
                    format!("{:.2}, {:.3}", r.p_max_at_mm[0], r.p_max_at_mm[1]),
                    if r.edge_loading { "yes" } else { "no" },
                    c.approach_um.unwrap_or(f64::NAN),
                    format!("{:.4} / {:.4}", r.half_width_mm[0], r.half_width_mm[1]),
                    r.crown_drop_end_um,
                    total
                );
            }
            _ => {
                let _ = writeln!(
                    s,
                    "{:<width$} not converged: {}",
                    c.label,
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
    use std::fmt::Write;
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
        let _ = write!(s, "{:<width$}", c.label);
        for e in &r.envelope {
            let mark = if e.edge_loading { "*" } else { " " };
            let _ = write!(s, " {:>9.1}{mark}", e.p_max);
        }
        let _ = writeln!(s, " {:>10.1}", r.worst_p_max.unwrap_or(f64::NAN));
        if let Some(t) = &r.tuned {
            let _ = writeln!(
                tuned,
                "{}: K1 = {:.4}, K2 = {:.4}, z_m = {:.4} µm ({} crowns searched)",
                c.label,
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
    use std::fmt::Write;
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
                c.label,
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

/// Writes `result.json`, `interface.csv` and the plots of p (and of Δh, when some case changes
/// the gap) along x (on a grid: along the points nearest the x axis).
fn write(report: &Report, dir: &mut ResultsDir) -> std::io::Result<()> {
    let json = serde_json::to_string_pretty(report).map_err(std::io::Error::other)?;
    dir.write("result.json", json.as_bytes())?;
    let mut csv = String::from("case,x,y,z,p_mpa,d_mm,dh_mm\n");
    for c in &report.cases {
        let label = csv_field(&c.label);
        for q in &c.interface {
            csv += &format!(
                "{label},{},{},{},{},{},{}\n",
                q.x[0], q.x[1], q.x[2], q.p, q.d, q.dh
            );
        }
    }
    dir.write("interface.csv", csv.as_bytes())?;
    let line =
        |c: &CaseReport, f: &dyn Fn(&contopt_scene::PointReport) -> f64| -> Vec<(f64, f64)> {
            let near = c
                .interface
                .iter()
                .map(|q| q.x[1].abs())
                .fold(f64::INFINITY, f64::min);
            let mut v: Vec<(f64, f64)> = c
                .interface
                .iter()
                .filter(|q| q.x[1].abs() <= near + 1e-9)
                .map(|q| (q.x[0], f(q)))
                .collect();
            v.sort_by(|a, b| a.0.total_cmp(&b.0));
            v
        };
    let changes_gap = report
        .cases
        .iter()
        .any(|c| c.interface.iter().any(|q| q.dh != 0.0));
    type Field<'a> = &'a dyn Fn(&contopt_scene::PointReport) -> f64;
    let plots: [(&str, &str, &str, Field, bool); 2] = [
        ("p.svg", "contact pressure", "p [MPa]", &|q| q.p, true),
        (
            "dh.svg",
            "gap change",
            "Δh [µm]",
            &|q| 1e3 * q.dh,
            changes_gap,
        ),
    ];
    for (file, title, label, f, wanted) in plots {
        let series: Vec<(String, Vec<(f64, f64)>)> = report
            .cases
            .iter()
            .filter(|c| c.converged)
            .map(|c| (c.label.clone(), line(c, f)))
            .collect();
        if !wanted || series.is_empty() {
            continue;
        }
        let svg = chart(
            &format!("{}: {title}", report.scene),
            "x [mm]",
            label,
            &series,
        );
        dir.write(file, svg.as_bytes())?;
    }
    write_maps(report, dir)
}

/// A line chart of labelled series.
fn chart(title: &str, x: &str, y: &str, series: &[(String, Vec<(f64, f64)>)]) -> String {
    let refs: Vec<(&str, &[(f64, f64)])> = series
        .iter()
        .map(|(l, v)| (l.as_str(), v.as_slice()))
        .collect();
    contopt::plot::line_plot(title, x, y, &refs)
}

/// A heat map of the pressure over a two-dimensional region, one per case:
/// `p_map_<case number>.svg`.
fn write_maps(report: &Report, dir: &mut ResultsDir) -> std::io::Result<()> {
    for (k, c) in report.cases.iter().enumerate() {
        let first_y = c.interface.first().map_or(0.0, |q| q.x[1]);
        if !c.converged || c.interface.iter().all(|q| (q.x[1] - first_y).abs() < 1e-12) {
            continue;
        }
        let points: Vec<(f64, f64, f64)> =
            c.interface.iter().map(|q| (q.x[0], q.x[1], q.p)).collect();
        let svg = contopt::plot::heat_map(
            &format!("{}: contact pressure, {}", report.scene, c.label),
            "x [mm] (along the axis)",
            "y [mm]",
            "MPa",
            &points,
        );
        dir.write(&format!("p_map_{}.svg", k + 1), svg.as_bytes())?;
    }
    write_envelopes(report, dir)
}

/// The centre-line pressure of a roller under each case of its envelope, one chart per case of
/// the scene: `envelope_<case number>.svg`.
fn write_envelopes(report: &Report, dir: &mut ResultsDir) -> std::io::Result<()> {
    for (k, c) in report.cases.iter().enumerate() {
        let Some(r) = c.roller.as_ref().filter(|r| !r.envelope.is_empty()) else {
            continue;
        };
        let nominal = r.envelope[0].load_n;
        let series: Vec<(String, Vec<(f64, f64)>)> = r
            .envelope
            .iter()
            .map(|e| {
                let label = format!("{:.1} Q, {:+.1}′", e.load_n / nominal, e.tilt_arcmin);
                (label, e.centre_line.iter().map(|p| (p[0], p[1])).collect())
            })
            .collect();
        let svg = chart(
            &format!("{}: centre-line pressure, {}", report.scene, c.label),
            "x [mm] (along the axis)",
            "p [MPa]",
            &series,
        );
        dir.write(&format!("envelope_{}.svg", k + 1), svg.as_bytes())?;
    }
    write_sections(report, dir)
}

/// The stresses on each vertical section below each body, one CSV per case,
/// `subsurface_<case number>.csv`, and a von Mises heat map per section,
/// `mises_<case number>_<section number>.svg` (sections numbered over the case's bodies).
fn write_sections(report: &Report, dir: &mut ResultsDir) -> std::io::Result<()> {
    use std::fmt::Write;
    for (k, c) in report.cases.iter().enumerate() {
        let Some(sub) = &c.subsurface else {
            continue;
        };
        let mut csv = String::from(
            "body,section,along,at_mm,position_mm,depth_mm,sxx_mpa,syy_mpa,szz_mpa,sxy_mpa,sxz_mpa,syz_mpa,von_mises_mpa,tresca_mpa,s1_mpa,s3_mpa\n",
        );
        let sections = sub
            .bodies
            .iter()
            .flat_map(|b| b.sections.iter().map(move |f| (b, f)));
        for (n, (body, field)) in sections.enumerate() {
            let along = match field.section.axis {
                contopt::SectionAxis::X => "x",
                contopt::SectionAxis::Y => "y",
            };
            let mut points = Vec::with_capacity(field.tensors.len());
            for (kd, depth) in field.depths.iter().enumerate() {
                for (i, position) in field.positions.iter().enumerate() {
                    let t = field.at(kd, i);
                    let [s1, _, s3] = t.principal();
                    let _ = writeln!(
                        csv,
                        "{},{},{along},{},{position},{depth},{},{},{},{},{},{},{},{},{s1},{s3}",
                        csv_field(&body.body),
                        n + 1,
                        field.section.at,
                        t.xx,
                        t.yy,
                        t.zz,
                        t.xy,
                        t.xz,
                        t.yz,
                        t.von_mises(),
                        t.tresca()
                    );
                    points.push((*position, *depth, t.von_mises()));
                }
            }
            let across = if along == "x" { "y" } else { "x" };
            let case = if c.label == report.scene {
                String::new()
            } else {
                format!(", {}", c.label)
            };
            let (top, depth) =
                points
                    .iter()
                    .fold((0.0, 0.0), |m, p| if p.2 > m.0 { (p.2, p.1) } else { m });
            let title = format!(
                "von Mises below the {}{case}, along {along} at {across} = {:.3} mm\n\
                 largest {top:.0} MPa at depth {depth:.3} mm",
                body.body, field.section.at
            );
            let svg = contopt::plot::section_map(
                &title,
                &format!("{along} [mm] along the section"),
                "MPa",
                &points,
            );
            dir.write(&format!("mises_{}_{}.svg", k + 1, n + 1), svg.as_bytes())?;
        }
        if sub.bodies.iter().any(|b| !b.sections.is_empty()) {
            dir.write(&format!("subsurface_{}.csv", k + 1), csv.as_bytes())?;
        }
    }
    Ok(())
}
