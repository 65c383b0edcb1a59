//! `contopt`: runs scene files (TOML or JSON) and writes their results.
//!
//! - `contopt run <scene> [--json] [--quiet] [--out DIR]`: solves every case, with a progress
//!   bar on stderr when it is a terminal, and writes the files of
//!   [`contopt_report::write()`] to `DIR/<name>/` (`result.json`, `interface.csv`, the charts as
//!   SVG and PNG, a finite-element case's fields for ParaView as `.vtu`), then prints a table (or, with `--json`, the report as one JSON document on
//!   stdout). Files go only into `DIR/<name>/`, never through a symbolic link.
//! - `contopt check <scene>`: reads and checks the scene exactly as `run` does, without
//!   solving;
//! - `contopt list`: the bundled scenes; `contopt show <name>`: one as a template to copy;
//! - `contopt schema`: the JSON Schema of `result.json`.
//!
//! A scene is a file, or a bundled scene's name. A name that is both (a file or folder of that
//! name here) is refused, saying how to choose. Exit status: see [`EXIT_CODES`].

mod files;
mod progress;
mod source;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use contopt_results::{CaseReport, Report, SCHEMA_VERSION};
use contopt_scene::{Scene, BUNDLED};
use files::ResultsDir;
use progress::Progress;

/// A bad scene: unreadable, unknown or missing keys, values out of range, too large.
const EXIT_BAD_INPUT: u8 = 1;
/// A usage error: an unknown option or a missing argument (clap's code).
const EXIT_USAGE: u8 = 2;
/// Some case did not converge, or its answer lies outside the model's limits (its report
/// says why and how far it got, or what the model needs).
const EXIT_NOT_SOLVED: u8 = 3;
/// The results could not be written.
const EXIT_WRITE: u8 = 4;

/// The exit codes, as `--help` shows them.
const EXIT_CODES: &str = "Exit status: 0 success; 1 bad scene (unreadable, invalid or too large); \
2 usage error; 3 some case did not converge or left the model's limits (a contact that reaches \
the edge of its zone); 4 the results could not be written.";

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
        /// The scene is the bundled one of that name, whatever lies in this folder.
        #[arg(long)]
        bundled: bool,
        /// Print the report as JSON on stdout (and nothing else there).
        #[arg(long)]
        json: bool,
        /// Print nothing but errors: no progress bar, no warnings (they stay in
        /// result.json), no table; the files are written as usual (and --json still prints
        /// the report).
        #[arg(long, short)]
        quiet: bool,
        /// Folder for the results (a subfolder per scene).
        #[arg(long, default_value = "results")]
        out: PathBuf,
    },
    /// Read and check a scene as `run` would, without solving.
    Check {
        /// Scene file or bundled name.
        scene: String,
        /// The scene is the bundled one of that name.
        #[arg(long)]
        bundled: bool,
    },
    /// List the bundled scenes.
    List,
    /// Print a bundled scene, a template to copy and change.
    Show {
        /// The bundled scene's name.
        name: String,
    },
    /// Print the JSON Schema of result.json and of `run --json`.
    Schema,
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
            for b in BUNDLED {
                let description = Scene::bundled(b.name)
                    .map(|s| s.description)
                    .unwrap_or_default();
                text += &format!("{:<20} {description}\n", b.name);
            }
            emit(&text);
            ExitCode::SUCCESS
        }
        Command::Show { name } => match contopt_scene::BUNDLED.iter().find(|b| b.name == name) {
            Some(b) => {
                emit(b.text);
                ExitCode::SUCCESS
            }
            None => fail(&source::not_bundled(&name)),
        },
        Command::Schema => {
            let schema = serde_json::to_string_pretty(&contopt_results::schema());
            emit(&(schema.unwrap_or_default() + "\n"));
            ExitCode::SUCCESS
        }
        Command::Check { scene, bundled } => match source::load(&scene, bundled, "check") {
            Ok(s) => {
                let cases = s.cases().len();
                emit(&format!("{}: ok ({cases} case(s))\n", s.file.display()));
                ExitCode::SUCCESS
            }
            Err(e) => fail(&e),
        },
        Command::Run {
            scene,
            bundled,
            json,
            quiet,
            out,
        } => match source::load(&scene, bundled, "run") {
            Ok(s) => run(&s, Print { json, quiet }, &out),
            Err(e) => fail(&e),
        },
    }
}

