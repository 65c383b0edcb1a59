//! crates/input against the well-kept crates: the same scene mistakes read by
//! `contopt_input` (its `Node` tree and deserializer), by `toml` 0.9's own deserializer, by
//! `serde_json`, and by both of these wrapped in `serde_path_to_error`; then the time each
//! takes to read the bundled scenes, and the memory of the trees.
//!
//! ```sh
//! cargo run --release -p contopt-input --example compare_parsers
//! ```
//!
//! Every mistake is the sample scene below (TOML and JSON) with one edit. An error is judged
//! on four things, each a character of the table's cell:
//! - where: `=` the line and column of the offending key or value, `~` its line only, `-` no
//!   place (or another line), `·` the mistake has no place (the whole text);
//! - `P` the key path (`body[1].material.e_mpa`), `p` a part of it, `-` none;
//! - `V` the value written (`"1 kN"`, `active_sets`), `-` not said;
//! - `A` what it must be (`f64`, the variants, the fields, the limit), `-` not said;
//!
//! `·` for a thing the mistake does not have. `acc` is a text accepted when it should not be,
//! `ok` / `REFUSED` a correct text accepted / refused. A value the types accept but the scene
//! refuses after reading (a negative cell size) is checked as a scene does: the check names
//! the key path, and each approach places it with what it has (the `Node` tree's spans, toml's
//! `DeTable` spans, nothing for `serde_json`).

use std::alloc::{GlobalAlloc, Layout, System};
use std::collections::{BTreeMap, HashMap};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use contopt_input::{line_column, InputError, Limits, Node};
use serde_json::value::RawValue;
use toml::de::{DeTable, DeValue};
use toml::Spanned;

/// The heap bytes in use: the memory a tree keeps is the growth while it is held.
static LIVE_BYTES: AtomicUsize = AtomicUsize::new(0);

/// The system allocator, counting the bytes in use.
struct Counting;

