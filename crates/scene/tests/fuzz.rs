//! Fuzz test of the scene reader and runner and of the libraries' public constructors (issue
//! 14): hostile input gives `Ok` or `Err`, never a panic, an abort (a refused allocation, a
//! stack overflow) or a hang; and what comes out `Ok` is finite.
//!
//! The properties:
//! 1. `mutated_scenes`: each bundled scene ([`contopt_scene::BUNDLED`]) with leaves replaced by
//!    hostile numbers and strings, keys deleted or added, whole sections replaced (a zone, a
//!    gap, a load, bodies, a solver, a design, …), values nested deeply and arrays resized,
//!    written back as TOML and as JSON and read by [`Scene::parse`] (which checks every case
//!    as its run would: each value, the pairing of the zone, the bodies, the gap and the load,
//!    the design, the memory). A scene that reads has cases, and its first and last case's
//!    resolved input serialises. A bundled scene is too large to run here (a roller on
//!    200 × 105 cells, 18 elements under a punch); a mutated one that became tiny runs, as a
//!    generated one does.
//!
//!    `generated_scenes`: scenes made from the schema — every zone kind, every body kind,
//!    every gap kind, every load, solver, design method, controller and Ω_v, each enum spelled
//!    the three ways a scene may — three in four plausible throughout, the others with each
//!    value hostile one time in eight; most pairs of bodies valid for their zone and some not
//!    (parts of two setups mixed, sides swapped, a body too few or too many). Imported bodies
//!    read small meshes of the repository's `meshes/` (copied beside the scenes): the paper's
//!    punch and base, the coarsest cylinder on a block. A scene whose pairing breaks a rule of
//!    the schema (two rigid bodies, a finite-element body off a zone of faces, an imported one
//!    off a zone of meshes, a half-space on faces, a roller off a grid, the measured gap
//!    without two meshes, a force on a held body, …) must be refused. The tiny ones (a few hundred points at most, few steps, no profile search or
//!    envelope split) are run, every case, by [`Scene::run`], and every [`CaseReport`] that
//!    comes out is finite: it meets the results schema (serde_json writes a NaN or an
//!    infinity as `null`, which the schema refuses where it requires a number) and every
//!    number of it, read field by field (where the schema allows `null`, for an absent
//!    figure, the JSON cannot tell), is finite.
//! 2. `arbitrary_text`: bytes, Unicode, token soup, spliced scene lines, deep nesting and huge
//!    arrays, read as TOML and as JSON. No more than "no panic": such text seldom makes a
//!    scene, and one that does is not known to be one of the schema's to check.
//! 3. `constructors_*`: the public constructors of the greens, fem, core, contact, optimise and
//!    roller crates, and the scene's finite-element bodies, with arbitrary numbers and counts
//!    (an absurd count must be an error before anything of its size is allocated); what they
//!    build `Ok` gives finite outputs: an interface's points, weights, normals, extent and
//!    area, a body's load displacement, its influence on a unit force and its rigid modes, a
//!    model's solved displacements, a contact solve's pressure and gap, a controller's values
//!    in [0, 1], a crown's drop, a roller's Hertz figures and cells, a search's minimum (no
//!    worse than its start).
//!
//! The defects of the libraries that the properties found are fixed, each with its regression
//! test at the end of this file (`fixed_*`); no input is exempt from the checks. (A defect
//! found and not fixed at once was listed as a named constant exempting its inputs, with an
//! `#[ignore]`d reproducer, until its fix deleted both; none is open now.)
//!
//! Running:
//! - Short (CI runs it in `cargo test --workspace`): `cargo test -p contopt-scene --test fuzz`,
//!   768 cases of each scene property and 512 of the others, from a fixed seed so that CI sees
//!   the same cases every time: about 10 s on two shared cores (9 s of CPU).
//! - Long, on demand: `PROPTEST_CASES=3000 cargo test -p contopt-scene --test fuzz`, for every
//!   property (about a minute); add `PROPTEST_RNG_SEED=<u64>` for other cases than CI's, and
//!   one test's name after `--` for one property. Proptest's `PROPTEST_*` variables win over
//!   the defaults here.
//! - `FUZZ_SURVEY=1` prints each non-finite output instead of failing on the first, to survey a long run; `FUZZ_STATS=1` prints how each
//!   generated or mutated scene fared (refused and why, read, run to which status). Both with
//!   `-- --nocapture`.
//!
//! Guards, since a failure here may be an abort or a hang rather than a panic:
//! - each case runs on a thread of its own with an 8 MiB stack (a main thread's), named after
//!   its input (a stack overflow prints the thread's name), and must end within
//!   [`CASE_LIMIT`]: past it the input is printed and the process aborts (a hang cannot be
//!   shrunk in process);
//! - this test binary's allocator holds at most [`MEMORY_CAP`] at once: past it the input is
//!   printed and the allocation fails, which aborts (unless the caller asked with
//!   `try_reserve`, as `std::fs::read_to_string` does).
//!
//! Panics are shrunk, and their seeds persisted in `tests/fuzz.proptest-regressions` beside this
//! file (not the default `proptest-regressions/` folder): CI's own cases are fixed by the seed
//! already, so the file matters for what a long or differently seeded run finds; committed with
//! the fix, it makes CI replay that case first. Set `PROPTEST_DISABLE_FAILURE_PERSISTENCE=1` to
//! explore without writing it.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::io::Write;
use std::ops::ControlFlow;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc, OnceLock};
use std::time::Duration;

use contopt_contact::{ActiveSet, ContactSolver, InterfaceProblem};
use contopt_core::{ElasticBody, Geometry, Interface, Material, RigidBody, Termination};
use contopt_fem::{Analysis, Component, ElementKind, FeBody, FeModel, Mesh, Spacing};
use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, HalfSpace, PlaneState, Winkler};
use contopt_results::CaseReport;
use contopt_scene::{Format, Scene};
use proptest::prelude::*;
use proptest::sample::{select, Index};
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};
use toml::Value;

// ---------------------------------------------------------------------------------------------
// Guards: time, memory, stack.

/// The longest one case may take (a tiny scene's run builds its bodies and solves a few
/// hundred points: well under a second each in the test profile).
const CASE_LIMIT: Duration = Duration::from_secs(10);

/// The most this test binary may hold at once \[bytes\]: above a scene's default memory limit
/// (4000 MB), well below the 24 GB machine.
const MEMORY_CAP: usize = 4 << 30;

/// A case's stack: a main thread's (the `contopt` command parses on its main thread).
const CASE_STACK: usize = 8 << 20;

struct Capped;

static LIVE: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// The input of the case this thread runs (for the message of a refused allocation); a
    /// raw pointer, so that reading it from the allocator allocates nothing.
    static CASE_INPUT: Cell<(*const u8, usize)> = const { Cell::new((std::ptr::null(), 0)) };
}

impl Capped {
    fn reserve(&self, size: usize) -> bool {
        let before = LIVE.fetch_add(size, Ordering::Relaxed);
        if before.saturating_add(size) > MEMORY_CAP {
            LIVE.fetch_sub(size, Ordering::Relaxed);
            refused(size, before);
            return false;
        }
        true
    }
}

/// Tells which case asked for more than [`MEMORY_CAP`]; writes without allocating.
fn refused(size: usize, live: usize) {
    let (ptr, len) = CASE_INPUT
        .try_with(Cell::get)
        .unwrap_or((std::ptr::null(), 0));
    let mut err = std::io::stderr().lock();
    let _ = write!(
        err,
        "\nfuzz: refused an allocation of {size} bytes with {live} held (cap {MEMORY_CAP}; an \
         abort follows unless the caller handles it); "
    );
    if ptr.is_null() {
        let _ = writeln!(err, "outside a case");
    } else {
        // SAFETY: the case's thread keeps its input alive while the pointer is set.
        let text = unsafe { std::slice::from_raw_parts(ptr, len.min(20_000)) };
        let _ = writeln!(err, "the case's input ({len} bytes):");
        let _ = err.write_all(text);
        let _ = writeln!(err);
    }
}

// SAFETY: every block comes from `System`; the count only decides whether to ask for it.
unsafe impl GlobalAlloc for Capped {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !self.reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        let p = System.alloc(layout);
        if p.is_null() {
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        p
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !self.reserve(layout.size()) {
            return std::ptr::null_mut();
        }
        let p = System.alloc_zeroed(layout);
        if p.is_null() {
            LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
        }
        p
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout);
        LIVE.fetch_sub(layout.size(), Ordering::Relaxed);
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        let old = layout.size();
        if new_size > old && !self.reserve(new_size - old) {
            return std::ptr::null_mut();
        }
        let p = System.realloc(ptr, layout, new_size);
        match (p.is_null(), new_size > old) {
            (true, true) => {
                LIVE.fetch_sub(new_size - old, Ordering::Relaxed);
            }
            (false, false) => {
                LIVE.fetch_sub(old - new_size, Ordering::Relaxed);
            }
            _ => {}
        }
        p
    }
}

#[global_allocator]
static ALLOCATOR: Capped = Capped;

/// At most `max` characters of `text`, escaped, for a thread name or a message.
fn preview(text: &str, max: usize) -> String {
    let mut s: String = text.chars().take(max).collect();
    if s.len() < text.len() {
        s.push_str(" …");
    }
    format!("{s:?}")
}

/// Runs `work` on a thread of its own named after `input`, within [`CASE_LIMIT`]: a panic is
/// passed on (proptest shrinks it), a hang prints the input and aborts.
fn guarded<T: Send + 'static>(
    what: &str,
    input: Arc<str>,
    work: impl FnOnce() -> T + Send + 'static,
) -> T {
    let (send, receive) = mpsc::channel();
    let shown = input.clone();
    let worker = std::thread::Builder::new()
        .name(format!("fuzz {what} {}", preview(&input, 300)))
        .stack_size(CASE_STACK)
        .spawn(move || {
            CASE_INPUT.with(|c| c.set((shown.as_ptr(), shown.len())));
            let out = work();
            CASE_INPUT.with(|c| c.set((std::ptr::null(), 0)));
            drop(shown);
            let _ = send.send(out);
        })
        .expect("a thread for the case");
    match receive.recv_timeout(CASE_LIMIT) {
        Ok(out) => {
            let _ = worker.join();
            out
        }
        Err(mpsc::RecvTimeoutError::Disconnected) => match worker.join() {
            Err(panic) => std::panic::resume_unwind(panic),
            Ok(()) => unreachable!("the case ended without an answer or a panic"),
        },
        Err(mpsc::RecvTimeoutError::Timeout) => {
            // Straight to stderr: the test harness's capture of `eprintln!` dies with the process.
            let _ = writeln!(
                std::io::stderr(),
                "\nfuzz: {what} took longer than {CASE_LIMIT:?}; its input ({} bytes):\n{}",
                input.len(),
                input.chars().take(20_000).collect::<String>()
            );
            std::process::abort();
        }
    }
}

/// The configuration of a property: `cases` unless `PROPTEST_CASES` says otherwise, CI's fixed
/// seed unless `PROPTEST_RNG_SEED` does, shrinking bounded to a minute.
fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(14),
        max_shrink_time: 60_000,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource(
            "proptest-regressions",
        ))),
        ..Config::default()
    }
}

// ---------------------------------------------------------------------------------------------
// Hostile values.

/// A number JSON cannot hold but a scene may: written as the largest u64 in JSON (TOML's
/// integers stop at i64) and as this string in TOML.
const U64_MAX: &str = "\u{1}u64::MAX";
/// JSON's null (TOML has none): this string in TOML.
const NULL: &str = "\u{1}null";

const SPECIAL_INTS: &[i64] = &[
    0,
    1,
    2,
    3,
    4,
    5,
    7,
    8,
    9,
    -1,
    -2,
    10,
    17,
    64,
    100,
    101,
    1000,
    1024,
    4096,
    10_000,
    65_535,
    65_536,
    100_000,
    1_000_000,
    1_000_000_000,
    2_147_483_647,
    4_294_967_295,
    4_294_967_296,
    1 << 40,
    i64::MAX - 1,
    i64::MAX,
    i64::MIN,
];

const SPECIAL_FLOATS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    0.3,
    0.499_999_999_9,
    -0.999_999_9,
    1e-300,
    -1e-300,
    5e-324,
    f64::MIN_POSITIVE,
    f64::EPSILON,
    1e-12,
    1e-9,
    1e-6,
    1e6,
    1e9,
    2e9,
    4_294_967_296.0,
    1e15,
    1e300,
    1.7e308,
    f64::MAX,
    -f64::MAX,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
];

/// Counts past any sensible mesh or grid, and one large but sensible one (a thousand elements
/// across a finite-element body is sensible too, but takes 20 s to build: slow, not wrong).
const BIG_COUNTS: &[i64] = &[100, 1_000_000, 1_000_000_000, 4_294_967_296, i64::MAX];

const HOSTILE_STRINGS: &[&str] = &[
    "",
    " ",
    ".",
    "..",
    "../../x",
    "/abs",
    "/",
    "/dev/zero",
    "/proc/self/mem",
    "a\"b",
    "a'b",
    "\u{0}",
    "\\",
    "\n",
    "\r\n",
    "\t",
    "🦀",
    "é",
    "\u{202e}",
    "\u{feff}",
    "q10",
    "Q8",
    "q8 ",
    "Grid",
    "half-space",
    "nan",
    "NaN",
    "inf",
    "-inf",
    "1e309",
    "null",
    "true",
    "[",
    "{",
    "}",
    "${HOME}",
    "%s%n",
    "CON",
    U64_MAX,
    NULL,
];

const ZONE_KINDS: &[&str] = &["grid", "rings", "strips", "faces", "mesh"];
const GAP_KINDS: &[&str] = &[
    "flat",
    "sphere",
    "cylinder",
    "flat_punch",
    "roller",
    "measured",
];
const BODY_KINDS: &[&str] = &[
    "rigid",
    "half_space",
    "fe_base",
    "fe_punch",
    "fe_block",
    "winkler",
    "fe_mesh",
];
/// The meshes a generated `fe_mesh` reads (`../meshes/<name>` from the scene's folder, where
/// [`scene_file`] puts them): small ones, so that a scene of them runs in a tenth of a second.
const MESHES: &[&str] = &[
    "paper-base.msh",
    "paper-punch.msh",
    "cylinder-on-block-b4.msh",
    "rectangle-metres.msh",
    "block-inner-curve.msh",
];
/// The physical groups of the meshes above, and some that are not.
const GROUPS: &[&str] = &[
    "base",
    "base_face",
    "base_top",
    "base_bottom",
    "base_axis",
    "punch",
    "punch_face",
    "punch_top",
    "punch_axis",
    "block",
    "block_face",
    "block_short",
    "block_bottom",
    "block_axis",
    "cylinder",
    "cylinder_face",
    "cylinder_top",
    "cylinder_axis",
    "inner",
    "nowhere",
];
const CROWNS: &[&str] = &[
    "straight",
    "iso",
    "lundberg",
    "johns_gohar",
    "fujiwara_kawase",
    "table",
];
const SOLVERS: &[&str] = &[
    "auto",
    "qp",
    "active_set",
    "penalty",
    "augmented_lagrangian",
    "polonsky_keer",
];
const METHODS: &[&str] = &[
    "given_load",
    "given_displacement",
    "linear_programme",
    "load_split",
    "envelope_split",
    "profile_search",
];
const ANALYSES: &[&str] = &["axisymmetric", "plane_stress", "plane_strain"];
const SUPPORTS: &[&str] = &["clamped", "axial", "symmetry"];

/// The names of the schema's variants.
const VARIANTS: &[&str] = &[
    "grid",
    "rings",
    "strips",
    "faces",
    "mesh",
    "flat",
    "sphere",
    "cylinder",
    "flat_punch",
    "roller",
    "measured",
    "rigid",
    "half_space",
    "fe_base",
    "fe_punch",
    "fe_block",
    "winkler",
    "fe_mesh",
    "force_n",
    "approach_mm",
    "none",
    "pressure_mpa",
    "displacement_mm",
    "q8",
    "q9",
    "axisymmetric",
    "plane_stress",
    "plane_strain",
    "clamped",
    "axial",
    "symmetry",
    "straight",
    "iso",
    "lundberg",
    "johns_gohar",
    "fujiwara_kawase",
    "table",
    "auto",
    "qp",
    "active_set",
    "penalty",
    "augmented_lagrangian",
    "polonsky_keer",
    "given_load",
    "given_displacement",
    "linear_programme",
    "load_split",
    "envelope_split",
    "profile_search",
    "constant",
    "trapezoid",
    "cubic",
    "product",
    "strip",
    "disc",
    "box",
    "x",
    "y",
    "z",
];

/// Dotted keys for sweeps and named cases.
const DOTTED: &[&str] = &[
    "contact.zone.cells",
    "contact.zone.cells.0",
    "contact.zone.cell_mm.1",
    "contact.zone.rings",
    "contact.zone.strips",
    "contact.zone.elements",
    "contact.zone.radius_mm",
    "contact.zone.half_width_mm",
    "contact.zone.grading",
    "contact.zone.element",
    "contact.zone.analysis",
    "contact.zone.analysis.plane_stress.thickness_mm",
    "contact.zone.kind",
    "contact.zone.search_mm",
    "contact.zone",
    "contact.gap.radius_mm",
    "contact.gap.diameter_mm",
    "contact.gap.length_mm",
    "contact.gap.tilt_arcmin",
    "contact.gap.reach_b",
    "contact.gap.profile",
    "contact.gap.profile.k1",
    "contact.gap.kind",
    "contact.gap",
    "contact.load.force_n",
    "contact.load.approach_mm",
    "contact.load",
    "body.0.material.e_mpa",
    "body.1.material.nu",
    "body.0.material",
    "body.0.radius_mm",
    "body.0.height_mm",
    "body.1.height_mm",
    "body.0.layers",
    "body.1.layers",
    "body.1.load.pressure_mpa",
    "body.0.size_mm",
    "body.0.modulus_mpa_per_mm",
    "body.0.supports",
    "body.0.datum_mm",
    "body.0.extent_mm.0",
    "body.1.extent_mm",
    "body.0.mesh",
    "body.1.contact",
    "body.1.loads.0.pressure_mpa",
    "body.0.supports.0.fix",
    "body.1.kind",
    "body.2",
    "body.-1",
    "body",
    "solver.c_mpa_per_mm",
    "solver.max_steps",
    "solver.kind",
    "solver",
    "optimisation.method.tolh_mm2",
    "optimisation.method.max_iterations",
    "optimisation.method",
    "optimisation.controller.l1_mm",
    "optimisation.controller.l2_mm",
    "optimisation.controller.a.level",
    "optimisation.controller",
    "optimisation.omega_v.radius_mm",
    "optimisation.profile_axis",
    "output.subsurface.depths",
    "envelope.load_factors",
    "envelope.tilts_arcmin.0",
    "dense_limit_mb",
    "memory_limit_mb",
    "sweep.values",
    "case",
    "name",
    "",
    ".",
    "..",
    "a..b",
    "contact..zone",
];

/// Key names of the schema, and some that are not.
const KEYS: &[&str] = &[
    "name",
    "description",
    "contact",
    "zone",
    "gap",
    "load",
    "body",
    "kind",
    "cells",
    "cell_mm",
    "rings",
    "radius_mm",
    "strips",
    "half_width_mm",
    "analysis",
    "thickness_mm",
    "elements",
    "grading",
    "element",
    "diameter_mm",
    "length_mm",
    "raceway_diameter_mm",
    "tilt_arcmin",
    "reach_b",
    "profile",
    "k1",
    "k2",
    "z_m_mm",
    "file",
    "force_n",
    "approach_mm",
    "material",
    "e_mpa",
    "nu",
    "datum_mm",
    "height_mm",
    "supports",
    "layers",
    "pressure_mpa",
    "displacement_mm",
    "size_mm",
    "modulus_mpa_per_mm",
    "solver",
    "c_mpa_per_mm",
    "tolerance",
    "max_steps",
    "accelerate",
    "optimisation",
    "method",
    "tolh_mm2",
    "max_iterations",
    "max_passes",
    "max_evaluations",
    "controller",
    "level",
    "l1_mm",
    "l2_mm",
    "axis",
    "a",
    "b",
    "omega_v",
    "from_mm",
    "to_mm",
    "centre_mm",
    "profile_axis",
    "envelope",
    "load_factors",
    "tilts_arcmin",
    "dense_limit_mb",
    "memory_limit_mb",
    "output",
    "subsurface",
    "max_depth_mm",
    "depths",
    "sections",
    "along",
    "at_mm",
    "sweep",
    "key",
    "values",
    "case",
    "label",
    "set",
    "unknown",
    "",
    " ",
    "a.b",
    "🦀",
    "__proto__",
    "$__toml_private_datetime",
];

fn int(v: i64) -> Value {
    Value::Integer(v)
}

fn text(s: &str) -> Value {
    Value::String(s.to_string())
}

/// A hostile number (integer or float; TOML keeps NaN and infinities, JSON writes them null).
fn number() -> BoxedStrategy<Value> {
    prop_oneof![
        3 => select(SPECIAL_INTS).prop_map(int),
        2 => (0i64..64).prop_map(int),
        1 => any::<i64>().prop_map(int),
        3 => select(SPECIAL_FLOATS).prop_map(Value::Float),
        1 => any::<f64>().prop_map(Value::Float),
        2 => (1e-3..1e3f64).prop_map(Value::Float),
        1 => Just(text(U64_MAX)),
    ]
    .boxed()
}

