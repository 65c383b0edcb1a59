//! Scene files: a contact problem, its solver and optionally the optimisation of its initial
//! gap, written in TOML or JSON, with a sweep over one parameter (L₁ in the paper's tables).
//!
//! [`Scene::load`] reads and checks a file: unknown or missing keys and impossible values are
//! [`SceneError`]s that name the file, the line and the key; reading builds no finite-element
//! body. [`Scene::cases`] expands the sweep, [`Case::run`] solves one case into a
//! [`CaseReport`], the unit of `result.json` (its schema is in the book's chapter "Scene files
//! and the `contopt` command"), and [`Scene::run`] runs them all, building each distinct set
//! of bodies once. [`geometry`] builds the finite-element bodies of a punch on a base.

mod budget;
mod build;
mod bundled;
mod envelope;
pub mod geometry;
mod reference;
mod report;
mod roller;
mod run;
mod spec;
mod subsurface;

pub use bundled::BUNDLED;

/// The methods of a case that contain contact solves, as they report to an observer: the
/// optimisation loop of §3.2 and the Fujiwara–Kawase search of a roller's envelope. Every other
/// method an observer sees is a contact solver.
pub const OUTER_METHODS: [&str; 2] = ["optimisation", envelope::TUNE_METHOD];
pub use report::{
    BodyStresses, CaseReport, EnvelopeCaseReport, IterationRow, PointReport, ReferenceCurve,
    Report, RollerReport, SubsurfaceReport, TunedProfile, PENETRATION_WARNING,
};
pub use run::Run;
pub use spec::{
    BaseSpec, BodySpec, ControllerSpec, EnvelopeSpec, Indenter, MaterialSpec, ModeSpec, OmegaVSpec,
    Optimise, OutputSpec, Problem, PunchOnBaseSpec, RigidLoad, SectionSpec, SolverSpec,
    SubsurfaceSpec, Sweep,
};

use std::path::{Path, PathBuf};

/// The largest scene file \[bytes\]: a scene is a page of settings, not data.
pub const MAX_TEXT_BYTES: u64 = 1_000_000;
/// The deepest nesting of tables and arrays in a scene (the parsers recurse on it).
pub const MAX_NESTING: usize = 32;
/// The most cases one scene may have (sweep values or `[[case]]`s).
pub const MAX_CASES: usize = 10_000;
/// 2⁵³: below it an f64 holds every whole number exactly, so a swept float becomes an integer
/// key's value without loss.
const MAX_EXACT_INTEGER: f64 = 9_007_199_254_740_992.0;

/// The text of `file`, read no further than one byte past [`MAX_TEXT_BYTES`] (so that
/// `/dev/zero` ends): a caller refuses text longer than the limit.
pub(crate) fn read_at_most(file: std::fs::File) -> std::io::Result<String> {
    let mut text = String::new();
    std::io::Read::read_to_string(
        &mut std::io::Read::take(file, MAX_TEXT_BYTES + 1),
        &mut text,
    )?;
    Ok(text)
}

/// Refuses text that is too long or nested too deeply to be a scene, before it is parsed.
fn check_text(text: &str) -> Result<(), String> {
    if text.len() as u64 > MAX_TEXT_BYTES {
        return Err(format!(
            "the scene is over {MAX_TEXT_BYTES} bytes: a scene holds settings, not data"
        ));
    }
    let (mut depth, mut deepest, mut quote) = (0usize, 0usize, None);
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        match (quote, c) {
            (Some('"'), '\\') => {
                chars.next();
            }
            (Some(q), c) if c == q => quote = None,
            (Some(_), _) => {}
            (None, '"' | '\'') => quote = Some(c),
            (None, '#') => {
                chars.by_ref().find(|&c| c == '\n');
            }
            (None, '[' | '{') => {
                depth += 1;
                deepest = deepest.max(depth);
            }
            (None, ']' | '}') => depth = depth.saturating_sub(1),
            _ => {}
        }
    }
    if deepest > MAX_NESTING {
        return Err(format!(
            "tables and arrays are nested {deepest} deep, at most {MAX_NESTING}"
        ));
    }
    Ok(())
}

