//! What the `contopt` command says about itself, each a defect the issue found: a name that is
//! both a bundled scene and something here, a name that is neither, an `--out` that is a file,
//! a contact outside the model, `check` refusing what `run` refuses in the same words, `show`
//! giving a template that `check` accepts.

use crate::common;

use std::path::Path;

use common::{bundled, bundled_text, contopt, fails_with, read_json, scratch, stderr, stdout};

/// This binary's scratch folders.
const BIN: &str = "commands";

/// `contopt <args>` in the folder `here`.
fn in_folder(here: &Path, args: &[&str]) -> std::process::Output {
    contopt().current_dir(here).args(args).output().unwrap()
}

/// A folder named `hertz` here used to hide the bundled scene silently (`run hertz` ran the
/// bundled one), and a file named `hertz` to win over it silently: both are refused, with the
/// two ways to say which (in the words of the command given), and nothing is written;
/// `--bundled hertz` and `./hertz` each run theirs.
#[test]
fn a_name_that_is_bundled_and_here_is_refused() {
    let here = scratch(BIN, "both");
    std::fs::create_dir(here.join("hertz")).unwrap();
    for command in ["run", "check"] {
        let output = in_folder(&here, &[command, "hertz"]);
        fails_with(
            &output,
            1,
            &[
                "`hertz` is both a bundled scene and a folder here",
                &format!("`contopt {command} --bundled hertz`"),
                "`./hertz`",
            ],
        );
    }
    assert!(!here.join("results").exists());
    let output = in_folder(&here, &["run", "--bundled", "hertz", "--quiet"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let report = read_json(&here.join("results/hertz/result.json"));
    assert_eq!(
        report["description"],
        contopt_scene::Scene::bundled("hertz").unwrap().description
    );

    // A file named `hertz`, a scene of its own (the Winkler bed, renamed).
    std::fs::remove_dir(here.join("hertz")).unwrap();
    let mine = bundled(
        "winkler-bed",
        &[("name = \"winkler-bed\"", "name = \"mine\"")],
    );
    std::fs::write(here.join("hertz"), mine).unwrap();
    let output = in_folder(&here, &["run", "hertz"]);
    fails_with(
        &output,
        1,
        &[
            "a bundled scene and a file here",
            "--bundled hertz",
            "./hertz",
        ],
    );
    assert!(!here.join("results/mine").exists());
    let output = in_folder(&here, &["run", "./hertz", "--quiet"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(here.join("results/mine/result.json").exists());
}

/// A name that is neither a file here nor a bundled scene says where the bundled ones are
/// listed; `--bundled` with a name that is not one lists them.
#[test]
fn a_name_that_is_nothing_says_contopt_list() {
    let here = scratch(BIN, "neither");
    for command in ["run", "check"] {
        let output = in_folder(&here, &[command, "no-such"]);
        fails_with(&output, 1, &["no-such", "`contopt list`"]);
    }
    let output = in_folder(&here, &["run", "--bundled", "no-such"]);
    let err = fails_with(&output, 1, &["no bundled scene `no-such`"]);
    for b in contopt_scene::BUNDLED {
        assert!(err.contains(b.name), "{err}");
    }
}

/// `--out` naming a regular file is refused before anything is solved, saying so (it used to
/// solve every case and then say `File exists`): exit 4, no report printed even with
/// `--json`, the file untouched.
#[test]
fn out_naming_a_file_is_refused_before_solving() {
    let here = scratch(BIN, "out-file");
    let taken = here.join("taken");
    std::fs::write(&taken, "mine").unwrap();
    let output = contopt()
        .args(["run", "--bundled", "hertz", "--json", "--out"])
        .arg(&taken)
        .output()
        .unwrap();
    let err = fails_with(&output, 4, &["--out", "taken is a file, not a folder"]);
    assert!(!err.contains("File exists"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(std::fs::read_to_string(&taken).unwrap(), "mine");
}

/// An output place the results could not go to is refused before anything is solved (each
/// used to solve every case first, then be refused): a scene folder `<out>/hertz` that is a
/// symbolic link, reached directly or by a path through `..`; a shard's folder that is one;
/// an `--out` that is a link to nothing (which said `File exists`). Exit 4, one line, and no
/// report on stdout even with `--json` (a run that solved prints its report before it
/// writes); the link's target untouched.
#[cfg(unix)]
#[test]
fn a_linked_results_folder_is_refused_before_solving() {
    let here = scratch(BIN, "out-link");
    let elsewhere = here.join("elsewhere");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let out = here.join("out");
    std::fs::create_dir_all(out.join("sub")).unwrap();
    std::os::unix::fs::symlink(&elsewhere, out.join("hertz")).unwrap();
    let through_dots = out.join("sub").join("..");
    let shards = here.join("shards");
    std::fs::create_dir_all(shards.join("hertz")).unwrap();
    std::os::unix::fs::symlink(&elsewhere, shards.join("hertz").join("shard_0_of_2")).unwrap();
    let dangling = here.join("dangling");
    std::os::unix::fs::symlink(here.join("nowhere"), &dangling).unwrap();
    let runs: [(&Path, &[&str], &str); 4] = [
        (&out, &[], "hertz is a symbolic link"),
        (&through_dots, &[], "hertz is a symbolic link"),
        (
            &shards,
            &["--shard", "0/2"],
            "shard_0_of_2 is a symbolic link",
        ),
        (&dangling, &[], "--out"),
    ];
    for (place, extra, said) in runs {
        let output = contopt()
            .args(["run", "--bundled", "hertz", "--json", "--out"])
            .arg(place)
            .args(extra)
            .output()
            .unwrap();
        let err = fails_with(&output, 4, &[said, "symbolic link"]);
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    assert_eq!(std::fs::read_dir(&elsewhere).unwrap().count(), 0);
}

/// A rigid sphere (R = 50 mm, steel) at 20 kN on a half-space grid of 100 × 100 cells of
/// 0.025 mm: Hertz's contact (a = 1.51 mm) runs off the ±1.25 mm grid. It used to report a
/// p_max 59 % above Hertz's with exit 0; now the run exits 3 with the limit's message on
/// stderr and under the case's row, and result.json says `outside_model` with the limit.
#[test]
fn a_contact_off_its_grid_is_outside_the_model() {
    let here = scratch(BIN, "off-grid");
    let text = "name = \"sphere\"\n\n[contact]\n\
                zone = { kind = \"grid\", cells = [100, 100], cell_mm = [0.025, 0.025] }\n\
                gap = { kind = \"sphere\", radius_mm = 50.0 }\n\
                load = { force_n = 20000.0 }\n\n\
                [[body]]\nkind = \"half_space\"\nmaterial = { e_mpa = 2.0e5, nu = 0.3 }\n\n\
                [[body]]\nkind = \"rigid\"\n";
    std::fs::write(here.join("sphere.toml"), text).unwrap();
    let output = in_folder(&here, &["run", "sphere.toml"]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let report = read_json(&here.join("results/sphere/result.json"));
    let case = &report["cases"][0];
    assert_eq!(case["status"], "outside_model", "{}", case["status"]);
    assert_eq!(case["termination"]["kind"], "converged");
    let limit = &case["limit"];
    let message = limit["message"].as_str().unwrap();
    assert!(message.contains("zone's edge"), "{message}");
    assert_eq!(limit["extent_mm"].as_f64(), Some(1.25));
    let a = common::number(&case["hertz"]["half_width_mm"]);
    assert!(common::number(&limit["needed_mm"]) >= 1.25 * a, "{limit}");
    assert!(
        stderr(&output).contains(&format!("error: sphere: {message}")),
        "{}",
        stderr(&output)
    );
    let table = stdout(&output);
    assert!(
        table.contains(&format!("  outside the model: {message}")),
        "{table}"
    );
}

/// A body meshed in Gmsh whose contact group is drawn shorter than the contact (the block's
/// top to 0.2 mm under a contact 0.3 mm wide, the top going on beyond): `check` accepts it,
/// `run` exits 3 naming the group and where it ends, and result.json says `outside_model`;
/// a mesh that is not there is refused by `check` with the path looked for and the scene's
/// folder, and nothing is run.
#[test]
fn an_imported_contact_group_too_short_is_outside_the_model() {
    let here = scratch(BIN, "mesh-limit");
    common::write_meshes(&here, "cylinder-on-block");
    let short = bundled(
        "cylinder-on-block",
        &[("contact = \"block_face\"", "contact = \"block_short\"")],
    );
    std::fs::write(here.join("short.toml"), short).unwrap();
    let checked = in_folder(&here, &["check", "short.toml"]);
    assert_eq!(checked.status.code(), Some(0), "{}", stderr(&checked));
    let output = in_folder(&here, &["run", "short.toml"]);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let report = read_json(&here.join("results/cylinder-on-block/result.json"));
    let case = &report["cases"][0];
    assert_eq!(case["status"], "outside_model", "{}", case["status"]);
    let message = case["limit"]["message"].as_str().unwrap();
    assert!(
        message.contains("\"block_short\"") && message.contains("goes on"),
        "{message}"
    );
    assert!(stderr(&output).contains(message), "{}", stderr(&output));
    let missing = bundled(
        "cylinder-on-block",
        &[("../meshes/cylinder-on-block-b8.msh", "block.msh")],
    );
    std::fs::write(here.join("missing.toml"), missing).unwrap();
    let output = in_folder(&here, &["check", "missing.toml"]);
    fails_with(
        &output,
        1,
        &[
            "missing.toml:",
            "body[0].mesh",
            "block.msh",
            "scene's folder",
        ],
    );
}

/// What `run` refuses, `check` refuses first, in the same words, and in the scene's words
/// rather than a Rust enum's: a given-load method where nothing floats (a punch pressed down
/// by a displacement), an envelope split without an `[envelope]`.
#[test]
fn check_refuses_what_run_refuses() {
    let here = scratch(BIN, "parity");
    let scenes = [
        (
            "given-load",
            bundled(
                "paper-table2",
                &[("\"given_displacement\"", "\"given_load\"")],
            ),
            "needs a given load on a floating body",
        ),
        (
            "split-alone",
            bundled(
                "roller-study",
                &[(
                    "\"load_split\", controller",
                    "\"envelope_split\", controller",
                )],
            ),
            "serves an [envelope] of load cases",
        ),
    ];
    for (name, text, words) in scenes {
        let file = format!("{name}.toml");
        std::fs::write(here.join(&file), text).unwrap();
        let checked = in_folder(&here, &["check", &file]);
        let checked = fails_with(&checked, 1, &[&file, "optimisation.method", words]);
        let ran = in_folder(&here, &["run", &file]);
        let ran = fails_with(&ran, 1, &[]);
        assert_eq!(checked, ran, "{name}");
        for rust in ["GivenLoad", "EnvelopeSplit", "LoadSplit", "GapIteration"] {
            assert!(!checked.contains(rust), "{rust} in {checked}");
        }
        assert!(!here.join("results").exists(), "{name}: run wrote results");
    }
}

/// `contopt show <name>` prints the bundled text (the file in `scenes/`), which `check`
/// accepts as a file of its own; a name that is not bundled fails, naming the bundled scenes.
#[test]
fn show_prints_a_template_that_check_accepts() {
    let here = scratch(BIN, "show");
    for b in contopt_scene::BUNDLED {
        let output = contopt().args(["show", b.name]).output().unwrap();
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        let shown = stdout(&output);
        assert_eq!(shown, bundled_text(b.name));
        let file =
            Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../../scenes/{}.toml", b.name));
        assert_eq!(shown, std::fs::read_to_string(file).unwrap(), "{}", b.name);
        let copy = format!("my-{}.toml", b.name);
        std::fs::write(here.join(&copy), &shown).unwrap();
        common::write_meshes(&here, b.name);
        let checked = in_folder(&here, &["check", &copy]);
        assert_eq!(checked.status.code(), Some(0), "{}", stderr(&checked));
        let cases = contopt_scene::Scene::bundled(b.name).unwrap().cases().len();
        assert_eq!(stdout(&checked), format!("{copy}: ok ({cases} case(s))\n"));
    }
    let output = contopt().args(["show", "nope"]).output().unwrap();
    let err = fails_with(&output, 1, &["no bundled scene `nope`", "contopt list"]);
    for b in contopt_scene::BUNDLED {
        assert!(err.contains(b.name), "{err}");
    }
}

/// `check` refuses a bad `[envelope]` as `run` does, in the same words (its load factors were
/// once checked only when the case ran).
#[test]
fn check_refuses_a_bad_envelope_as_run_does() {
    let here = scratch(BIN, "envelope-parity");
    let text = bundled(
        "roller-envelope",
        &[
            ("cells = [200, 105]", "cells = [20, 11]"),
            (
                "load_factors = [0.5, 1.0, 1.5]",
                "load_factors = [1.0, -0.5]",
            ),
        ],
    );
    std::fs::write(here.join("bad.toml"), text).unwrap();
    let needles = ["bad.toml:", "envelope.load_factors[1]", "-0.5"];
    let ran = fails_with(&in_folder(&here, &["run", "bad.toml"]), 1, &needles);
    let checked = fails_with(&in_folder(&here, &["check", "bad.toml"]), 1, &needles);
    assert_eq!(checked, ran);
}

/// A given load where nothing floats is refused naming the value the scene wrote
/// (`given_load`), not the library's method id (`gap_iteration`).
#[test]
fn a_refused_method_is_named_as_written() {
    let here = scratch(BIN, "method-words");
    let text = bundled(
        "paper-table2",
        &[("\"given_displacement\"", "\"given_load\"")],
    );
    std::fs::write(here.join("given-load.toml"), text).unwrap();
    let checked = in_folder(&here, &["check", "given-load.toml"]);
    let err = fails_with(
        &checked,
        1,
        &["optimisation.method: invalid value given_load:"],
    );
    assert!(!err.contains("gap_iteration"), "{err}");
}