/// A count: mostly small, sometimes absurd, seldom not a count.
fn count() -> BoxedStrategy<Value> {
    prop_oneof![
        8 => (0i64..=40).prop_map(int),
        2 => select(BIG_COUNTS).prop_map(int),
        1 => number(),
    ]
    .boxed()
}

/// A hostile string.
fn string() -> BoxedStrategy<Value> {
    prop_oneof![
        4 => select(HOSTILE_STRINGS).prop_map(text),
        3 => select(VARIANTS).prop_map(text),
        1 => select(DOTTED).prop_map(text),
        2 => any::<String>().prop_map(Value::String),
        1 => (select(vec!["x", "🦀", "\u{0}", "a\""]), select(vec![1000usize, 10_000]))
            .prop_map(|(s, n)| Value::String(s.repeat(n))),
    ]
    .boxed()
}

/// Any scalar.
fn scalar() -> BoxedStrategy<Value> {
    prop_oneof![
        4 => number(),
        3 => string(),
        1 => any::<bool>().prop_map(Value::Boolean),
        1 => Just(Value::Datetime(
            "1979-05-27T07:32:00Z".parse().expect("a TOML date-time")
        )),
    ]
    .boxed()
}

/// Any value: a scalar, or small arrays and tables of them.
fn value() -> BoxedStrategy<Value> {
    scalar()
        .prop_recursive(3, 24, 6, |inner| {
            prop_oneof![
                proptest::collection::vec(inner.clone(), 0..6).prop_map(Value::Array),
                proptest::collection::btree_map(select(KEYS), inner, 0..5).prop_map(|m| {
                    Value::Table(m.into_iter().map(|(k, v)| (k.to_string(), v)).collect())
                }),
            ]
        })
        .boxed()
}

/// A table of the entries that are present.
fn table(entries: Vec<(&str, Option<Value>)>) -> Value {
    Value::Table(
        entries
            .into_iter()
            .filter_map(|(k, v)| v.map(|v| (k.to_string(), v)))
            .collect(),
    )
}

/// An enum value as a scene may spell it, by `style`: `{ kind = "x", fields… }`,
/// `{ x = { fields… } }`, or the bare name `"x"` when no field is present (contopt-input reads
/// the three alike). A kind that is not a string is written the first way.
fn tagged(style: u8, kind: Value, fields: Vec<(&str, Option<Value>)>) -> Value {
    let bare = fields.iter().all(|(_, v)| v.is_none());
    match (style % 3, kind) {
        (0, Value::String(name)) if bare => Value::String(name),
        (1, Value::String(name)) => Value::Table([(name, table(fields))].into_iter().collect()),
        (_, kind) => {
            let mut entries = vec![("kind", Some(kind))];
            entries.extend(fields);
            table(entries)
        }
    }
}

fn opt(s: BoxedStrategy<Value>) -> BoxedStrategy<Option<Value>> {
    proptest::option::weighted(0.7, s).boxed()
}

fn kind_name(pool: &'static [&'static str]) -> BoxedStrategy<Value> {
    prop_oneof![4 => select(pool).prop_map(text), 1 => string()].boxed()
}

fn numbers(max: usize) -> BoxedStrategy<Value> {
    proptest::collection::vec(number(), 0..max)
        .prop_map(Value::Array)
        .boxed()
}

// ---------------------------------------------------------------------------------------------
// Hostile sections of the schema: each kind of a choice with hostile fields.

fn material() -> BoxedStrategy<Value> {
    (opt(number()), opt(number()))
        .prop_map(|(e, nu)| table(vec![("e_mpa", e), ("nu", nu)]))
        .boxed()
}

/// A finite-element analysis: a name, or a plane analysis with its thickness.
fn analysis() -> BoxedStrategy<Value> {
    (any::<u8>(), kind_name(ANALYSES), opt(number()))
        .prop_map(|(style, name, thickness)| match name.as_str() {
            Some("axisymmetric") => tagged(style, name, vec![]),
            _ => tagged(style, name, vec![("thickness_mm", thickness)]),
        })
        .boxed()
}

/// A contact zone of any kind.
fn zone() -> BoxedStrategy<Value> {
    let cells = proptest::collection::vec(count(), 0..4).prop_map(Value::Array);
    prop_oneof![
        (any::<u8>(), kind_name(&["grid"]), cells, opt(numbers(4)))
            .prop_map(|(s, k, c, d)| tagged(s, k, vec![("cells", Some(c)), ("cell_mm", d)])),
        (
            any::<u8>(),
            kind_name(&["rings"]),
            opt(count()),
            opt(number())
        )
            .prop_map(|(s, k, n, r)| tagged(s, k, vec![("rings", n), ("radius_mm", r)])),
        (
            any::<u8>(),
            kind_name(&["strips"]),
            opt(count()),
            opt(number()),
            opt(analysis())
        )
            .prop_map(|(s, k, n, a, an)| tagged(
                s,
                k,
                vec![("strips", n), ("half_width_mm", a), ("analysis", an)]
            )),
        (
            (any::<u8>(), kind_name(&["faces"]), opt(analysis())),
            (
                opt(number()),
                opt(count()),
                opt(number()),
                opt(kind_name(&["q8", "q9"]))
            ),
        )
            .prop_map(|((s, k, an), (r, n, g, e))| tagged(
                s,
                k,
                vec![
                    ("analysis", an),
                    ("radius_mm", r),
                    ("elements", n),
                    ("grading", g),
                    ("element", e),
                ]
            )),
        (
            any::<u8>(),
            kind_name(&["mesh"]),
            opt(analysis()),
            opt(number())
        )
            .prop_map(|(s, k, an, d)| tagged(
                s,
                k,
                vec![("analysis", an), ("search_mm", d)]
            )),
    ]
    .boxed()
}

/// A roller's crown of any kind.
fn profile() -> BoxedStrategy<Value> {
    (
        any::<u8>(),
        kind_name(CROWNS),
        (opt(number()), opt(number()), opt(number())),
        proptest::option::weighted(0.3, string()),
    )
        .prop_map(|(style, kind, (k1, k2, z_m), file)| match kind.as_str() {
            Some("fujiwara_kawase") => {
                tagged(style, kind, vec![("k1", k1), ("k2", k2), ("z_m_mm", z_m)])
            }
            Some("table") => tagged(style, kind, vec![("file", file)]),
            _ => tagged(style, kind, vec![]),
        })
        .boxed()
}

/// A gap of any kind.
fn gap() -> BoxedStrategy<Value> {
    let roller = (
        (opt(number()), opt(number()), opt(number())),
        (opt(number()), opt(number()), opt(profile())),
    );
    (any::<u8>(), kind_name(GAP_KINDS), opt(number()), roller)
        .prop_map(
            |(style, kind, r, ((d, l, dr), (tilt, reach, profile)))| match kind.as_str() {
                Some("flat") => tagged(style, kind, vec![]),
                Some("roller") => tagged(
                    style,
                    kind,
                    vec![
                        ("diameter_mm", d),
                        ("length_mm", l),
                        ("raceway_diameter_mm", dr),
                        ("tilt_arcmin", tilt),
                        ("reach_b", reach),
                        ("profile", profile),
                    ],
                ),
                _ => tagged(style, kind, vec![("radius_mm", r)]),
            },
        )
        .boxed()
}

/// A load of the contact or of a punch: `{ force_n = … }` and its kin, `"none"`, or junk.
fn load() -> BoxedStrategy<Value> {
    const LOADS: &[&str] = &["force_n", "approach_mm", "pressure_mpa", "displacement_mm"];
    prop_oneof![
        4 => (select(LOADS), number()).prop_map(|(k, v)| table(vec![(k, Some(v))])),
        1 => Just(text("none")),
        1 => string(),
    ]
    .boxed()
}

/// A base's supports: names, some not supports, repeated or missing.
fn supports() -> BoxedStrategy<Value> {
    proptest::collection::vec(kind_name(SUPPORTS), 0..4)
        .prop_map(Value::Array)
        .boxed()
}

/// A body of any kind.
fn body() -> BoxedStrategy<Value> {
    prop_oneof![6 => built_body(), 1 => mesh_body()].boxed()
}

/// A body of the kinds built on a zone, or of any name.
fn built_body() -> BoxedStrategy<Value> {
    let dims = (opt(number()), opt(number()), opt(number()), opt(count()));
    (
        (any::<u8>(), kind_name(BODY_KINDS), opt(string())),
        (opt(material()), dims),
        (opt(supports()), opt(load()), opt(number())),
    )
        .prop_map(
            |((style, kind, name), (m, (radius, height, size, layers)), (supports, load, k))| {
                let fields = match kind.as_str() {
                    Some("rigid") => vec![],
                    Some("half_space") => vec![("material", m), ("datum_mm", size)],
                    Some("fe_base") => vec![
                        ("material", m),
                        ("radius_mm", radius),
                        ("height_mm", height),
                        ("supports", supports),
                        ("layers", layers),
                    ],
                    Some("fe_punch") => vec![
                        ("material", m),
                        ("height_mm", height),
                        ("load", load),
                        ("layers", layers),
                    ],
                    Some("fe_block") => vec![("material", m), ("size_mm", size)],
                    Some("winkler") => vec![("modulus_mpa_per_mm", k)],
                    _ => vec![("material", m), ("radius_mm", radius)],
                };
                let mut fields = fields;
                fields.push(("name", name));
                tagged(style, kind, fields)
            },
        )
        .boxed()
}

/// An `fe_mesh` body with hostile fields: a mesh of the folder or junk, groups or junk, an
/// extent of hostile numbers, supports and loads of any shape.
fn mesh_body() -> BoxedStrategy<Value> {
    let name = || prop_oneof![3 => select(GROUPS).prop_map(text), 1 => string()].boxed();
    let mesh = prop_oneof![
        3 => select(MESHES).prop_map(|m| text(&format!("../meshes/{m}"))),
        1 => string(),
    ]
    .boxed();
    let fix = proptest::collection::vec(kind_name(&["x", "y", "z"]), 0..3)
        .prop_map(Value::Array)
        .boxed();
    let support = (opt(name()), opt(fix))
        .prop_map(|(group, fix)| table(vec![("group", group), ("fix", fix)]))
        .boxed();
    let load = (
        opt(name()),
        select(&["pressure_mpa", "traction_mpa", "displacement_mm", "along"][..]),
        prop_oneof![number(), numbers(3), kind_name(&["x", "y"])],
        opt(number()),
    )
        .prop_map(|(group, key, v, p)| {
            table(vec![("group", group), (key, Some(v)), ("pressure_mpa", p)])
        })
        .boxed();
    (
        (any::<u8>(), opt(mesh), opt(name()), opt(name())),
        (opt(numbers(3)), opt(material())),
        (
            opt(proptest::collection::vec(support, 0..3)
                .prop_map(Value::Array)
                .boxed()),
            opt(proptest::collection::vec(load, 0..3)
                .prop_map(Value::Array)
                .boxed()),
        ),
    )
        .prop_map(
            |((style, mesh, surface, contact), (extent, m), (supports, loads))| {
                tagged(
                    style,
                    text("fe_mesh"),
                    vec![
                        ("mesh", mesh),
                        ("surface", surface),
                        ("contact", contact),
                        ("extent_mm", extent),
                        ("material", m),
                        ("supports", supports),
                        ("loads", loads),
                    ],
                )
            },
        )
        .boxed()
}

fn bodies() -> BoxedStrategy<Value> {
    prop_oneof![
        4 => proptest::collection::vec(body(), 2..=2).prop_map(Value::Array),
        1 => proptest::collection::vec(body(), 0..5).prop_map(Value::Array),
    ]
    .boxed()
}

fn solver() -> BoxedStrategy<Value> {
    (
        (any::<u8>(), kind_name(SOLVERS), opt(number())),
        (
            proptest::option::weighted(0.4, number()),
            proptest::option::weighted(0.4, count()),
            proptest::option::weighted(0.2, scalar()),
        ),
    )
        .prop_map(|((style, kind, c), (tolerance, steps, accelerate))| {
            let fields = match kind.as_str() {
                Some("auto" | "active_set") => vec![],
                Some("qp") => vec![("tolerance", tolerance)],
                Some("penalty") => vec![("c_mpa_per_mm", c)],
                Some("polonsky_keer") => vec![("tolerance", tolerance), ("max_steps", steps)],
                _ => vec![
                    ("c_mpa_per_mm", c),
                    ("tolerance", tolerance),
                    ("max_steps", steps),
                    ("accelerate", accelerate),
                ],
            };
            tagged(style, kind, fields)
        })
        .boxed()
}

/// A design method of any kind with its settings.
fn method() -> BoxedStrategy<Value> {
    (
        any::<u8>(),
        kind_name(METHODS),
        proptest::option::weighted(0.4, number()),
        proptest::option::weighted(0.4, count()),
    )
        .prop_map(|(style, kind, tolerance, steps)| method_value(style, kind, tolerance, steps))
        .boxed()
}

/// A design method with its tolerance (or TOLH) and its count of steps (iterations, passes,
/// evaluations), each as the method names it.
fn method_value(style: u8, kind: Value, tolerance: Option<Value>, steps: Option<Value>) -> Value {
    let fields = match kind.as_str() {
        Some("given_load" | "given_displacement") => {
            vec![("tolh_mm2", tolerance), ("max_iterations", steps)]
        }
        Some("linear_programme") => vec![("max_passes", steps), ("tolerance", tolerance)],
        Some("profile_search") => vec![("tolerance", tolerance), ("max_evaluations", steps)],
        _ => vec![("tolerance", tolerance), ("max_iterations", steps)],
    };
    tagged(style, kind, fields)
}

fn controller() -> BoxedStrategy<Value> {
    let leaf = (
        (any::<u8>(), kind_name(&["constant", "trapezoid", "cubic"])),
        (opt(number()), opt(number()), opt(number())),
        proptest::option::weighted(0.3, count()),
    )
        .prop_map(|((style, kind), (level, l1, l2), axis)| {
            let fields = match kind.as_str() {
                Some("constant") => vec![("level", level)],
                _ => vec![("l1_mm", l1), ("l2_mm", l2), ("axis", axis)],
            };
            tagged(style, kind, fields)
        });
    products(leaf, 6, 32)
}

/// Ω_v: a strip, a disc or a box, with hostile numbers.
fn omega_v() -> BoxedStrategy<Value> {
    (
        (any::<u8>(), kind_name(&["strip", "disc", "box"])),
        proptest::option::weighted(0.7, count()),
        proptest::option::weighted(0.7, prop_oneof![number(), numbers(3)]),
        proptest::option::weighted(0.7, prop_oneof![number(), numbers(3)]),
        proptest::option::weighted(0.7, numbers(3)),
        proptest::option::weighted(0.7, number()),
    )
        .prop_map(|((style, kind), axis, from, to, centre, radius)| {
            let fields = match kind.as_str() {
                Some("strip") => vec![("axis", axis), ("from_mm", from), ("to_mm", to)],
                Some("disc") => vec![("centre_mm", centre), ("radius_mm", radius)],
                _ => vec![("from_mm", from), ("to_mm", to)],
            };
            tagged(style, kind, fields)
        })
        .boxed()
}

fn optimisation() -> BoxedStrategy<Value> {
    (
        method(),
        proptest::option::weighted(0.8, controller()),
        proptest::option::weighted(0.4, omega_v()),
        proptest::option::weighted(0.4, count()),
    )
        .prop_map(|(method, controller, omega_v, axis)| {
            table(vec![
                ("method", Some(method)),
                ("controller", controller),
                ("omega_v", omega_v),
                ("profile_axis", axis),
            ])
        })
        .boxed()
}

fn subsurface() -> BoxedStrategy<Value> {
    let section = (kind_name(&["x", "y"]), opt(number()))
        .prop_map(|(along, at)| table(vec![("along", Some(along)), ("at_mm", at)]));
    (
        opt(number()),
        opt(count()),
        proptest::option::weighted(0.5, proptest::collection::vec(section, 0..4)),
    )
        .prop_map(|(depth, depths, sections)| {
            let sub = table(vec![
                ("max_depth_mm", depth),
                ("depths", depths),
                ("sections", sections.map(Value::Array)),
            ]);
            table(vec![("subsurface", Some(sub))])
        })
        .boxed()
}

fn named_cases() -> BoxedStrategy<Value> {
    let case = (
        string(),
        proptest::collection::btree_map(select(DOTTED), value(), 0..3),
    )
        .prop_map(|(label, set)| {
            let set = set.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
            table(vec![
                ("label", Some(label)),
                ("set", Some(Value::Table(set))),
            ])
        });
    proptest::collection::vec(case, 0..4)
        .prop_map(Value::Array)
        .boxed()
}

/// A section or value of the schema, with hostile leaves, and where it goes.
fn section() -> BoxedStrategy<(Vec<&'static str>, Value)> {
    proptest::strategy::Union::new(contact_sections().into_iter().chain(other_sections())).boxed()
}

/// A section of the schema at `path`.
fn at(
    path: &'static [&'static str],
    s: BoxedStrategy<Value>,
) -> BoxedStrategy<(Vec<&'static str>, Value)> {
    s.prop_map(move |v| (path.to_vec(), v)).boxed()
}

/// The parts of `[contact]` and the bodies, with hostile leaves.
fn contact_sections() -> Vec<BoxedStrategy<(Vec<&'static str>, Value)>> {
    const ZONE_NUMBERS: &[&str] = &[
        "cells",
        "cell_mm",
        "rings",
        "radius_mm",
        "strips",
        "half_width_mm",
        "elements",
        "grading",
    ];
    const GAP_NUMBERS: &[&str] = &[
        "radius_mm",
        "diameter_mm",
        "length_mm",
        "raceway_diameter_mm",
        "tilt_arcmin",
        "reach_b",
    ];
    const BODY_NUMBERS: &[&str] = &[
        "radius_mm",
        "height_mm",
        "size_mm",
        "layers",
        "datum_mm",
        "modulus_mpa_per_mm",
    ];
    let leaf = |path: &'static str, keys: &'static [&'static str]| {
        (select(keys), prop_oneof![count(), number()])
            .prop_map(move |(k, v)| (vec!["contact", path, k], v))
            .boxed()
    };
    let body_number = (select(&["0", "1"][..]), select(BODY_NUMBERS), number())
        .prop_map(|(k, key, v)| (vec!["body", k, key], v))
        .boxed();
    let body_at = (select(&["0", "1", "2"][..]), body())
        .prop_map(|(k, b)| (vec!["body", k], b))
        .boxed();
    let material_at = (select(&["0", "1"][..]), material())
        .prop_map(|(k, m)| (vec!["body", k, "material"], m))
        .boxed();
    vec![
        at(&["contact", "zone"], zone()),
        at(&["contact", "zone", "analysis"], analysis()),
        at(&["contact", "gap"], gap()),
        at(&["contact", "gap", "profile"], profile()),
        at(&["contact", "load"], load()),
        leaf("zone", ZONE_NUMBERS),
        leaf("gap", GAP_NUMBERS),
        at(&["body"], bodies()),
        body_at,
        body_number,
        material_at,
    ]
}

/// The sections other than the contact's and the bodies'.
fn other_sections() -> Vec<BoxedStrategy<(Vec<&'static str>, Value)>> {
    let envelope = (numbers(6), numbers(6))
        .prop_map(|(f, t)| table(vec![("load_factors", Some(f)), ("tilts_arcmin", Some(t))]))
        .boxed();
    let sweep = (
        prop_oneof![3 => select(DOTTED).prop_map(text), 1 => string()],
        numbers(8),
    )
        .prop_map(|(key, values)| table(vec![("key", Some(key)), ("values", Some(values))]))
        .boxed();
    vec![
        at(&["solver"], solver()),
        at(&["optimisation"], optimisation()),
        at(&["optimisation", "method"], method()),
        at(&["optimisation", "controller"], controller()),
        at(&["optimisation", "omega_v"], omega_v()),
        at(&["optimisation", "profile_axis"], count()),
        at(&["output"], subsurface()),
        at(&["envelope"], envelope),
        at(&["sweep"], sweep),
        at(&["case"], named_cases()),
        at(&["dense_limit_mb"], number()),
        at(&["memory_limit_mb"], number()),
        at(&["name"], string()),
        at(&["description"], scalar()),
    ]
}

// ---------------------------------------------------------------------------------------------
// Property 1: the bundled scenes, mutated.

/// Every bundled scene.
const SCENES: &[contopt_scene::Bundled] = contopt_scene::BUNDLED;

/// A step into a tree of values.
#[derive(Clone, Debug, PartialEq)]
enum Step {
    Key(String),
    At(usize),
}

/// One change of a scene's tree; `at` picks among the nodes it applies to.
#[derive(Clone, Debug)]
enum Mutation {
    /// Replaces a scalar.
    Scalar { at: Index, value: Value },
    /// Replaces a number.
    Number { at: Index, value: Value },
    /// Replaces a string.
    Text { at: Index, value: Value },
    /// Removes a key.
    Delete { at: Index },
    /// Adds (or replaces) a key of a table.
    Add {
        at: Index,
        key: &'static str,
        value: Value,
    },
    /// Puts a section at its place in the schema (making the tables on the way).
    Set {
        path: Vec<&'static str>,
        value: Value,
    },
    /// Wraps a node in `depth` arrays or tables.
    Nest {
        at: Index,
        depth: usize,
        array: bool,
    },
    /// Replaces an array by `len` copies of `item`.
    Resize { at: Index, len: usize, item: Value },
}

