//! Scene files: a contact problem composed of its parts — the contact zone, two bodies of any
//! kinds the physics allows, the gap and load that bring them together, the solver, the design
//! of the gap, and the outputs — written in TOML or JSON, with a sweep over one key or a list
//! of cases.
//!
//! [`Scene::load`] reads a file and checks every case as its run would, without solving or
//! building a finite-element body: every error names the file, line and column, the key, the
//! value and what it must be ([`SceneError`]). [`Scene::run`] runs the cases, building each
//! distinct pair of bodies once, into [`CaseReport`]s, the unit of `result.json`
//! ([`contopt_results`]).
//!
//! The kinds a scene may name — bodies, zones, gaps, design methods, contact solvers — are
//! those of a [`Registry`]: [`Registry::standard`] has the library's, and a crate of one's own
//! adds its own and reads scenes through it ([`Registry::load`]), without editing this crate.
//!
//! A case runs as one pipeline, each stage a module whose input is the previous one's output:
//! the **plan** (`plan/`: the checks, the zone's layout, the memory budget, the design chosen;
//! [`Memory`]), the **build** of its bodies ([`Built`], shared by the cases with equal keys,
//! on any number of threads), the **design** on the contact problem ([`Design`], given a
//! [`Context`], returning [`Designed`]; a bearing is one of them), and the **report**
//! (`report/`: from what the design found to the [`CaseReport`] — the figures, the model's
//! limits, the stresses and fields asked for; a bearing's lives are a stage of their own,
//! `lives.rs`, from its contacts' slice loads to the lives per ring, in hours and modified). The
//! kinds import only the small shared types below them (the zone, the gap, the load); no module
//! of the crate imports one that imports it.

mod bearing;
mod bearing_spec;
mod bodies;
mod build;
mod bundled;
mod cases;
mod chosen;
mod contact;
mod error;
mod gap;
mod lives;
mod load;
mod mesh_surface;
mod meshes;
mod methods;
pub mod parallel;
mod plan;
mod reference;
mod region;
mod registry;
mod report;
mod run;
mod spec;
mod subsurface;
mod zone;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use contopt_input::{Limits, Node};

pub use bearing_spec::{
    BearingLoadSpec, BearingObjective, BearingSpec, RacewaySpec, FREE_END_WEIGHT,
};
pub use bodies::{
    misplaced, own_surface, BodyKind, Carried, Direction, FeBase, FeBlock, FeMesh, FePunch,
    FreeEndsSpec, GroupLoad, GroupSupport, HalfSpaceBody, Placement, PunchLoad, Rigid, Side, Solid,
    SolidAxis, SolidLoad, SolidSupport, Support, Takes, WinklerBed,
};
pub use build::Built;
pub use bundled::{Bundled, BUNDLED};
pub use error::{Located, SceneError};
pub use gap::{Cylinder, Flat, FlatPunch, GapKind, Measured, RollerGap, Sphere};
pub use mesh_surface::{ChainEnd, FreeMotion, MeshPart, MeshSurface};
pub use meshes::{Imported, MeshFiles};
pub use methods::{
    BearingCrown, CaseView, Check, Circular, CircularSearch, Context, Design, Designed,
    EnvelopeSplit, Family, FujiwaraKawase, FujiwaraKawaseSearch, Gap, ProfileSearch,
};
pub use parallel::Ran;
pub use plan::{Memory, DEFAULT_MEMORY_LIMIT_BYTES};
pub use reference::{ClosedForm, Hertz, ReferenceCase};
pub use region::OmegaVSpec;
pub use registry::{Chosen, Registry, SolverKind};
pub use report::{sharp_edge_warning, MIN_CELLS_ACROSS, PENETRATION_WARNING};
pub use run::Run;
pub use spec::{CaseSpec, ContactSpec, LoadSpec, OptimisationSpec, OutputSpec};
pub use subsurface::{SectionSpec, SubsurfaceSpec};
pub use zone::{
    FacesZone, GridZone, Layout, MeshZone, Natural, RingsZone, StripsZone, Surface, ZoneKind,
};

pub use contopt_results::{CaseReport, Report};

use error::Locator;
use plan::Plan;

