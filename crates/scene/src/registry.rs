//! The kinds a scene may name — bodies (`[[body]] kind`), contact zones (`contact.zone`),
//! initial gaps (`contact.gap`), designs (`[optimisation] method`) and contact solvers
//! (`solver`) — held in a [`Registry`] value. [`Registry::standard`] has the library's own; a
//! crate of one's own adds its kinds by type and name and hands the registry to the scene
//! reader ([`Registry::load`], [`Registry::parse`]) and to the command
//! line (`contopt_cli::main_with`), without editing this crate:
//!
//! ```
//! use contopt_scene::{Registry, WinklerBed};
//!
//! // A registry that knows the library's kinds and a bed under a second name.
//! let registry = Registry::standard().with_body::<WinklerBed>("springs");
//! assert!(registry.body_kinds().any(|name| name == "springs"));
//! ```
//!
//! A kind's name is written once, where it is registered; a scene spells a kind in any of the
//! three ways of [`contopt_input`] (`"rigid"`, `{ kind = "rigid", … }`,
//! `{ rigid = { … } }`), and an unknown name is refused at its place with the registered
//! names. A kind is read from its settings with serde (its own `Deserialize`, with its own
//! defaults), and written back into `result.json` with its `Serialize`.

use std::fmt;
use std::marker::PhantomData;
use std::sync::Arc;

use contopt_contact::{ContactSolver, SolverSettings};
use contopt_input::{InputError, Node, Value};
use contopt_optimise::OptimisationMethod;
use serde::de::DeserializeOwned;
use serde::Serialize;

use crate::bodies::{
    BodyKind, FeBase, FeBlock, FeMesh, FePunch, HalfSpaceBody, Rigid, Solid, WinklerBed,
};
pub use crate::chosen::Chosen;
use crate::gap::{Cylinder, Flat, FlatPunch, GapKind, Measured, RollerGap, Sphere};
use crate::methods::{CircularSearch, Design, EnvelopeSplit, FujiwaraKawaseSearch, Gap};
use crate::zone::{FacesZone, GridZone, MeshZone, RingsZone, StripsZone, ZoneKind};

/// The key of a table that names its kind.
const KIND_KEY: &str = "kind";

/// A contact solver as a scene names it: settings that build the solver.
pub trait SolverKind: Send + Sync {
    /// The solver, its settings checked.
    fn build(&self) -> contopt_core::Result<Box<dyn ContactSolver>>;
}

impl SolverKind for SolverSettings {
    fn build(&self) -> contopt_core::Result<Box<dyn ContactSolver>> {
        SolverSettings::build(self)
    }
}

/// A kind's node as the scene spells it.
struct Tagged<'n> {
    /// The name as written.
    name: &'n str,
    /// The whole node, and its path as errors render it (`body[1]`).
    whole: &'n Node,
    path: &'n str,
    /// The kind's own settings (the table less its `kind`, the table under the name, or an
    /// empty table for a bare name) and their path.
    content: Node,
    content_path: String,
}

