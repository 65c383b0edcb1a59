//! `contopt`: runs scene files (TOML or JSON) and writes their results.
//!
//! - `contopt run <scene> [--json] [--quiet] [--out DIR]`: solves every case, with a progress
//!   bar on stderr when it is a terminal, and writes the files of
//!   [`contopt_report::write()`] to `DIR/<name>/` (`result.json`, `interface.csv`, the charts as
//!   SVG and PNG, a finite-element case's fields for ParaView as `.vtu`), then prints a table (or, with `--json`, the report as one JSON document on
//!   stdout). Files go only into `DIR/<name>/`, never through a symbolic link; a place they
//!   could not go to is refused before anything is solved.
//! - `contopt run <scene> --shard K/N`: runs shard K (from 0) of N of the scene's cases, one
//!   task of a job array, into `DIR/<name>/shard_K_of_N/` (`partial.json` and the files of its
//!   cases); `contopt merge DIR/<name>` joins the shards into exactly the files one run writes
//!   ([`contopt_results::shard`], the book's "Many cases").
//! - `contopt run <scene> --jobs N`: N threads (default: one per core this process may use)
//!   for N cases at once, and inside a case for its independent contact solves (an envelope's
//!   cases under one crown), within the scene's memory limit, every file the same as on one
//!   thread ([`Scene::run_parallel`], `contopt_contact::parallel`).
//! - `contopt check <scene>`: reads and checks the scene exactly as `run` does, without
//!   solving;
//! - `contopt list`: the bundled scenes; `contopt show <name>`: one as a template to copy;
//! - `contopt schema`: the JSON Schema of `result.json`.
//!
//! A scene is a file, or a bundled scene's name. A name that is both (a file or folder of that
//! name here) is refused, saying how to choose. Exit status: see [`EXIT_CODES`].
//!
//! The command is this library's [`main_with`] over a [`Registry`] of the kinds a scene may
//! name; the `contopt` binary runs it with [`Registry::standard`]. A binary of one's own that
//! registers its own kinds keeps every command:
//!
//! ```no_run
//! use contopt_scene::{Registry, WinklerBed};
//!
//! fn main() -> std::process::ExitCode {
//!     contopt_cli::main_with(Registry::standard().with_body::<WinklerBed>("springs"))
//! }
//! ```

mod files;
mod merge;
mod progress;
mod source;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use contopt_results::shard::{Partial, Shard};
use contopt_results::{CaseReport, Report, SCHEMA_VERSION};
use contopt_scene::{Registry, Scene, BUNDLED};
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
pub const EXIT_CODES: &str =
    "Exit status: 0 success; 1 bad scene (unreadable, invalid or too large); \
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
        /// Run shard K (counted from 0) of N of the cases, one task of a job array
        /// (`--shard $SLURM_ARRAY_TASK_ID/$SLURM_ARRAY_TASK_COUNT`), into
        /// `<out>/<name>/shard_K_of_N/`; `contopt merge` joins the shards.
        #[arg(long, value_name = "K/N", value_parser = parse_shard)]
        shard: Option<Shard>,
        /// Threads (default: one per core): this many cases at once, and a case's independent
        /// contacts (an envelope's loads under one crown) at once, within the scene's memory
        /// limit; the results are the same for any N.
        #[arg(long, short, value_name = "N", value_parser = parse_jobs)]
        jobs: Option<usize>,
    },
    /// Join the shards of a job array (`run --shard K/N`) into the results one run writes.
    Merge {
        /// The shards' folders (`results/<name>/shard_K_of_N`), or the folder that holds them
        /// (`results/<name>`).
        #[arg(required = true)]
        shards: Vec<PathBuf>,
        /// Print the report as JSON on stdout (and nothing else there).
        #[arg(long)]
        json: bool,
        /// Print nothing but errors.
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

/// The `contopt` command with the library's kinds ([`Registry::standard`]).
pub fn main() -> ExitCode {
    main_with(Registry::standard())
}

/// The `contopt` command, its arguments from the process's, its scenes read with the kinds of
/// `registry`.
pub fn main_with(registry: Registry) -> ExitCode {
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
                let description = registry
                    .bundled(b.name)
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
        Command::Check { scene, bundled } => {
            match source::load(&registry, &scene, bundled, "check") {
                Ok(s) => {
                    let cases = s.cases().len();
                    emit(&format!("{}: ok ({cases} case(s))\n", s.file.display()));
                    ExitCode::SUCCESS
                }
                Err(e) => fail(&e),
            }
        }
        Command::Run {
            scene,
            bundled,
            json,
            quiet,
            out,
            shard,
            jobs,
        } => match source::load(&registry, &scene, bundled, "run") {
            Ok(s) => {
                let jobs = jobs.unwrap_or_else(all_cores);
                run(&s, Print { json, quiet }, &out, shard, jobs)
            }
            Err(e) => fail(&e),
        },
        Command::Merge {
            shards,
            json,
            quiet,
            out,
        } => merge::merge(&shards, Print { json, quiet }, &out),
    }
}

/// `--jobs N`: a whole number, at least 1.
fn parse_jobs(text: &str) -> Result<usize, String> {
    match text.parse::<usize>() {
        Ok(n) if n >= 1 => Ok(n),
        _ => Err(format!(
            "{text:?} is not a number of threads: give a whole number ≥ 1 (the default is one \
             per core)"
        )),
    }
}

/// The cores this process may use (one when the system does not say).
fn all_cores() -> usize {
    std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
}

/// `--shard K/N`, checked.
fn parse_shard(text: &str) -> Result<Shard, String> {
    Shard::parse(text).map_err(|e| match e {
        contopt_results::shard::ShardError::Spec { reason, .. } => reason,
        other => other.to_string(),
    })
}