/// Prints an error and gives the bad-input status.
fn fail(e: &dyn std::fmt::Display) -> ExitCode {
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

/// What a run prints.
#[derive(Clone, Copy)]
struct Print {
    /// The report as JSON on stdout instead of the table.
    json: bool,
    /// Nothing but errors (and the JSON when asked for).
    quiet: bool,
}

/// Runs every case, writes the results and prints them; the exit code.
fn run(scene: &Scene, print: Print, out: &Path) -> ExitCode {
    if let Err(e) = files::check_out(out) {
        eprintln!("error: {e}");
        return ExitCode::from(EXIT_WRITE);
    }
    let cases = match solve(scene, print.quiet) {
        Ok(cases) => cases,
        Err(e) => return fail(&e),
    };
    let report = Report {
        schema_version: SCHEMA_VERSION,
        scene: scene.name.clone(),
        description: scene.description.clone(),
        cases,
    };
    if !print.quiet {
        warn(&report);
    }
    let written = ResultsDir::create(out, &scene.name).and_then(|mut dir| {
        contopt_report::write(&report, &mut dir)?;
        dir.finish()
    });
    if print.json {
        emit(&(serde_json::to_string_pretty(&report).unwrap_or_default() + "\n"));
    } else if !print.quiet {
        emit(&contopt_report::table(&report));
    }
    match written {
        Ok(dir) if !print.json && !print.quiet => emit(&written_files(&dir)),
        Ok(_) => {}
        Err(e) => {
            eprintln!(
                "error: could not write the results to {}: {e}",
                out.join(&scene.name).display()
            );
            return ExitCode::from(EXIT_WRITE);
        }
    }
    let solved = report.cases.iter().all(CaseReport::is_solved);
    ExitCode::from(if solved { 0 } else { EXIT_NOT_SOLVED })
}

/// Each case's warnings, and why a case is not solved, on stderr.
fn warn(report: &Report) {
    for c in &report.cases {
        for w in &c.warnings {
            eprintln!("warning: {}: {w}", c.label);
        }
        if let Some(limit) = &c.limit {
            eprintln!("error: {}: {}", c.label, limit.message);
        } else if !c.is_solved() {
            eprintln!("error: {}: did not converge: {}", c.label, c.termination);
        }
    }
}

/// Runs the cases in turn under a progress bar, cleared when they end (or one fails); cases
/// that share their bodies share one build of them ([`Scene::run_observed`]).
fn solve(scene: &Scene, quiet: bool) -> Result<Vec<CaseReport>, contopt_scene::SceneError> {
    let progress = Progress::new(quiet);
    let mut run = scene.run_observed(&progress);
    progress.cases(run.len());
    let mut reports = Vec::with_capacity(run.len());
    for k in 0..run.len() {
        progress.start(&run.cases()[k].label);
        match run.next() {
            Some(report) => reports.push(report?),
            None => break,
        }
        progress.done();
    }
    Ok(reports)
}

/// Files listed by name up to this many; past it, counted.
const LISTED_FILES: usize = 12;

/// The line that says where the results went: every file by name, or past
/// [`LISTED_FILES`] every kind of file, a case's and a section's number written `*`
/// (`fields_*.vtu`), or the first few when the kinds are too many too.
fn written_files(dir: &ResultsDir) -> String {
    let names = dir.written();
    if names.len() <= LISTED_FILES {
        return format!(
            "results: {}/{{{}}}\n",
            dir.path().display(),
            names.join(",")
        );
    }
    let mut kinds: Vec<String> = vec![];
    for kind in names.iter().map(|n| numbered(n)) {
        if !kinds.contains(&kind) {
            kinds.push(kind);
        }
    }
    let shown = if kinds.len() <= LISTED_FILES {
        kinds.join(", ")
    } else {
        names[..LISTED_FILES / 2].join(", ") + ", …"
    };
    format!(
        "results: {}/ ({} files: {shown})\n",
        dir.path().display(),
        names.len()
    )
}

/// A file's kind: its name with each number that follows an underscore (a case's, a
/// section's) written `*`.
fn numbered(name: &str) -> String {
    let mut kind = String::with_capacity(name.len());
    let mut chars = name.chars().peekable();
    while let Some(c) = chars.next() {
        kind.push(c);
        if c == '_' && chars.peek().is_some_and(char::is_ascii_digit) {
            while chars.peek().is_some_and(char::is_ascii_digit) {
                chars.next();
            }
            kind.push('*');
        }
    }
    kind
}

#[cfg(test)]
mod tests {
    use super::numbered;

    /// A case's and a section's number become `*`; other digits stay.
    #[test]
    fn kinds_of_files() {
        assert_eq!(numbered("fields_12.vtu"), "fields_*.vtu");
        assert_eq!(numbered("mises_3_2.png"), "mises_*_*.png");
        assert_eq!(numbered("subsurface_1.csv"), "subsurface_*.csv");
        assert_eq!(numbered("p2.svg"), "p2.svg");
        assert_eq!(numbered("result.json"), "result.json");
    }
}