fn mutation() -> BoxedStrategy<Mutation> {
    prop_oneof![
        3 => (any::<Index>(), scalar()).prop_map(|(at, value)| Mutation::Scalar { at, value }),
        4 => (any::<Index>(), prop_oneof![number(), count()])
            .prop_map(|(at, value)| Mutation::Number { at, value }),
        2 => (any::<Index>(), string()).prop_map(|(at, value)| Mutation::Text { at, value }),
        2 => any::<Index>().prop_map(|at| Mutation::Delete { at }),
        2 => (any::<Index>(), select(KEYS), value())
            .prop_map(|(at, key, value)| Mutation::Add { at, key, value }),
        6 => section().prop_map(|(path, value)| Mutation::Set { path, value }),
        1 => (
            any::<Index>(),
            prop_oneof![1usize..8, select(vec![50usize, 127, 128, 129, 200])],
            any::<bool>()
        )
            .prop_map(|(at, depth, array)| Mutation::Nest { at, depth, array }),
        1 => (
            any::<Index>(),
            prop_oneof![0usize..6, select(vec![100usize, 1000, 10_000])],
            prop_oneof![number(), count()]
        )
            .prop_map(|(at, len, item)| Mutation::Resize { at, len, item }),
    ]
    .boxed()
}

/// Every node below `v` with its path, depth first.
fn nodes(v: &Value, path: &mut Vec<Step>, out: &mut Vec<(Vec<Step>, Value)>) {
    match v {
        Value::Table(t) => {
            for (k, child) in t {
                path.push(Step::Key(k.clone()));
                out.push((path.clone(), child.clone()));
                nodes(child, path, out);
                path.pop();
            }
        }
        Value::Array(a) => {
            for (i, child) in a.iter().enumerate() {
                path.push(Step::At(i));
                out.push((path.clone(), child.clone()));
                nodes(child, path, out);
                path.pop();
            }
        }
        _ => {}
    }
}

fn node_mut<'a>(root: &'a mut Value, path: &[Step]) -> Option<&'a mut Value> {
    path.iter().try_fold(root, |v, step| match (v, step) {
        (Value::Table(t), Step::Key(k)) => t.get_mut(k),
        (Value::Array(a), Step::At(i)) => a.get_mut(*i),
        _ => None,
    })
}

/// Puts `value` at `path` of `root`, making the tables on the way (replacing what is not one);
/// a step that is an index of an array goes into it.
fn set_section(root: &mut Value, path: &[&str], value: Value) {
    let mut node = root;
    for (k, key) in path.iter().enumerate() {
        let last = k + 1 == path.len();
        if let (Value::Array(a), Ok(i)) = (&*node, key.parse::<usize>()) {
            if i < a.len() {
                let Value::Array(a) = node else {
                    unreachable!()
                };
                node = &mut a[i];
                continue;
            }
        }
        if !matches!(node, Value::Table(_)) {
            *node = Value::Table(Default::default());
        }
        let Value::Table(t) = node else {
            unreachable!()
        };
        node = t.entry(key.to_string()).or_insert_with(|| {
            if last {
                Value::Boolean(false)
            } else {
                Value::Table(Default::default())
            }
        });
    }
    *node = value;
}

/// `v` wrapped in `depth` arrays or tables.
fn nested(mut v: Value, depth: usize, array: bool) -> Value {
    for _ in 0..depth {
        v = if array {
            Value::Array(vec![v])
        } else {
            Value::Table([("a".to_string(), v)].into_iter().collect())
        };
    }
    v
}

/// Applies `m` to `root`; a mutation with no node to act on does nothing.
fn apply(root: &mut Value, m: &Mutation) {
    let mut all = vec![(vec![], root.clone())];
    nodes(root, &mut vec![], &mut all);
    let pick = |at: &Index, keep: &dyn Fn(&[Step], &Value) -> bool| -> Option<Vec<Step>> {
        let found: Vec<&Vec<Step>> = all
            .iter()
            .filter(|(p, v)| keep(p, v))
            .map(|(p, _)| p)
            .collect();
        (!found.is_empty()).then(|| found[at.index(found.len())].clone())
    };
    let not_root = |p: &[Step]| !p.is_empty();
    let replace = |root: &mut Value, path: Option<Vec<Step>>, value: Value| {
        if let Some(node) = path.and_then(|p| node_mut(root, &p)) {
            *node = value;
        }
    };
    match m {
        Mutation::Scalar { at, value } => {
            let path = pick(at, &|p, v| {
                not_root(p) && !matches!(v, Value::Table(_) | Value::Array(_))
            });
            replace(root, path, value.clone());
        }
        Mutation::Number { at, value } => {
            let path = pick(at, &|_, v| matches!(v, Value::Integer(_) | Value::Float(_)));
            replace(root, path, value.clone());
        }
        Mutation::Text { at, value } => {
            let path = pick(at, &|_, v| matches!(v, Value::String(_)));
            replace(root, path, value.clone());
        }
        Mutation::Delete { at } => {
            let path = pick(at, &|p, _| matches!(p.last(), Some(Step::Key(_))));
            if let Some(mut path) = path {
                if let Some(Step::Key(k)) = path.pop() {
                    if let Some(Value::Table(t)) = node_mut(root, &path) {
                        t.remove(&k);
                    }
                }
            }
        }
        Mutation::Add { at, key, value } => {
            let path = pick(at, &|_, v| matches!(v, Value::Table(_)));
            if let Some(Value::Table(t)) = path.and_then(|p| node_mut(root, &p)) {
                t.insert(key.to_string(), value.clone());
            }
        }
        Mutation::Set { path, value } => set_section(root, path, value.clone()),
        Mutation::Nest { at, depth, array } => {
            let path = pick(at, &|p, _| not_root(p));
            if let Some(node) = path.and_then(|p| node_mut(root, &p)) {
                *node = nested(node.clone(), *depth, *array);
            }
        }
        Mutation::Resize { at, len, item } => {
            let path = pick(at, &|_, v| matches!(v, Value::Array(_)));
            replace(root, path, Value::Array(vec![item.clone(); *len]));
        }
    }
}

/// A tree of values as JSON: NaN and the infinities become null (as serde_json writes them),
/// the sentinels their JSON values.
fn to_json(v: &Value) -> serde_json::Value {
    use serde_json::Value as J;
    match v {
        Value::String(s) if s == U64_MAX => J::from(u64::MAX),
        Value::String(s) if s == NULL => J::Null,
        Value::String(s) => J::String(s.clone()),
        Value::Integer(i) => J::from(*i),
        Value::Float(f) => serde_json::Number::from_f64(*f).map_or(J::Null, J::Number),
        Value::Boolean(b) => J::Bool(*b),
        Value::Datetime(d) => J::String(d.to_string()),
        Value::Array(a) => J::Array(a.iter().map(to_json).collect()),
        Value::Table(t) => J::Object(t.iter().map(|(k, v)| (k.clone(), to_json(v))).collect()),
    }
}

/// A bundled scene with its mutations.
#[derive(Clone)]
struct MutatedScene {
    scene: usize,
    mutations: Vec<Mutation>,
}

impl MutatedScene {
    fn tree(&self) -> Value {
        let mut root: Value = toml::from_str(SCENES[self.scene].text).expect("a bundled scene");
        for m in &self.mutations {
            apply(&mut root, m);
        }
        root
    }

    /// The scene as TOML (when TOML can write it) and as JSON.
    fn texts(&self) -> (Option<String>, String) {
        let tree = self.tree();
        let json = serde_json::to_string_pretty(&to_json(&tree)).expect("JSON writes any tree");
        (toml::to_string(&tree).ok(), json)
    }
}

impl std::fmt::Debug for MutatedScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (toml, json) = self.texts();
        writeln!(
            f,
            "scene {} with {:?}",
            SCENES[self.scene].name, self.mutations
        )?;
        match toml {
            Some(toml) => writeln!(f, "--- as TOML:\n{}", preview_block(&toml)),
            None => writeln!(f, "--- as JSON:\n{}", preview_block(&json)),
        }
    }
}

fn preview_block(text: &str) -> String {
    if text.len() <= 8000 {
        text.to_string()
    } else {
        let cut: String = text.chars().take(8000).collect();
        format!("{cut}\n… ({} bytes in all)", text.len())
    }
}

fn mutated_scene() -> impl Strategy<Value = MutatedScene> {
    (0..SCENES.len(), proptest::collection::vec(mutation(), 1..5))
        .prop_map(|(scene, mutations)| MutatedScene { scene, mutations })
}

proptest! {
    #![proptest_config(config(SCENE_CASES))]

    /// Mutated bundled scenes, as TOML and as JSON, read by [`read_and_run`]: a bundled
    /// scene is too large to run here, and seldom becomes tiny (then it runs).
    #[test]
    fn mutated_scenes(case in mutated_scene()) {
        let tree = SceneTree(case.tree());
        let (toml, json) = tree.texts();
        if let Some(toml) = toml {
            read_and_run(toml, Format::Toml, tree.tiny(), Some(&tree));
        }
        read_and_run(json, Format::Json, false, Some(&tree));
    }
}

// ---------------------------------------------------------------------------------------------
// Property 1b: scenes made from the schema, most of them plausible throughout and the rest
// with each value hostile one time in eight ([`HOSTILITY`]), most pairs of bodies valid for
// their zone and some not, so that most of them get past the reader to the checks of the
// pairing and the bodies (and, when tiny, to the solvers).

/// The chance that a value of a hostile generated scene is hostile (a quarter of the scenes
/// are; the others are plausible throughout).
const HOSTILITY: f64 = 0.125;

/// The cases of each scene property in the short run.
const SCENE_CASES: u32 = 768;
/// The cases of each other property in the short run.
const OTHER_CASES: u32 = 512;

/// The file a scene is read as: in a folder of its own that holds `crown.csv`, the crown table
/// a generated roller may name, beside a folder `meshes` of the meshes generated imported
/// bodies and the bundled scenes read (`../meshes/…`).
fn scene_file() -> PathBuf {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    let dir = DIR.get_or_init(|| {
        let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("fuzz");
        let dir = root.join("scenes");
        std::fs::create_dir_all(&dir).expect("a folder for the fuzz scenes");
        let table = "x_mm, drop_mm\n0, 0\n2, 0.0005\n4.5, 0.01\n";
        std::fs::write(dir.join("crown.csv"), table).expect("a crown table");
        let meshes = root.join("meshes");
        std::fs::create_dir_all(&meshes).expect("a folder for the meshes");
        let repository = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../meshes");
        for name in MESHES {
            std::fs::copy(repository.join(name), meshes.join(name)).expect("a mesh");
        }
        for (path, bytes) in SCENES.iter().flat_map(|s| s.meshes) {
            std::fs::write(dir.join(path), bytes).expect("a bundled scene's mesh");
        }
        dir
    });
    dir.join("fuzz.toml")
}

/// A hostile number with probability `h` (the scene's hostility), to replace a plausible
/// value.
fn spoiler(h: f64) -> BoxedStrategy<Option<Value>> {
    chance(h, number())
}

/// A value of `s` with probability `p`, else `None` (proptest refuses a weight of 0).
fn chance(p: f64, s: BoxedStrategy<Value>) -> BoxedStrategy<Option<Value>> {
    if p > 0.0 {
        proptest::option::weighted(p, s).boxed()
    } else {
        Just(None).boxed()
    }
}

/// `v`, or the hostile number that spoils it.
fn spoil(v: f64, spoiler: Option<Value>) -> Value {
    spoiler.unwrap_or(Value::Float(v))
}

/// A float in `lo..hi`, or (with probability `h`) a hostile number.
fn real_in(h: f64, lo: f64, hi: f64) -> BoxedStrategy<Value> {
    (lo..hi, spoiler(h)).prop_map(|(v, s)| spoil(v, s)).boxed()
}

/// An integer in `lo..=hi`, or (with probability `h`) a hostile count.
fn count_in(h: f64, lo: i64, hi: i64) -> BoxedStrategy<Value> {
    (lo..=hi, chance(h, count()))
        .prop_map(|(n, s)| s.unwrap_or(int(n)))
        .boxed()
}

/// One of `names`, or (with probability `h`) a hostile string.
fn one_of(h: f64, names: &'static [&'static str]) -> BoxedStrategy<Value> {
    (select(names), chance(h, string()))
        .prop_map(|(n, s)| s.unwrap_or(text(n)))
        .boxed()
}

fn maybe(p: f64, s: BoxedStrategy<Value>) -> BoxedStrategy<Option<Value>> {
    proptest::option::weighted(p, s).boxed()
}

fn plausible_material(h: f64) -> BoxedStrategy<Value> {
    (real_in(h, 1e4, 3e5), real_in(h, 0.0, 0.45))
        .prop_map(|(e, nu)| table(vec![("e_mpa", Some(e)), ("nu", Some(nu))]))
        .boxed()
}

/// A plane analysis with its thickness, spelled either way.
fn plane_analysis(h: f64) -> BoxedStrategy<Value> {
    (
        any::<u8>(),
        one_of(h, &["plane_stress", "plane_strain"]),
        real_in(h, 1.0, 20.0),
    )
        .prop_map(|(style, name, t)| tagged(style, name, vec![("thickness_mm", Some(t))]))
        .boxed()
}

/// The contact and the bodies of a generated scene, and what a plausible design needs of them.
#[derive(Clone, Debug)]
struct Setup {
    zone: Value,
    gap: Option<Value>,
    load: Option<Value>,
    bodies: Vec<Value>,
    /// How far the zone reaches from its centre along x (or r) and y \[mm\], roughly: plausible
    /// controllers and Ω_v lie within it.
    extent: [f64; 2],
    /// Whether a body floats under a given load (a contact force, a punch's pressure).
    floating: bool,
    /// Whether the gap is a roller's.
    roller: bool,
}

/// The draw of a gap: its kind, a radius of its own, and a flat punch's radius as a fraction
/// of the zone's reach.
#[derive(Clone, Debug)]
struct GapDraw {
    kind: &'static str,
    radius: f64,
    fraction: f64,
    spoiler: Option<Value>,
    style: u8,
}

impl GapDraw {
    /// The gap on a zone that reaches `extent` \[mm\]; a flat gap sometimes left to its default.
    fn value(&self, extent: f64) -> Option<Value> {
        let r = match self.kind {
            "flat_punch" => extent * self.fraction,
            _ => self.radius,
        };
        let r = spoil(r, self.spoiler.clone());
        match self.kind {
            "flat" if self.style.is_multiple_of(2) => None,
            "flat" => Some(tagged(self.style, text("flat"), vec![])),
            "measured" => Some(tagged(self.style, text("measured"), vec![])),
            kind => Some(tagged(self.style, text(kind), vec![("radius_mm", Some(r))])),
        }
    }
}

fn gap_draw(h: f64, kinds: &'static [&'static str]) -> BoxedStrategy<GapDraw> {
    (
        select(kinds),
        0.5..50.0f64,
        0.3..1.2f64,
        spoiler(h),
        any::<u8>(),
    )
        .prop_map(|(kind, radius, fraction, spoiler, style)| GapDraw {
            kind,
            radius,
            fraction,
            spoiler,
            style,
        })
        .boxed()
}

/// The draw of the contact's load: a force, or an approach as a fraction of the zone's reach.
#[derive(Clone, Debug)]
struct LoadDraw {
    force: bool,
    newtons: f64,
    fraction: f64,
    spoiler: Option<Value>,
}

impl LoadDraw {
    /// A force when `force` (the body above takes one), else an approach.
    fn value(&self, force: bool, extent: f64) -> Value {
        if force {
            let f = spoil(self.newtons, self.spoiler.clone());
            table(vec![("force_n", Some(f))])
        } else {
            let a = spoil(extent * self.fraction, self.spoiler.clone());
            table(vec![("approach_mm", Some(a))])
        }
    }
}

fn load_draw(h: f64) -> BoxedStrategy<LoadDraw> {
    (any::<bool>(), 1.0..1e4f64, 1e-4..1e-2f64, spoiler(h))
        .prop_map(|(force, newtons, fraction, spoiler)| LoadDraw {
            force,
            newtons,
            fraction,
            spoiler,
        })
        .boxed()
}

/// A body that grids its surface (`half_space`) or stands on one (`rigid`, `winkler`); a
/// half-space on strips sometimes has its datum.
fn surface_body(h: f64, kind: &'static str, strips: bool) -> BoxedStrategy<Value> {
    (
        any::<u8>(),
        plausible_material(h),
        maybe(0.3, real_in(h, 1.0, 1000.0)),
        real_in(h, 1.0, 1e5),
        maybe(0.2, one_of(h, &["a", "b", "bed"])),
    )
        .prop_map(move |(style, m, datum, k, name)| {
            let mut fields = match kind {
                "half_space" => vec![
                    ("material", Some(m)),
                    ("datum_mm", datum.filter(|_| strips)),
                ],
                "winkler" => vec![("modulus_mpa_per_mm", Some(k))],
                _ => vec![],
            };
            fields.push(("name", name));
            tagged(style, text(kind), fields)
        })
        .boxed()
}

/// Two bodies of a pair of kinds and the kind of the second.
fn pair_of(
    h: f64,
    pairs: &'static [(&'static str, &'static str)],
    strips: bool,
) -> BoxedStrategy<(Value, Value, &'static str)> {
    select(pairs)
        .prop_flat_map(move |(a, b)| {
            (
                surface_body(h, a, strips),
                surface_body(h, b, strips),
                Just(b),
            )
        })
        .boxed()
}

/// Pairs on a grid: half-spaces on either side, rigid bodies and beds.
const GRID_PAIRS: &[(&str, &str)] = &[
    ("half_space", "rigid"),
    ("half_space", "half_space"),
    ("winkler", "rigid"),
    ("rigid", "half_space"),
    ("half_space", "winkler"),
    ("rigid", "winkler"),
    ("winkler", "half_space"),
];

/// Pairs on rings or strips: a half-space below only.
const LINE_PAIRS: &[(&str, &str)] = &[
    ("half_space", "rigid"),
    ("winkler", "rigid"),
    ("half_space", "winkler"),
    ("rigid", "winkler"),
    ("winkler", "winkler"),
];

fn grid_setup(h: f64) -> BoxedStrategy<Setup> {
    (
        (1i64..=20, 1i64..=20, spoiler(h)),
        (
            1e-3..1.0f64,
            1e-3..1.0f64,
            spoiler(h),
            proptest::bool::weighted(0.7),
        ),
        pair_of(h, GRID_PAIRS, false),
        gap_draw(h, &["flat", "sphere", "cylinder", "flat_punch"]),
        load_draw(h),
        any::<u8>(),
    )
        .prop_map(
            |((nx, ny, s), (dx, dy, sd, omit), (below, above, kind), gap, load, style)| {
                // A sphere's grid may take its cell size from Hertz's contact; other gaps have no
                // extent of their own to span (one time in twenty they are left without, wrongly).
                let omit = omit && (gap.kind == "sphere" || style % 20 == 0);
                let extent = if omit {
                    [0.5, 0.5]
                } else {
                    [0.5 * nx as f64 * dx, 0.5 * ny as f64 * dy]
                };
                let cells = Value::Array(vec![spoil_count(nx, s), int(ny)]);
                let cell_mm = Value::Array(vec![spoil(dx, sd), Value::Float(dy)]);
                let fields = vec![
                    ("cells", Some(cells)),
                    ("cell_mm", (!omit).then_some(cell_mm)),
                ];
                let force = load.force && kind != "winkler";
                Setup {
                    zone: tagged(style, text("grid"), fields),
                    gap: gap.value(extent[0].min(extent[1])),
                    load: Some(load.value(force, extent[0].min(extent[1]))),
                    bodies: vec![below, above],
                    extent,
                    floating: force,
                    roller: false,
                }
            },
        )
        .boxed()
}

/// The count `n`, or the hostile number that spoils it.
fn spoil_count(n: i64, spoiler: Option<Value>) -> Value {
    spoiler.unwrap_or(int(n))
}

/// Rings (`strips` false) or strips, and the bodies on them.
fn line_setup(h: f64, strips: bool) -> BoxedStrategy<Setup> {
    let gaps: &'static [&'static str] = if strips {
        &["flat", "cylinder", "flat_punch"]
    } else {
        &["flat", "sphere", "flat_punch"]
    };
    (
        (1i64..=60, spoiler(h), 0.1..20.0f64, spoiler(h)),
        pair_of(h, LINE_PAIRS, strips),
        gap_draw(h, gaps),
        load_draw(h),
        (any::<u8>(), plane_analysis(h)),
    )
        .prop_map(
            move |((n, sn, a, sa), (below, above, kind), gap, load, (style, analysis))| {
                let fields = if strips {
                    vec![
                        ("strips", Some(spoil_count(n, sn))),
                        ("half_width_mm", Some(spoil(a, sa))),
                        ("analysis", Some(analysis)),
                    ]
                } else {
                    vec![
                        ("rings", Some(spoil_count(n, sn))),
                        ("radius_mm", Some(spoil(a, sa))),
                    ]
                };
                let name = if strips { "strips" } else { "rings" };
                let force = load.force && kind != "winkler";
                Setup {
                    zone: tagged(style, text(name), fields),
                    gap: gap.value(a),
                    load: Some(load.value(force, a)),
                    bodies: vec![below, above],
                    extent: [a, 0.0],
                    floating: force,
                    roller: false,
                }
            },
        )
        .boxed()
}

