//! `contopt`: runs scene files (TOML or JSON) and writes their results.
//!
//! - `contopt run <scene> [--json] [--quiet] [--out DIR]`: solves every case, with a progress
//!   bar on stderr when it is a terminal, and writes the files of
//!   [`contopt_report::write()`] to `DIR/<name>/` (`result.json`, `interface.csv`, the charts as
//!   SVG and PNG), then prints a table (or, with `--json`, the report as one JSON document on
//!   stdout). Files go only into `DIR/<name>/`, never through a symbolic link.
//! - `contopt check <scene>`: reads and checks the scene without solving;
//! - `contopt list`: the bundled scenes, which `run` and `check` also take by name.
//!
//! Exit status: see [`EXIT_CODES`].

mod files;
mod progress;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use contopt_scene::{CaseReport, Format, Report, Scene, SceneError, BUNDLED};
use files::ResultsDir;
use progress::Progress;

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
        /// Print nothing but errors: no progress bar, no warnings (they stay in
        /// result.json), no table; the files are written as usual (and --json still prints
        /// the report).
        #[arg(long, short)]
        quiet: bool,
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
        Command::Run {
            scene,
            json,
            quiet,
            out,
        } => match load(&scene).and_then(|s| run(&s, Print { json, quiet }, &out)) {
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

/// What a run prints.
#[derive(Clone, Copy)]
struct Print {
    /// The report as JSON on stdout instead of the table.
    json: bool,
    /// Nothing but errors (and the JSON when asked for).
    quiet: bool,
}

/// Runs every case, writes the results and prints them; the exit code.
fn run(scene: &Scene, print: Print, out: &Path) -> Result<u8, SceneError> {
    let report = Report {
        scene: scene.spec.name.clone(),
        cases: solve(scene, print.quiet)?,
    };
    if !print.quiet {
        for c in &report.cases {
            for w in &c.warnings {
                eprintln!("warning: {}: {w}", c.label);
            }
        }
    }
    let written = ResultsDir::create(out, &scene.spec.name).and_then(|mut dir| {
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
                out.join(&scene.spec.name).display()
            );
            return Ok(EXIT_WRITE);
        }
    }
    let converged = report.cases.iter().all(|c| c.converged);
    Ok(if converged { 0 } else { EXIT_NOT_CONVERGED })
}

/// Runs the cases in turn under a progress bar, cleared when they end (or one fails); cases
/// that share their bodies share one build of them ([`Scene::run_observed`]).
fn solve(scene: &Scene, quiet: bool) -> Result<Vec<CaseReport>, SceneError> {
    let progress = Progress::new(quiet);
    let mut run = scene.run_observed(&progress)?;
    progress.cases(run.len());
    let mut reports = Vec::with_capacity(run.len());
    for k in 0..run.len() {
        progress.start(&run.cases()[k]);
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

/// The line that says where the results went.
fn written_files(dir: &ResultsDir) -> String {
    let names = dir.written();
    if names.len() <= LISTED_FILES {
        format!(
            "results: {}/{{{}}}\n",
            dir.path().display(),
            names.join(",")
        )
    } else {
        let shown = names[..LISTED_FILES / 2].join(", ");
        format!(
            "results: {}/ ({} files: {shown}, …)\n",
            dir.path().display(),
            names.len()
        )
    }
}