/// The largest scene file \[bytes\]: a scene is a page of settings, not data.
pub const MAX_TEXT_BYTES: u64 = 1_000_000;
/// The deepest nesting of tables and arrays in a scene.
pub const MAX_NESTING: usize = 32;
/// The most cases one scene may have (sweep values or `[[case]]`s).
pub const MAX_CASES: usize = 10_000;
/// The longest scene name \[bytes\] (a file name's limit on common file systems).
pub const MAX_NAME_BYTES: usize = 255;

/// The file formats.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// TOML (`.toml`).
    Toml,
    /// JSON (`.json`).
    Json,
}

/// A scene: its cases, each read and checked.
#[derive(Debug)]
pub struct Scene {
    /// Where it came from (for messages).
    pub file: PathBuf,
    /// Its name, which names its results folder.
    pub name: String,
    /// What it shows.
    pub description: String,
    cases: Vec<Case>,
}

/// One case of a scene: the scene with its sweep value or its `[[case]]` values put in, read
/// into typed settings and checked.
#[derive(Debug)]
pub struct Case {
    /// Its label in tables, files and charts (`L1 = 20 mm`, `ISO/TS 16281`; the scene's name
    /// when it is alone).
    pub label: String,
    /// The keys it changed from the scene (dotted paths) with their numbers.
    pub params: std::collections::BTreeMap<String, f64>,
    /// Its settings.
    pub spec: CaseSpec,
    locator: Locator,
    plan: Plan,
    /// The mesh files of the scene, read once for all its cases.
    meshes: Arc<MeshFiles>,
}

impl Registry {
    /// Reads and checks a scene file (TOML, or JSON when the name ends in `.json`), its kinds
    /// this registry's.
    pub fn load(&self, path: &Path) -> Result<Scene, SceneError> {
        let io = |source| SceneError::Io {
            file: path.to_owned(),
            source,
        };
        let file = std::fs::File::open(path).map_err(io)?;
        if !file.metadata().map_err(io)?.is_file() {
            return Err(io(std::io::Error::new(
                std::io::ErrorKind::InvalidInput,
                "not a regular file (a scene is a .toml or .json file)",
            )));
        }
        let text = read_at_most(file).map_err(io)?;
        let format = if path.extension().is_some_and(|e| e == "json") {
            Format::Json
        } else {
            Format::Toml
        };
        self.parse(&text, format, path)
    }

    /// The bundled scene `name` (one of [`BUNDLED`]), as if read from `scenes/<name>.toml`.
    pub fn bundled(&self, name: &str) -> Result<Scene, SceneError> {
        let file = Path::new("scenes").join(format!("{name}.toml"));
        match bundled::find(name) {
            Some(scene) => {
                let (text, tree) = read(scene.text, Format::Toml, &file)?;
                self.scene_of(text, tree, &file, bundled::meshes(scene, &file))
            }
            None => {
                let names: Vec<&str> = BUNDLED.iter().map(|b| b.name).collect();
                let locator =
                    Locator::new(&file, "".into(), Arc::new(Node::table::<&str>([])), None);
                Err(locator.at(
                    "",
                    format!(
                        "no bundled scene {name:?}; the bundled scenes are {}",
                        names.join(", ")
                    ),
                ))
            }
        }
    }

    /// The bundled scene `name` with `edits`: dotted keys and their TOML values
    /// (`("contact.zone.elements", Some("36"))`), or `None` to remove a key — a study of a
    /// bundled scene from Rust.
    pub fn bundled_with(
        &self,
        name: &str,
        edits: &[(&str, Option<&str>)],
    ) -> Result<Scene, SceneError> {
        let file = Path::new("scenes").join(format!("{name}.toml"));
        let scene = bundled::find(name).ok_or_else(|| {
            let locator = Locator::new(&file, "".into(), Arc::new(Node::table::<&str>([])), None);
            locator.at("", format!("no bundled scene {name:?}"))
        })?;
        self.edited(
            scene.text,
            Format::Toml,
            &file,
            edits,
            bundled::meshes(scene, &file),
        )
    }

