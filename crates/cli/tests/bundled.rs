//! Every bundled scene through `contopt run --json`: its `result.json` conforms to the committed
//! JSON Schema (`crates/results/result.schema.json`), says the schema's version, names its
//! cases' parameters by dotted paths into their inputs, and each case's `input` reads back as a
//! scene (`contopt check`) that resolves to the same input. The roller scenes run on 40 × 21
//! cells, the bearing on 24 × 11 (the bundled grids take seconds to minutes); nothing else
//! changes.

use crate::common;

use std::path::Path;

use common::{
    assert_conforms, bundled, bundled_text, contopt, read_json, report, run_json_output, scratch,
    stderr, stdout, write_scene,
};
use serde_json::Value;

/// This binary's scratch folders.
const BIN: &str = "bundled";

/// The scenes whose grids are shrunk, and how: the same area in fewer cells.
const SHRUNK: [(&str, &str, &str); 4] = [
    (
        "roller",
        "cells = [200, 105], cell_mm = [0.05, 0.0086672]",
        "cells = [40, 21], cell_mm = [0.25, 0.0433360]",
    ),
    ("roller-study", "cells = [200, 105]", "cells = [40, 21]"),
    // Its profile search solves each crown under nine load cases: 30 × 15 cells.
    ("roller-envelope", "cells = [200, 105]", "cells = [30, 15]"),
    // Its searches solve each crown under every loaded roller of three load cases, thrice.
    ("bearing", "cells = [80, 49]", "cells = [24, 11]"),
];

/// The bundled scene `name` as a file in a scratch folder, shrunk when it is in [`SHRUNK`],
/// with its meshes where it names them.
fn scene_file(name: &str) -> std::path::PathBuf {
    let text = match SHRUNK.iter().find(|(n, _, _)| *n == name) {
        Some((_, from, to)) => bundled(name, &[(from, to)]),
        None => bundled_text(name).to_string(),
    };
    let dir = scratch(BIN, name);
    common::write_meshes(&dir, name);
    write_scene(&dir, name, &text)
}

/// Runs the bundled scene `name` and checks its report: the exit status agrees with the cases'
/// status (0 when all are solved, else 3), the report printed is the one written and conforms
/// to the schema, its version is [`contopt_results::SCHEMA_VERSION`], its parameters are dotted
/// paths into the inputs, and every input reads back as the same scene.
fn conforms(name: &str) {
    let path = scene_file(name);
    let out = path.with_file_name("results");
    let output = run_json_output(&[path.as_os_str()], &out);
    let printed = report(&output);
    let written = read_json(&out.join(name).join("result.json"));
    assert_conforms(&written, &format!("{name}/result.json"));
    assert_eq!(printed, written, "{name}: --json and result.json differ");
    assert_eq!(
        written["schema_version"].as_u64(),
        Some(contopt_results::SCHEMA_VERSION.into())
    );
    assert_eq!(written["scene"], name);
    let cases = written["cases"].as_array().unwrap();
    let solved = cases.iter().all(|c| c["status"] == "solved");
    let code = if solved { 0 } else { 3 };
    assert_eq!(output.status.code(), Some(code), "{}", stderr(&output));
    for (k, case) in cases.iter().enumerate() {
        params_are_paths_into_the_input(case);
        input_reads_back(case, &path.with_file_name(format!("input-{k}.json")));
    }
}

/// Each of a case's `params` is a dotted path of the scene (`optimisation.controller.l1_mm`)
/// that leads, through its input, to its value. The input writes a choice as a table under its
/// kind (`{"cubic": {"l1_mm": …}}`), which a scene's path steps over.
fn params_are_paths_into_the_input(case: &Value) {
    for (key, value) in case["params"].as_object().unwrap() {
        let parts: Vec<&str> = key.split('.').collect();
        assert!(
            parts.len() > 1 && parts.iter().all(|p| !p.is_empty()),
            "{key}"
        );
        let mut at = &case["input"];
        for part in parts {
            at = step(at, part).unwrap_or_else(|| panic!("{key}: no {part} in {at}"));
        }
        assert_eq!(at, value, "{key}");
    }
}

