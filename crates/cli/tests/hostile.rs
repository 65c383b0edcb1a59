//! The `contopt` command under careless or hostile input: each case gives the right answer or a
//! clear error with its exit code, results stay in their folder, and no output file holds a NaN
//! or an infinity. Also the numerical stress cases of whole scenes: units, no contact, full
//! contact, zero and unbalanced loads.

use crate::common;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Output, Stdio};

use common::{
    assert_conforms, bundled, contopt, number, report, scratch, stderr, walk, without_sweep,
};
use serde_json::Value;

/// This binary's scratch folders.
const BIN: &str = "hostile";

/// The Hertz scene without its stresses, on 16 × 16 cells of 0.05 mm (a = 0.324 mm), with
/// `changes` made.
fn small_hertz(changes: &[(&str, &str)]) -> String {
    let mut all = vec![
        ("cells = [64, 64]", "cells = [16, 16]"),
        ("cell_mm = [0.0125, 0.0125]", "cell_mm = [0.05, 0.05]"),
    ];
    all.extend_from_slice(changes);
    let text = bundled("hertz", &all);
    text[..text.find("# Stresses below").unwrap()].to_string()
}

/// Runs `text` as a scene in its own folder with `--json`: the output and the results folder.
fn run(name: &str, text: &str) -> (Output, PathBuf) {
    let dir = scratch(BIN, name);
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, text).unwrap();
    let output = contopt()
        .args(["run", "--json", "--out"])
        .arg(dir.join("results"))
        .arg(&path)
        .output()
        .unwrap();
    (output, dir.join("results"))
}

/// A run refused as a bad scene: exit 1, nothing solved or written, `needle` on stderr.
fn refused(name: &str, text: &str, needle: &str) {
    let (output, results) = run(name, text);
    assert_eq!(output.status.code(), Some(1), "{name}: {}", stderr(&output));
    assert!(output.stdout.is_empty(), "{name}");
    assert!(
        stderr(&output).contains(needle),
        "{name}: {}",
        stderr(&output)
    );
    assert!(!results.exists(), "{name}: wrote {}", results.display());
}

/// The fields of a case that are null when it has no such value: every optional figure. The
/// schema says which fields may be null; this says where a null is expected at all.
const NULL_BY_DESIGN: [&str; 18] = [
    "method",
    "solver",
    "limit",
    "p_max_mpa",
    "bound_p_max_mpa",
    "dh_max_um",
    "omega_nv_excess_mpa",
    "approach_um",
    "penetration_um",
    "hertz",
    "resolution",
    "roller",
    "bearing",
    "subsurface",
    "reference",
    "worst_p_max_mpa",
    "tuned",
    "solve",
];

/// A VTK file of fields parses, and every coordinate and value in it is finite.
fn assert_finite_vtu(path: &Path) {
    use vtkio::model::{Attribute, DataSet, Vtk};
    let bytes = std::fs::read(path).unwrap();
    let vtk = Vtk::parse_xml(&bytes[..]).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        panic!("{}: not an unstructured grid", path.display());
    };
    for piece in pieces {
        let piece = piece.load_piece_data(None).unwrap();
        let mut values = piece.points.cast_into::<f64>().unwrap();
        for a in piece.data.point.iter().chain(&piece.data.cell) {
            if let Attribute::DataArray(d) = a {
                values.extend(d.data.cast_into::<f64>().unwrap());
            }
        }
        assert!(
            values.iter().all(|v| v.is_finite()),
            "a value that is not finite in {}",
            path.display()
        );
    }
}

/// No output under `dir` holds a NaN or an infinity: no CSV or SVG spells one; every JSON
/// report conforms to the schema (a non-finite number, which serde writes as null, breaks a
/// number's type) and holds no null outside [`NULL_BY_DESIGN`] (its `input` aside: a scene's
/// unset options); every PNG is one.
fn assert_finite_outputs(dir: &Path) {
    let mut files = 0;
    for entry in walk(dir) {
        let name = entry.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".png") {
            let png = std::fs::read(&entry).unwrap();
            assert!(png.starts_with(b"\x89PNG\r\n"), "{}", entry.display());
        } else if name.ends_with(".json") {
            let report = common::read_json(&entry);
            assert_conforms(&report, &name);
            assert_no_null(&report, "", &entry);
        } else if name.ends_with(".vtu") {
            // Base64 spells any word: the values are read back instead.
            assert_finite_vtu(&entry);
        } else {
            let text = std::fs::read_to_string(&entry).unwrap();
            for bad in ["NaN", "nan", "inf"] {
                assert!(!text.contains(bad), "{bad} in {}", entry.display());
            }
        }
        files += 1;
    }
    assert!(files > 0, "no outputs in {}", dir.display());
}