/// The longest scene name \[bytes\] (a file name's limit on common file systems).
pub const MAX_NAME_BYTES: usize = 255;

/// A scene's name names its results folder: a plain file name, nothing that leads elsewhere.
pub fn check_name(name: &str) -> Result<(), String> {
    let reason = if name.is_empty() {
        "is empty"
    } else if name.len() > MAX_NAME_BYTES {
        "is longer than 255 bytes"
    } else if name == "." || name == ".." {
        "is a reference to a folder"
    } else if name.contains(['/', '\\']) {
        "holds a path separator"
    } else if name.chars().any(char::is_control) {
        "holds a control character"
    } else {
        return Ok(());
    };
    Err(format!(
        "{reason}; the name names the results folder and must be a plain file name"
    ))
}

/// What can go wrong with a scene.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// The file cannot be read.
    #[error("{file}: {source}")]
    Io {
        /// The file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// Syntax, an unknown or missing key, or a value of the wrong type or out of range.
    #[error("{file}: {message}")]
    Parse {
        /// The file.
        file: PathBuf,
        /// The parser's message, with line, column and key.
        message: String,
    },
    /// A value the bodies, solver or optimisation reject.
    #[error("{file}{}: {case}{key}: {source}", line.map_or(String::new(), |l| format!(":{l}")))]
    Invalid {
        /// The file.
        file: PathBuf,
        /// The line that sets the rejected field, when it can be found.
        line: Option<usize>,
        /// The case (sweep label and a space, or empty).
        case: String,
        /// The scene key of the offending section.
        key: String,
        /// The library's error, which names the field and the value.
        source: Box<contopt_core::Error>,
    },
}

/// The file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML (`.toml`).
    Toml,
    /// JSON (`.json`).
    Json,
}

/// A scene as written, before the sweep is expanded.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Where it came from (for messages).
    pub file: PathBuf,
    /// The typed scene.
    pub spec: spec::SceneSpec,
    /// The same as a tree of values, which the sweep edits.
    tree: serde_json::Value,
    /// The text, to find the line of a rejected value.
    text: std::sync::Arc<str>,
}

/// One case of a scene: the scene with the sweep's value put in.
#[derive(Clone, Debug)]
pub struct Case {
    /// `key = value` of the sweep, or the scene's name.
    pub label: String,
    /// The swept parameter and its value (empty without a sweep).
    pub params: std::collections::BTreeMap<String, f64>,
    /// The case's scene.
    pub spec: spec::SceneSpec,
    file: PathBuf,
    text: std::sync::Arc<str>,
}