/// Reads a kind from its tagged node.
type Reader<T> = Arc<dyn Fn(&'static str, &Tagged) -> Result<Chosen<T>, InputError> + Send + Sync>;

/// The registered kinds of one sort, in the order of registration.
struct Kinds<T: ?Sized> {
    /// The sort in messages (`body kind`).
    what: &'static str,
    entries: Vec<(&'static str, Reader<T>)>,
}

impl<T: ?Sized> Clone for Kinds<T> {
    fn clone(&self) -> Self {
        Self {
            what: self.what,
            entries: self.entries.clone(),
        }
    }
}

impl<T: ?Sized> Kinds<T> {
    fn new(what: &'static str) -> Self {
        Self {
            what,
            entries: vec![],
        }
    }

    /// Registers `read` under `name`, in place of a kind registered under it before.
    fn add(&mut self, name: &'static str, read: Reader<T>) {
        match self.entries.iter_mut().find(|(n, _)| *n == name) {
            Some(entry) => entry.1 = read,
            None => self.entries.push((name, read)),
        }
    }

    fn names(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.entries.iter().map(|(name, _)| *name)
    }

    /// Reads the kind at `node`, whose path errors render as `path`.
    fn read(&self, node: &Node, path: &str) -> Result<Chosen<T>, InputError> {
        let tagged = self.tagged(node, path)?;
        let (name, read) = self
            .entries
            .iter()
            .find(|(name, _)| *name == tagged.name)
            .ok_or_else(|| self.unknown(&tagged, node))?;
        read(name, &tagged)
    }

    /// How `node` names its kind: a bare name, a table whose only key is a registered name, or
    /// a table with a `kind` key.
    fn tagged<'n>(&self, node: &'n Node, path: &'n str) -> Result<Tagged<'n>, InputError> {
        let bare = |name: &'n str| Tagged {
            name,
            whole: node,
            path,
            content: Node::table::<&str>([]).with_span(node.span()),
            content_path: path.to_string(),
        };
        let entries = match node.value() {
            Value::String(name) => return Ok(bare(name)),
            Value::Table(entries) => entries,
            other => {
                return Err(InputError::new(
                    path,
                    node.span(),
                    format!(
                        "invalid type: {}, expected a {} ({})",
                        other.kind(),
                        self.what,
                        self.listed()
                    ),
                ))
            }
        };
        if let [(key, value)] = &entries[..] {
            if key.name() != KIND_KEY && self.names().any(|n| n == key.name()) {
                return Ok(Tagged {
                    name: key.name(),
                    whole: node,
                    path,
                    content: value.clone(),
                    content_path: join(path, key.name()),
                });
            }
        }
        let Some((_, tag)) = entries.iter().find(|(key, _)| key.name() == KIND_KEY) else {
            return Err(InputError::new(
                path,
                node.span(),
                format!(
                    "expected the name of a {} (one of {}) as a string, as the only key of a \
                     table, or as the value of a `{KIND_KEY}` key",
                    self.what,
                    self.listed()
                ),
            ));
        };
        let Value::String(name) = tag.value() else {
            return Err(InputError::new(
                join(path, KIND_KEY),
                tag.span(),
                format!(
                    "invalid type: {}, expected the name of a {}",
                    tag.value().kind(),
                    self.what
                ),
            ));
        };
        let mut content = node.clone();
        content.remove(KIND_KEY);
        Ok(Tagged {
            name,
            whole: node,
            path,
            content,
            content_path: path.to_string(),
        })
    }

    /// An unknown name, at the name, with the registered ones.
    fn unknown(&self, tagged: &Tagged, node: &Node) -> InputError {
        let (path, span) = match node.get(KIND_KEY) {
            Some(tag) => (join(tagged.path, KIND_KEY), tag.span()),
            None => (tagged.path.to_string(), node.span()),
        };
        InputError::new(
            path,
            span,
            format!(
                "unknown variant `{}`, expected one of {}",
                tagged.name,
                self.listed()
            ),
        )
    }

    /// `` `a`, `b` ``.
    fn listed(&self) -> String {
        let names: Vec<String> = self.names().map(|n| format!("`{n}`")).collect();
        names.join(", ")
    }
}

/// `path.key`, or `key` at the root.
fn join(path: &str, key: &str) -> String {
    match path {
        "" => key.to_string(),
        _ => format!("{path}.{key}"),
    }
}

/// A kind `K` read from its own settings, written back under its name.
fn own<K: DeserializeOwned + Serialize>(
    name: &'static str,
    tagged: &Tagged,
) -> Result<(K, serde_json::Value), InputError> {
    let kind: K = tagged
        .content
        .deserialize_seed(PhantomData::<K>, &tagged.content_path)?;
    let settings = written(&kind, tagged)?;
    Ok((kind, under(name, settings)))
}

/// A kind's settings written back under its name, `{ "<name>": { … } }`; a kind without
/// settings as its bare name, as a scene writes it (`gap = "flat"`).
fn under(name: &'static str, settings: serde_json::Value) -> serde_json::Value {
    match settings {
        serde_json::Value::Object(table) if table.is_empty() => name.into(),
        settings => serde_json::json!({ name: settings }),
    }
}

/// `kind`'s settings as [`own`] writes them back under `name`, for a kind chosen without a
/// scene's text (a default).
pub(crate) fn written_under<K: Serialize>(name: &'static str, kind: &K) -> serde_json::Value {
    under(
        name,
        serde_json::to_value(kind).unwrap_or(serde_json::Value::Null),
    )
}

/// The reader of a kind `K` from its own settings, chosen as the sort `T` (`upcast` is the
/// coercion `Arc<K>` → `Arc<T>`).
fn reader<T, K>(upcast: fn(Arc<K>) -> Arc<T>) -> Reader<T>
where
    T: ?Sized + 'static,
    K: DeserializeOwned + Serialize + Send + Sync + 'static,
{
    Arc::new(move |name, tagged| {
        let (kind, written) = own::<K>(name, tagged)?;
        let kind = Arc::new(kind);
        Ok(Chosen::new(name, written, upcast(kind.clone()), kind))
    })
}

/// A member of an externally tagged enum `E` of kinds, read from the whole node (the enum
/// names its variants as the registry does) and written back as the enum writes itself.
fn member<E: DeserializeOwned + Serialize>(
    tagged: &Tagged,
) -> Result<(E, serde_json::Value), InputError> {
    let kind: E = tagged
        .whole
        .deserialize_seed(PhantomData::<E>, tagged.path)?;
    let written = written(&kind, tagged)?;
    Ok((kind, written))
}

/// `kind` as a JSON value, for `result.json` and the identity of a choice.
fn written<K: Serialize>(kind: &K, tagged: &Tagged) -> Result<serde_json::Value, InputError> {
    serde_json::to_value(kind).map_err(|e| {
        InputError::new(
            tagged.path,
            tagged.whole.span(),
            format!("cannot be written back: {e}"),
        )
    })
}

/// The names of an externally tagged enum's variants, as serde gives them to a reader.
fn variants<E: DeserializeOwned>() -> &'static [&'static str] {
    /// A reader that only asks an enum for its variants.
    struct Names(Option<&'static [&'static str]>);
    #[derive(Debug)]
    struct Asked;
    impl fmt::Display for Asked {
        fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("asked")
        }
    }
    impl std::error::Error for Asked {}
    impl serde::de::Error for Asked {
        fn custom<M: fmt::Display>(_: M) -> Self {
            Asked
        }
    }
    impl<'de> serde::Deserializer<'de> for &mut Names {
        type Error = Asked;
        fn deserialize_any<V: serde::de::Visitor<'de>>(self, _: V) -> Result<V::Value, Asked> {
            Err(Asked)
        }
        fn deserialize_enum<V: serde::de::Visitor<'de>>(
            self,
            _: &'static str,
            variants: &'static [&'static str],
            _: V,
        ) -> Result<V::Value, Asked> {
            self.0 = Some(variants);
            Err(Asked)
        }
        serde::forward_to_deserialize_any! {
            bool i8 i16 i32 i64 i128 u8 u16 u32 u64 u128 f32 f64 char str string bytes
            byte_buf option unit unit_struct newtype_struct seq tuple tuple_struct map struct
            identifier ignored_any
        }
    }
    let mut names = Names(None);
    let _ = E::deserialize(&mut names);
    names.0.unwrap_or(&[])
}