/// Prints an error and gives the bad-input status.
fn fail(e: &dyn std::fmt::Display) -> ExitCode {
    eprintln!("error: {e}");
    ExitCode::from(EXIT_BAD_INPUT)
}

/// Prints `text` on stdout; a reader that has gone (`contopt run … | head`) ends the output
/// quietly instead of a panic.
fn emit(text: &str) {
    emit_with(&mut |out| out.write_all(text.as_bytes()));
}

/// Prints what `write` writes, streamed through a buffer, as [`emit`] does.
fn emit_with(write: &mut dyn FnMut(&mut dyn Write) -> std::io::Result<()>) {
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    if let Err(e) = write(&mut out).and_then(|()| out.flush()) {
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

/// Runs every case (or a shard's), writes the results and prints them; the exit code.
fn run(scene: &Scene, print: Print, out: &Path, shard: Option<Shard>, jobs: usize) -> ExitCode {
    let shard_folder = shard.map(|s| s.folder());
    let folders: Vec<&str> = std::iter::once(scene.name.as_str())
        .chain(shard_folder.as_deref())
        .collect();
    if let Err(e) = files::check_place(out, &folders) {
        eprintln!("error: {e}");
        return ExitCode::from(EXIT_WRITE);
    }
    let total = scene.cases().len();
    let range = shard.map_or(0..total, |s| s.cases(total));
    let cases = match solve(scene, range.clone(), print.quiet, jobs) {
        Ok(cases) => cases,
        Err(e) => return fail(&e),
    };
    let report = Report {
        schema_version: SCHEMA_VERSION,
        scene: scene.name.clone(),
        description: scene.description.clone(),
        cases,
    };
    let written = match shard {
        None => write_folder(&report, out),
        Some(shard) => {
            let partial = Partial {
                contopt_version: env!("CARGO_PKG_VERSION").to_string(),
                shard,
                scene_cases: total,
                fingerprint: scene.fingerprint(),
                report,
            };
            let written = write_shard(&partial, range.start + 1, out);
            return finish(&partial.report, print, written, &out.join(&scene.name));
        }
    };
    finish(&report, print, written, &out.join(&scene.name))
}

/// Writes the files of `contopt run` for `report` into `out/<scene>/` (`result.json`,
/// `interface.csv`, the charts, each case's fields), never through a symbolic link, and
/// removes the files an earlier run wrote there that this one did not: the folder. What
/// `run` writes, for the Python package's `Report.write`.
pub fn write_results(report: &Report, out: &Path) -> std::io::Result<PathBuf> {
    write_folder(report, out).map(|dir| dir.path().to_path_buf())
}

/// [`write_results`], the folder with the names of the files written.
fn write_folder(report: &Report, out: &Path) -> std::io::Result<ResultsDir> {
    files::check_out(out)?;
    let mut dir = ResultsDir::create(out, &report.scene)?;
    contopt_report::write(report, &mut dir)?;
    dir.finish()
}

/// Writes a shard's `partial.json` and the files of its cases, numbered from `first`, to
/// `<out>/<scene>/shard_K_of_N/`.
fn write_shard(partial: &Partial, first: usize, out: &Path) -> std::io::Result<ResultsDir> {
    let scene = ResultsDir::create(out, &partial.report.scene)?;
    let mut dir = ResultsDir::create(scene.path(), &partial.shard.folder())?;
    dir.write_with(merge::PARTIAL, &mut |w| {
        serde_json::to_writer_pretty(w, partial).map_err(std::io::Error::other)
    })?;
    contopt_report::write_cases(&partial.report, first, &mut dir)?;
    dir.finish()
}

/// Prints what a run or a merge gave, and says where its files went (into `folder`, or why
/// they could not be written); the exit code.
fn finish(
    report: &Report,
    print: Print,
    written: std::io::Result<ResultsDir>,
    folder: &Path,
) -> ExitCode {
    if !print.quiet {
        warn(report);
    }
    if print.json {
        emit_with(&mut |out| {
            serde_json::to_writer_pretty(&mut *out, report).map_err(std::io::Error::other)?;
            out.write_all(b"\n")
        });
    } else if !print.quiet {
        emit(&contopt_report::table(report));
    }
    match written {
        Ok(dir) if !print.json && !print.quiet => emit(&written_files(&dir)),
        Ok(_) => {}
        Err(e) => {
            eprintln!(
                "error: could not write the results to {}: {e}",
                folder.display()
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

/// Runs the cases `range` under a progress bar, cleared when they end (or one fails); cases
/// that share their bodies share one build of them. On one thread in turn, the bar showing
/// each case's methods ([`Scene::run_cases`]), every contact solved in turn; on several, the
/// cases done ([`Scene::run_parallel`], the same threads solving a case's independent
/// contacts), and the first error in the scene's order.
fn solve(
    scene: &Scene,
    range: std::ops::Range<usize>,
    quiet: bool,
    jobs: usize,
) -> Result<Vec<CaseReport>, contopt_scene::SceneError> {
    let progress = Progress::new(quiet);
    if jobs > 1 {
        progress.cases(range.len());
        progress.start(&format!("{jobs} threads"));
        let counter = progress.counter();
        return scene
            .run_parallel(range, jobs, &counter)?
            .results
            .into_iter()
            .collect();
    }
    // One thread for the contact solves inside a case too: they run on the global pool. It
    // is built here first; were it built before, its threads would change no result.
    let _ = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build_global();
    let mut run = scene.run_cases(range, &progress);
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