    /// [`Registry::parse`] with `edits` made to the text's keys first (see
    /// [`Scene::bundled_with`]).
    pub fn parse_with(
        &self,
        text: &str,
        format: Format,
        file: &Path,
        edits: &[(&str, Option<&str>)],
    ) -> Result<Scene, SceneError> {
        self.edited(
            text,
            format,
            file,
            edits,
            MeshFiles::in_folder(&folder(file)),
        )
    }

    /// [`Registry::parse_with`] reading its meshes from `meshes`.
    fn edited(
        &self,
        text: &str,
        format: Format,
        file: &Path,
        edits: &[(&str, Option<&str>)],
        meshes: MeshFiles,
    ) -> Result<Scene, SceneError> {
        let (text, tree) = read(text, format, file)?;
        let mut tree = tree;
        let whole = Locator::new(file, text.clone(), Arc::new(tree.clone()), None);
        for (key, value) in edits {
            match value {
                None => {
                    let removed = match key.rsplit_once('.') {
                        Some(_) => None,
                        None => tree.remove(key),
                    };
                    if removed.is_none() {
                        return Err(whole.at(key, "an edit removes top-level keys only"));
                    }
                }
                Some(value) => {
                    let holder = Node::parse_toml(&format!("value = {value}"))
                        .map_err(|e| whole.at(key, format!("the edit's value: {e}")))?;
                    let node = holder.get("value").cloned().unwrap_or(holder);
                    tree.insert(key, node).map_err(|e| whole.input(e))?;
                }
            }
        }
        self.scene_of(text, tree, file, meshes)
    }

    /// Reads scene text and checks every case as its run would, without solving; `file`
    /// names it in messages and its folder is where the files a scene names are read.
    pub fn parse(&self, text: &str, format: Format, file: &Path) -> Result<Scene, SceneError> {
        let (text, tree) = read(text, format, file)?;
        self.scene_of(text, tree, file, MeshFiles::in_folder(&folder(file)))
    }

    /// The scene of a tree read from `text`, its bodies' meshes read from `meshes`.
    fn scene_of(
        &self,
        text: Arc<str>,
        tree: Node,
        file: &Path,
        meshes: MeshFiles,
    ) -> Result<Scene, SceneError> {
        let whole = Locator::new(file, text.clone(), Arc::new(tree.clone()), None);
        let inputs = cases::expand(tree, &whole)?;
        let single = inputs.len() == 1 && inputs[0].named.is_none();
        let meshes = Arc::new(meshes);
        let cases = inputs
            .into_iter()
            .map(|input| Case::prepare(input, file, &text, single, &meshes, self))
            .collect::<Result<Vec<_>, _>>()?;
        let first = &cases[0].spec;
        check_name(&first.name).map_err(|reason| {
            cases[0]
                .locator
                .at("name", format!("{:?} {reason}", first.name))
        })?;
        Ok(Scene {
            file: file.to_owned(),
            name: first.name.clone(),
            description: first.description.clone(),
            cases,
        })
    }
}

/// The text read into a tree within the scene's limits.
fn read(text: &str, format: Format, file: &Path) -> Result<(Arc<str>, Node), SceneError> {
    let limits = Limits {
        max_bytes: MAX_TEXT_BYTES,
        max_depth: MAX_NESTING,
    };
    let text: Arc<str> = text.into();
    let empty = Arc::new(Node::table::<&str>([]));
    let whole = Locator::new(file, text.clone(), empty, None);
    let tree = match format {
        Format::Toml => Node::parse_toml_with(&text, &limits),
        Format::Json => Node::parse_json_with(&text, &limits),
    }
    .map_err(|e| whole.input(e))?;
    Ok((text, tree))
}

impl Scene {
    /// Reads and checks a scene file (TOML, or JSON when the name ends in `.json`) with the
    /// library's kinds ([`Registry::load`] with one's own).
    pub fn load(path: &Path) -> Result<Self, SceneError> {
        Registry::standard().load(path)
    }

    /// The bundled scene `name` (one of [`BUNDLED`]), as if read from `scenes/<name>.toml`.
    pub fn bundled(name: &str) -> Result<Self, SceneError> {
        Registry::standard().bundled(name)
    }