/// Pairs on finite-element faces: a base or a block below, a punch above, and the rigid bodies
/// and beds that stand on their faces.
const FACE_PAIRS: &[(&str, &str)] = &[
    ("fe_base", "fe_punch"),
    ("fe_base", "rigid"),
    ("fe_block", "rigid"),
    ("fe_base", "winkler"),
    ("fe_block", "fe_punch"),
    ("rigid", "fe_punch"),
    ("winkler", "fe_punch"),
    ("fe_block", "winkler"),
];

/// The draw of a body on faces, its sizes relative to the zone's radius.
#[derive(Clone, Debug)]
struct FeDraw {
    material: Value,
    height: Value,
    /// A base's radius over the zone's.
    wider: f64,
    /// A block's size over the zone's radius.
    larger: f64,
    spoiler: Option<Value>,
    layers: Option<Value>,
    supports: usize,
    /// A punch pressed by a pressure, else pushed down.
    pressure: bool,
    pressure_mpa: Value,
    /// A punch's push as a fraction of the zone's radius.
    sink: f64,
    modulus: Value,
    style: u8,
}

fn fe_draw(h: f64) -> BoxedStrategy<FeDraw> {
    (
        (plausible_material(h), real_in(h, 1.0, 100.0)),
        (1.2..3.0f64, 2.5..10.0f64, spoiler(h)),
        (maybe(0.4, count_in(h, 1, 8)), 0usize..6, any::<bool>()),
        (
            real_in(h, 1.0, 500.0),
            1e-4..1e-3f64,
            real_in(h, 1.0, 1e5),
            any::<u8>(),
        ),
    )
        .prop_map(
            |((material, height), (wider, larger, spoiler), (layers, supports, pressure), rest)| {
                let (pressure_mpa, sink, modulus, style) = rest;
                FeDraw {
                    material,
                    height,
                    wider,
                    larger,
                    spoiler,
                    layers,
                    supports,
                    pressure,
                    pressure_mpa,
                    sink,
                    modulus,
                    style,
                }
            },
        )
        .boxed()
}

impl FeDraw {
    /// The body of `kind` on faces of radius `radius` \[mm\] and `elements` elements,
    /// axisymmetric or plane: a base wider than the zone with the supports its analysis
    /// allows, a punch pressed or pushed, a block large enough for its 40 elements outside the
    /// zone to grow from the zone's, a rigid body or a bed.
    fn body(&self, kind: &'static str, radius: f64, axisymmetric: bool, elements: i64) -> Value {
        let options: &[&[&str]] = if axisymmetric {
            &[&["clamped"], &["axial"]]
        } else {
            &[
                &["clamped"],
                &["axial", "symmetry"],
                &["clamped", "symmetry"],
            ]
        };
        let supports = options[self.supports % options.len()];
        let supports = Value::Array(supports.iter().map(|s| text(s)).collect());
        let m = Some(self.material.clone());
        let fields = match kind {
            "fe_base" => vec![
                ("material", m),
                (
                    "radius_mm",
                    Some(spoil(radius * self.wider, self.spoiler.clone())),
                ),
                ("height_mm", Some(self.height.clone())),
                ("supports", Some(supports)),
                ("layers", self.layers.clone()),
            ],
            "fe_punch" => {
                let load = if self.pressure {
                    table(vec![("pressure_mpa", Some(self.pressure_mpa.clone()))])
                } else {
                    let w = spoil(-radius * self.sink, self.spoiler.clone());
                    table(vec![("displacement_mm", Some(w))])
                };
                vec![
                    ("material", m),
                    ("height_mm", Some(self.height.clone())),
                    ("load", Some(load)),
                    ("layers", self.layers.clone()),
                ]
            }
            "fe_block" => vec![
                ("material", m),
                (
                    "size_mm",
                    Some(spoil(
                        radius * self.larger.max(1.0 + 41.0 / elements as f64),
                        self.spoiler.clone(),
                    )),
                ),
            ],
            "winkler" => vec![("modulus_mpa_per_mm", Some(self.modulus.clone()))],
            _ => vec![],
        };
        tagged(self.style, text(kind), fields)
    }
}

fn faces_setup(h: f64) -> BoxedStrategy<Setup> {
    (
        (any::<bool>(), plane_analysis(h), 1.0..100.0f64, spoiler(h)),
        (
            (1i64..=8, chance(h, count())),
            maybe(0.3, real_in(h, 0.2, 5.0)),
            maybe(0.3, one_of(h, &["q8", "q9"])),
        ),
        (select(FACE_PAIRS), fe_draw(h), fe_draw(h)),
        gap_draw(h, &["flat", "flat", "curved", "flat_punch"]),
        load_draw(h),
        any::<u8>(),
    )
        .prop_map(
            |((axi, plane, r, sr), mesh, ((below, above), d0, d1), gap, load, style)| {
                let ((elements, spoiled), grading, element) = mesh;
                let analysis = if axi {
                    tagged(style, text("axisymmetric"), vec![])
                } else {
                    plane
                };
                let fields = vec![
                    ("analysis", Some(analysis)),
                    ("radius_mm", Some(spoil(r, sr))),
                    ("elements", Some(spoil_count(elements, spoiled))),
                    ("grading", grading),
                    ("element", element),
                ];
                let mut gap = gap;
                if gap.kind == "curved" {
                    gap.kind = if axi { "sphere" } else { "cylinder" };
                }
                // A punch carries its own load (or is pushed in); a rigid body takes a force or an
                // approach; a bed is pushed in.
                let (force, contact_load) = match above {
                    "fe_punch" if load.force => (false, None),
                    "rigid" => (load.force, Some(load.value(load.force, r))),
                    _ => (false, Some(load.value(false, r))),
                };
                Setup {
                    zone: tagged(style, text("faces"), fields),
                    gap: gap.value(r),
                    load: contact_load,
                    bodies: vec![
                        d0.body(below, r, axi, elements),
                        d1.body(above, r, axi, elements),
                    ],
                    extent: [r, 0.0],
                    floating: force || (above == "fe_punch" && d1.pressure),
                    roller: false,
                }
            },
        )
        .boxed()
}

fn raceway(h: f64) -> BoxedStrategy<Value> {
    prop_oneof![real_in(h, 20.0, 200.0), real_in(h, -500.0, -60.0)].boxed()
}

/// A crown of any kind; a table names the generated scene's `crown.csv`, or junk.
fn plausible_crown(h: f64) -> BoxedStrategy<Value> {
    (
        any::<u8>(),
        one_of(h, CROWNS),
        (
            real_in(h, 0.1, 3.0),
            real_in(h, 0.05, 1.0),
            real_in(h, 1e-4, 0.05),
        ),
        prop_oneof![4 => Just(text("crown.csv")), 1 => string()],
    )
        .prop_map(|(style, kind, (k1, k2, z_m), file)| match kind.as_str() {
            Some("fujiwara_kawase") => tagged(
                style,
                kind,
                vec![("k1", Some(k1)), ("k2", Some(k2)), ("z_m_mm", Some(z_m))],
            ),
            Some("table") => tagged(style, kind, vec![("file", Some(file))]),
            _ => tagged(style, kind, vec![]),
        })
        .boxed()
}

/// A roller on its raceway: two half-spaces on a grid (its cell size mostly from the roller),
/// pressed by a force.
fn roller_setup(h: f64) -> BoxedStrategy<Setup> {
    (
        (1i64..=24, 1i64..=7, spoiler(h)),
        proptest::option::weighted(0.1, (1e-3..0.5f64, 1e-3..0.05f64)),
        (1.0..50.0f64, 1.0..50.0f64, spoiler(h), spoiler(h)),
        (
            maybe(0.3, raceway(h)),
            maybe(0.3, real_in(h, -10.0, 10.0)),
            maybe(0.3, real_in(h, 0.5, 5.0)),
        ),
        plausible_crown(h),
        (
            plausible_material(h),
            plausible_material(h),
            real_in(h, 10.0, 1e4),
        ),
        any::<u8>(),
    )
        .prop_map(
            |((nx, half, s), cell, (d, l, sd, sl), shape, profile, forces, style)| {
                let (raceway, tilt, reach) = shape;
                let (m1, m2, force) = forces;
                let cells = Value::Array(vec![spoil_count(nx, s), int(2 * half + 1)]);
                let cell_mm =
                    cell.map(|(dx, dy)| Value::Array(vec![Value::Float(dx), Value::Float(dy)]));
                let gap = tagged(
                    style,
                    text("roller"),
                    vec![
                        ("diameter_mm", Some(spoil(d, sd))),
                        ("length_mm", Some(spoil(l, sl))),
                        ("raceway_diameter_mm", raceway),
                        ("tilt_arcmin", tilt),
                        ("reach_b", reach),
                        ("profile", Some(profile)),
                    ],
                );
                let body = |name: &str, m: Value| {
                    table(vec![
                        ("kind", Some(text("half_space"))),
                        ("name", Some(text(name))),
                        ("material", Some(m)),
                    ])
                };
                Setup {
                    zone: tagged(
                        style,
                        text("grid"),
                        vec![("cells", Some(cells)), ("cell_mm", cell_mm)],
                    ),
                    gap: Some(gap),
                    load: Some(table(vec![("force_n", Some(force))])),
                    bodies: vec![body("raceway", m1), body("roller", m2)],
                    extent: [0.5 * l, 0.1],
                    floating: true,
                    roller: true,
                }
            },
        )
        .boxed()
}

/// An imported body (`fe_mesh`) of the paper's geometry (`paper-base.msh`, `paper-punch.msh`)
/// or of the cylinder on a block (`cylinder-on-block-b4.msh`, plane only), as `role` names
/// it: its mesh, surface, contact group (or, with probability `h`, a hostile one), extent,
/// supports for `axisymmetric` and loads (a pressure `p` \[MPa\] on a punch or a cylinder
/// when `pressed`, else a punch pushed down by `push` \[mm\]).
#[derive(Clone, Debug)]
struct MeshDraw {
    h: f64,
    material: Value,
    pressed: bool,
    p: Value,
    push: f64,
    group: Option<Value>,
    extent: Option<Value>,
    style: u8,
}

impl MeshDraw {
    fn body(&self, role: &str, axisymmetric: bool) -> Value {
        let held = |group: &str, fix: &[&str]| {
            let fix = Value::Array(fix.iter().map(|d| text(d)).collect());
            table(vec![("group", Some(text(group))), ("fix", Some(fix))])
        };
        let (mesh, surface, contact, extent, supports, loads) = match role {
            "base" if axisymmetric => (
                "paper-base.msh",
                None,
                "base_face",
                [100.0, 50.0],
                vec![held("base_bottom", &["x", "y"])],
                vec![],
            ),
            "base" => (
                "paper-base.msh",
                None,
                "base_face",
                [100.0, 50.0],
                vec![held("base_bottom", &["y"]), held("base_axis", &["x"])],
                vec![],
            ),
            "punch" => {
                let load = match self.pressed {
                    true => ("pressure_mpa", self.p.clone()),
                    false => ("displacement_mm", Value::Float(-self.push)),
                };
                let supports = match axisymmetric {
                    true => vec![],
                    false => vec![held("punch_axis", &["x"])],
                };
                let load = table(vec![
                    ("group", Some(text("punch_top"))),
                    (load.0, Some(load.1)),
                ]);
                (
                    "paper-punch.msh",
                    None,
                    "punch_face",
                    [50.0, 50.0],
                    supports,
                    vec![load],
                )
            }
            "block" => (
                "cylinder-on-block-b4.msh",
                Some("block"),
                "block_face",
                [40.0, 40.0],
                vec![
                    held("block_bottom", &["x", "y"]),
                    held("block_axis", &["x"]),
                ],
                vec![],
            ),
            _ => {
                let load = table(vec![
                    ("group", Some(text("cylinder_top"))),
                    ("pressure_mpa", Some(self.p.clone())),
                ]);
                (
                    "cylinder-on-block-b4.msh",
                    Some("cylinder"),
                    "cylinder_face",
                    [10.0, 10.0],
                    vec![held("cylinder_axis", &["x"])],
                    vec![load],
                )
            }
        };
        let extent = self
            .extent
            .clone()
            .unwrap_or(Value::Array(extent.map(Value::Float).to_vec()));
        let contact = match &self.group {
            Some(g) if self.h > 0.0 => g.clone(),
            _ => text(contact),
        };
        tagged(
            self.style,
            text("fe_mesh"),
            vec![
                ("mesh", Some(text(&format!("../meshes/{mesh}")))),
                ("surface", surface.map(text)),
                ("contact", Some(contact)),
                ("extent_mm", Some(extent)),
                ("material", Some(self.material.clone())),
                ("supports", Some(Value::Array(supports))),
                ("loads", Some(Value::Array(loads))),
            ],
        )
    }
}

fn mesh_draw(h: f64) -> BoxedStrategy<MeshDraw> {
    (
        (plausible_material(h), any::<bool>(), real_in(h, 1.0, 200.0)),
        (1e-4..1e-2f64, maybe(0.3, one_of(h, GROUPS)), any::<u8>()),
        chance(h, numbers(3)),
    )
        .prop_map(
            move |((material, pressed, p), (push, group, style), extent)| MeshDraw {
                h,
                material,
                pressed,
                p,
                push,
                group,
                extent,
                style,
            },
        )
        .boxed()
}

/// Pairs on imported meshes: the paper's base under its punch (either analysis), the block
/// under the cylinder (plane), a rigid body or a bed on the base, the punch on a rigid floor;
/// the gap measured between two meshes (left to its default, or named), or given.
fn mesh_setup(h: f64) -> BoxedStrategy<Setup> {
    (
        (any::<bool>(), plane_analysis(h), 0usize..5, any::<u8>()),
        (mesh_draw(h), mesh_draw(h)),
        gap_draw(h, &["flat", "curved", "flat_punch", "measured"]),
        load_draw(h),
        maybe(0.2, real_in(h, 0.1, 20.0)),
    )
        .prop_map(|((axi, plane, pair, style), (d0, d1), gap, load, search)| {
            let axi = axi && pair != 1;
            let analysis = if axi {
                tagged(style, text("axisymmetric"), vec![])
            } else {
                plane
            };
            let zone = tagged(
                style,
                text("mesh"),
                vec![("analysis", Some(analysis)), ("search_mm", search)],
            );
            let r = if pair == 1 { 2.0 } else { 50.0 };
            let kind = match gap.kind {
                "curved" if axi => "sphere",
                "curved" => "cylinder",
                k => k,
            };
            let given = GapDraw { kind, ..gap };
            let (bodies, contact_gap, contact_load, floating) = match pair {
                0 | 1 => {
                    let (a, b) = if pair == 0 {
                        ("base", "punch")
                    } else {
                        ("block", "cylinder")
                    };
                    let measured = match given.kind {
                        "measured" => Some(tagged(style, text("measured"), vec![])),
                        _ if style % 3 == 0 => given.value(r),
                        _ => None,
                    };
                    let floats = pair == 1 || d1.pressed;
                    (
                        vec![d0.body(a, axi), d1.body(b, axi)],
                        measured,
                        None,
                        floats,
                    )
                }
                2 => {
                    let force = load.force;
                    let rigid = tagged(style, text("rigid"), vec![]);
                    (
                        vec![d0.body("base", axi), rigid],
                        given.value(r),
                        Some(load.value(force, r)),
                        force,
                    )
                }
                3 => {
                    let bed = tagged(
                        style,
                        text("winkler"),
                        vec![("modulus_mpa_per_mm", Some(Value::Float(100.0)))],
                    );
                    (
                        vec![d0.body("base", axi), bed],
                        given.value(r),
                        Some(load.value(false, r)),
                        false,
                    )
                }
                _ => {
                    let floor = tagged(style, text("rigid"), vec![]);
                    (
                        vec![floor, d1.body("punch", axi)],
                        given.value(r),
                        None,
                        d1.pressed,
                    )
                }
            };
            Setup {
                zone,
                gap: contact_gap,
                load: contact_load,
                bodies,
                extent: [r, 0.0],
                floating,
                roller: false,
            }
        })
        .boxed()
}

fn valid_setup(h: f64) -> BoxedStrategy<Setup> {
    prop_oneof![
        3 => grid_setup(h),
        2 => line_setup(h, false),
        2 => line_setup(h, true),
        3 => faces_setup(h),
        2 => roller_setup(h),
        2 => mesh_setup(h),
    ]
    .boxed()
}

/// A setup whose parts come from two: the zone of one, the bodies, the gap and the load of
/// either (sometimes one body or three, sometimes the sides swapped), so that many pairings
/// break a rule and some do not.
fn mixed_setup(h: f64) -> BoxedStrategy<Setup> {
    (valid_setup(h), valid_setup(h), any::<u8>())
        .prop_map(|(a, b, pick)| {
            let from = |bit: u8| if pick & bit != 0 { &b } else { &a };
            let mut bodies = from(1).bodies.clone();
            if pick & 8 != 0 {
                bodies.reverse();
            }
            match pick >> 5 {
                0 => {
                    bodies.pop();
                }
                1 => bodies.push(from(2).bodies[0].clone()),
                _ => {}
            }
            Setup {
                zone: a.zone.clone(),
                gap: from(2).gap.clone(),
                load: from(4).load.clone(),
                bodies,
                extent: a.extent,
                floating: from(4).floating,
                roller: from(2).roller,
            }
        })
        .boxed()
}

fn setup(h: f64) -> BoxedStrategy<Setup> {
    prop_oneof![6 => valid_setup(h), 1 => mixed_setup(h)].boxed()
}

/// Controllers from `leaf`, and products of them nested up to `depth` deep with at most `size`
/// controllers in all.
fn products(
    leaf: impl Strategy<Value = Value> + 'static,
    depth: u32,
    size: u32,
) -> BoxedStrategy<Value> {
    leaf.prop_recursive(depth, size, 2, |inner| {
        (any::<u8>(), inner.clone(), inner).prop_map(|(style, a, b)| {
            tagged(style, text("product"), vec![("a", Some(a)), ("b", Some(b))])
        })
    })
    .boxed()
}

fn plausible_solver(h: f64) -> BoxedStrategy<Option<Value>> {
    let tolerance = || maybe(0.3, real_in(h, 1e-12, 1e-4));
    let named =
        |kind: &'static str| any::<u8>().prop_map(move |s| Some(tagged(s, text(kind), vec![])));
    prop_oneof![
        2 => Just(None),
        1 => named("auto"),
        2 => named("active_set"),
        1 => (any::<u8>(), tolerance())
            .prop_map(|(s, t)| Some(tagged(s, text("qp"), vec![("tolerance", t)]))),
        1 => (any::<u8>(), real_in(h, 1e3, 1e10)).prop_map(|(s, c)| {
            Some(tagged(s, text("penalty"), vec![("c_mpa_per_mm", Some(c))]))
        }),
        1 => (
            (any::<u8>(), real_in(h, 1e3, 1e10), tolerance()),
            (maybe(0.3, count_in(h, 1, 200)), proptest::option::weighted(0.3, any::<bool>())),
        )
            .prop_map(|((s, c, t), (steps, accelerate))| {
                Some(tagged(
                    s,
                    text("augmented_lagrangian"),
                    vec![
                        ("c_mpa_per_mm", Some(c)),
                        ("tolerance", t),
                        ("max_steps", steps),
                        ("accelerate", accelerate.map(Value::Boolean)),
                    ],
                ))
            }),
        2 => (any::<u8>(), tolerance(), maybe(0.3, count_in(h, 1, 2000))).prop_map(|(s, t, steps)| {
            Some(tagged(
                s,
                text("polonsky_keer"),
                vec![("tolerance", t), ("max_steps", steps)],
            ))
        }),
    ]
    .boxed()
}

/// A controller within the zone's reach `extent` (along x or r, and y) \[mm\].
fn plausible_controller(h: f64, extent: [f64; 2]) -> BoxedStrategy<Value> {
    let leaf = prop_oneof![
        (any::<u8>(), real_in(h, 0.1, 1.0))
            .prop_map(|(s, level)| { tagged(s, text("constant"), vec![("level", Some(level))]) }),
        (
            (any::<u8>(), one_of(h, &["trapezoid", "cubic"])),
            (0.0..1.0f64, 0.0..1.0f64, spoiler(h), spoiler(h)),
            proptest::option::weighted(0.3, 0usize..=1),
        )
            .prop_map(move |((s, kind), (a, b, s1, s2), axis)| {
                let reach = extent[axis.unwrap_or(0)];
                let fields = vec![
                    ("l1_mm", Some(spoil(reach * a.min(b), s1))),
                    ("l2_mm", Some(spoil(reach * a.max(b), s2))),
                    ("axis", axis.map(|k| int(k as i64))),
                ];
                tagged(s, kind, fields)
            }),
    ];
    products(leaf, 2, 4)
}