// SAFETY: every call is passed to `System` unchanged; the counter is only arithmetic.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: the caller's contract is System's.
        let pointer = unsafe { System.alloc(layout) };
        if !pointer.is_null() {
            LIVE_BYTES.fetch_add(layout.size(), Ordering::Relaxed);
        }
        pointer
    }

    unsafe fn dealloc(&self, pointer: *mut u8, layout: Layout) {
        // SAFETY: the caller's contract is System's.
        unsafe { System.dealloc(pointer, layout) };
        LIVE_BYTES.fetch_sub(layout.size(), Ordering::Relaxed);
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// A scene-like schema: the choices externally tagged (serde's default), so that every
/// approach can read the sample; its fields are read by serde and the checks only.
#[allow(dead_code)]
mod schema {
    use serde::Deserialize;

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Scene {
        pub name: String,
        pub contact: Contact,
        pub solver: Solver,
        pub body: Vec<Body>,
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Contact {
        pub zone: Zone,
        pub law: Law,
        pub load: Load,
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Zone {
        pub cells: [u32; 2],
        pub cell_mm: [f64; 2],
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Load {
        pub force_n: f64,
        #[serde(default)]
        pub angle_deg: f64,
    }

    #[derive(Deserialize, Debug)]
    #[serde(rename_all = "snake_case", deny_unknown_fields)]
    pub enum Law {
        Rigid,
        Penalty { c_mpa_per_mm: f64 },
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Solver {
        pub method: Method,
        #[serde(default)]
        pub max_iterations: Option<u32>,
    }

    #[derive(Deserialize, Debug)]
    #[serde(rename_all = "snake_case")]
    pub enum Method {
        ActiveSet,
        Lemke,
    }

    #[derive(Deserialize, Debug)]
    #[serde(deny_unknown_fields)]
    pub struct Body {
        pub name: String,
        pub plane: Plane,
        pub material: Material,
    }

    #[derive(Deserialize, Debug)]
    #[serde(rename_all = "snake_case", deny_unknown_fields)]
    pub enum Plane {
        PlaneStrain,
        PlaneStress { thickness_mm: f64 },
    }

    /// A material validated as it is read, as the scene's are.
    #[derive(Deserialize, Debug)]
    #[serde(try_from = "RawMaterial")]
    pub struct Material {
        pub e_mpa: f64,
        pub nu: f64,
    }

    #[derive(Deserialize)]
    #[serde(deny_unknown_fields)]
    struct RawMaterial {
        e_mpa: f64,
        nu: f64,
    }

    impl TryFrom<RawMaterial> for Material {
        type Error = String;

        fn try_from(raw: RawMaterial) -> Result<Self, String> {
            if raw.nu.is_nan() || raw.nu <= -1.0 || raw.nu >= 0.5 {
                return Err(format!(
                    "invalid nu = {}: Poisson's ratio is above -1 and below 0.5",
                    raw.nu
                ));
            }
            Ok(Self {
                e_mpa: raw.e_mpa,
                nu: raw.nu,
            })
        }
    }
}

use schema::Scene;

const SAMPLE_TOML: &str = r#"name = "hertz"

[contact]
zone = { cells = [16, 16], cell_mm = [0.05, 0.05] }
law = { penalty = { c_mpa_per_mm = 2e9 } }

[contact.load]
force_n = 1000.0
angle_deg = 0.0

[solver]
method = "active_set"

[[body]]
name = "ball"
plane = { plane_stress = { thickness_mm = 10.0 } }
material = { e_mpa = 210000.0, nu = 0.3 }

[[body]]
name = "block"
plane = "plane_strain"
material = { e_mpa = 70000.0, nu = 0.33 }
"#;

const SAMPLE_JSON: &str = r#"{
  "name": "hertz",
  "contact": {
    "zone": { "cells": [16, 16], "cell_mm": [0.05, 0.05] },
    "law": { "penalty": { "c_mpa_per_mm": 2e9 } },
    "load": { "force_n": 1000.0, "angle_deg": 0.0 }
  },
  "solver": { "method": "active_set" },
  "body": [
    {
      "name": "ball",
      "plane": { "plane_stress": { "thickness_mm": 10.0 } },
      "material": { "e_mpa": 210000.0, "nu": 0.3 }
    },
    {
      "name": "block",
      "plane": "plane_strain",
      "material": { "e_mpa": 70000.0, "nu": 0.33 }
    }
  ]
}
"#;

/// How deep the too-deep mistake nests its arrays: past every parser's limit (32 here, 80 in
/// toml, 128 in serde_json).
const DEEP: usize = 200;

/// The size of the over-large text: twice the 1 MB that crates/input accepts by default.
const LARGE_BYTES: usize = 2_000_000;

/// Where a mistake's error should point.
#[derive(Clone, Copy)]
enum Mark {
    /// At this text within the edit's new text.
    InEdit(&'static str),
    /// At this byte of the edit's new text.
    InEditAt(usize),
    /// At the first occurrence of this text in the edited document.
    Text(&'static str),
    /// Nowhere: the mistake is the whole text.
    Nowhere,
}

/// A document to read, and the byte an error should point at.
struct Case {
    text: String,
    at: Option<usize>,
}

/// `sample` with `from` (which must be there) replaced by `to`, marked by `mark`.
fn edit(sample: &str, from: &str, to: &str, mark: Mark) -> Case {
    let start = sample
        .find(from)
        .unwrap_or_else(|| panic!("{from:?} is not in the sample"));
    let text = sample.replacen(from, to, 1);
    let at = match mark {
        Mark::InEdit(marker) => to.find(marker).map(|offset| start + offset),
        Mark::InEditAt(offset) => Some(start + offset),
        Mark::Text(marker) => text.find(marker),
        Mark::Nowhere => None,
    };
    assert!(!matches!(mark, Mark::InEdit(_)) || at.is_some(), "{to:?}");
    Case { text, at }
}

/// A scene mistake, in TOML and in JSON, and what a good error says of it.
struct Mistake {
    what: &'static str,
    toml: Case,
    json: Case,
    /// The key path of the offending key; empty for the whole text.
    path: &'static str,
    /// The value as written, any of these; none for a mistake without one.
    value: &'static [&'static str],
    /// What the value must be, any of these.
    allowed: &'static [&'static str],
    /// A correct text: it should be accepted.
    correct: bool,
}

fn mistakes() -> Vec<Mistake> {
    let deep = format!("{}{}", "[".repeat(DEEP), "]".repeat(DEEP));
    let both = |from: &str, to: &str, mark| {
        (
            edit(SAMPLE_TOML, from, to, mark),
            edit(SAMPLE_JSON, from, to, mark),
        )
    };
    let mistake = |what, (toml, json), path, value, allowed| Mistake {
        what,
        toml,
        json,
        path,
        value,
        allowed,
        correct: false,
    };
    let large_toml = Case {
        text: format!("{SAMPLE_TOML}#{}\n", "x".repeat(LARGE_BYTES)),
        at: None,
    };
    let large_json = Case {
        text: format!("{SAMPLE_JSON}{}", " ".repeat(LARGE_BYTES)),
        at: None,
    };
    vec![
        mistake(
            "unknown key",
            (
                edit(SAMPLE_TOML, "angle_deg", "angel_deg", Mark::InEdit("a")),
                edit(
                    SAMPLE_JSON,
                    "\"angle_deg\"",
                    "\"angel_deg\"",
                    Mark::InEdit("\""),
                ),
            ),
            "contact.load.angel_deg",
            &["angel_deg"],
            &["`force_n`"],
        ),
        mistake(
            "wrong type",
            (
                edit(
                    SAMPLE_TOML,
                    "force_n = 1000.0",
                    "force_n = \"1 kN\"",
                    Mark::InEdit("\""),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"force_n\": 1000.0",
                    "\"force_n\": \"1 kN\"",
                    Mark::InEdit("\"1"),
                ),
            ),
            "contact.load.force_n",
            &["1 kN"],
            &["f64"],
        ),
        mistake(
            "missing field",
            (
                edit(
                    SAMPLE_TOML,
                    "force_n = 1000.0\n",
                    "",
                    Mark::Text("[contact.load]"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"force_n\": 1000.0, ",
                    "",
                    Mark::Text("{ \"angle_deg\""),
                ),
            ),
            "contact.load.force_n",
            &[],
            &["`force_n`"],
        ),
        mistake(
            "bad enum tag",
            both("\"active_set\"", "\"active_sets\"", Mark::InEdit("\"")),
            "solver.method",
            &["active_sets"],
            &["lemke"],
        ),
        mistake(
            "out of range, checked after reading",
            both("[0.05, 0.05]", "[-0.05, 0.05]", Mark::InEdit("-")),
            "contact.zone.cell_mm[0]",
            &["-0.05"],
            &["positive"],
        ),
        mistake(
            "refused by the type (try_from)",
            (
                edit(SAMPLE_TOML, "nu = 0.3", "nu = 0.5", Mark::InEdit("0")),
                edit(SAMPLE_JSON, "\"nu\": 0.3", "\"nu\": 0.5", Mark::InEdit("0")),
            ),
            "body[0].material.nu",
            &["0.5"],
            &["below 0.5"],
        ),
        mistake(
            "[[body]] 1: wrong type",
            (
                edit(
                    SAMPLE_TOML,
                    "e_mpa = 70000.0",
                    "e_mpa = \"steel\"",
                    Mark::InEdit("\""),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"e_mpa\": 70000.0",
                    "\"e_mpa\": \"steel\"",
                    Mark::InEdit("\"s"),
                ),
            ),
            "body[1].material.e_mpa",
            &["steel"],
            &["f64"],
        ),
        mistake(
            "nested inline table: unknown key",
            (
                edit(SAMPLE_TOML, "thickness_mm", "thickness", Mark::InEdit("t")),
                edit(
                    SAMPLE_JSON,
                    "\"thickness_mm\"",
                    "\"thickness\"",
                    Mark::InEdit("\""),
                ),
            ),
            "body[0].plane.plane_stress.thickness",
            &["`thickness`", "thickness,"],
            &["thickness_mm"],
        ),
        mistake(
            "duplicate key",
            (
                edit(
                    SAMPLE_TOML,
                    "angle_deg = 0.0",
                    "angle_deg = 0.0\nforce_n = 2000.0",
                    Mark::InEdit("f"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"angle_deg\": 0.0",
                    "\"angle_deg\": 0.0, \"force_n\": 2000.0",
                    Mark::InEdit("\"f"),
                ),
            ),
            "contact.load.force_n",
            &["force_n"],
            &["duplicate"],
        ),
        mistake(
            "syntax error",
            (
                edit(
                    SAMPLE_TOML,
                    "force_n = 1000.0",
                    "force_n = = 1000.0",
                    Mark::InEdit("= 1"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"force_n\": 1000.0,",
                    "\"force_n\": 1000.0",
                    Mark::Text("\"angle_deg\""),
                ),
            ),
            "contact.load",
            &[],
            &["expected"],
        ),
        mistake(
            "too deep (200 arrays)",
            both("\"hertz\"", &deep, Mark::InEditAt(32)),
            "name",
            &[],
            &["32", "80", "128"],
        ),
        mistake(
            "over-large text (2 MB)",
            (large_toml, large_json),
            "",
            &[],
            &["1000000"],
        ),
        mistake(
            "integer overflow",
            (
                edit(
                    SAMPLE_TOML,
                    "\"active_set\"",
                    "\"active_set\"\nmax_iterations = 99999999999999999999",
                    Mark::InEdit("9"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"active_set\"",
                    "\"active_set\", \"max_iterations\": 99999999999999999999",
                    Mark::InEdit("9"),
                ),
            ),
            "solver.max_iterations",
            &["99999999999999999999", "1e20", "100000000000000000000"],
            &["u32", "9223372036854775807"],
        ),
        mistake(
            "float overflow (1e400)",
            (
                edit(
                    SAMPLE_TOML,
                    "force_n = 1000.0",
                    "force_n = 1e400",
                    Mark::InEdit("1"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"force_n\": 1000.0",
                    "\"force_n\": 1e400",
                    Mark::InEdit("1"),
                ),
            ),
            "contact.load.force_n",
            &["1e400", "inf"],
            &["finite", "range"],
        ),
        mistake(
            "NaN literal",
            (
                edit(
                    SAMPLE_TOML,
                    "force_n = 1000.0",
                    "force_n = nan",
                    Mark::InEdit("nan"),
                ),
                edit(
                    SAMPLE_JSON,
                    "\"force_n\": 1000.0",
                    "\"force_n\": NaN",
                    Mark::InEdit("N"),
                ),
            ),
            "contact.load.force_n",
            &["nan", "NaN", "'N'"],
            &["finite", "value"],
        ),
        Mistake {
            correct: true,
            ..mistake(
                "(correct) `kind` spelling",
                (
                    edit(
                        SAMPLE_TOML,
                        "{ penalty = { c_mpa_per_mm = 2e9 } }",
                        "{ kind = \"penalty\", c_mpa_per_mm = 2e9 }",
                        Mark::Nowhere,
                    ),
                    edit(
                        SAMPLE_JSON,
                        "{ \"penalty\": { \"c_mpa_per_mm\": 2e9 } }",
                        "{ \"kind\": \"penalty\", \"c_mpa_per_mm\": 2e9 }",
                        Mark::Nowhere,
                    ),
                ),
                "",
                &[],
                &[],
            )
        },
    ]
}

/// What a scene refuses after reading, with the key path the check names.
struct Refusal {
    path: String,
    message: String,
}

/// The checks a scene makes of values its types accept.
fn check(scene: &Scene) -> Result<(), Refusal> {
    let force = scene.contact.load.force_n;
    if !(force.is_finite() && force > 0.0) {
        return Err(Refusal {
            path: "contact.load.force_n".into(),
            message: format!("must be a finite force above 0 [N], got {force}"),
        });
    }
    for (index, &size) in scene.contact.zone.cell_mm.iter().enumerate() {
        if size.is_nan() || size <= 0.0 {
            return Err(Refusal {
                path: format!("contact.zone.cell_mm[{index}]"),
                message: format!("must be positive [mm], got {size}"),
            });
        }
    }
    Ok(())
}

/// A step of a key path.
enum Step<'a> {
    Key(&'a str),
    Index(usize),
}

/// The steps of a key path as errors write it: `body[1].material`.
fn steps(path: &str) -> Vec<Step<'_>> {
    let mut steps = Vec::new();
    for part in path.split('.').filter(|part| !part.is_empty()) {
        let (key, indices) = part.split_once('[').unwrap_or((part, ""));
        if !key.is_empty() {
            steps.push(Step::Key(key));
        }
        for index in indices.split('[') {
            if let Ok(index) = index.trim_end_matches(']').parse() {
                steps.push(Step::Index(index));
            }
        }
    }
    steps
}

/// What an approach said of a text.
struct Outcome {
    accepted: bool,
    place: Option<(usize, usize)>,
    path: String,
    message: String,
}

impl Outcome {
    fn accepted() -> Self {
        Self {
            accepted: true,
            place: None,
            path: String::new(),
            message: String::new(),
        }
    }

    fn from_input(text: &str, error: &InputError) -> Self {
        Self {
            accepted: false,
            place: error.line_column(text),
            path: error.path.clone(),
            message: error.message.clone(),
        }
    }

    /// toml's error: the span's place and the message; the key path only as toml's display
    /// gives it (`in \`a.b\``, for an error without a span).
    fn from_toml(text: &str, error: &toml::de::Error) -> Self {
        let shown = error.to_string();
        let path = shown
            .split_once("in `")
            .and_then(|(_, rest)| rest.split_once('`'))
            .map_or(String::new(), |(path, _)| path.to_owned());
        Self {
            accepted: false,
            place: error.span().map(|span| line_column(text, span.start)),
            path,
            message: error.message().replace('\n', " / "),
        }
    }

    /// serde_json's error: its line and column, the message without them.
    fn from_json(error: &serde_json::Error) -> Self {
        let (line, column) = (error.line(), error.column());
        let shown = error.to_string();
        let suffix = format!(" at line {line} column {column}");
        Self {
            accepted: false,
            place: (line > 0).then_some((line, column)),
            path: String::new(),
            message: shown.strip_suffix(&suffix).unwrap_or(&shown).to_owned(),
        }
    }

    /// A scene's refusal after reading, placed at `span` when the approach can find one.
    fn refused(text: &str, refusal: Refusal, span: Option<Range<usize>>) -> Self {
        Self {
            accepted: false,
            place: span.map(|span| line_column(text, span.start)),
            path: refusal.path,
            message: refusal.message,
        }
    }

    /// `line:column path: message`, as a scene error reads.
    fn render(&self) -> String {
        if self.accepted {
            return "(accepted)".into();
        }
        let place = self
            .place
            .map_or("-:-".into(), |(line, column)| format!("{line}:{column}"));
        let path = match self.path.as_str() {
            "" => String::new(),
            path => format!("{path}: "),
        };
        format!("{place} {path}{}", self.message)
    }
}

/// The scene read by contopt_input from its tree, the checks placed by the tree's spans.
fn contopt(text: &str, parse: fn(&str, &Limits) -> Result<Node, InputError>) -> Outcome {
    let node = match parse(text, &Limits::default()) {
        Ok(node) => node,
        Err(error) => return Outcome::from_input(text, &error),
    };
    let scene: Scene = match node.deserialize() {
        Ok(scene) => scene,
        Err(error) => return Outcome::from_input(text, &error),
    };
    match check(&scene) {
        Ok(()) => Outcome::accepted(),
        Err(refusal) => {
            let dotted: Vec<String> = steps(&refusal.path)
                .iter()
                .map(|step| match step {
                    Step::Key(key) => (*key).to_owned(),
                    Step::Index(index) => index.to_string(),
                })
                .collect();
            let span = node.get(&dotted.join(".")).and_then(Node::span);
            Outcome::refused(text, refusal, span)
        }
    }
}

fn contopt_toml(text: &str) -> Outcome {
    contopt(text, Node::parse_toml_with)
}

fn contopt_json(text: &str) -> Outcome {
    contopt(text, Node::parse_json_with)
}

/// The span of the value at `path` in a TOML text, from toml's spanned `DeTable`.
fn toml_span(text: &str, path: &str) -> Option<Range<usize>> {
    let root = DeTable::parse(text).ok()?;
    let root = Spanned::new(root.span(), DeValue::Table(root.into_inner()));
    let mut at = &root;
    for step in steps(path) {
        at = match (at.get_ref(), step) {
            (DeValue::Table(table), Step::Key(name)) => {
                table.iter().find(|(key, _)| key.get_ref() == name)?.1
            }
            (DeValue::Array(items), Step::Index(index)) => items.get(index)?,
            _ => return None,
        };
    }
    Some(at.span())
}

/// The span of the value at `path` in a JSON text, from the offsets of serde_json's
/// `RawValue`s in the text: serde_json's own trees have no spans, but a raw value borrows its
/// text. Each step parses the raw value of the step before again.
fn json_span(text: &str, path: &str) -> Option<Range<usize>> {
    let mut at: &RawValue = serde_json::from_str(text).ok()?;
    for step in steps(path) {
        at = match step {
            Step::Key(name) => *serde_json::from_str::<HashMap<String, &RawValue>>(at.get())
                .ok()?
                .get(name)?,
            Step::Index(index) => *serde_json::from_str::<Vec<&RawValue>>(at.get())
                .ok()?
                .get(index)?,
        };
    }
    let start = at.get().as_ptr() as usize - text.as_ptr() as usize;
    Some(start..start + at.get().len())
}

/// Every value of a JSON text with its span, from serde_json's `RawValue`s as [`json_span`]
/// finds one: what a `Node` tree read by serde_json's parser would cost. Returns the number of
/// values (the keys would need a scan back from their values).
fn json_spans(text: &str, raw: &RawValue) -> usize {
    let start = raw.get().as_ptr() as usize - text.as_ptr() as usize;
    let span = start..start + raw.get().len();
    std::hint::black_box(span);
    let children: Vec<&RawValue> = match raw.get().as_bytes().first() {
        Some(b'{') => serde_json::from_str::<BTreeMap<String, &RawValue>>(raw.get())
            .map(|map| map.into_values().collect())
            .unwrap_or_default(),
        Some(b'[') => serde_json::from_str(raw.get()).unwrap_or_default(),
        _ => {
            let leaf = serde_json::from_str::<serde_json::Value>(raw.get());
            std::hint::black_box(leaf.is_ok());
            Vec::new()
        }
    };
    1 + children
        .into_iter()
        .map(|child| json_spans(text, child))
        .sum::<usize>()
}

/// The scene read by toml's deserializer; the checks placed by toml's `DeTable`.
fn toml_only(text: &str) -> Outcome {
    match toml::from_str::<Scene>(text) {
        Err(error) => Outcome::from_toml(text, &error),
        Ok(scene) => match check(&scene) {
            Ok(()) => Outcome::accepted(),
            Err(refusal) => {
                let span = toml_span(text, &refusal.path);
                Outcome::refused(text, refusal, span)
            }
        },
    }
}

/// The key path serde_path_to_error found, without its mark for the root.
fn spte_path<E>(error: &serde_path_to_error::Error<E>) -> String {
    match error.path().to_string().as_str() {
        "." => String::new(),
        path => path.to_owned(),
    }
}

/// toml's deserializer wrapped in serde_path_to_error.
fn toml_spte(text: &str) -> Outcome {
    let deserializer = match toml::Deserializer::parse(text) {
        Ok(deserializer) => deserializer,
        Err(error) => return Outcome::from_toml(text, &error),
    };
    match serde_path_to_error::deserialize::<_, Scene>(deserializer) {
        Err(error) => Outcome {
            path: spte_path(&error),
            ..Outcome::from_toml(text, error.inner())
        },
        Ok(scene) => match check(&scene) {
            Ok(()) => Outcome::accepted(),
            Err(refusal) => {
                let span = toml_span(text, &refusal.path);
                Outcome::refused(text, refusal, span)
            }
        },
    }
}

/// The scene read by serde_json; the checks have no place (its `Value` has no spans).
fn json_only(text: &str) -> Outcome {
    match serde_json::from_str::<Scene>(text) {
        Err(error) => Outcome::from_json(&error),
        Ok(scene) => match check(&scene) {
            Ok(()) => Outcome::accepted(),
            Err(refusal) => Outcome::refused(text, refusal, None),
        },
    }
}

/// serde_json wrapped in serde_path_to_error.
fn json_spte(text: &str) -> Outcome {
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let scene = match serde_path_to_error::deserialize::<_, Scene>(&mut deserializer) {
        Ok(scene) => scene,
        Err(error) => {
            return Outcome {
                path: spte_path(&error),
                ..Outcome::from_json(error.inner())
            }
        }
    };
    if let Err(error) = deserializer.end() {
        return Outcome::from_json(&error);
    }
    match check(&scene) {
        Ok(()) => Outcome::accepted(),
        Err(refusal) => Outcome::refused(text, refusal, None),
    }
}

/// A way of reading a scene: its name, the format, the reader.
type Approach = (&'static str, bool, fn(&str) -> Outcome);

const APPROACHES: [Approach; 6] = [
    ("contopt TOML", true, contopt_toml),
    ("toml", true, toml_only),
    ("spte+toml", true, toml_spte),
    ("contopt JSON", false, contopt_json),
    ("serde_json", false, json_only),
    ("spte+json", false, json_spte),
];

/// The cell of the table for `outcome` of `mistake` read from `case`.
fn cell(mistake: &Mistake, case: &Case, outcome: &Outcome) -> String {
    if mistake.correct {
        return if outcome.accepted { "ok" } else { "REFUSED" }.into();
    }
    if outcome.accepted {
        return "acc".into();
    }
    let place = match (case.at, outcome.place) {
        (None, _) => '·',
        (Some(at), Some(place)) if line_column(&case.text, at) == place => '=',
        (Some(at), Some((line, _))) if line_column(&case.text, at).0 == line => '~',
        _ => '-',
    };
    let path = match (mistake.path, outcome.path.as_str()) {
        ("", _) => '·',
        (expected, found) if expected == found => 'P',
        (expected, found)
            if !found.is_empty()
                && (expected.starts_with(found) || found.starts_with(expected)) =>
        {
            'p'
        }
        _ => '-',
    };
    let says = |words: &[&str], mark| match words {
        [] => '·',
        _ if words.iter().any(|word| outcome.message.contains(word)) => mark,
        _ => '-',
    };
    let value = says(mistake.value, 'V');
    let allowed = says(mistake.allowed, 'A');
    format!("{place}{path}{value}{allowed}")
}

/// The best time of `batches` runs of `repetitions` calls of `read`, per call \[µs\].
fn time<R>(repetitions: usize, mut read: impl FnMut() -> R) -> f64 {
    const BATCHES: usize = 9;
    let mut best = f64::INFINITY;
    for _ in 0..BATCHES {
        let start = Instant::now();
        for _ in 0..repetitions {
            std::hint::black_box(read());
        }
        best = best.min(start.elapsed().as_secs_f64() / repetitions as f64);
    }
    best * 1e6
}

/// The heap bytes that `make`'s value keeps while it is held.
fn kept<R>(make: impl FnOnce() -> R) -> usize {
    let before = LIVE_BYTES.load(Ordering::Relaxed);
    let value = make();
    let after = LIVE_BYTES.load(Ordering::Relaxed);
    drop(value);
    after.saturating_sub(before)
}

/// The bundled scenes: `paper-table2.toml` and the largest.
fn bundled() -> Vec<(String, String)> {
    let folder = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenes");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&folder)
        .expect("the scenes folder")
        .filter_map(|entry| entry.ok().map(|entry| entry.path()))
        .filter(|path| path.extension().is_some_and(|e| e == "toml"))
        .collect();
    files.sort_by_key(|path| std::fs::metadata(path).map_or(0, |m| m.len()));
    let largest = files.last().cloned().expect("a bundled scene");
    [folder.join("paper-table2.toml"), largest]
        .into_iter()
        .map(|path| {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            (
                name,
                std::fs::read_to_string(&path).expect("a readable scene"),
            )
        })
        .collect()
}

fn print_errors() {
    let mistakes = mistakes();
    println!("Errors: where = / ~ / -, P path, V value, A what it must be (see the source)\n");
    print!("| {:<36} |", "mistake");
    for (name, _, _) in APPROACHES {
        print!(" {name:<12} |");
    }
    println!();
    print!("| {:-<36} |", "");
    for _ in APPROACHES {
        print!(" {:-<12} |", "");
    }
    println!();
    let mut messages = Vec::new();
    for mistake in &mistakes {
        print!("| {:<36} |", mistake.what);
        for (name, is_toml, read) in APPROACHES {
            let case = if is_toml {
                &mistake.toml
            } else {
                &mistake.json
            };
            let outcome = read(&case.text);
            print!(" {:<12} |", cell(mistake, case, &outcome));
            messages.push((mistake.what, name, outcome.render()));
        }
        println!();
    }
    println!("\nThe messages (line:column key path: message):");
    let mut last = "";
    for (what, name, message) in messages {
        if what != last {
            println!("\n{what}:");
            last = what;
        }
        let mut short: String = message.chars().take(150).collect();
        if short.len() < message.len() {
            short.push('…');
        }
        println!("  {name:<12} {short}");
    }
    let out_of_range = &mistakes[4];
    let path = "contact.zone.cell_mm[0]";
    let json = json_span(&out_of_range.json.text, path);
    let place = json.map(|span| line_column(&out_of_range.json.text, span.start));
    println!(
        "\nA JSON span recovered from serde_json's RawValue offsets: {path} at {place:?} \
         (contopt JSON: {:?})",
        contopt_json(&out_of_range.json.text).place
    );
}

fn print_times() {
    const REPETITIONS: usize = 3000;
    let mut inputs = bundled();
    inputs.push(("sample (typed)".into(), SAMPLE_TOML.into()));
    println!(
        "\nTimes: the best of 9 runs of {REPETITIONS} reads, per read [µs]; \
         the JSON is the TOML converted"
    );
    print!("| {:<44} |", "approach");
    for (name, text) in &inputs {
        print!(" {:>22} |", format!("{name} ({} B)", text.len()));
    }
    println!();
    print!("| {:-<44} |", "");
    for _ in &inputs {
        print!(" {:->22} |", ":");
    }
    println!();
    type Value = serde_json::Value;
    type Reader = fn(&str, &str, bool) -> bool;
    let rows: [(&str, Reader); 10] = [
        ("contopt_input TOML: parse to Node", |toml, _, _| {
            Node::parse_toml(toml).is_ok()
        }),
        (
            "contopt_input TOML: Node, then deserialise",
            |toml, _, typed| {
                let node = Node::parse_toml(toml).unwrap();
                match typed {
                    true => node.deserialize::<Scene>().is_ok(),
                    false => node.deserialize::<Value>().is_ok(),
                }
            },
        ),
        ("toml: DeTable::parse", |toml, _, _| {
            DeTable::parse(toml).is_ok()
        }),
        ("toml: from_str", |toml, _, typed| match typed {
            true => toml::from_str::<Scene>(toml).is_ok(),
            false => toml::from_str::<Value>(toml).is_ok(),
        }),
        ("serde_path_to_error + toml", |toml, _, typed| {
            let de = toml::Deserializer::parse(toml).unwrap();
            match typed {
                true => serde_path_to_error::deserialize::<_, Scene>(de).is_ok(),
                false => serde_path_to_error::deserialize::<_, Value>(de).is_ok(),
            }
        }),
        ("contopt_input JSON: parse to Node", |_, json, _| {
            Node::parse_json(json).is_ok()
        }),
        (
            "contopt_input JSON: Node, then deserialise",
            |_, json, typed| {
                let node = Node::parse_json(json).unwrap();
                match typed {
                    true => node.deserialize::<Scene>().is_ok(),
                    false => node.deserialize::<Value>().is_ok(),
                }
            },
        ),
        ("serde_json: from_str", |_, json, typed| match typed {
            true => serde_json::from_str::<Scene>(json).is_ok(),
            false => serde_json::from_str::<Value>(json).is_ok(),
        }),
        ("serde_json: RawValue walk (spans)", |_, json, _| {
            let root: &RawValue = serde_json::from_str(json).unwrap();
            json_spans(json, root) > 0
        }),
        ("serde_path_to_error + serde_json", |_, json, typed| {
            let mut de = serde_json::Deserializer::from_str(json);
            match typed {
                true => serde_path_to_error::deserialize::<_, Scene>(&mut de).is_ok(),
                false => serde_path_to_error::deserialize::<_, Value>(&mut de).is_ok(),
            }
        }),
    ];
    let jsons: Vec<String> = inputs
        .iter()
        .map(|(_, toml)| {
            let value: Value = toml::from_str(toml).expect("a bundled scene is TOML");
            serde_json::to_string_pretty(&value).expect("JSON")
        })
        .collect();
    for (name, read) in rows {
        print!("| {name:<44} |");
        for ((input, toml), json) in inputs.iter().zip(&jsons) {
            let typed = input.starts_with("sample");
            assert!(read(toml, json, typed), "{name} cannot read {input}");
            let micros = time(REPETITIONS, || read(toml, json, typed));
            print!(" {micros:>22.1} |");
        }
        println!();
    }
    println!(
        "\n(Deserialised into serde_json::Value for the bundled scenes, into the example's typed"
    );
    println!("Scene for its sample. Built with --release; other work shares the machine.)");
    let (name, toml) = &inputs[1];
    let json = &jsons[1];
    println!(
        "\nMemory kept by the tree of {name} ({} B TOML, {} B JSON) [bytes]:",
        toml.len(),
        json.len()
    );
    let trees: [(&str, usize); 5] = [
        (
            "contopt_input Node from TOML",
            kept(|| Node::parse_toml(toml)),
        ),
        (
            "contopt_input Node from JSON",
            kept(|| Node::parse_json(json)),
        ),
        (
            "toml DeTable (borrows the text)",
            kept(|| DeTable::parse(toml)),
        ),
        ("toml::Table", kept(|| toml::from_str::<toml::Table>(toml))),
        (
            "serde_json::Value",
            kept(|| serde_json::from_str::<Value>(json)),
        ),
    ];
    for (what, bytes) in trees {
        println!("  {what:<34} {bytes:>8}");
    }
}

fn main() {
    print_errors();
    print_times();
}