    /// The bundled scene `name` with `edits`: dotted keys and their TOML values
    /// (`("contact.zone.elements", Some("36"))`), or `None` to remove a key — a study of a
    /// bundled scene from Rust.
    pub fn bundled_with(name: &str, edits: &[(&str, Option<&str>)]) -> Result<Self, SceneError> {
        Registry::standard().bundled_with(name, edits)
    }

    /// [`Scene::parse`] with `edits` made to the text's keys first (see
    /// [`Scene::bundled_with`]).
    pub fn parse_with(
        text: &str,
        format: Format,
        file: &Path,
        edits: &[(&str, Option<&str>)],
    ) -> Result<Self, SceneError> {
        Registry::standard().parse_with(text, format, file, edits)
    }

    /// Reads scene text and checks every case as its run would, without solving; `file`
    /// names it in messages and its folder is where the files a scene names are read.
    pub fn parse(text: &str, format: Format, file: &Path) -> Result<Self, SceneError> {
        Registry::standard().parse(text, format, file)
    }

    /// The cases, in the scene's order.
    pub fn cases(&self) -> &[Case] {
        &self.cases
    }

    /// A fingerprint of the scene as it runs: FNV-1a (64 bits, in hexadecimal) of every
    /// case's label, changed keys and resolved inputs, so that two copies of a scene that
    /// differ only in comments, layout or the order of keys agree, and any change to what is
    /// solved differs. Shards of a job array carry it, and their merge refuses to join two
    /// that differ.
    pub fn fingerprint(&self) -> String {
        let mut hash = FNV_OFFSET;
        for case in &self.cases {
            let text = serde_json::json!([case.label, case.params, case.input()]).to_string();
            for byte in text.bytes().chain([0]) {
                hash = (hash ^ u64::from(byte)).wrapping_mul(FNV_PRIME);
            }
        }
        format!("{hash:016x}")
    }
}

/// FNV-1a's offset basis (64 bits).
const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
/// FNV-1a's prime (64 bits).
const FNV_PRIME: u64 = 0x0000_0100_0000_01b3;

impl Case {
    /// Reads a case's tree into its settings and checks them ([`prepare`]).
    fn prepare(
        input: cases::CaseInput,
        file: &Path,
        text: &Arc<str>,
        single: bool,
        meshes: &Arc<MeshFiles>,
        registry: &Registry,
    ) -> Result<Self, SceneError> {
        let case_name = (!single).then(|| input.label.clone());
        let mut tree = input.tree;
        let whole = Locator::new(
            file,
            text.clone(),
            Arc::new(tree.clone()),
            case_name.clone(),
        );
        bearing::compose(&mut tree, &whole)?;
        let locator = Locator::new(file, text.clone(), Arc::new(tree), case_name);
        let spec = CaseSpec::read(&locator.tree, registry)
            .map_err(|e| cases::explain(&input.tables, locator.input(e)))?;
        let label = if single {
            spec.name.clone()
        } else {
            input.label
        };
        let plan = plan::plan(&spec, &locator, meshes)?;
        Ok(Self {
            label,
            params: input.params,
            spec,
            locator,
            plan,
            meshes: meshes.clone(),
        })
    }

    /// The memory the case needs, estimated by its check from what each part says of itself
    /// before anything is built, and the scene's limit it was checked against.
    pub fn memory(&self) -> plan::Memory {
        self.plan.memory
    }

    /// The case's zone with every size known, as its check laid it out (for a zone of
    /// imported meshes, [`MeshSurface`]: the points, the bodies' node counts).
    pub fn layout(&self) -> &Layout {
        &self.plan.layout
    }

    /// The folder of the scene file, where the files it names are read.
    pub fn dir(&self) -> &Path {
        self.locator.dir()
    }

    /// The case's inputs as resolved: its settings with every default written out (a
    /// bearing's without the contact and bodies it composes, so that they read back as a
    /// scene).
    pub fn input(&self) -> serde_json::Value {
        let mut value = serde_json::to_value(&self.spec).unwrap_or(serde_json::Value::Null);
        if let (Some(_), Some(table)) = (&self.spec.bearing, value.as_object_mut()) {
            table.remove("contact");
            table.remove("body");
        }
        value
    }
}

/// The folder of the scene file `file`, where the files it names are read.
fn folder(file: &Path) -> PathBuf {
    match file.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

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