/// Ω_v within the zone's reach: a strip across the centre, a disc about it or a box around it.
fn plausible_omega_v(h: f64, extent: [f64; 2]) -> BoxedStrategy<Value> {
    (any::<u8>(), 0u8..3, 0usize..=1, 0.05..1.0f64, spoiler(h))
        .prop_map(move |(s, shape, axis, f, spoiler)| {
            let h = [extent[0] * f, extent[1] * f];
            let pair = |a: f64, b: f64| Value::Array(vec![Value::Float(a), Value::Float(b)]);
            match shape {
                0 => tagged(
                    s,
                    text("strip"),
                    vec![
                        ("axis", Some(int(axis as i64))),
                        ("from_mm", Some(spoil(-h[axis], spoiler))),
                        ("to_mm", Some(Value::Float(h[axis]))),
                    ],
                ),
                1 => tagged(
                    s,
                    text("disc"),
                    vec![
                        ("centre_mm", Some(pair(0.0, 0.0))),
                        ("radius_mm", Some(spoil(h[0].max(h[1]), spoiler))),
                    ],
                ),
                _ => tagged(
                    s,
                    text("box"),
                    vec![
                        ("from_mm", Some(pair(-h[0], -h[1]))),
                        ("to_mm", Some(pair(h[0], h[1]))),
                    ],
                ),
            }
        })
        .boxed()
}

/// A design for the setup: the methods its load allows (one time in eight any name), few
/// steps mostly, a controller (none for a profile search, one time in ten the other way).
fn plausible_optimisation(h: f64, s: &Setup) -> BoxedStrategy<Option<Value>> {
    let methods: &'static [&'static str] = match (s.roller, s.floating) {
        (true, _) => &[
            "load_split",
            "load_split",
            "linear_programme",
            "envelope_split",
            "profile_search",
        ],
        (false, true) => &["given_load", "load_split", "linear_programme"],
        (false, false) => &["given_displacement", "linear_programme"],
    };
    let extent = s.extent;
    let method = (
        any::<u8>(),
        one_of(h, methods),
        maybe(0.3, real_in(h, 1e-9, 1e-4)),
        maybe(0.85, count_in(h, 1, 12)),
    )
        .prop_map(|(style, kind, tolerance, steps)| method_value(style, kind, tolerance, steps));
    let optimisation = (
        method,
        plausible_controller(h, extent),
        maybe(0.3, plausible_omega_v(h, extent)),
        maybe(0.3, count_in(h, 0, 1)),
        proptest::bool::weighted(0.1),
    )
        .prop_map(|(method, controller, omega_v, axis, flip)| {
            let search = kind_of(&method) == Some("profile_search");
            table(vec![
                ("controller", (search == flip).then_some(controller)),
                ("method", Some(method)),
                ("omega_v", omega_v),
                ("profile_axis", axis),
            ])
        });
    maybe(0.45, optimisation.boxed())
}

/// An envelope of load cases: mostly for a roller, seldom (and wrongly) for another gap.
fn plausible_envelope(h: f64, roller: bool) -> BoxedStrategy<Option<Value>> {
    let envelope = (
        proptest::collection::vec(real_in(h, 0.1, 2.0), 1..3),
        proptest::collection::vec(real_in(h, -5.0, 5.0), 1..3),
    )
        .prop_map(|(f, t)| {
            table(vec![
                ("load_factors", Some(Value::Array(f))),
                ("tilts_arcmin", Some(Value::Array(t))),
            ])
        });
    maybe(if roller { 0.5 } else { 0.03 }, envelope.boxed())
}

fn plausible_subsurface(h: f64) -> BoxedStrategy<Value> {
    let section = (one_of(h, &["x", "y"]), real_in(h, -10.0, 10.0))
        .prop_map(|(along, at)| table(vec![("along", Some(along)), ("at_mm", Some(at))]));
    (
        maybe(0.5, real_in(h, 0.01, 10.0)),
        maybe(0.8, count_in(h, 1, 20)),
        maybe(
            0.3,
            proptest::collection::vec(section, 0..3)
                .prop_map(Value::Array)
                .boxed(),
        ),
    )
        .prop_map(|(depth, depths, sections)| {
            let sub = table(vec![
                ("max_depth_mm", depth),
                ("depths", depths),
                ("sections", sections),
            ]);
            table(vec![("subsurface", Some(sub))])
        })
        .boxed()
}

/// Keys of numbers a generated scene may hold, to sweep or set.
const SWEEP_KEYS: &[&str] = &[
    "contact.load.force_n",
    "contact.load.approach_mm",
    "contact.zone.cells.0",
    "contact.zone.rings",
    "contact.zone.strips",
    "contact.zone.elements",
    "contact.zone.radius_mm",
    "contact.gap.radius_mm",
    "contact.gap.tilt_arcmin",
    "body.0.material.e_mpa",
    "body.1.material.nu",
    "body.1.height_mm",
    "optimisation.controller.l1_mm",
    "solver.c_mpa_per_mm",
];

/// The draw of a sweep or of named cases over keys the scene holds: for each value, a factor
/// on the key's number, or a whole count for an integer key.
#[derive(Clone, Debug)]
enum CasesDraw {
    None,
    Sweep { key: Index, values: Vec<(f64, i64)> },
    Named(Vec<(Index, f64, i64)>),
}

fn cases_draw() -> BoxedStrategy<CasesDraw> {
    let value = || (0.5..2.0f64, 1i64..=8);
    prop_oneof![
        6 => Just(CasesDraw::None),
        1 => (any::<Index>(), proptest::collection::vec(value(), 1..4))
            .prop_map(|(key, values)| CasesDraw::Sweep { key, values }),
        1 => proptest::collection::vec((any::<Index>(), value()), 1..4)
            .prop_map(|sets| CasesDraw::Named(sets.into_iter().map(|(k, (f, n))| (k, f, n)).collect())),
    ]
    .boxed()
}

impl CasesDraw {
    /// The `[sweep]` and the `[[case]]`s of the scene `tree`.
    fn sections(&self, tree: &Value) -> (Option<Value>, Option<Value>) {
        let present: Vec<(&str, &Value)> = SWEEP_KEYS
            .iter()
            .filter_map(|k| lookup(tree, k).map(|v| (*k, v)))
            .filter(|(_, v)| matches!(v, Value::Integer(_) | Value::Float(_)))
            .collect();
        if present.is_empty() {
            return (None, None);
        }
        let value = |current: &Value, factor: f64, count: i64| match current {
            Value::Integer(_) => int(count),
            Value::Float(f) => Value::Float(f * factor),
            other => other.clone(),
        };
        match self {
            CasesDraw::None => (None, None),
            CasesDraw::Sweep { key, values } => {
                let (k, current) = present[key.index(present.len())];
                let values = values.iter().map(|(f, n)| value(current, *f, *n)).collect();
                let sweep = table(vec![
                    ("key", Some(text(k))),
                    ("values", Some(Value::Array(values))),
                ]);
                (Some(sweep), None)
            }
            CasesDraw::Named(sets) => {
                let cases = sets
                    .iter()
                    .enumerate()
                    .map(|(i, (key, f, n))| {
                        let (k, current) = present[key.index(present.len())];
                        let set = [(k.to_string(), value(current, *f, *n))];
                        table(vec![
                            ("label", Some(text(&format!("case {i}")))),
                            ("set", Some(Value::Table(set.into_iter().collect()))),
                        ])
                    })
                    .collect();
                (None, Some(Value::Array(cases)))
            }
        }
    }
}

/// The value at the dotted path `key` of `tree` (numbers index arrays).
fn lookup<'a>(tree: &'a Value, key: &str) -> Option<&'a Value> {
    key.split('.').try_fold(tree, |v, k| match v {
        Value::Table(t) => t.get(k),
        Value::Array(a) => k.parse::<usize>().ok().and_then(|i| a.get(i)),
        _ => None,
    })
}

/// Generated scenes: three in four plausible throughout, one in four with each value hostile
/// one time in eight.
fn generated_scene() -> impl Strategy<Value = SceneTree> {
    prop_oneof![3 => scene_of(0.0), 1 => scene_of(HOSTILITY)]
}

/// A scene whose values are hostile with probability `h`.
fn scene_of(h: f64) -> BoxedStrategy<SceneTree> {
    let parts = setup(h).prop_flat_map(move |s| {
        let optimisation = plausible_optimisation(h, &s);
        let envelope = plausible_envelope(h, s.roller);
        (Just(s), optimisation, envelope)
    });
    (
        parts,
        (
            one_of(h, &["fuzz", "a-scene", "Ω"]),
            maybe(0.2, one_of(h, &["", "what it shows"])),
        ),
        plausible_solver(h),
        maybe(0.3, plausible_subsurface(h)),
        (cases_draw(), proptest::bool::weighted(0.9)),
        (
            maybe(0.1, real_in(h, 1.0, 5000.0)),
            maybe(0.1, real_in(h, 1.0, 5000.0)),
        ),
    )
        .prop_map(
            |(parts, (name, description), solver, output, (cases, straight), limits)| {
                let (mut s, optimisation, envelope) = parts;
                // A design of a roller's crown starts from the straight roller (mostly).
                if let (Some(Value::Table(gap)), true) = (&mut s.gap, optimisation.is_some()) {
                    if let Some(profile) = gap.get_mut("profile").filter(|_| straight) {
                        *profile = text("straight");
                    }
                }
                let contact = table(vec![
                    ("zone", Some(s.zone)),
                    ("gap", s.gap),
                    ("load", s.load),
                ]);
                let mut tree = table(vec![
                    ("name", Some(name)),
                    ("description", description),
                    ("contact", Some(contact)),
                    ("body", Some(Value::Array(s.bodies))),
                    ("solver", solver),
                    ("optimisation", optimisation),
                    ("envelope", envelope),
                    ("output", output),
                    ("dense_limit_mb", limits.0),
                    ("memory_limit_mb", limits.1),
                ]);
                let (sweep, case) = cases.sections(&tree);
                if let Value::Table(t) = &mut tree {
                    t.extend(sweep.map(|v| ("sweep".to_string(), v)));
                    t.extend(case.map(|v| ("case".to_string(), v)));
                }
                SceneTree(tree)
            },
        )
        .boxed()
}

/// The fields of an enum value as a scene spells it: the table around `kind`, or the table
/// under the variant's only key (`None` for a bare name or junk).
fn fields(v: &Value) -> Option<&toml::Table> {
    let Value::Table(t) = v else {
        return None;
    };
    match (t.get("kind"), t.len()) {
        (Some(_), _) => Some(t),
        (None, 1) => t.values().next().and_then(Value::as_table),
        _ => None,
    }
}

/// The variant an enum value names: its bare name, its `kind`, or its only key.
fn kind_of(v: &Value) -> Option<&str> {
    match v {
        Value::String(s) => Some(s),
        Value::Table(t) => match t.get("kind") {
            Some(k) => k.as_str(),
            None if t.len() == 1 => t.keys().next().map(String::as_str),
            None => None,
        },
        _ => None,
    }
}

/// A scene as a tree of values: made from the schema, or a bundled scene mutated.
#[derive(Clone)]
struct SceneTree(Value);

impl SceneTree {
    fn texts(&self) -> (Option<String>, String) {
        let json = serde_json::to_string_pretty(&to_json(&self.0)).expect("JSON writes any tree");
        (toml::to_string(&self.0).ok(), json)
    }

    /// The value at `path`: table keys, and indices into arrays.
    fn get(&self, path: &[&str]) -> Option<&Value> {
        lookup(&self.0, &path.join("."))
    }

    /// Whether its cases are small enough to run: few cells, rings, strips, elements, layers,
    /// cases, depths and steps, and no design that solves the contact many times over (an
    /// envelope split, a profile search: 16 s for a tuned crown on 22 × 25 cells by the QP).
    fn tiny(&self) -> bool {
        let at_most = |v: Option<&Value>, max: i64| match v {
            Some(Value::Integer(k)) => *k <= max,
            _ => true,
        };
        let zone = self.get(&["contact", "zone"]).and_then(fields);
        let field = |name: &str| zone.and_then(|z| z.get(name));
        // The dense methods (the QP, the linear programme) take seconds past a few hundred
        // points (14 s for the linear programme on 26 × 31 cells).
        // A bearing composes its roller's grid from `bearing.cells`.
        let bearing = self.get(&["bearing"]).and_then(fields);
        let cells = match field("cells").or_else(|| bearing.and_then(|b| b.get("cells"))) {
            Some(Value::Array(a)) => a
                .iter()
                .map(|v| v.as_integer().unwrap_or(1))
                .fold(1i64, i64::saturating_mul),
            _ => 1,
        };
        let layers = match self.get(&["body"]) {
            Some(Value::Array(a)) => a
                .iter()
                .all(|b| at_most(fields(b).and_then(|f| f.get("layers")), 8)),
            _ => true,
        };
        let solver = self.get(&["solver"]).and_then(fields);
        let list = |path: &[&str]| match self.get(path) {
            Some(Value::Array(a)) => a.len(),
            _ => 1,
        };
        // An imported body is tiny on the meshes generated scenes name (the bundled ones have
        // thousands of nodes).
        let meshes = match self.get(&["body"]) {
            Some(Value::Array(a)) => {
                a.iter()
                    .all(|b| match fields(b).and_then(|f| f.get("mesh")) {
                        Some(Value::String(m)) => MESHES.iter().any(|small| m.ends_with(small)),
                        _ => true,
                    })
            }
            _ => true,
        };
        let depths = match self.get(&["output", "subsurface"]) {
            None => true,
            Some(sub) => sub.get("depths").is_some() && at_most(sub.get("depths"), 20),
        };
        (0..=256).contains(&cells)
            && at_most(field("rings"), 60)
            && at_most(field("strips"), 60)
            && at_most(field("elements"), 8)
            && layers
            && meshes
            && at_most(solver.and_then(|s| s.get("max_steps")), 2000)
            && self.design_tiny()
            && depths
            && list(&["sweep", "values"]) <= 3
            && list(&["case"]) <= 3
            && list(&["envelope", "load_factors"]) * list(&["envelope", "tilts_arcmin"]) <= 4
    }

    /// Whether the design takes few steps: an iteration or a load split with at most 20 given
    /// (the default of 100 is not tiny), a linear programme of at most 10 passes, or none.
    fn design_tiny(&self) -> bool {
        let Some(method) = self.get(&["optimisation", "method"]) else {
            return self.get(&["optimisation"]).is_none();
        };
        let settings = fields(method);
        let steps = |name: &str, default: Option<i64>, max: i64| match settings
            .and_then(|f| f.get(name))
            .map(Value::as_integer)
        {
            None => default.is_some_and(|d| d <= max),
            Some(Some(k)) => k <= max,
            Some(None) => true,
        };
        match kind_of(method) {
            Some("given_load" | "given_displacement" | "load_split") => {
                steps("max_iterations", None, 20)
            }
            Some("linear_programme") => steps("max_passes", Some(10), 10),
            _ => false,
        }
    }
}

impl std::fmt::Debug for SceneTree {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (toml, json) = self.texts();
        writeln!(
            f,
            "scene (tiny: {}, breaks: {:?}):",
            self.tiny(),
            self.breaks()
        )?;
        writeln!(f, "{}", preview_block(toml.as_deref().unwrap_or(&json)))
    }
}

/// What a scene's contact is made of, as far as its tree names known kinds.
struct Pairing<'a> {
    zone: &'a str,
    /// The analysis of a zone of faces: axisymmetric or not (`None`: not known).
    axisymmetric: Option<bool>,
    bodies: Vec<&'a str>,
    gap: &'a str,
    load: &'a str,
    /// Whether a half-space gives a datum.
    datum: bool,
}

impl SceneTree {
    /// The kinds of the zone, the bodies, the gap and the load, when each is one the schema
    /// knows; `None` when the scene has a sweep or cases (which may change them) or a kind is
    /// junk (the reader refuses that anyway).
    fn pairing(&self) -> Option<Pairing<'_>> {
        if self.get(&["sweep"]).is_some() || self.get(&["case"]).is_some() {
            return None;
        }
        fn known<'a>(pool: &[&str], v: Option<&'a str>) -> Option<&'a str> {
            v.filter(|k| pool.contains(k))
        }
        let zone_value = self.get(&["contact", "zone"])?;
        let zone = known(ZONE_KINDS, kind_of(zone_value))?;
        let axisymmetric = fields(zone_value)
            .and_then(|z| z.get("analysis"))
            .and_then(kind_of)
            .and_then(|a| known(ANALYSES, Some(a)))
            .map(|a| a == "axisymmetric");
        let Some(Value::Array(list)) = self.get(&["body"]) else {
            return None;
        };
        let bodies = list
            .iter()
            .map(|b| known(BODY_KINDS, kind_of(b)))
            .collect::<Option<Vec<&str>>>()?;
        let datum = list.iter().any(|b| {
            kind_of(b) == Some("half_space")
                && fields(b).is_some_and(|f| f.contains_key("datum_mm"))
        });
        let gap = match self.get(&["contact", "gap"]) {
            None => "flat",
            Some(v) => known(GAP_KINDS, kind_of(v))?,
        };
        let load = match self.get(&["contact", "load"]) {
            None => "none",
            Some(v) => known(&["force_n", "approach_mm", "none"], kind_of(v))?,
        };
        Some(Pairing {
            zone,
            axisymmetric,
            bodies,
            gap,
            load,
            datum,
        })
    }

    /// The rule of the schema the scene's pairing breaks, when it surely breaks one: the
    /// scene must then be refused, whatever its values.
    fn breaks(&self) -> Option<&'static str> {
        let p = self.pairing()?;
        let &[below, above] = p.bodies.as_slice() else {
            return Some("a contact has two bodies");
        };
        let fe = |k: &str| matches!(k, "fe_base" | "fe_punch" | "fe_block");
        let faces = p.zone == "faces";
        let meshes = p.zone == "mesh";
        let imported = p.bodies.iter().filter(|k| **k == "fe_mesh").count();
        let lines = matches!(p.zone, "rings" | "strips");
        let plane = p.zone == "strips" || ((faces || meshes) && p.axisymmetric == Some(false));
        let round = p.zone == "rings" || ((faces || meshes) && p.axisymmetric == Some(true));
        let held_above = matches!(
            above,
            "winkler" | "fe_base" | "fe_block" | "fe_punch" | "fe_mesh"
        ) || (above == "half_space" && p.zone != "grid");
        let rules = [
            (below == "rigid" && above == "rigid", "two rigid bodies"),
            (
                !faces && (fe(below) || fe(above)),
                "a finite-element body off faces",
            ),
            (
                faces && !fe(below) && !fe(above),
                "faces without a finite-element body",
            ),
            (below == "fe_punch", "a punch below the zone"),
            (
                matches!(above, "fe_base" | "fe_block"),
                "a base or a block above the zone",
            ),
            (
                (faces || meshes) && (below == "half_space" || above == "half_space"),
                "a half-space on faces",
            ),
            (
                !meshes && imported > 0,
                "an imported body off a zone of meshes",
            ),
            (
                meshes && imported == 0,
                "a zone of meshes without an imported body",
            ),
            (
                p.gap == "measured" && !(meshes && imported == 2),
                "the measured gap without two imported bodies",
            ),
            (
                lines && above == "half_space",
                "a half-space above rings or strips",
            ),
            (p.gap == "roller" && p.zone != "grid", "a roller off a grid"),
            (
                p.gap == "roller" && (below, above) != ("half_space", "half_space"),
                "a roller not between half-spaces",
            ),
            (
                p.gap == "roller" && p.load != "force_n",
                "a roller not pressed by a force",
            ),
            (p.gap == "sphere" && plane, "a sphere on a plane zone"),
            (
                p.gap == "cylinder" && round,
                "a cylinder on an axisymmetric zone",
            ),
            (p.load == "force_n" && held_above, "a force on a held body"),
            (
                p.load == "none" && above != "fe_punch" && imported == 0,
                "nothing presses the bodies",
            ),
            (p.datum && p.zone != "strips", "a datum off strips"),
        ];
        rules
            .into_iter()
            .find(|(broken, _)| *broken)
            .map(|(_, rule)| rule)
    }
}

/// Reads scene text, within the case limit: `Ok` or `Err`. A scene that reads has cases, and
/// its first and last case's resolved input (every default written out) serialises; a scene
/// that breaks a pairing rule must be refused ([`SceneTree::breaks`]); when `run`, every case
/// runs, and each report that comes out is finite ([`non_finite`]). `tree` is the scene's,
/// when it was made as one.
fn read_and_run(text: String, format: Format, run: bool, tree: Option<&SceneTree>) {
    let breaks = tree.and_then(SceneTree::breaks);
    let text: Arc<str> = text.into();
    let input = text.clone();
    guarded("read and run", input, move || {
        let scene = match Scene::parse(&text, format, &scene_file()) {
            Ok(scene) => scene,
            Err(e) => {
                let rule = breaks
                    .map(|r| format!(" (it breaks: {r})"))
                    .unwrap_or_default();
                note(&format!("refused{rule}: {e}"));
                return;
            }
        };
        if let Some(rule) = breaks {
            panic!("a scene that breaks a rule of the schema ({rule}) was read");
        }
        let cases = scene.cases();
        assert!(!cases.is_empty(), "a scene that parsed has no case");
        for case in [cases.first(), cases.last()].into_iter().flatten() {
            serde_json::to_string(&case.input()).expect("a case's input serialises");
        }
        if !run {
            note("read");
            return;
        }
        for (case, report) in scene.cases().iter().zip(scene.run()) {
            match report {
                Ok(report) => {
                    note(&format!("ran {:?}", report.status));
                    let what = format!("the report of case {:?}", case.label);
                    expect_finite(&what, non_finite(&report));
                }
                Err(e) => {
                    note("run refused");
                    let _ = e.to_string();
                }
            }
        }
    })
}