/// The kinds a scene may name: bodies, contact zones, initial gaps, designs and contact
/// solvers.
#[derive(Clone)]
pub struct Registry {
    bodies: Kinds<dyn BodyKind>,
    zones: Kinds<dyn ZoneKind>,
    gaps: Kinds<dyn GapKind>,
    designs: Kinds<dyn Design>,
    solvers: Kinds<dyn SolverKind>,
}

impl fmt::Debug for Registry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Registry")
            .field("bodies", &self.bodies.names().collect::<Vec<_>>())
            .field("zones", &self.zones.names().collect::<Vec<_>>())
            .field("gaps", &self.gaps.names().collect::<Vec<_>>())
            .field("designs", &self.designs.names().collect::<Vec<_>>())
            .field("solvers", &self.solvers.names().collect::<Vec<_>>())
            .finish()
    }
}

impl Default for Registry {
    /// [`Registry::standard`].
    fn default() -> Self {
        Self::standard()
    }
}

impl Registry {
    /// No kinds at all: a registry to fill from scratch.
    pub fn empty() -> Self {
        Self {
            bodies: Kinds::new("body kind"),
            zones: Kinds::new("zone kind"),
            gaps: Kinds::new("gap kind"),
            designs: Kinds::new("design method"),
            solvers: Kinds::new("contact solver"),
        }
    }