impl Scene {
    /// Reads and checks a scene file (TOML, or JSON when the name ends in `.json`).
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        let io = |source| SceneError::Io {
            file: path.to_owned(),
            source,
        };
        let text = read_at_most(std::fs::File::open(path).map_err(io)?).map_err(io)?;
        let format = if path.extension().is_some_and(|e| e == "json") {
            Format::Json
        } else {
            Format::Toml
        };
        Self::parse(&text, format, path)
    }

    /// The bundled scene `name` (one of [`BUNDLED`]), as if read from `scenes/<name>.toml`.
    pub fn bundled(name: &str) -> Result<Self, SceneError> {
        let file = Path::new("scenes").join(format!("{name}.toml"));
        match BUNDLED.iter().find(|(n, _)| *n == name) {
            Some((_, text)) => Self::parse(text, Format::Toml, &file),
            None => Err(SceneError::Parse {
                file,
                message: format!(
                    "no bundled scene {name:?}; the bundled scenes are {}",
                    BUNDLED
                        .iter()
                        .map(|(n, _)| *n)
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            }),
        }
    }

    /// Parses and checks scene text; `file` names it in messages.
    pub fn parse(text: &str, format: Format, file: &Path) -> Result<Self, SceneError> {
        let parse = |message: String| SceneError::Parse {
            file: file.to_owned(),
            message: locate_unknown(text, message),
        };
        check_text(text).map_err(|message| SceneError::Parse {
            file: file.to_owned(),
            message,
        })?;
        let (spec, tree) = match format {
            Format::Toml => {
                let spec: spec::SceneSpec =
                    toml::from_str(text).map_err(|e| parse(e.to_string()))?;
                let value: toml::Value = toml::from_str(text).map_err(|e| parse(e.to_string()))?;
                let tree = serde_json::to_value(value).map_err(|e| parse(e.to_string()))?;
                (spec, tree)
            }
            Format::Json => {
                let spec: spec::SceneSpec =
                    serde_json::from_str(text).map_err(|e| parse(e.to_string()))?;
                let tree = serde_json::from_str(text).map_err(|e| parse(e.to_string()))?;
                (spec, tree)
            }
        };
        check_name(&spec.name).map_err(|reason| SceneError::Parse {
            file: file.to_owned(),
            message: format!("name {:?}: {reason}", spec.name),
        })?;
        let scene = Self {
            file: file.to_owned(),
            spec,
            tree,
            text: text.into(),
        };
        // Each distinct problem is checked once (without building a finite-element body);
        // cases that differ only outside it check the rest.
        let mut checked = std::collections::HashSet::new();
        for case in scene.cases()? {
            if checked.insert(case.problem_key()) {
                case.check()?;
            } else {
                case.check_memory()?;
                case.check_without_bodies()?;
            }
        }
        Ok(scene)
    }

    /// The cases: one per `[[case]]`, one per value of the sweep, or the scene itself.
    pub fn cases(&self) -> Result<Vec<Case>, SceneError> {
        if !self.spec.case.is_empty() {
            return self.named_cases();
        }
        match &self.spec.sweep {
            Some(sweep) => self.swept_cases(sweep),
            None => Ok(vec![Case {
                label: self.spec.name.clone(),
                params: Default::default(),
                spec: self.spec.clone(),
                file: self.file.clone(),
                text: self.text.clone(),
            }]),
        }
    }

    /// One case per value of the sweep: the scene with `sweep.key` set to it (an integer where
    /// the scene has one there, a mesh's `elements`; the value must then be whole).
    fn swept_cases(&self, sweep: &Sweep) -> Result<Vec<Case>, SceneError> {
        let parse = |message: String| SceneError::Parse {
            file: self.file.clone(),
            message,
        };
        if sweep.values.is_empty() {
            return Err(parse("sweep.values: give at least one value".into()));
        }
        if sweep.values.len() > MAX_CASES {
            return Err(parse(format!(
                "sweep.values: {} values, at most {MAX_CASES} cases in one scene",
                sweep.values.len()
            )));
        }
        // Each case edits its own copy of the tree, without the sweep (whose values would make
        // the copies grow with the square of their number).
        let mut base = self.tree.clone();
        if let Some(map) = base.as_object_mut() {
            map.remove("sweep");
        }
        let name = short_name(&base, &sweep.key);
        let name = name.as_str();
        sweep
            .values
            .iter()
            .map(|value| {
                let mut tree = base.clone();
                set_number(&mut tree, &sweep.key, value).map_err(parse)?;
                let spec: spec::SceneSpec = serde_json::from_value(tree)
                    .map_err(|e| parse(format!("sweep value {value} for `{}`: {e}", sweep.key)))?;
                let number = value.as_f64().unwrap_or(f64::NAN);
                Ok(Case {
                    label: format!("{name} = {number}"),
                    params: [(name.to_string(), number)].into_iter().collect(),
                    spec,
                    file: self.file.clone(),
                    text: self.text.clone(),
                })
            })
            .collect()
    }
}