/// One step of a dotted path: a table's key, an array's index, or the key within a choice
/// written as a table under its kind.
fn step<'v>(at: &'v Value, part: &str) -> Option<&'v Value> {
    if let Ok(index) = part.parse::<usize>() {
        return at.get(index);
    }
    at.get(part).or_else(|| match at.as_object() {
        Some(choice) if choice.len() == 1 => choice.values().next()?.get(part),
        _ => None,
    })
}

/// A case's `input`, written as `path` (JSON), is a scene of one case that `contopt check`
/// accepts and that resolves to the same input.
fn input_reads_back(case: &Value, path: &Path) {
    let input = &case["input"];
    std::fs::write(path, serde_json::to_string_pretty(input).unwrap()).unwrap();
    let output = contopt().arg("check").arg(path).output().unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    assert!(
        stdout(&output).ends_with(": ok (1 case(s))\n"),
        "{}",
        stdout(&output)
    );
    let scene = contopt_scene::Scene::load(path).unwrap();
    assert_eq!(&scene.cases()[0].input(), input, "{}", case["label"]);
}

macro_rules! every_bundled_scene {
    ($($test:ident: $name:literal),* $(,)?) => {
        $(
            #[test]
            fn $test() {
                conforms($name);
            }
        )*

        /// The tests above cover every bundled scene.
        #[test]
        fn every_bundled_scene_is_tested() {
            let tested = [$($name),*];
            for b in contopt_scene::BUNDLED {
                assert!(tested.contains(&b.name), "{} is not tested", b.name);
            }
        }
    };
}

every_bundled_scene!(
    paper_table1: "paper-table1",
    paper_table2: "paper-table2",
    paper_table3: "paper-table3",
    roller: "roller",
    roller_study: "roller-study",
    roller_envelope: "roller-envelope",
    bearing: "bearing",
    hertz: "hertz",
    flat_punch: "flat-punch",
    punch_on_block: "punch-on-block",
    steel_on_aluminium: "steel-on-aluminium",
    winkler_bed: "winkler-bed",
    cylinder_on_block: "cylinder-on-block",
    filleted_punch: "filleted-punch",
    shrink_fit: "shrink-fit",
    sphere_on_solid_block: "sphere-on-solid-block",
    solid_sphere_on_block: "solid-sphere-on-block",
);

/// The first field of a CSV row (RFC 4180: quoted when it holds a comma or a quote, quotes
/// doubled).
fn first_field(row: &str) -> String {
    match row.strip_prefix('"') {
        None => row.split(',').next().unwrap().to_string(),
        Some(rest) => {
            let mut field = String::new();
            let mut chars = rest.chars().peekable();
            while let Some(c) = chars.next() {
                match (c, chars.peek()) {
                    ('"', Some('"')) => {
                        field.push('"');
                        chars.next();
                    }
                    ('"', _) => break,
                    _ => field.push(c),
                }
            }
            field
        }
    }
}

/// A case has one label: the table's rows, `result.json` and the `case` column of
/// `interface.csv` name a swept case (`L1 = 20 mm`) and a listed one (`aluminium punch on a
/// steel base, held axially`, quoted in the CSV) by the same string, in the scene's order.
#[test]
fn a_case_has_one_label_everywhere() {
    for name in ["paper-table1", "steel-on-aluminium"] {
        let out = scratch(BIN, &format!("labels-{name}"));
        let output = contopt()
            .args(["run", "--bundled", name, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
        let report = read_json(&out.join(name).join("result.json"));
        let labels: Vec<String> = report["cases"]
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["label"].as_str().unwrap().to_string())
            .collect();
        assert!(labels.len() > 1, "{name}");
        let table = stdout(&output);
        let rows: Vec<&str> = table
            .lines()
            .skip(1)
            .filter(|l| {
                labels
                    .iter()
                    .any(|label| l.starts_with(&format!("{label} ")))
            })
            .collect();
        assert_eq!(rows.len(), labels.len(), "{table}");
        for (row, label) in rows.iter().zip(&labels) {
            assert!(
                row.starts_with(&format!("{label} ")),
                "{row} is not {label}"
            );
        }
        let csv = std::fs::read_to_string(out.join(name).join("interface.csv")).unwrap();
        let mut column: Vec<String> = csv.lines().skip(1).map(first_field).collect();
        column.dedup();
        assert_eq!(column, labels, "{name}");
    }
}