    /// The library's kinds: the bodies `rigid`, `half_space`, `fe_base`, `fe_punch`,
    /// `fe_block`, `winkler`, `fe_mesh`, `solid`; the zones `grid`, `rings`, `strips`, `faces`, `mesh`;
    /// the gaps `flat`, `sphere`, `cylinder`, `flat_punch`,
    /// `roller`, `measured`; the designs of [`OptimisationMethod`] (`given_load`,
    /// `given_displacement`, `linear_programme`, `load_split`) and a roller's
    /// `envelope_split`, `profile_search` and `circular_search`; the solvers of
    /// [`SolverSettings`] (`auto`, `qp`, `active_set`, `penalty`, `augmented_lagrangian`,
    /// `polonsky_keer`).
    pub fn standard() -> Self {
        Self::empty()
            .with_body::<Rigid>("rigid")
            .with_body::<HalfSpaceBody>("half_space")
            .with_body::<FeBase>("fe_base")
            .with_body::<FePunch>("fe_punch")
            .with_body::<FeBlock>("fe_block")
            .with_body::<WinklerBed>("winkler")
            .with_body::<FeMesh>("fe_mesh")
            .with_body::<Solid>("solid")
            .with_zone::<GridZone>("grid")
            .with_zone::<RingsZone>("rings")
            .with_zone::<StripsZone>("strips")
            .with_zone::<FacesZone>("faces")
            .with_zone::<MeshZone>("mesh")
            .with_gap::<Flat>("flat")
            .with_gap::<Sphere>("sphere")
            .with_gap::<Cylinder>("cylinder")
            .with_gap::<FlatPunch>("flat_punch")
            .with_gap::<RollerGap>("roller")
            .with_gap::<Measured>("measured")
            .with_design_family::<OptimisationMethod>(|m| Arc::new(Gap(m)))
            .with_design::<EnvelopeSplit>("envelope_split")
            .with_design::<FujiwaraKawaseSearch>("profile_search")
            .with_design::<CircularSearch>("circular_search")
            .with_solver_family::<SolverSettings>()
    }