/// The name of the dotted `key` in labels and parameters: its last part, or as many of its last
/// parts as tell it from the other keys of `tree` (`l1_mm`; `punch.radius_mm` where the base
/// and Ω_v have a `radius_mm` too).
fn short_name(tree: &serde_json::Value, key: &str) -> String {
    fn leaves(v: &serde_json::Value, path: &str, out: &mut Vec<String>) {
        match v {
            serde_json::Value::Object(map) => {
                for (k, child) in map {
                    leaves(child, &format!("{path}.{k}"), out);
                }
            }
            _ => out.push(path.to_string()),
        }
    }
    let mut all = vec![];
    leaves(tree, "", &mut all);
    let parts: Vec<&str> = key.split('.').collect();
    (1..parts.len())
        .map(|k| parts[parts.len() - k..].join("."))
        .find(|name| {
            let suffix = format!(".{name}");
            all.iter().filter(|leaf| leaf.ends_with(&suffix)).count() <= 1
        })
        .unwrap_or_else(|| key.to_string())
}

/// Sets the number at the dotted `key` of `tree` to `value`: as an integer where the scene has
/// an integer (a whole value only), else as it is.
fn set_number(
    tree: &mut serde_json::Value,
    key: &str,
    value: &serde_json::Number,
) -> Result<(), String> {
    let mut node = tree;
    for part in key.split('.') {
        node = node
            .get_mut(part)
            .filter(|n| !n.is_null())
            .ok_or_else(|| format!("sweep.key `{key}`: the scene has no `{part}` there"))?;
    }
    if !node.is_number() {
        return Err(format!("sweep.key `{key}` is not a number in the scene"));
    }
    let whole = value
        .as_f64()
        .filter(|v| v.fract() == 0.0 && v.abs() < MAX_EXACT_INTEGER);
    *node = match (node.is_f64(), value.is_f64(), whole) {
        (false, true, Some(v)) => serde_json::json!(v as i64),
        (false, true, None) => {
            return Err(format!(
                "sweep value {value} for `{key}`: the scene has an integer there, so give whole \
                 numbers"
            ))
        }
        _ => serde_json::Value::Number(value.clone()),
    };
    Ok(())
}

impl Scene {
    /// The `[[case]]` list: each case the scene with its keys replaced (a key must exist in the
    /// scene; the value may be of any kind the schema takes there).
    fn named_cases(&self) -> Result<Vec<Case>, SceneError> {
        let parse = |message: String| SceneError::Parse {
            file: self.file.clone(),
            message,
        };
        if self.spec.sweep.is_some() {
            return Err(parse("give either a [sweep] or [[case]]s, not both".into()));
        }
        if self.spec.case.len() > MAX_CASES {
            return Err(parse(format!(
                "case: {} cases, at most {MAX_CASES} in one scene",
                self.spec.case.len()
            )));
        }
        let mut base = self.tree.clone();
        if let Some(map) = base.as_object_mut() {
            map.remove("case");
        }
        self.spec
            .case
            .iter()
            .map(|case| {
                let mut tree = base.clone();
                let mut params = std::collections::BTreeMap::new();
                for (key, value) in &case.set {
                    let mut node = &mut tree;
                    for part in key.split('.') {
                        node = node.get_mut(part).ok_or_else(|| {
                            parse(format!(
                                "case `{}`: the scene has no `{key}` (no `{part}` there)",
                                case.label
                            ))
                        })?;
                    }
                    *node = value.clone();
                    if let Some(v) = value.as_f64() {
                        params.insert(short_name(&base, key), v);
                    }
                }
                let spec: spec::SceneSpec = serde_json::from_value(tree)
                    .map_err(|e| parse(format!("case `{}`: {e}", case.label)))?;
                Ok(Case {
                    label: case.label.clone(),
                    params,
                    spec,
                    file: self.file.clone(),
                    text: self.text.clone(),
                })
            })
            .collect()
    }
}