fn assert_no_null(value: &Value, key: &str, file: &Path) {
    match value {
        Value::Null => assert!(
            NULL_BY_DESIGN.contains(&key),
            "`{key}` is null in {}",
            file.display()
        ),
        Value::Array(items) => items.iter().for_each(|v| assert_no_null(v, key, file)),
        Value::Object(map) => map
            .iter()
            .filter(|(k, _)| *k != "input")
            .for_each(|(k, v)| assert_no_null(v, k, file)),
        _ => {}
    }
}

/// Exit codes: 1 for a bad scene, 2 for a usage error, 3 when a case did not converge, 4 when
/// the results cannot be written; `--help` lists them.
#[test]
fn exit_codes_say_what_went_wrong() {
    refused(
        "bad",
        &small_hertz(&[("nu = 0.3", "nu = 0.7")]),
        "body[0].material.nu",
    );

    let usage = contopt().args(["run", "--bogus"]).output().unwrap();
    assert_eq!(usage.status.code(), Some(2));

    let stopped = small_hertz(&[(
        "kind = \"polonsky_keer\"",
        "kind = \"polonsky_keer\"\nmax_steps = 1",
    )]);
    let (output, _) = run("stopped", &stopped);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let case = &report(&output)["cases"][0];
    assert_eq!(case["status"], "not_converged");
    assert_eq!(case["termination"]["kind"], "step_limit", "{case}");
    assert!(case["p_max_mpa"].is_null());
    assert!(stderr(&output).contains("error: hertz: did not converge: stopped at its limit"));

    // Results that cannot be written: a folder below a file, refused before solving (no
    // report printed with --json), as the file itself as --out is (tests/commands.rs).
    let (ok, dir) = run("unwritable", &small_hertz(&[]));
    assert_eq!(ok.status.code(), Some(0), "{}", stderr(&ok));
    let blocked = contopt()
        .args(["run", "--bundled", "hertz", "--json", "--out"])
        .arg(dir.join("hertz").join("result.json").join("below"))
        .output()
        .unwrap();
    assert_eq!(blocked.status.code(), Some(4), "{}", stderr(&blocked));
    assert!(blocked.stdout.is_empty());
    assert!(stderr(&blocked).contains("below cannot be a folder"));

    let help = contopt().arg("--help").output().unwrap();
    let text = String::from_utf8_lossy(&help.stdout);
    for code in [
        "1 bad scene",
        "2 usage",
        "3 some case did not converge",
        "4 the results",
    ] {
        assert!(text.contains(code), "{code} not in --help");
    }
}

/// A scene name that leads out of the results folder is refused; a symbolic link where the
/// scene's folder should be is refused, and one at a result's name is replaced, its target
/// untouched; a label with a quote and a comma stays one CSV field.
#[test]
fn results_stay_in_their_folder() {
    for name in ["../../x", "/tmp/abs", "..", ".", "a\\u0000b", "tab\\there"] {
        let text = small_hertz(&[("name = \"hertz\"", &format!("name = \"{name}\""))]);
        refused("escape", &text, "plain file name");
    }

    let dir = scratch(BIN, "links");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, "keep").unwrap();
    let out = dir.join("results");
    std::fs::create_dir_all(out.join("hertz")).unwrap();
    std::os::unix::fs::symlink(&victim, out.join("hertz").join("p.svg")).unwrap();
    let output = contopt()
        .args(["run", "--bundled", "hertz", "--out"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "keep");
    assert!(std::fs::read_to_string(out.join("hertz").join("p.svg"))
        .unwrap()
        .starts_with("<svg"));

    let linked = dir.join("linked");
    std::fs::create_dir_all(&linked).unwrap();
    std::os::unix::fs::symlink(&dir, linked.join("hertz")).unwrap();
    let output = contopt()
        .args(["run", "--bundled", "hertz", "--out"])
        .arg(&linked)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(4));
    assert!(stderr(&output).contains("symbolic link"));

    let text = small_hertz(&[(
        "[contact]",
        "[[case]]\nlabel = 'say \"a, b\"'\nset = { \"contact.load.force_n\" = 900.0 }\n\n\
         [contact]",
    )]);
    let (output, results) = run("quoted", &text);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert_eq!(report(&output)["cases"][0]["label"], "say \"a, b\"");
    let csv = std::fs::read_to_string(results.join("hertz").join("interface.csv")).unwrap();
    let row = csv.lines().nth(1).unwrap();
    assert!(row.starts_with("\"say \"\"a, b\"\"\","), "{row}");
    assert_eq!(row.matches(',').count(), 7 + 1, "{row}");
}