    /// Registers the body kind `K` as `name` (replacing a kind of that name).
    pub fn with_body<K>(mut self, name: &'static str) -> Self
    where
        K: BodyKind + DeserializeOwned + Serialize + 'static,
    {
        self.bodies
            .add(name, reader::<dyn BodyKind, K>(|kind| kind));
        self
    }

    /// Registers a body kind read at run time by `read` (a binding's kinds, whose types Rust
    /// does not know) as `name`, replacing a kind of that name: `read` is given the kind's
    /// settings as JSON (the table less its `kind`) and returns the kind or a message, which
    /// is placed at the settings. The settings are written back into `result.json` as they
    /// were read.
    pub fn with_body_reader<F>(mut self, name: &'static str, read: F) -> Self
    where
        F: Fn(&serde_json::Value) -> Result<Arc<dyn BodyKind>, String> + Send + Sync + 'static,
    {
        self.bodies.add(
            name,
            Arc::new(move |name, tagged| {
                let settings: serde_json::Value = tagged
                    .content
                    .deserialize_seed(PhantomData, &tagged.content_path)?;
                let kind = read(&settings).map_err(|message| {
                    InputError::new(&tagged.content_path, tagged.content.span(), message)
                })?;
                let written = under(name, settings.clone());
                Ok(Chosen::new(name, written, kind, Arc::new(settings)))
            }),
        );
        self
    }

    /// Registers the zone kind `K` as `name` (replacing a kind of that name).
    pub fn with_zone<K>(mut self, name: &'static str) -> Self
    where
        K: ZoneKind + DeserializeOwned + Serialize + 'static,
    {
        self.zones.add(name, reader::<dyn ZoneKind, K>(|kind| kind));
        self
    }

    /// Registers the gap kind `K` as `name` (replacing a kind of that name).
    pub fn with_gap<K>(mut self, name: &'static str) -> Self
    where
        K: GapKind + DeserializeOwned + Serialize + 'static,
    {
        self.gaps.add(name, reader::<dyn GapKind, K>(|kind| kind));
        self
    }

    /// Registers the design `D` as the method `name` (replacing a method of that name).
    pub fn with_design<D>(mut self, name: &'static str) -> Self
    where
        D: Design + DeserializeOwned + Serialize + 'static,
    {
        self.designs.add(name, reader::<dyn Design, D>(|kind| kind));
        self
    }

    /// Registers every variant of the enum `E` of design settings as a method of its own
    /// name, each designing by `design`.
    pub fn with_design_family<E>(mut self, design: fn(E) -> Arc<dyn Design>) -> Self
    where
        E: DeserializeOwned + Serialize + Clone + Send + Sync + 'static,
    {
        for &name in variants::<E>() {
            self.designs.add(
                name,
                Arc::new(move |name, tagged| {
                    let (settings, written) = member::<E>(tagged)?;
                    let kind = design(settings.clone());
                    Ok(Chosen::new(name, written, kind, Arc::new(settings)))
                }),
            );
        }
        self
    }

    /// Registers the contact solver `S` as `name` (replacing a solver of that name).
    pub fn with_solver<S>(mut self, name: &'static str) -> Self
    where
        S: SolverKind + DeserializeOwned + Serialize + 'static,
    {
        self.solvers
            .add(name, reader::<dyn SolverKind, S>(|kind| kind));
        self
    }

    /// Registers every variant of the enum `E` of solver settings as a solver of its own name.
    pub fn with_solver_family<E>(mut self) -> Self
    where
        E: SolverKind + DeserializeOwned + Serialize + 'static,
    {
        for &name in variants::<E>() {
            self.solvers.add(
                name,
                Arc::new(|name, tagged| {
                    let (kind, written) = member::<E>(tagged)?;
                    let kind = Arc::new(kind);
                    Ok(Chosen::new(name, written, kind.clone(), kind))
                }),
            );
        }
        self
    }

    /// The registered body kinds' names.
    pub fn body_kinds(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.bodies.names()
    }

    /// The registered zone kinds' names.
    pub fn zone_kinds(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.zones.names()
    }

    /// The registered gap kinds' names.
    pub fn gap_kinds(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.gaps.names()
    }

    /// The registered design methods' names.
    pub fn designs(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.designs.names()
    }

    /// The registered contact solvers' names.
    pub fn solvers(&self) -> impl Iterator<Item = &'static str> + '_ {
        self.solvers.names()
    }

    /// The body at `node` (path `path` in errors).
    pub(crate) fn body(&self, node: &Node, path: &str) -> Result<Chosen<dyn BodyKind>, InputError> {
        self.bodies.read(node, path)
    }

    /// The contact zone at `node`.
    pub(crate) fn zone(&self, node: &Node, path: &str) -> Result<Chosen<dyn ZoneKind>, InputError> {
        self.zones.read(node, path)
    }

    /// The gap at `node`.
    pub(crate) fn gap(&self, node: &Node, path: &str) -> Result<Chosen<dyn GapKind>, InputError> {
        self.gaps.read(node, path)
    }

    /// The design method at `node`.
    pub(crate) fn design(&self, node: &Node, path: &str) -> Result<Chosen<dyn Design>, InputError> {
        self.designs.read(node, path)
    }

    /// The contact solver at `node`.
    pub(crate) fn solver(
        &self,
        node: &Node,
        path: &str,
    ) -> Result<Chosen<dyn SolverKind>, InputError> {
        self.solvers.read(node, path)
    }
}

/// The solver of a scene that names none: `auto`, the library's choice per problem.
pub(crate) fn default_solver() -> Chosen<dyn SolverKind> {
    let settings = Arc::new(SolverSettings::default());
    let written = serde_json::to_value(&*settings).unwrap_or(serde_json::Value::Null);
    Chosen::new("auto", written, settings.clone(), settings)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_body(text: &str) -> Result<Chosen<dyn BodyKind>, InputError> {
        let node = Node::parse_toml(text).unwrap();
        Registry::standard().body(node.get("body").unwrap(), "body")
    }

    #[test]
    fn three_spellings_read_alike() {
        let a = read_body("body = \"rigid\"").unwrap();
        let b = read_body("body = { kind = \"rigid\" }").unwrap();
        let c = read_body("body = { rigid = {} }").unwrap();
        assert_eq!(a, b);
        assert_eq!(b, c);
        assert_eq!(a.name(), "rigid");
        assert_eq!(
            a.written(),
            &serde_json::json!({ "rigid": { "name": null } })
        );
    }

    #[test]
    fn settings_tell_kinds_apart() {
        let a = read_body("body = { kind = \"winkler\", modulus_mpa_per_mm = 2.0 }").unwrap();
        let b = read_body("body = { kind = \"winkler\", modulus_mpa_per_mm = 3.0 }").unwrap();
        assert_ne!(a, b);
    }

    #[test]
    fn an_unknown_kind_lists_the_registered_ones_at_its_name() {
        let text = "body = { kind = \"marble\" }";
        let e = read_body(text).unwrap_err();
        assert_eq!(e.path, "body.kind");
        assert_eq!(e.line_column(text), Some((1, 17)));
        assert!(e.message.contains("unknown variant `marble`"), "{e}");
        assert!(e.message.contains("`rigid`, `half_space`"), "{e}");
    }

    #[test]
    fn errors_inside_a_kind_keep_their_path() {
        let text = "[body]\nkind = \"winkler\"\nmodulus_mpa_per_mm = \"stiff\"\n";
        let e = read_body(text).unwrap_err();
        assert_eq!(e.path, "body.modulus_mpa_per_mm");
        assert_eq!(e.line_column(text), Some((3, 22)));
        let text = "[body.winkler]\nmodulus = 2.0\n";
        let e = read_body(text).unwrap_err();
        assert_eq!(e.path, "body.winkler.modulus");
    }

    #[test]
    fn an_enum_family_registers_each_variant_by_serde_name() {
        let names: Vec<_> = Registry::standard().solvers().collect();
        assert_eq!(
            names,
            [
                "auto",
                "qp",
                "active_set",
                "penalty",
                "augmented_lagrangian",
                "polonsky_keer"
            ]
        );
        let designs: Vec<_> = Registry::standard().designs().collect();
        assert!(designs.starts_with(&["given_load", "given_displacement"]));
    }

    #[test]
    fn a_reader_registers_a_kind_known_at_run_time() {
        let registry = Registry::standard().with_body_reader("springs", |settings| {
            serde_json::from_value::<WinklerBed>(settings.clone())
                .map(|bed| Arc::new(bed) as Arc<dyn BodyKind>)
                .map_err(|e| e.to_string())
        });
        let read = |text: &str| {
            let node = Node::parse_toml(text).unwrap();
            registry.body(node.get("body").unwrap(), "body")
        };
        let body = read("body = { kind = \"springs\", modulus_mpa_per_mm = 2.0 }").unwrap();
        assert_eq!(body.name(), "springs");
        let written = serde_json::json!({ "springs": { "modulus_mpa_per_mm": 2.0 } });
        assert_eq!(body.written(), &written);
        let e = read("body = { kind = \"springs\", modulus = 2.0 }").unwrap_err();
        assert_eq!(e.path, "body");
        assert!(e.message.contains("unknown field `modulus`"), "{e}");
    }

    #[test]
    fn a_later_registration_replaces_an_earlier_one() {
        let registry = Registry::standard().with_body::<WinklerBed>("rigid");
        assert_eq!(registry.body_kinds().filter(|&n| n == "rigid").count(), 1);
        // A rigid body would refuse the bed's modulus.
        let node =
            Node::parse_toml("body = { kind = \"rigid\", modulus_mpa_per_mm = 1.0 }").unwrap();
        let body = registry.body(node.get("body").unwrap(), "body").unwrap();
        assert_eq!(body.name(), "rigid");
    }
}