impl Case {
    /// The error of a section of this case.
    fn invalid(&self, key: &str, source: contopt_core::Error) -> SceneError {
        let line = match &source {
            contopt_core::Error::InvalidInput { field, .. } => {
                line_of(&self.text, field.rsplit('.').next().unwrap_or(field))
            }
            _ => None,
        };
        SceneError::Invalid {
            line,
            file: self.file.clone(),
            case: if self.label == self.spec.name {
                String::new()
            } else {
                format!("[{}] ", self.label)
            },
            key: key.to_string(),
            source: Box::new(source),
        }
    }
}

/// The first line (from 1) that sets a key named `name` or `name_<unit>` (`nu`, `e` → `e_mpa`),
/// in TOML (`name =`) or JSON (`"name":`).
fn line_of(text: &str, name: &str) -> Option<usize> {
    line_of_from(text, name, 1)
}

/// [`line_of`] from line `first` (from 1) on.
fn line_of_from(text: &str, name: &str, first: usize) -> Option<usize> {
    let is_key_char = |c: char| c.is_ascii_alphanumeric() || c == '_';
    text.lines()
        .skip(first.saturating_sub(1))
        .position(|line| {
            line.match_indices(name).any(|(at, _)| {
                let before = line[..at].chars().next_back();
                if before.is_some_and(is_key_char) {
                    return false;
                }
                let mut rest = &line[at + name.len()..];
                if let Some(unit) = rest.strip_prefix('_') {
                    rest = unit.trim_start_matches(is_key_char);
                }
                let rest = rest.trim_start_matches('"').trim_start();
                rest.starts_with('=') || rest.starts_with(':')
            })
        })
        .map(|i| i + first.max(1))
}

/// Adds the line of an unknown key to a parser message that gives only its table's line (a
/// tagged section such as `[problem]` is read as a whole).
fn locate_unknown(text: &str, message: String) -> String {
    // The parser's line: the table's, or the inline table's that holds the key.
    let reported = message
        .split("at line ")
        .nth(1)
        .and_then(|rest| {
            rest.split(|c: char| !c.is_ascii_digit())
                .next()?
                .parse()
                .ok()
        })
        .unwrap_or(1);
    let key = message
        .split("unknown field `")
        .nth(1)
        .and_then(|rest| rest.split('`').next());
    let line = |k| line_of_from(text, k, reported).or_else(|| line_of(text, k));
    if let Some((k, line)) = key.and_then(|k| line(k).map(|l| (k, l))) {
        return format!("{message}\n(`{k}` is set at line {line})");
    }
    // `invalid type: string "stiff", expected f64`: find the value's line and key.
    let value = message.split("invalid type: ").nth(1).and_then(|rest| {
        let rest = rest.split_once(' ')?.1;
        let quote = rest.chars().next()?;
        let end = rest[1..].find(quote)? + 1;
        Some(if quote == '"' {
            &rest[..=end]
        } else {
            &rest[1..end]
        })
    });
    let found = value.and_then(|v| {
        text.lines().enumerate().find_map(|(i, line)| {
            let (key, rest) = line.split_once(['=', ':'])?;
            rest.trim_start()
                .starts_with(v)
                .then(|| (key.trim().trim_matches('"').to_string(), i + 1))
        })
    });
    match found {
        Some((k, line)) => format!("{message}\n(`{k}` is set at line {line})"),
        None if message.contains("expected struct variant") => {
            // `analysis = "plane_stress"`: a plane analysis is a table with its thickness.
            let line = line_of(text, "analysis").map_or(String::new(), |l| format!(" at line {l}"));
            format!(
                "{message}\n(`analysis`{line}: a plane analysis gives its thickness, \
                 `analysis = {{ plane_stress = {{ thickness_mm = 10.0 }} }}`)"
            )
        }
        None if message.contains("expected map with a single key") => format!(
            "{message}\n(a choice takes one key: `load = {{ pressure_mpa = 100.0 }}`, \
             `analysis = {{ plane_stress = {{ thickness_mm = 10.0 }} }}`)"
        ),
        None => message,
    }
}
