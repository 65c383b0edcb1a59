//! What the `contopt` tests share: the command, scratch folders, bundled scenes with changes,
//! runs with `--json`, and the checks every output must pass (the committed JSON Schema of
//! result.json, no NaN or infinity).
//!
//! Each test binary uses part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::Output;

use assert_cmd::Command;
use serde_json::Value;

/// The `contopt` binary of this build.
pub fn contopt() -> Command {
    Command::cargo_bin("contopt").unwrap()
}

/// A fresh scratch folder `name` of the test binary `binary`, in Cargo's folder for the
/// integration tests' files (below the target folder): a rerun replaces it, so runs do not pile
/// up in the system's temporary folder.
pub fn scratch(binary: &str, name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("contopt-{binary}-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The text of the bundled scene `scene`, as `contopt show` prints it.
pub fn bundled_text(scene: &str) -> &'static str {
    contopt_scene::BUNDLED
        .iter()
        .find(|b| b.name == scene)
        .unwrap_or_else(|| panic!("no bundled scene {scene}"))
        .text
}

/// A bundled scene's text with `changes` made, each `(from, to)` replacing its first
/// occurrence (each must apply).
pub fn bundled(scene: &str, changes: &[(&str, &str)]) -> String {
    let mut text = bundled_text(scene).to_string();
    for (from, to) in changes {
        assert!(text.contains(from), "{scene} has no {from:?}");
        text = text.replacen(from, to, 1);
    }
    text
}

/// `text` without its `[sweep]` (the first case alone, the scene's name its label).
pub fn without_sweep(text: &str) -> &str {
    &text[..text.find("[sweep]").expect("a [sweep]")]
}

/// Writes the meshes of the bundled scene `scene` where a copy of it in `dir` reads them
/// (`../meshes/…` from `dir`), as a user copies a scene with its meshes.
pub fn write_meshes(dir: &Path, scene: &str) {
    let bundled = contopt_scene::BUNDLED
        .iter()
        .find(|b| b.name == scene)
        .unwrap();
    for (path, bytes) in bundled.meshes {
        // Written beside and renamed over: tests running at once share `../meshes`.
        let file = dir.join(path);
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        let unique = format!("{}.{:?}", std::process::id(), std::thread::current().id());
        let part = file.with_extension(format!("part-{}", unique.replace(['(', ')'], "")));
        std::fs::write(&part, bytes).unwrap();
        std::fs::rename(&part, &file).unwrap();
    }
}

/// Writes `text` as `<dir>/<name>.toml`.
pub fn write_scene(dir: &Path, name: &str, text: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    path
}

/// The stderr of a run, as text.
pub fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The stdout of a run, as text.
pub fn stdout(output: &Output) -> String {
    String::from_utf8_lossy(&output.stdout).into_owned()
}

/// `contopt run <args…> --json --out <out>`: the output, unchecked.
pub fn run_json_output(args: &[&std::ffi::OsStr], out: &Path) -> Output {
    contopt()
        .arg("run")
        .args(args)
        .args(["--json", "--out"])
        .arg(out)
        .output()
        .unwrap()
}

/// The report a `--json` run printed: one JSON document on stdout and nothing else, which
/// conforms to the committed schema.
pub fn report(output: &Output) -> Value {
    let report: Value = serde_json::from_slice(&output.stdout).unwrap_or_else(|e| {
        panic!("{e}: {}\n{}", stdout(output), stderr(output));
    });
    assert_conforms(&report, "the --json report");
    report
}

/// Runs `args` with `--json` into `out`, which must succeed (exit 0): the report on stdout,
/// equal to the `result.json` written, both conforming to the schema.
pub fn run_json(args: &[&std::ffi::OsStr], out: &Path) -> Value {
    let output = run_json_output(args, out);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let printed = report(&output);
    let name = printed["scene"].as_str().unwrap();
    let written = read_json(&out.join(name).join("result.json"));
    assert_eq!(printed, written, "--json and result.json differ");
    printed
}

/// Runs the bundled scene `scene` (by `--bundled`, whatever lies in the working folder) into
/// a scratch folder of `binary`: its report and the folder of its results.
pub fn run_bundled(binary: &str, scene: &str) -> (Value, PathBuf) {
    let out = scratch(binary, scene);
    let report = run_json(&["--bundled".as_ref(), scene.as_ref()], &out);
    (report, out.join(scene))
}

/// Runs the scene file `path` with `--json`, its results beside it: the report and the
/// folder of its results.
pub fn run_file(path: &Path) -> (Value, PathBuf) {
    let out = path.parent().unwrap().join("results");
    let report = run_json(&[path.as_os_str()], &out);
    let folder = out.join(report["scene"].as_str().unwrap());
    (report, folder)
}

/// A JSON file.
pub fn read_json(path: &Path) -> Value {
    let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The committed schema of result.json, `crates/results/result.schema.json`.
pub fn committed_schema() -> Value {
    read_json(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../results/result.schema.json"))
}

/// `document` conforms to the committed schema (`what` names it in the message).
pub fn assert_conforms(document: &Value, what: &str) {
    let found = contopt_results::violations(&committed_schema(), document);
    assert!(found.is_empty(), "{what} breaks the schema: {found:#?}");
}

/// The case labelled `label`.
pub fn case<'r>(report: &'r Value, label: &str) -> &'r Value {
    report["cases"]
        .as_array()
        .unwrap()
        .iter()
        .find(|c| c["label"] == label)
        .unwrap_or_else(|| panic!("no case {label:?}"))
}

/// A number of a report.
pub fn number(value: &Value) -> f64 {
    value
        .as_f64()
        .unwrap_or_else(|| panic!("{value} is not a number"))
}

/// A failed command: exit `code`, nothing on stdout, and each of `needles` on stderr; the
/// stderr.
pub fn fails_with(output: &Output, code: i32, needles: &[&str]) -> String {
    let err = stderr(output);
    assert_eq!(output.status.code(), Some(code), "{err}");
    assert!(output.stdout.is_empty(), "stdout: {}", stdout(output));
    for needle in needles {
        assert!(err.contains(needle), "`{needle}` not in: {err}");
    }
    err
}

/// Every file below `dir`.
pub fn walk(dir: &Path) -> Vec<PathBuf> {
    let mut all = vec![];
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            all.extend(walk(&path));
        } else {
            all.push(path);
        }
    }
    all
}