/// Counts an outcome when `FUZZ_STATS` is set (`--nocapture` shows them): how many generated
/// scenes are refused, read, and run to each status.
fn note(outcome: &str) {
    if std::env::var_os("FUZZ_STATS").is_some() {
        eprintln!("fuzz-outcome: {outcome}");
    }
}

proptest! {
    #![proptest_config(config(SCENE_CASES))]

    /// Scenes made from the schema, as TOML and as JSON; the tiny ones are run too (as TOML).
    #[test]
    fn generated_scenes(scene in generated_scene()) {
        let (toml, json) = scene.texts();
        if let Some(toml) = toml {
            read_and_run(toml, Format::Toml, scene.tiny(), Some(&scene));
        }
        read_and_run(json, Format::Json, false, Some(&scene));
    }
}

// ---------------------------------------------------------------------------------------------
// What comes out `Ok` is finite.

/// The results schema, derived once.
fn results_schema() -> &'static serde_json::Value {
    static SCHEMA: OnceLock<serde_json::Value> = OnceLock::new();
    SCHEMA.get_or_init(contopt_results::schema)
}

/// Why `report` is not finite, `None` when it is: the places where it breaks the results
/// schema as JSON (serde_json writes a NaN or an infinity as `null`, which the schema refuses
/// where it requires a number), or else its first number, read field by field, that is not
/// finite (where the schema allows `null`, for an absent figure, the JSON cannot tell).
fn non_finite(report: &CaseReport) -> Option<String> {
    let case = serde_json::to_value(report).expect("a report serialises");
    let document = serde_json::json!({
        "schema_version": contopt_results::SCHEMA_VERSION,
        "scene": "fuzz",
        "description": "",
        "cases": [case],
    });
    let broken = contopt_results::violations(results_schema(), &document);
    if !broken.is_empty() {
        return Some(format!(
            "it breaks the results schema: {}",
            broken.join("; ")
        ));
    }
    report_numbers(report)
        .into_iter()
        .find(|(_, v)| !v.is_finite())
        .map(|(name, v)| format!("{name} = {v}"))
}

/// Every number of a report with its field's name.
fn report_numbers(r: &CaseReport) -> Vec<(String, f64)> {
    let mut out: Vec<(String, f64)> = vec![];
    let mut put = |name: &str, v: f64| out.push((name.to_string(), v));
    for (name, v) in [
        ("p_max_mpa", r.p_max_mpa),
        ("bound_p_max_mpa", r.bound_p_max_mpa),
        ("dh_max_um", r.dh_max_um),
        ("omega_nv_excess_mpa", r.omega_nv_excess_mpa),
        ("approach_um", r.approach_um),
        ("penetration_um", r.penetration_um),
    ] {
        if let Some(v) = v {
            put(name, v);
        }
    }
    for (k, v) in r.params.iter().chain(&r.timings_ms) {
        put(k, *v);
    }
    if let Some(h) = &r.hertz {
        put("hertz.p0_mpa", h.p0_mpa);
        put("hertz.half_width_mm", h.half_width_mm);
    }
    if let Some(res) = &r.resolution {
        put("resolution.half_width_mm", res.half_width_mm);
        put("resolution.cells", res.cells);
    }
    if let Some(l) = &r.limit {
        put("limit.extent_mm", l.extent_mm);
        put("limit.needed_mm", l.needed_mm);
    }
    for p in &r.passes {
        put("passes.bound_p_max_mpa", p.bound_p_max_mpa);
        put("passes.dh_max_um", p.dh_max_um);
        put("passes.tolh_mm2", p.tolh_mm2);
    }
    for q in &r.interface {
        for x in q.x_mm {
            put("interface.x_mm", x);
        }
        put("interface.p_mpa", q.p_mpa);
        put("interface.d_um", q.d_um);
        put("interface.dh_um", q.dh_um);
        put("interface.h_um", q.h_um);
    }
    for c in r.reference.iter().flat_map(|c| &c.points) {
        put("reference.x_mm", c.x_mm);
        put("reference.p_mpa", c.p_mpa);
    }
    termination_numbers(&r.termination, &mut out);
    roller_numbers(r, &mut out);
    subsurface_numbers(r, &mut out);
    out
}

fn termination_numbers(t: &Termination, out: &mut Vec<(String, f64)>) {
    match t {
        Termination::StepLimit {
            measure, tolerance, ..
        } => {
            out.push(("termination.measure".into(), *measure));
            out.push(("termination.tolerance".into(), *tolerance));
        }
        Termination::LargeDisplacement {
            displacement_mm,
            size_mm,
        } => {
            out.push(("termination.displacement_mm".into(), *displacement_mm));
            out.push(("termination.size_mm".into(), *size_mm));
        }
        Termination::Inner { termination, .. } => termination_numbers(termination, out),
        _ => {}
    }
}

fn roller_numbers(r: &CaseReport, out: &mut Vec<(String, f64)>) {
    let Some(roller) = &r.roller else {
        return;
    };
    let mut put = |name: &str, v: f64| out.push((format!("roller.{name}"), v));
    for v in roller.p_max_at_mm {
        put("p_max_at_mm", v);
    }
    for v in roller.half_width_mm {
        put("half_width_mm", v);
    }
    put("crown_drop_end_um", roller.crown_drop_end_um);
    if let Some(w) = roller.worst_p_max_mpa {
        put("worst_p_max_mpa", w);
    }
    if let Some(t) = &roller.tuned {
        if let Some(k1) = t.k1 {
            put("tuned.k1", k1);
        }
        if let Some(r) = t.radius_mm {
            put("tuned.radius_mm", r);
        }
        put("tuned.k2", t.k2);
        put("tuned.z_m_um", t.z_m_um);
    }
    for e in &roller.envelope {
        put("envelope.load_n", e.load_n);
        put("envelope.tilt_arcmin", e.tilt_arcmin);
        put("envelope.p_max_mpa", e.p_max_mpa);
        put("envelope.approach_um", e.approach_um);
        for v in e.p_max_at_mm {
            put("envelope.p_max_at_mm", v);
        }
        for c in &e.centre_line {
            put("envelope.centre_line.x_mm", c.x_mm);
            put("envelope.centre_line.p_mpa", c.p_mpa);
        }
    }
}

/// The subsurface figures, and the sections' fields (written to CSV, not to the JSON report):
/// a section holds no optional number, so a `null` anywhere in its JSON is a non-finite one.
fn subsurface_numbers(r: &CaseReport, out: &mut Vec<(String, f64)>) {
    let Some(sub) = &r.subsurface else {
        return;
    };
    for d in &sub.depths_mm {
        out.push(("subsurface.depths_mm".into(), *d));
    }
    for body in &sub.bodies {
        let p = &body.peaks;
        for (name, peak) in [
            ("von_mises", p.von_mises),
            ("tresca", p.tresca),
            ("max_principal", p.max_principal),
            ("min_principal", p.min_principal),
            ("shear_xz", p.shear_xz),
        ]
        .into_iter()
        .chain(p.shear_yz.map(|q| ("shear_yz", q)))
        {
            for v in [peak.value_mpa, peak.x_mm, peak.y_mm, peak.depth_mm] {
                out.push((format!("subsurface.peaks.{name}"), v));
            }
        }
        for section in &body.sections {
            let json = serde_json::to_value(section).expect("a section serialises");
            if has_null(&json) {
                out.push(("subsurface.sections".into(), f64::NAN));
            }
        }
    }
}

/// Whether a JSON value holds a `null` anywhere.
fn has_null(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Null => true,
        serde_json::Value::Array(a) => a.iter().any(has_null),
        serde_json::Value::Object(o) => o.values().any(has_null),
        _ => false,
    }
}

// ---------------------------------------------------------------------------------------------
// Property 2: arbitrary text.

const TOKENS: &[&str] = &[
    "[",
    "]",
    "[[",
    "]]",
    "{",
    "}",
    "=",
    ",",
    ":",
    ".",
    "\"",
    "'",
    "\"\"\"",
    "'''",
    "\n",
    " ",
    "#",
    "\\",
    "\\u0000",
    "\\uD800",
    "a",
    "name",
    "kind",
    "contact",
    "zone",
    "body",
    "solver",
    "\"x\"",
    "'x'",
    "1",
    "-1",
    "0",
    "1e400",
    "-0",
    "1_000",
    "0x10",
    "0o7",
    "0b1",
    "nan",
    "+inf",
    "-inf",
    "1.",
    ".5",
    "true",
    "false",
    "null",
    "1979-05-27T07:32:00Z",
    "07:32:00",
    "1979-05-27",
    "18446744073709551616",
    "9223372036854775808",
    "\u{0}",
    "\u{feff}",
    "🦀",
    "\r",
    "half_space",
    "fe_punch",
    "roller",
    "elements",
    "cells",
    "[contact]",
    "[[body]]",
    "[solver]",
    "[[case]]",
    "[sweep]",
    "values",
    "key",
];

/// Deep nesting: opening, inner, closing, each repeated `depth` times around the inner.
const NESTS: &[(&str, &str, &str)] = &[
    ("a = ", "[", "]"),
    ("a = ", "{a = ", "}"),
    ("", "[", "]"),
    ("", "{\"a\":", "}"),
    ("", "[{\"a\":", "}]"),
    ("a = ", "[{a = ", "}]"),
    ("[", "a.", "a]"),
    ("", "\"", "\""),
];