/// `contopt run … --json | head`: the reader goes away, the command ends quietly.
#[test]
fn a_closed_pipe_is_not_a_panic() {
    let mut child = std::process::Command::new(assert_cmd::cargo::cargo_bin("contopt"))
        .args(["run", "--bundled", "paper-table1", "--json", "--out"])
        .arg(scratch(BIN, "pipe"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut first = [0u8; 16];
    child.stdout.take().unwrap().read_exact(&mut first).unwrap();
    let output = child.wait_with_output().unwrap();
    assert!(!stderr(&output).contains("panicked"), "{}", stderr(&output));
    assert_ne!(output.status.code(), Some(101));
}

/// A case that did not converge: exit 3, its termination of `kind` in the report, `words` in
/// its error on stderr, and every output finite.
fn not_converged(name: &str, text: &str, kind: &str, words: &str) {
    let (output, dir) = run(name, text);
    assert_eq!(output.status.code(), Some(3), "{}", stderr(&output));
    let case = &report(&output)["cases"][0];
    assert_eq!(case["status"], "not_converged", "{case}");
    assert_eq!(case["termination"]["kind"], kind, "{}", case["termination"]);
    assert!(stderr(&output).contains(words), "{}", stderr(&output));
    assert_finite_outputs(&dir);
}

/// The silent wrong answers of the issue, each now an answer or a clear error.
#[test]
fn hostile_values_give_answers_or_clear_errors() {
    // A force that overflows f64 in the products: not converged, naming the non-finite value.
    let overflow = small_hertz(&[
        ("kind = \"polonsky_keer\"", "kind = \"active_set\""),
        ("force_n = 1000.0", "force_n = 1.7e308"),
    ]);
    not_converged("overflow", &overflow, "non_finite", "is not finite");
    // E = 1e-300: displacements of 1e303 mm are no small-strain answer.
    let soft = small_hertz(&[("e_mpa = 2.0e5", "e_mpa = 1e-300")]);
    let words = "exceeds the size of the interface";
    not_converged("soft", &soft, "large_displacement", words);

    // A flat punch smaller than the first ring has no point under it.
    let text = bundled(
        "flat-punch",
        &[(
            "\"flat_punch\", radius_mm = 10.0",
            "\"flat_punch\", radius_mm = 0.01",
        )],
    );
    refused(
        "small-punch",
        &text,
        "no point of the zone lies under the gap",
    );

    // A penalty c = E·10⁻³: the solution penetrates by 3.4 times its elastic displacement, the
    // design cannot hold p = v·p_max at the rim (it passes it by 95 % of p_max): not converged,
    // naming the point of Ω_v, with the penetration's warning beside it.
    let text = bundled(
        "paper-table1",
        &[("c_mpa_per_mm = 2.0e9", "c_mpa_per_mm = 200.0")],
    );
    not_converged("soft-penalty", without_sweep(&text), "infeasible", "of Ω_v");
    let (output, _) = run("soft-penalty-warning", without_sweep(&text));
    let case = &report(&output)["cases"][0];
    let penetration = number(&case["penetration_um"]);
    assert!(penetration > 100.0, "{penetration} µm");
    assert!(case["warnings"][0].as_str().unwrap().contains("penetrates"));
    assert!(stderr(&output).contains("warning: paper-table1: the solution penetrates"));

    // A controller of level 1e-12: the bound is 1e14 MPa, the largest pressure 100 MPa.
    let text = bundled(
        "paper-table1",
        &[(
            "controller = { kind = \"cubic\", l1_mm = 0.0, l2_mm = 50.0 }",
            "controller = { kind = \"constant\", level = 1e-12 }",
        )],
    );
    let (output, _) = run("level", without_sweep(&text));
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let case = &report(&output)["cases"][0];
    let (p_max, bound) = (number(&case["p_max_mpa"]), number(&case["bound_p_max_mpa"]));
    assert!((p_max / 100.0 - 1.0).abs() < 1e-6, "{p_max}");
    assert!((bound / 1e14 - 1.0).abs() < 1e-6, "{bound}");
}

/// Sizes that would abort or overflow are refused before anything is allocated, with the
/// memory they would take. (The active set holds up to 6 dense n × n matrices by the scene's
/// estimate now, each part counting its own: A, the contact set's matrix, its eigenvectors,
/// the eigensolver's copy and faer's two divide-and-conquer blocks.) A nesting past the
/// reader's limit of 32 is refused at that limit.
#[test]
fn sizes_are_refused_with_their_memory() {
    for (name, changes, needle) in [
        (
            "huge-grid",
            vec![("cells = [16, 16]", "cells = [100000, 100000]")],
            "10000000000 interface points",
        ),
        (
            "wrapping-grid",
            vec![("cells = [16, 16]", "cells = [4294967296, 4294967296]")],
            "more bytes than 64 bits count",
        ),
        (
            "dense-grid",
            vec![
                ("cells = [16, 16]", "cells = [128, 128]"),
                ("kind = \"polonsky_keer\"", "kind = \"active_set\""),
            ],
            "6 dense 16384 × 16384 matrices",
        ),
    ] {
        let mut text = small_hertz(&[]);
        for (from, to) in changes {
            text = text.replacen(from, to, 1);
        }
        let (output, _) = run(name, &text);
        assert_eq!(output.status.code(), Some(1), "{name}");
        let message = stderr(&output);
        assert!(
            message.contains(needle) && message.contains("limit of 4000 MB"),
            "{message}"
        );
    }
    for (scene, from, to) in [
        ("paper-table1", "elements = 18", "elements = 100000"),
        ("flat-punch", "rings = 60", "rings = 100000"),
    ] {
        refused(scene, &bundled(scene, &[(from, to)]), "over the limit");
    }
    let values: Vec<String> = (0..20_000).map(|k| k.to_string()).collect();
    let sweep = format!(
        "{}[sweep]\nkey = \"contact.load.force_n\"\nvalues = [{}]\n",
        small_hertz(&[]),
        values.join(", ")
    );
    refused("long-sweep", &sweep, "20000 cases, at most 10000");
    let deep = format!(
        "name = \"deep\"\nx = {}1{}\n",
        "[".repeat(200),
        "]".repeat(200)
    );
    refused("deep", &deep, "nested more than 32 deep");
}

/// Hertz in N-mm-MPa, N-m-Pa (lengths ×10⁻³, E ×10⁶) and N-µm-TPa (lengths ×10³, E ×10⁻⁶):
/// one physical answer by Polonsky–Keer and by the active set (p in the scene's units scales
/// as E).
#[test]
fn units_do_not_change_hertz() {
    let hertz = |solver: &str, length: f64, stress: f64| {
        let text = small_hertz(&[
            ("kind = \"polonsky_keer\"", &format!("kind = \"{solver}\"")),
            ("e_mpa = 2.0e5", &format!("e_mpa = {:e}", 2.0e5 * stress)),
            (
                "cell_mm = [0.05, 0.05]",
                &format!("cell_mm = [{0:e}, {0:e}]", 0.05 * length),
            ),
            (
                "radius_mm = 10.0",
                &format!("radius_mm = {:e}", 10.0 * length),
            ),
        ]);
        let (output, dir) = run(&format!("units-{solver}-{length}"), &text);
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        assert_finite_outputs(&dir);
        number(&report(&output)["cases"][0]["p_max_mpa"]) / stress
    };
    for solver in ["polonsky_keer", "active_set"] {
        let mm = hertz(solver, 1.0, 1.0);
        for (length, stress) in [(1e-3, 1e6), (1e3, 1e-6)] {
            let other = hertz(solver, length, stress);
            assert!((other / mm - 1.0).abs() < 1e-8, "{solver}: {other} vs {mm}");
        }
    }
}

/// Table 1's first case in N-mm-MPa and N-m-Pa (lengths ×10⁻³, E, p and c·mm ×10⁶, TOLH
/// ×10⁻⁶): one physical answer.
#[test]
fn units_do_not_change_table1() {
    let text = bundled("paper-table1", &[]);
    let metres = text
        .replace("radius_mm = 50.0, elements", "radius_mm = 0.05, elements")
        .replace("radius_mm = 100.0", "radius_mm = 0.1")
        .replace("height_mm = 50.0", "height_mm = 0.05")
        .replace("e_mpa = 2.0e5", "e_mpa = 2.0e11")
        .replace("pressure_mpa = 100.0", "pressure_mpa = 1.0e8")
        .replace("c_mpa_per_mm = 2.0e9", "c_mpa_per_mm = 2.0e18")
        .replace("l1_mm = 0.0, l2_mm = 50.0", "l1_mm = 0.0, l2_mm = 0.05")
        .replace("tolh_mm2 = 0.5e-6", "tolh_mm2 = 0.5e-12");
    let metres = without_sweep(&metres);
    // Every length, modulus and load above changed: none is left in millimetres.
    for (kept, count) in [("50.0", 0), ("2.0e5", 0), ("0.05", 4), ("2.0e11", 2)] {
        assert_eq!(metres.matches(kept).count(), count, "{kept}");
    }
    let (mm, _) = run("table1-mm", without_sweep(&text));
    let (m, _) = run("table1-m", metres);
    let (mm, m) = (&report(&mm)["cases"][0], &report(&m)["cases"][0]);
    for (key, scale) in [
        ("bound_p_max_mpa", 1e6),
        ("p_max_mpa", 1e6),
        ("dh_max_um", 1e-3),
    ] {
        let (a, b) = (number(&mm[key]), number(&m[key]) / scale);
        assert!((b / a - 1.0).abs() < 1e-6, "{key}: {b} vs {a}");
    }
}

/// No contact (an approach short of the nearest point), full contact (a flat punch as wide as
/// the zone: Sneddon's pressure), zero load and a load pulling the bodies apart.
#[test]
fn degenerate_contacts() {
    let (output, dir) = run(
        "no-contact",
        &small_hertz(&[("force_n = 1000.0", "approach_mm = 1e-9")]),
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let case = &report(&output)["cases"][0];
    assert_eq!(case["p_max_mpa"].as_f64(), Some(0.0));
    assert_finite_outputs(&dir);

    let (output, dir) = run("full-contact", bundled("flat-punch", &[]).as_str());
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let case = &report(&output)["cases"][0];
    let points = case["interface"].as_array().unwrap();
    assert!(points.iter().all(|q| number(&q["p_mpa"]) > 0.0));
    // Sneddon: p(r) = F/(2πa√(a² − r²)); at r = a/2, F/(√3 π a²).
    let (f, a) = (31415.93, 10.0);
    let half = points
        .iter()
        .min_by(|p, q| {
            let d = |v: &Value| (number(&v["x_mm"][0]) - 0.5 * a).abs();
            d(p).total_cmp(&d(q))
        })
        .unwrap();
    let sneddon = f / (3f64.sqrt() * std::f64::consts::PI * a * a);
    let p = number(&half["p_mpa"]);
    assert!((p / sneddon - 1.0).abs() < 0.02, "{p} vs {sneddon}");
    assert_finite_outputs(&dir);

    refused(
        "zero-load",
        &small_hertz(&[("force_n = 1000.0", "force_n = 0.0")]),
        "contact.load.force_n: invalid value 0: must be positive",
    );
    for (name, pressure) in [("zero-punch-load", "0.0"), ("pulled", "-100.0")] {
        let text = bundled(
            "paper-table1",
            &[(
                "pressure_mpa = 100.0",
                &format!("pressure_mpa = {pressure}"),
            )],
        );
        refused(name, &text, "must press the punch onto the base");
    }
}