#[derive(Clone, Debug)]
enum Text {
    /// Any string proptest makes.
    Any(String),
    /// Bytes, invalid UTF-8 replaced.
    Bytes(Vec<u8>),
    /// Tokens of TOML and JSON, joined.
    Tokens(Vec<&'static str>),
    /// Lines of the bundled scenes, in any order, with junk between.
    Lines(Vec<(Index, Index, Option<&'static str>)>),
    /// One pattern of [`NESTS`] nested `depth` deep, closed or not.
    Nested {
        pattern: usize,
        depth: usize,
        closed: bool,
    },
    /// A scene whose controller is a product `depth` deep (TOML) or JSON nested alike.
    DeepController { depth: usize, json: bool },
    /// An array or string of `len` elements (`a = [1, 1, …]`, `a = "xxx…"`).
    Huge { len: usize, string: bool },
}

impl Text {
    fn render(&self) -> String {
        match self {
            Text::Any(s) => s.clone(),
            Text::Bytes(b) => String::from_utf8_lossy(b).into_owned(),
            Text::Tokens(t) => t.concat(),
            Text::Lines(picks) => {
                let mut out = String::new();
                for (scene, line, junk) in picks {
                    let lines: Vec<&str> = SCENES[scene.index(SCENES.len())].text.lines().collect();
                    out.push_str(lines[line.index(lines.len())]);
                    out.push_str(junk.unwrap_or(""));
                    out.push('\n');
                }
                out
            }
            Text::Nested {
                pattern,
                depth,
                closed,
            } => {
                let (head, open, close) = NESTS[*pattern];
                let mut s = head.to_string() + &open.repeat(*depth) + "1";
                if *closed {
                    s.push_str(&close.repeat(*depth));
                }
                s
            }
            Text::DeepController { depth, json } => deep_controller(*depth, *json),
            Text::Huge { len, string } => {
                if *string {
                    format!("name = \"{}\"", "x".repeat(*len))
                } else {
                    format!("a = [{}]", "1,".repeat(*len))
                }
            }
        }
    }
}

/// paper-table1 with its controller a product `depth` deep.
fn deep_controller(depth: usize, json: bool) -> String {
    let scene = SCENES
        .iter()
        .find(|b| b.name == "paper-table1")
        .expect("paper-table1 is bundled")
        .text;
    let line = scene
        .lines()
        .find(|l| l.starts_with("controller"))
        .expect("paper-table1 has a controller");
    if json {
        // serde_json's writer and drop recurse: a deep tree is made, written and dropped on a
        // thread of its own.
        return std::thread::Builder::new()
            .stack_size(256 << 20)
            .spawn(move || {
                let mut tree = to_json(&toml::from_str::<Value>(scene).expect("a bundled scene"));
                let leaf = serde_json::json!({ "kind": "constant", "level": 1.0 });
                let mut c = leaf.clone();
                for _ in 0..depth {
                    let mut product = serde_json::Map::new();
                    product.insert("kind".into(), "product".into());
                    product.insert("a".into(), c);
                    product.insert("b".into(), leaf.clone());
                    c = serde_json::Value::Object(product);
                }
                tree["optimisation"]["controller"] = c;
                serde_json::to_string(&tree).expect("JSON writes any tree")
            })
            .expect("a thread")
            .join()
            .expect("written");
    }
    let leaf = "{ kind = \"constant\", level = 1.0 }";
    let c = "controller = ".to_string()
        + &"{ kind = \"product\", b = { kind = \"constant\", level = 1.0 }, a = ".repeat(depth)
        + leaf
        + &" }".repeat(depth);
    scene.replace(line, &c)
}

const DEPTHS: &[usize] = &[
    1, 2, 10, 50, 100, 127, 128, 129, 200, 500, 1000, 5000, 20_000, 100_000,
];

fn text_input() -> impl Strategy<Value = Text> {
    prop_oneof![
        3 => any::<String>().prop_map(Text::Any),
        2 => proptest::collection::vec(any::<u8>(), 0..400).prop_map(Text::Bytes),
        3 => proptest::collection::vec(select(TOKENS), 0..120).prop_map(Text::Tokens),
        3 => proptest::collection::vec(
            (any::<Index>(), any::<Index>(), proptest::option::weighted(0.2, select(TOKENS))),
            0..40
        )
        .prop_map(Text::Lines),
        2 => (0..NESTS.len(), select(DEPTHS), any::<bool>())
            .prop_map(|(pattern, depth, closed)| Text::Nested { pattern, depth, closed }),
        1 => (select(DEPTHS), any::<bool>())
            .prop_map(|(depth, json)| Text::DeepController { depth, json }),
        1 => (select(vec![0usize, 1, 1000, 100_000, 1_000_000]), any::<bool>())
            .prop_map(|(len, string)| Text::Huge { len, string }),
    ]
}

proptest! {
    #![proptest_config(config(OTHER_CASES))]

    /// Arbitrary text, as TOML and as JSON: no panic (such text seldom makes a scene, and
    /// one that does is small and runs nothing here).
    #[test]
    fn arbitrary_text(input in text_input()) {
        let text = input.render();
        read_and_run(text.clone(), Format::Toml, false, None);
        read_and_run(text, Format::Json, false, None);
    }
}

// ---------------------------------------------------------------------------------------------
// Property 3: the libraries' public constructors.

/// Any f64: plausible, special or arbitrary.
fn real() -> BoxedStrategy<f64> {
    prop_oneof![
        4 => 1e-3..1e3f64,
        1 => -1e3..0.0f64,
        3 => select(SPECIAL_FLOATS),
        1 => any::<f64>(),
    ]
    .boxed()
}

/// A count for a constructor: mostly small, sometimes absurd (past any limit of memory; a
/// large but sensible count is slow, not wrong, and left out).
fn size() -> BoxedStrategy<usize> {
    prop_oneof![
        8 => 0usize..24,
        2 => select(vec![
            1_000_000_000usize,
            1 << 32,
            1_000_000_000_000,
            usize::MAX / 2,
            usize::MAX,
        ]),
    ]
    .boxed()
}

/// A material: its E and ν, mostly valid.
fn material_args() -> BoxedStrategy<(f64, f64)> {
    prop_oneof![
        3 => (1e3..1e6f64, -0.9..0.49f64),
        1 => (real(), real()),
    ]
    .boxed()
}

/// The material, or steel where the arguments are not one (to reach further checks).
fn material_or_steel((e, nu): (f64, f64)) -> Material {
    Material::new(e, nu).unwrap_or_else(|_| Material::new(2e5, 0.3).expect("steel"))
}

/// Runs a constructor case on a guarded thread; `args` is its description.
fn construct(args: String, work: impl FnOnce() + Send + 'static) {
    guarded("construct", args.into(), work);
}

/// Fails the case when `why` says an output is not finite (with `FUZZ_SURVEY`, prints it).
fn expect_finite(what: &str, why: Option<String>) {
    let Some(why) = why else {
        return;
    };
    if std::env::var_os("FUZZ_SURVEY").is_some() {
        let input: String = std::thread::current()
            .name()
            .unwrap_or("")
            .chars()
            .take(600)
            .collect();
        eprintln!("SURVEY: {what} is Ok, but {why} ;; {input}");
        return;
    }
    panic!("{what} is Ok, but {why}");
}

/// The first of `values` that is not finite, named by `what`.
fn not_finite(what: &str, values: impl IntoIterator<Item = f64>) -> Option<String> {
    values
        .into_iter()
        .find(|v| !v.is_finite())
        .map(|v| format!("{what} holds {v}"))
}

/// Why an interface has a number that is not finite: its points, weights and normals, its
/// extent and its area.
fn interface_not_finite(i: &Interface) -> Option<String> {
    not_finite("its points", i.points().iter().flatten().copied())
        .or_else(|| not_finite("its weights", i.weights().iter().copied()))
        .or_else(|| not_finite("its normals", i.normals().iter().flatten().copied()))
        .or_else(|| not_finite("its extent", [i.extent()]))
        .or_else(|| not_finite("its area", [i.area()]))
}

/// Why a body has an output that is not finite: its interface, its load displacement, its
/// influence on a unit force at its first, middle and last point, its rigid modes.
fn body_not_finite(body: &dyn ElasticBody) -> Option<String> {
    let interface = body.interface();
    if let Some(why) = interface_not_finite(interface) {
        return Some(format!("its interface: {why}"));
    }
    if let Ok(u) = body.load_displacement() {
        if let Some(why) = not_finite("its load displacement", u) {
            return Some(why);
        }
    }
    let n = interface.len();
    let mut force = vec![0.0; n];
    let mut displacement = vec![0.0; n];
    for j in [0, n / 2, n - 1] {
        force[j] = 1.0;
        body.apply_influence(&force, &mut displacement);
        force[j] = 0.0;
        let what = format!("its influence on a unit force at point {j}");
        if let Some(why) = not_finite(&what, displacement.iter().copied()) {
            return Some(why);
        }
    }
    body.rigid_modes().iter().find_map(|m| {
        not_finite(
            &format!("its rigid mode {:?}", m.name),
            m.interface_displacement.iter().copied().chain([m.load]),
        )
    })
}

/// Region edges: a list, or `n` + 1 evenly spaced ones (made inside the case: an absurd `n`
/// is the constructor's to refuse, though its edges alone are large).
#[derive(Clone, Debug)]
enum Edges {
    List(Vec<f64>),
    Even { n: usize, start: f64, step: f64 },
}

impl Edges {
    fn make(&self) -> Vec<f64> {
        match self {
            Edges::List(v) => v.clone(),
            Edges::Even { n, start, step } => (0..=(*n).min(1 << 24))
                .map(|k| start + step * k as f64)
                .collect(),
        }
    }
}

fn edges() -> BoxedStrategy<Edges> {
    prop_oneof![
        2 => proptest::collection::vec(real(), 0..12).prop_map(Edges::List),
        2 => (
            prop_oneof![8 => 0usize..24, 2 => select(vec![100_000usize, 1_000_000, 1 << 24])],
            real(),
            real()
        )
            .prop_map(|(n, start, step)| Edges::Even { n, start, step }),
    ]
    .boxed()
}

/// A controller's settings with hostile numbers, products nested a few deep.
fn controller_settings() -> BoxedStrategy<contopt_optimise::ControllerSettings> {
    use contopt_optimise::ControllerSettings as C;
    let leaf = prop_oneof![
        real().prop_map(|level| C::Constant { level }),
        (real(), real(), size()).prop_map(|(l1_mm, l2_mm, axis)| C::Trapezoid {
            l1_mm,
            l2_mm,
            axis
        }),
        (real(), real(), size()).prop_map(|(l1_mm, l2_mm, axis)| C::Cubic { l1_mm, l2_mm, axis }),
    ];
    leaf.prop_recursive(4, 16, 2, |inner| {
        (inner.clone(), inner).prop_map(|(a, b)| C::Product {
            a: Box::new(a),
            b: Box::new(b),
        })
    })
    .boxed()
}

/// Why a controller has a value outside [0, 1] at a finite point of `points`.
fn controller_off(
    what: &str,
    v: &dyn contopt_optimise::Controller,
    points: &[[f64; 3]],
) -> Option<String> {
    points
        .iter()
        .filter(|x| x.iter().all(|c| c.is_finite()))
        .map(|&x| (x, v.value(x)))
        .find(|(_, value)| !(0.0..=1.0).contains(value))
        .map(|(x, value)| format!("{what} is {value} at {x:?}, outside [0, 1]"))
}

/// Points where a profile of `l1`, `l2` falls, along each axis: just past L1, halfway, just
/// short of L2 (where round-off might carry a fall outside [0, 1]).
fn falling_points(l1: f64, l2: f64, x: [f64; 3]) -> Vec<[f64; 3]> {
    let mut points = vec![x];
    for t in [1e-9, 0.5, 1.0 - 1e-9, 1.0 - f64::EPSILON] {
        let s = l1 + t * (l2 - l1);
        for axis in 0..3 {
            let mut p = [0.0; 3];
            p[axis] = s;
            points.push(p);
        }
    }
    points
}

proptest! {
    #![proptest_config(config(OTHER_CASES))]

    /// `Material::new` and its moduli; the elliptic integrals for a modulus in (−1, 1).
    #[test]
    fn constructors_material_elliptic(e in real(), nu in real(), k in real()) {
        construct(format!("Material::new({e:?}, {nu:?}); elliptic::complete({k:?})"), move || {
            if let Ok(m) = Material::new(e, nu) {
                let moduli = [m.e(), m.nu(), m.plane_strain_modulus(), m.contact_compliance()];
                expect_finite("Material::new", not_finite("its moduli", moduli));
            }
            let (kk, ee) = contopt_greens::elliptic::complete(k);
            if k.abs() < 1.0 {
                expect_finite("elliptic::complete", not_finite("K and E", [kk, ee]));
            }
        });
    }

    /// `Constant::new`, `Profile::trapezoid` / `cubic`, `along`, `ControllerSettings::build`
    /// and `check_reach`: a controller built `Ok` has values in [0, 1] at finite points.
    #[test]
    fn constructors_controllers(
        level in real(),
        l in (real(), real()),
        axis in size(),
        x in (real(), real(), real()),
        settings in controller_settings(),
        reach in ((real(), real(), real()), (real(), real(), real())),
    ) {
        construct(
            format!("Constant::new({level:?}); Profile::trapezoid/cubic({l:?}).along({axis}); \
                     value({x:?}); {settings:?}.build(), check_reach({reach:?})"),
            move || {
                use contopt_optimise::{Constant, Profile};
                let x = [x.0, x.1, x.2];
                let points = falling_points(l.0, l.1, x);
                if let Ok(c) = Constant::new(level) {
                    expect_finite("Constant::new", controller_off("v", &c, &points));
                }
                for p in [Profile::trapezoid(l.0, l.1), Profile::cubic(l.0, l.1)] {
                    if let Ok(p) = p.and_then(|p| p.along(axis)) {
                        expect_finite("Profile", controller_off("v", &p, &points));
                    }
                }
                if let Ok(v) = settings.build() {
                    let mut points = vec![x, [0.0; 3]];
                    collect_falls(&settings, x, &mut points);
                    expect_finite("ControllerSettings::build", controller_off("v", &v, &points));
                }
                let ((hx, hy, hz), (cx, cy, cz)) = reach;
                let _ = settings.check_reach([hx, hy, hz], [cx, cy, cz]);
            },
        );
    }

    /// The crowns of `contopt_roller::Crown`: a crown built `Ok` drops by a finite amount
    /// wherever `drop` answers `Ok`.
    #[test]
    fn constructors_crowns(
        p in (real(), real(), real(), real(), real(), real()),
        table in proptest::collection::vec((real(), real()), 0..6),
        x in real(),
        length in real(),
    ) {
        construct(format!("Crown::* with {p:?}, table {table:?}; drop({x:?}, {length:?})"), move || {
            use contopt_roller::Crown;
            let (a, b, c, d, e, f) = p;
            let (xs, drops): (Vec<f64>, Vec<f64>) = table.into_iter().unzip();
            for crown in [
                Crown::iso(a),
                Crown::lundberg(a, b, c),
                Crown::johns_gohar(a, b, c, d),
                Crown::fujiwara_kawase(a, b, c, d, e, f),
                Crown::table(xs, drops),
            ]
            .into_iter()
            .flatten()
            {
                let what = format!("{crown:?}");
                expect_finite(&what, crown_not_finite(&crown, x, length));
            }
        });
    }

    /// `HalfSpace::grid`, `periodic` and `cells_interface`, `upper` and `pressed`: a body
    /// built `Ok` gives finite outputs.
    #[test]
    fn constructors_half_space(
        m in material_args(),
        nx in size(),
        ny in size(),
        dx in real(),
        dy in real(),
        origin in (real(), real()),
        periodic in any::<bool>(),
        force in real(),
    ) {
        construct(
            format!("HalfSpace::{}(material {m:?}, {nx}, {ny}, {dx:?}, {dy:?}, {origin:?}).pressed({force:?})",
                if periodic { "periodic" } else { "grid" }),
            move || {
                let material = material_or_steel(m);
                let origin = [origin.0, origin.1];
                if let Ok(surface) = HalfSpace::cells_interface(nx, ny, dx, dy, origin) {
                    expect_finite("HalfSpace::cells_interface", interface_not_finite(&surface));
                }
                let body = if periodic {
                    HalfSpace::periodic("fuzz", material, nx, ny, dx, dy, origin)
                } else {
                    HalfSpace::grid("fuzz", material, nx, ny, dx, dy, origin)
                };
                if let Ok(body) = body {
                    expect_finite("HalfSpace", body_not_finite(&body));
                    if let Ok(pressed) = body.upper().pressed(force) {
                        expect_finite("HalfSpace::pressed", body_not_finite(&pressed));
                    }
                }
            },
        );
    }

    /// `HalfPlane::new`, `AxisymmetricHalfSpace::new` and their surfaces.
    #[test]
    fn constructors_half_plane_axisymmetric(
        m in material_args(),
        strain in any::<bool>(),
        thickness in real(),
        edges in edges(),
        datum in real(),
    ) {
        construct(
            format!("HalfPlane::new(material {m:?}, strain {strain}, {thickness:?}, edges {edges:?}, {datum:?}) and AxisymmetricHalfSpace::new"),
            move || {
                let edges = edges.make();
                let material = material_or_steel(m);
                let state = if strain { PlaneState::Strain } else { PlaneState::Stress };
                if let Ok(s) = HalfPlane::strips_interface(&edges, thickness) {
                    expect_finite("HalfPlane::strips_interface", interface_not_finite(&s));
                }
                if let Ok(s) = AxisymmetricHalfSpace::rings_interface(&edges) {
                    expect_finite("AxisymmetricHalfSpace::rings_interface", interface_not_finite(&s));
                }
                if let Ok(b) = HalfPlane::new("fuzz", material, state, thickness, &edges, datum) {
                    expect_finite("HalfPlane::new", body_not_finite(&b));
                }
                if let Ok(b) = AxisymmetricHalfSpace::new("fuzz", material, &edges) {
                    expect_finite("AxisymmetricHalfSpace::new", body_not_finite(&b));
                }
            },
        );
    }

    /// `Winkler::on` a grid's, rings' or strips' surface: its influence and its
    /// preconditioner are finite.
    #[test]
    fn constructors_winkler(
        k in real(),
        grid in (size(), size(), real(), real()),
        edges in edges(),
        which in 0..3usize,
    ) {
        construct(
            format!("Winkler::on(surface {which} of grid {grid:?} or edges {edges:?}, {k:?})"),
            move || {
                let edges = edges.make();
                let surface = match which {
                    0 => HalfSpace::cells_interface(grid.0, grid.1, grid.2, grid.3, [0.0, 0.0]),
                    1 => AxisymmetricHalfSpace::rings_interface(&edges),
                    _ => HalfPlane::strips_interface(&edges, grid.2),
                };
                let Ok(surface) = surface else {
                    return;
                };
                let Ok(bed) = Winkler::on("bed", surface, k) else {
                    return;
                };
                expect_finite("Winkler::on", body_not_finite(&bed));
                let n = bed.interface().len();
                let mut force = vec![0.0; n];
                bed.precondition(&vec![1.0; n], &mut force);
                expect_finite("Winkler::on", not_finite("its preconditioner", force));
            },
        );
    }
}

/// The profiles of a controller's settings: points where each falls.
fn collect_falls(
    settings: &contopt_optimise::ControllerSettings,
    x: [f64; 3],
    points: &mut Vec<[f64; 3]>,
) {
    use contopt_optimise::ControllerSettings as C;
    match settings {
        C::Constant { .. } => {}
        C::Trapezoid { l1_mm, l2_mm, .. } | C::Cubic { l1_mm, l2_mm, .. } => {
            points.extend(falling_points(*l1_mm, *l2_mm, x));
        }
        C::Product { a, b } => {
            collect_falls(a, x, points);
            collect_falls(b, x, points);
        }
    }
}

/// Why a crown's drop is not finite where it answers `Ok`: at `x`, and across a roller of
/// `length` and of unit length, from the middle to just short of the ends.
fn crown_not_finite(crown: &contopt_roller::Crown, x: f64, length: f64) -> Option<String> {
    let mut at = vec![(x, length)];
    for l in [length, 1.0] {
        for t in [0.0, 0.5, -0.9, 0.999, -0.999_999, 1.0 - f64::EPSILON] {
            at.push((0.5 * t * l, l));
        }
    }
    at.into_iter().find_map(|(x, l)| match crown.drop(x, l) {
        Ok(z) if !z.is_finite() => Some(format!("its drop at x = {x:?} of length {l:?} is {z}")),
        _ => None,
    })
}

/// The arguments of [`interface_case`].
#[derive(Clone, Debug)]
struct InterfaceArgs {
    points: Vec<[f64; 3]>,
    weights: Vec<f64>,
    normal: [f64; 3],
    geometry: usize,
    axis: [f64; 3],
    force: f64,
    shape_axis: usize,
    rows: Vec<Vec<(usize, f64)>>,
    node: usize,
    /// A bed's modulus and the rigid body's approach into it.
    bed: (f64, f64),
}

fn interface_args() -> BoxedStrategy<InterfaceArgs> {
    let triple = || (real(), real(), real()).prop_map(|(a, b, c)| [a, b, c]);
    (
        (
            proptest::collection::vec(triple(), 0..8),
            proptest::collection::vec(real(), 0..8),
            prop_oneof![Just([0.0, 0.0, 1.0]), Just([0.0, 1.0, 0.0]), triple()],
            0..3usize,
        ),
        (triple(), real(), size()),
        (
            proptest::collection::vec(proptest::collection::vec((size(), real()), 0..3), 0..8),
            size(),
            (real(), real()),
        ),
    )
        .prop_map(
            |(
                (points, weights, normal, geometry),
                (axis, force, shape_axis),
                (rows, node, bed),
            )| {
                InterfaceArgs {
                    points,
                    weights,
                    normal,
                    geometry,
                    axis,
                    force,
                    shape_axis,
                    rows,
                    node,
                    bed,
                }
            },
        )
        .boxed()
}

/// Whether a termination says a value became NaN or infinite (here or in a method inside).
fn says_non_finite(t: &Termination) -> bool {
    match t {
        Termination::NonFinite { .. } => true,
        Termination::Inner { termination, .. } => says_non_finite(termination),
        _ => false,
    }
}

/// Why a contact state has a value that is not finite, unless its termination says so.
fn state_not_finite(s: &contopt_core::ContactState) -> Option<String> {
    if says_non_finite(&s.termination) {
        return None;
    }
    not_finite("its pressure", s.pressure.iter().copied())
        .or_else(|| not_finite("its gap", s.gap.iter().copied()))
        .or_else(|| not_finite("its rigid amplitudes", s.rigid.iter().copied()))
        .map(|why| format!("{why}, and it ended {}", s.termination))
}

/// `Interface::new` and what is built on an interface: `GapShape::new` / `extruded` /
/// `symmetric`, `RigidBody::fixed` / `pressed`, a Winkler bed under a rigid body, the
/// `InterfaceProblem` of the two and its solve by the active set, an `Optimisation` of it.
fn interface_case(a: InterfaceArgs) {
    use contopt_core::GapShape;
    use contopt_optimise::{Constant, Optimisation, Reference, Region};
    let geometry = match a.geometry {
        0 => Geometry::Axisymmetric,
        1 => Geometry::Plane { thickness: 1.0 },
        _ => Geometry::Surface,
    };
    let n = a.points.len();
    if let Ok(shape) = GapShape::new(a.points.clone(), a.rows) {
        let nodes = shape.nodes().iter().flatten().copied();
        expect_finite("GapShape::new", not_finite("its nodes", nodes));
    }
    let Ok(interface) = Interface::new(geometry, a.points, a.weights, vec![a.normal; n]) else {
        return;
    };
    expect_finite("Interface::new", interface_not_finite(&interface));
    let shapes = [
        GapShape::extruded(&interface, a.shape_axis),
        GapShape::symmetric(&interface, a.shape_axis),
    ];
    for shape in shapes.into_iter().flatten() {
        let change = shape.apply(&vec![1.0; shape.nodes().len()]);
        expect_finite(
            "GapShape::extruded",
            not_finite("Q applied to ones", change),
        );
    }
    let fixed = RigidBody::fixed("fixed", &interface);
    expect_finite("RigidBody::fixed", body_not_finite(&fixed));
    // A rigid body on a rigid body: an error, not a panic.
    let other = RigidBody::fixed("other", fixed.interface());
    let _ = InterfaceProblem::new(&fixed, &other, &vec![0.0; n]);
    let Ok(bed) = Winkler::on("bed", interface.clone(), a.bed.0) else {
        return;
    };
    let solver = ActiveSet::new(Default::default()).expect("the active set");
    if let Ok(pressed) = RigidBody::pressed("pressed", &interface, a.axis, a.force) {
        expect_finite("RigidBody::pressed", body_not_finite(&pressed));
        if let Ok(problem) = InterfaceProblem::new(&bed, &pressed, &vec![0.0; n]) {
            if let Ok(state) = solver.solve(&problem) {
                let what = "a pressed rigid body's contact";
                expect_finite(what, state_not_finite(&state));
            }
        }
    }
    let Ok(problem) = InterfaceProblem::new(&bed, &fixed, &vec![-a.bed.1; n]) else {
        return;
    };
    if let Ok(state) = solver.solve(&problem) {
        expect_finite("a fixed rigid body's contact", state_not_finite(&state));
    }
    let shape = GapShape::pointwise(&interface);
    let v = Constant::new(1.0).expect("level 1");
    if let Ok(opt) = Optimisation::new(&problem, &shape, &v) {
        let regions = vec![Region::OmegaV; n];
        let _ = opt
            .with_regions(regions)
            .and_then(|o| o.with_reference(Reference::Node(a.node)));
    }
}

/// The arguments of [`fe_model_case`]: a material, an analysis and its thickness, a rectangle
/// of `nx` × `ny` elements of width `width`, a value for loads and prescriptions, a node and
/// a face.
type FeModelArgs = (
    (f64, f64),
    usize,
    f64,
    usize,
    usize,
    f64,
    f64,
    usize,
    (usize, usize),
);

/// `FeModel::new`, its supports and loads, its solve, and `FeBody::new` on its top.
fn fe_model_case(args: FeModelArgs) {
    let (m, analysis, thickness, nx, ny, width, value, node, face) = args;
    let analysis = match analysis {
        0 => Analysis::Axisymmetric,
        1 => Analysis::PlaneStress { thickness },
        _ => Analysis::PlaneStrain { thickness },
    };
    let (Ok(x), Ok(y)) = (
        Spacing::uniform(0.0, width, nx),
        Spacing::uniform(-width, 0.0, ny),
    ) else {
        return;
    };
    let Ok(mesh) = Mesh::rectangle(ElementKind::Q8, &x, &y) else {
        return;
    };
    let Ok(mut model) = FeModel::new(mesh, material_or_steel(m), analysis) else {
        return;
    };
    let bottom = model.mesh().nodes_on_y(-width, 0.0, width);
    let top = model.mesh().faces_on_y(0.0, 0.0, width);
    let face = contopt_fem::Face {
        element: face.0,
        local: face.1,
    };
    let _ = model.prescribe(&[node], Component::Y, value);
    let _ = model.nodal_force(node, [value, value]);
    let _ = model.pressure(&[face], value);
    let _ = model.traction(&top, [value, 0.0]);
    let _ = model
        .fix(&bottom, Component::Y)
        .and_then(|m| m.fix(&bottom, Component::X));
    let _ = model.pressure(&top, value);
    if let Ok(solution) = model.solve() {
        let u = solution.displacement;
        expect_finite("FeModel::solve", not_finite("its displacements", u));
    }
    if let Ok(body) = FeBody::new("fuzz", model.clone(), &top) {
        expect_finite("FeBody::new", body_not_finite(&body));
        let n = body.interface().len();
        let rigid = vec![0.0; body.rigid_modes().len()];
        if let Ok(u) = body.displacement(&vec![1.0; n], &rigid) {
            expect_finite(
                "FeBody::new",
                not_finite("its displacement under unit forces", u),
            );
        }
    }
    let _ = FeBody::new("fuzz", model, &[face]);
}

/// Why a spacing is not one: a coordinate not finite, or not above the one before.
fn spacing_off(s: &Spacing) -> Option<String> {
    not_finite("its coordinates", s.coords().iter().copied()).or_else(|| {
        s.coords()
            .windows(2)
            .find(|w| w[1] <= w[0])
            .map(|w| format!("its coordinates do not increase: {} then {}", w[0], w[1]))
    })
}

fn mesh_not_finite(mesh: &Mesh) -> Option<String> {
    not_finite("its nodes", mesh.nodes().iter().flatten().copied())
}

/// The supports of a base, as a scene may name them.
const SUPPORT_SETS: &[&[&str]] = &[
    &["clamped"],
    &["axial"],
    &["axial", "symmetry"],
    &["clamped", "symmetry"],
    &[],
    &["symmetry"],
    &["clamped", "axial"],
];

/// The arguments of [`fe_scene`].
#[derive(Clone, Debug)]
struct FeSceneArgs {
    /// Analysis (0 axisymmetric, 1 plane stress, 2 plane strain), its thickness, the zone's
    /// radius, its elements, grading and element.
    zone: (usize, f64, f64, i64, Option<f64>, bool),
    pair: (&'static str, &'static str),
    /// A base's material, radius, height, supports and layers.
    base: ((f64, f64), f64, f64, &'static [&'static str], Option<i64>),
    /// A punch's material, height, pressure (else a displacement) and its value, layers.
    punch: ((f64, f64), f64, bool, f64, Option<i64>),
    /// A block's material and size; a bed's modulus.
    block: ((f64, f64), f64, f64),
}

fn fe_scene_args() -> BoxedStrategy<FeSceneArgs> {
    let layers = || proptest::option::of(1i64..=10);
    (
        (
            0..3usize,
            real(),
            real(),
            1i64..=10,
            proptest::option::of(real()),
            any::<bool>(),
        ),
        select(FACE_PAIRS),
        (
            material_args(),
            real(),
            real(),
            select(SUPPORT_SETS),
            layers(),
        ),
        (material_args(), real(), any::<bool>(), real(), layers()),
        (material_args(), real(), real()),
    )
        .prop_map(|(zone, pair, base, punch, block)| FeSceneArgs {
            zone,
            pair,
            base,
            punch,
            block,
        })
        .boxed()
}

/// The scene of a pair on finite-element faces with hostile dimensions, as TOML.
fn fe_scene(a: &FeSceneArgs) -> Option<String> {
    let f = Value::Float;
    let material = |(e, nu): (f64, f64)| table(vec![("e_mpa", Some(f(e))), ("nu", Some(f(nu)))]);
    let (analysis, thickness, radius, elements, grading, q9) = a.zone;
    let analysis = match analysis {
        0 => text("axisymmetric"),
        k => tagged(
            1,
            text(ANALYSES[k]),
            vec![("thickness_mm", Some(f(thickness)))],
        ),
    };
    let zone = tagged(
        2,
        text("faces"),
        vec![
            ("analysis", Some(analysis)),
            ("radius_mm", Some(f(radius))),
            ("elements", Some(int(elements))),
            ("grading", grading.map(f)),
            ("element", Some(text(if q9 { "q9" } else { "q8" }))),
        ],
    );
    let (m, r, h, supports, layers) = a.base;
    let supports = Value::Array(supports.iter().map(|s| text(s)).collect());
    let base = vec![
        ("material", Some(material(m))),
        ("radius_mm", Some(f(r))),
        ("height_mm", Some(f(h))),
        ("supports", Some(supports)),
        ("layers", layers.map(int)),
    ];
    let (m, h, pressure, value, layers) = a.punch;
    let load = table(vec![(
        if pressure {
            "pressure_mpa"
        } else {
            "displacement_mm"
        },
        Some(f(value)),
    )]);
    let punch = vec![
        ("material", Some(material(m))),
        ("height_mm", Some(f(h))),
        ("load", Some(load)),
        ("layers", layers.map(int)),
    ];
    let (m, size, k) = a.block;
    let body = |kind: &str| {
        let fields = match kind {
            "fe_base" => base.clone(),
            "fe_punch" => punch.clone(),
            "fe_block" => vec![("material", Some(material(m))), ("size_mm", Some(f(size)))],
            "winkler" => vec![("modulus_mpa_per_mm", Some(f(k)))],
            _ => vec![],
        };
        tagged(2, text(kind), fields)
    };
    let load = (a.pair.1 != "fe_punch").then(|| table(vec![("approach_mm", Some(f(1e-3)))]));
    let contact = table(vec![("zone", Some(zone)), ("load", load)]);
    let bodies = Value::Array(vec![body(a.pair.0), body(a.pair.1)]);
    let scene = table(vec![
        ("name", Some(text("fuzz"))),
        ("contact", Some(contact)),
        ("body", Some(bodies)),
    ]);
    toml::to_string(&scene).ok()
}

/// Builds the bodies of the first case of a scene that reads: finite outputs, or an error.
fn build_scene_bodies(text: &str) {
    let Ok(scene) = Scene::parse(text, Format::Toml, &scene_file()) else {
        return;
    };
    let Some(case) = scene.cases().first() else {
        panic!("a scene that parsed has no case");
    };
    if let Ok(built) = case.build() {
        for body in [built.first(), built.second()] {
            expect_finite(
                &format!("the scene's {}", body.name()),
                body_not_finite(body),
            );
        }
    }
}

proptest! {
    #![proptest_config(config(OTHER_CASES))]

    /// `Interface::new` and what is built on it ([`interface_case`]).
    #[test]
    fn constructors_interface(args in interface_args()) {
        construct(format!("{args:?}"), move || interface_case(args));
    }

    /// `Spacing::*`, `Mesh::rectangle` / `stacked` / `new`: what is built `Ok` is finite, a
    /// spacing increasing.
    #[test]
    fn constructors_spacing_mesh(
        a in real(),
        b in real(),
        n in size(),
        ratio in real(),
        first in real(),
        points in proptest::collection::vec(real(), 0..4),
        coords in proptest::collection::vec(real(), 0..8),
        q9 in any::<bool>(),
        nodes in proptest::collection::vec((real(), real()), 0..10),
        elements in proptest::collection::vec(proptest::collection::vec(size(), 0..10), 0..3),
    ) {
        construct(
            format!("Spacing a {a:?} b {b:?} n {n} ratio {ratio:?} first {first:?} points {points:?} coords {coords:?}; \
                     Mesh q9 {q9} nodes {nodes:?} elements {elements:?}"),
            move || {
                let kind = if q9 { ElementKind::Q9 } else { ElementKind::Q8 };
                let spacings = [
                    Spacing::from_coords(coords),
                    Spacing::uniform(a, b, n),
                    Spacing::geometric(a, b, n, ratio),
                    Spacing::geometric_first(a, b, n, first),
                    Spacing::graded(a, b, n, &points, ratio),
                ];
                let ok: Vec<Spacing> = spacings.into_iter().flatten().collect();
                for x in &ok {
                    expect_finite("Spacing", spacing_off(x));
                    if let Ok(r) = x.restrict(a, b) {
                        expect_finite("Spacing::restrict", spacing_off(&r));
                    }
                    for y in &ok {
                        // Only small meshes: a large one is a legitimate, slow request.
                        if x.len() * y.len() <= 400 {
                            if let Ok(mesh) = Mesh::rectangle(kind, x, y) {
                                expect_finite("Mesh::rectangle", mesh_not_finite(&mesh));
                            }
                            if let Ok((lower, upper)) = Mesh::stacked(kind, x, y, (a, b), y) {
                                expect_finite("Mesh::stacked", mesh_not_finite(&lower));
                                expect_finite("Mesh::stacked", mesh_not_finite(&upper));
                            }
                        }
                        if let Ok(z) = x.then(y) {
                            expect_finite("Spacing::then", spacing_off(&z));
                        }
                    }
                }
                let nodes = nodes.into_iter().map(|(x, y)| [x, y]).collect();
                if let Ok(mesh) = Mesh::new(kind, nodes, elements) {
                    expect_finite("Mesh::new", mesh_not_finite(&mesh));
                }
            },
        );
    }

    /// `FeModel::new`, its supports, loads and solve, and `FeBody::new`, on small rectangles
    /// ([`fe_model_case`]).
    #[test]
    fn constructors_fe_model(
        m in material_args(),
        analysis in 0..3usize,
        thickness in real(),
        nx in 1usize..5,
        ny in 1usize..5,
        width in real(),
        value in real(),
        node in size(),
        face in (size(), size()),
    ) {
        let args = (m, analysis, thickness, nx, ny, width, value, node, face);
        construct(format!("FeModel with {args:?}"), move || fe_model_case(args));
    }

    /// The scene's finite-element bodies (`fe_base`, `fe_punch`, `fe_block`, and a rigid body
    /// or a bed on their faces) with hostile dimensions: a scene that reads builds its bodies
    /// to finite outputs, or refuses to.
    #[test]
    fn constructors_scene_bodies(args in fe_scene_args()) {
        let Some(text) = fe_scene(&args) else {
            return Ok(());
        };
        let input: Arc<str> = text.into();
        let shown = input.clone();
        guarded("build", shown, move || build_scene_bodies(&input));
    }

    /// `Roller` (its modulus, radius, Hertz contact, cells and bodies) and its crowns built by
    /// `CrownSettings::build`.
    #[test]
    fn constructors_roller(
        shape in (real(), real(), proptest::option::of(real()), real(), real()),
        m in (material_args(), material_args()),
        grid in (size(), size(), real()),
        crown in (0..6usize, real(), real(), real()),
    ) {
        construct(
            format!("Roller {{ diameter, length, raceway, load, tilt {shape:?}, materials {m:?} }}; \
                     cells and reach {grid:?}; crown {crown:?}"),
            move || roller_case(shape, m, grid, crown),
        );
    }

    /// `nelder_mead` with hostile starts, steps and settings: its minimum is no worse than its
    /// start, never NaN.
    #[test]
    fn constructors_nelder_mead(
        start in proptest::collection::vec(real(), 0..4),
        step in proptest::collection::vec(real(), 0..4),
        tolerance in real(),
        max_evaluations in 0usize..10_000,
    ) {
        construct(
            format!("nelder_mead(sum of squares, start {start:?}, step {step:?}, tolerance {tolerance:?}, max {max_evaluations})"),
            move || {
                let settings = contopt_optimise::SearchSettings { tolerance, max_evaluations };
                let squares = |x: &[f64]| x.iter().map(|v| v * v).sum::<f64>();
                let objective = |x: &[f64]| -> contopt_core::Result<ControlFlow<Termination, f64>> {
                    Ok(ControlFlow::Continue(squares(x)))
                };
                if let Ok(min) = contopt_optimise::nelder_mead(objective, &start, &step, &settings) {
                    assert!(!min.value.is_nan(), "a NaN minimum: {min:?}");
                    let at_start = squares(&start);
                    assert!(
                        at_start.is_nan() || min.value <= at_start,
                        "a minimum {} worse than the start's {at_start}",
                        min.value
                    );
                    if min.value.is_finite() {
                        expect_finite("nelder_mead", not_finite("its point", min.x));
                    }
                }
            },
        );
    }
}

/// A roller's figures and bodies ([`constructors_roller`]).
fn roller_case(
    (diameter, length, raceway_diameter, load, tilt): (f64, f64, Option<f64>, f64, f64),
    m: ((f64, f64), (f64, f64)),
    (nx, ny, reach): (usize, usize, f64),
    (crown, k1, k2, z_m): (usize, f64, f64, f64),
) {
    use contopt_roller::{Crown, CrownSettings, Roller};
    let roller = Roller {
        diameter,
        length,
        raceway_diameter,
        roller: material_or_steel(m.0),
        raceway: material_or_steel(m.1),
        load,
        tilt,
        crown: Crown::Straight,
    };
    expect_finite("Roller", not_finite("its modulus", [roller.e_star()]));
    if let Ok(r) = roller.radius() {
        expect_finite("Roller", not_finite("its radius", [r]));
    }
    if let Ok((b, p0)) = roller.hertz() {
        expect_finite("Roller", not_finite("its Hertz contact", [b, p0]));
    }
    if let Ok(cell) = roller.cell(nx, ny, reach) {
        expect_finite("Roller::cell", not_finite("its cell", cell));
    }
    if let Ok((raceway, upper, gap)) = roller.bodies(nx, ny, reach) {
        expect_finite("Roller::bodies", body_not_finite(&raceway));
        expect_finite("Roller::bodies", body_not_finite(&upper));
        expect_finite("Roller::bodies", not_finite("its gap", gap));
    }
    let settings = match crown {
        0 => CrownSettings::Straight,
        1 => CrownSettings::Iso,
        2 => CrownSettings::Lundberg,
        3 => CrownSettings::JohnsGohar,
        4 => CrownSettings::FujiwaraKawase {
            k1,
            k2,
            z_m_mm: z_m,
        },
        _ => CrownSettings::Table {
            file: "crown.csv".into(),
        },
    };
    let dir = scene_file()
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    if let Ok(built) = settings.build(&roller, &dir) {
        let what = format!("{settings:?}.build");
        expect_finite(&what, crown_not_finite(&built, 0.25 * length, length));
    }
}

// ---------------------------------------------------------------------------------------------
// Regression tests of the defects the properties found, each its reproducer: what should hold,
// and now does.

fn steel() -> Material {
    Material::new(2e5, 0.3).expect("steel")
}

/// Fixed: `Roller::bodies` with an even or too small `ny` subtracted 1 from `ny` before
/// `Roller::cell` refused it: `ny = 0` overflowed (a panic in debug builds, where CI tests).
#[test]
fn fixed_roller_bodies_without_rows() {
    let roller = contopt_roller::Roller {
        diameter: 10.0,
        length: 10.0,
        raceway_diameter: None,
        roller: steel(),
        raceway: steel(),
        load: 1000.0,
        tilt: 0.0,
        crown: contopt_roller::Crown::Straight,
    };
    assert!(roller.bodies(4, 0, 1.0).is_err());
}

/// Fixed: the cubic controller 1 − 3s² + 2s³ came out −2.2e-16 just short of L2 (round-off),
/// which `Optimisation::new` refuses as a controller value outside [0, 1].
#[test]
fn fixed_cubic_controller_short_of_l2() {
    use contopt_optimise::{Controller, Profile};
    let v = Profile::cubic(0.0, 0.001).expect("a profile");
    let value = v.value([0.000_999_999_999, 0.0, 0.0]);
    assert!((0.0..=1.0).contains(&value), "{value}");
}

/// Fixed: a scene with `case = []` panicked in `Scene::parse` (no first case to name the
/// scene); an empty list of cases is refused.
#[test]
fn fixed_empty_list_of_cases() {
    let text = contopt_scene::BUNDLED
        .iter()
        .find(|b| b.name == "winkler-bed")
        .expect("winkler-bed is bundled")
        .text;
    let text = format!("case = []\n{text}");
    assert!(Scene::parse(&text, Format::Toml, Path::new("fuzz.toml")).is_err());
}

/// Fixed: the iteration's step 6 fits the gap change at the design nodes to the Ω_v points
/// by least squares; with fewer Ω_v points than nodes (one element's face, two of its three
/// Gauss points in Ω_v) faer's solve asserted and the run panicked. It is an error now.
#[test]
fn fixed_step_six_with_fewer_points_than_nodes() {
    let text = r#"
        name = "fuzz"
        [contact]
        zone = { faces = { elements = 1, radius_mm = 1.0, analysis = { kind = "plane_stress", thickness_mm = 1.0 } } }
        gap = { cylinder = { radius_mm = 3.29 } }
        load = { approach_mm = 0.0023 }
        [[body]]
        kind = "fe_base"
        height_mm = 1.0
        radius_mm = 1.2
        supports = ["clamped"]
        material = { e_mpa = 55626.0, nu = 0.0 }
        [[body]]
        fe_punch = { height_mm = 89.2, load = { pressure_mpa = 484.6 }, material = { e_mpa = 217923.0, nu = 0.068 } }
        [solver]
        kind = "active_set"
        [optimisation]
        method = { kind = "given_load", max_iterations = 1 }
        controller = { kind = "constant", level = 0.1 }
        omega_v = { kind = "disc", centre_mm = [0.0, 0.0], radius_mm = 0.833 }
    "#;
    let scene = Scene::parse(text, Format::Toml, Path::new("fuzz.toml")).expect("a scene");
    for report in scene.run() {
        assert!(report.is_err(), "{report:?}");
    }
}

/// Fixed: `Spacing::restrict(a, b)` with `b` a boundary before `a` sliced its coordinates
/// from the later to the earlier and panicked; it is an error now.
#[test]
fn fixed_spacing_restricted_backwards() {
    let spacing = Spacing::uniform(0.0, 1.0, 2).expect("a spacing");
    assert!(spacing.restrict(1.0, 0.0).is_err());
}

/// Fixed (extreme magnitudes): a `Material` of E = f64::MAX was built, and its plane-strain
/// modulus E/(1 − ν²) was infinite. The libraries took any finite magnitude and their
/// arithmetic overflowed far from any physical input; now what a constructor derives is
/// checked finite (`contopt_core::check::derived`), an error naming the input.
#[test]
fn fixed_extreme_material_modulus() {
    let built = Material::new(f64::MAX, 0.3).map(|m| m.plane_strain_modulus());
    let e = built.expect_err("refused").to_string();
    assert!(e.contains("e_mpa") && e.contains("beyond f64"), "{e}");
}

/// Fixed (extreme magnitudes): a grid of 1 × 1e-300 mm cells had a NaN kernel (it divided by
/// the cell's area); the kernel is taken in units of the larger side now, finite.
#[test]
fn fixed_extreme_half_space_cell() {
    let body = HalfSpace::grid("fuzz", steel(), 1, 1, 1.0, 1e-300, [0.0, 0.0]).expect("a grid");
    assert_eq!(body_not_finite(&body), None);
}

/// Fixed (extreme magnitudes): an axisymmetric model of one Q8 element, 10 mm wide, under a
/// pressure of 1.7e308 MPa (finite, so taken) solved to NaN displacements: its nodal forces
/// overflowed. The pressure is refused now, and `FeModel::solve` checks its answer.
#[test]
fn fixed_extreme_fe_load() {
    let x = Spacing::uniform(0.0, 10.0, 1).expect("a spacing");
    let y = Spacing::uniform(-10.0, 0.0, 1).expect("a spacing");
    let mesh = Mesh::rectangle(ElementKind::Q8, &x, &y).expect("a mesh");
    let mut model = FeModel::new(mesh, steel(), Analysis::Axisymmetric).expect("a model");
    let bottom = model.mesh().nodes_on_y(-10.0, 0.0, 10.0);
    let top = model.mesh().faces_on_y(0.0, 0.0, 10.0);
    model.fix(&bottom, Component::X).expect("held");
    model.fix(&bottom, Component::Y).expect("held");
    let e = model
        .pressure(&top, 1.7e308)
        .expect_err("refused")
        .to_string();
    assert!(
        e.contains("pressure.value") && e.contains("beyond f64"),
        "{e}"
    );
    model.pressure(&top, 1e300).expect("a pressure");
    if let Ok(solution) = model.solve() {
        assert_eq!(not_finite("its displacements", solution.displacement), None);
    }
}

/// Fixed (extreme magnitudes): an interface of two points 2e200 mm apart had an infinite
/// extent (the diagonal of its bounding box, from squares); it is a `hypot` now.
#[test]
fn fixed_extreme_interface_extent() {
    let points = vec![[-1e200, 0.0, 0.0], [1e200, 0.0, 0.0]];
    let interface = Interface::new(
        Geometry::Surface,
        points,
        vec![1.0; 2],
        vec![[0.0, 0.0, 1.0]; 2],
    );
    assert_eq!(interface.expect("an interface").extent(), 2e200);
}

/// Fixed (extreme magnitudes): Lundberg's crown for a load of 1e300 N on 1e-300 mm had an
/// infinite scale Q/(π l E*), and its drop at the middle was ∞ · 0 = NaN; it is refused.
#[test]
fn fixed_extreme_crown_scale() {
    let crown = contopt_roller::Crown::lundberg(1e300, 1e-300, 2e5);
    assert!(crown.is_err(), "{crown:?}");
}

/// Fixed: `Crown::drop(x, length)` refused |x| ≥ length/2 by 2|x|/length < 1, which a
/// negative length passed whatever x: ISO's crown of a 10 mm roller dropped NaN at x = 5 of a
/// length of −1 mm. The length must be positive now. (Scenes check it first.)
#[test]
fn fixed_crown_drop_negative_length() {
    let crown = contopt_roller::Crown::iso(10.0).expect("ISO's crown");
    let drop = crown.drop(5.0, -1.0);
    assert!(drop.is_err(), "{drop:?}");
}

/// Fixed: `GapShape::new` checked its rows (node indices, finite weights) but not its nodes:
/// a design node at (NaN, 0, 0) was taken.
#[test]
fn fixed_gap_shape_non_finite_nodes() {
    let shape = contopt_core::GapShape::new(vec![[f64::NAN, 0.0, 0.0]], vec![vec![(0, 1.0)]]);
    assert!(shape.is_err(), "{shape:?}");
}

/// Fixed: `Interface::new` checked that each normal has unit length by
/// `(len - 1).abs() > GEOMETRY_TOLERANCE`, false for a NaN length: a NaN normal was taken.
#[test]
fn fixed_interface_nan_normal() {
    let interface = Interface::new(
        Geometry::Surface,
        vec![[0.0; 3]],
        vec![1.0],
        vec![[f64::NAN, 0.0, 0.0]],
    );
    assert!(interface.is_err(), "{interface:?}");
}

/// Fixed: `RigidBody::pressed` checked its axis as `Interface::new` its normals: a NaN axis was
/// taken, and the body's rigid mode moved its points by NaN.
#[test]
fn fixed_rigid_body_nan_axis() {
    let surface = Interface::new(
        Geometry::Surface,
        vec![[0.0; 3]],
        vec![1.0],
        vec![[0.0, 0.0, 1.0]],
    )
    .expect("a surface");
    let pressed = RigidBody::pressed("punch", &surface, [f64::NAN, 0.0, 0.0], 1.0);
    assert!(pressed.is_err(), "{pressed:?}");
}

/// Fixed: `Spacing::from_coords` checked coordinates 1.. for finiteness and order, not
/// coordinate 0: `[-∞, 0]` was taken as a spacing of one infinite element.
#[test]
fn fixed_spacing_infinite_first_coordinate() {
    let spacing = Spacing::from_coords(vec![f64::NEG_INFINITY, 0.0]);
    assert!(spacing.is_err(), "{spacing:?}");
}

/// Fixed: Love's kernel of a 1 × 1e-8 mm cell (aspect ratio 10⁸) was infinite at the cell
/// itself and NaN at its neighbour: `love` formed s + √(s² + t²) for s = −a, t = b ≪ a, which
/// cancels to 0 (t²/(√(s² + t²) − s) does not).
#[test]
fn fixed_love_kernel_of_an_elongated_cell() {
    let body = HalfSpace::grid("fuzz", steel(), 2, 1, 1.0, 1e-8, [0.0, 0.0]).expect("a grid");
    assert_eq!(body_not_finite(&body), None);
}

/// Fixed: `Roller::cell(nx, ny, reach)` did not check `reach` (`bodies` did): a NaN reach gave
/// a NaN cell size across.
#[test]
fn fixed_roller_cell_reach() {
    let roller = contopt_roller::Roller {
        diameter: 10.0,
        length: 10.0,
        raceway_diameter: None,
        roller: steel(),
        raceway: steel(),
        load: 1000.0,
        tilt: 0.0,
        crown: contopt_roller::Crown::Straight,
    };
    let cell = roller.cell(10, 5, f64::NAN);
    assert!(cell.is_err(), "{cell:?}");
}

/// Fixed: the load split measured its miss of v·p_max on Ω_v relative to p_max; when p_max is
/// 0 (this punch carries its load off Ω_v, at the Gauss point of its one element that Ω_v
/// leaves out) the miss was 0/0, and a split stopped at its limit reported
/// `Termination::StepLimit { measure: NaN }`: a NaN in the report (`CaseReport::settle`
/// checked the figures, not the termination), written as `null` where the schema wants a
/// number. The miss is 0 there now (its target v·0 met), so the split stops at once and ends as
/// infeasible, its pressure above v·p_max on Ω_nv: Ω_v holds none of the pressure. (`settle`
/// checks a termination's numbers too now.)
#[test]
fn fixed_load_split_nan_miss() {
    let text = r#"
        name = "fuzz"
        [contact]
        zone = { faces = { elements = 1, radius_mm = 46.342266155629446, analysis = "axisymmetric" } }
        gap = { kind = "flat_punch", radius_mm = 29.651289063117414 }
        [[body]]
        kind = "fe_base"
        height_mm = 12.39443232684248
        radius_mm = 100.54939676754587
        supports = ["clamped"]
        material = { e_mpa = 10000.0, nu = 0.0 }
        [[body]]
        kind = "fe_punch"
        height_mm = 11.004982803673995
        layers = 3
        load = { pressure_mpa = 156.67315211938893 }
        material = { e_mpa = 157944.18469062907, nu = 0.018594358514327836 }
        [optimisation]
        method = { kind = "load_split", max_iterations = 1 }
        controller = { kind = "product", a = { trapezoid = { l1_mm = 3.4644509737343268, l2_mm = 20.643417674032193 } }, b = { kind = "trapezoid", l1_mm = 9.3210061056358, l2_mm = 36.94629221234104 } }
        omega_v = { kind = "box", from_mm = [-20.259753753158677, -0.0], to_mm = [20.259753753158677, 0.0] }
        profile_axis = 1
    "#;
    let scene = Scene::parse(text, Format::Toml, Path::new("fuzz.toml")).expect("a scene");
    for report in scene.run() {
        let report = report.expect("a report");
        match &report.termination {
            Termination::Infeasible { cause } => assert!(cause.on_omega_nv(), "{cause}"),
            other => panic!("ended {other:?}"),
        }
        assert!(report.omega_nv_excess_mpa.is_some_and(|e| e > 0.0));
        assert_eq!(non_finite(&report), None);
    }
}
