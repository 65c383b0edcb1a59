//! Fuzz test of the scene parser and of the libraries' public constructors (issue 14): hostile
//! input gives `Ok` or `Err`, never a panic, an abort (a refused allocation, a stack overflow)
//! or a hang.
//!
//! The properties:
//! 1. `mutated_scenes`: each bundled scene (`scenes/*.toml`) with leaves replaced by hostile
//!    numbers and strings, keys deleted or added, whole sections replaced, values nested deeply
//!    and arrays resized, written back as TOML and as JSON and parsed by [`Scene::parse`] (which
//!    checks every case: a finite-element body by its dimensions and mesh, the other bodies
//!    built). A scene that parses must expand into cases, whose first and last check again.
//!
//!    `generated_scenes`: scenes made from the schema, every value plausible or (one time in
//!    eight) hostile, so that most get past the parser to the bodies; the tiny ones (a few
//!    hundred points, few steps, no tuned or robust crown) are run too, every case, by
//!    [`Scene::run`] (which builds each distinct problem once).
//! 2. `arbitrary_text`: bytes, Unicode, token soup, spliced scene lines, deep nesting and huge
//!    arrays, parsed as TOML and as JSON.
//! 3. `constructors_*`: the public constructors of the greens, fem, core, optimise and roller
//!    crates with arbitrary numbers and counts (an absurd count must be an error before anything
//!    of its size is allocated).
//!
//! Running:
//! - Short (CI runs it in `cargo test --workspace`): `cargo test -p contopt-scene --test fuzz`,
//!   128 cases of each scene property and 256 of the others, from a fixed seed so that CI sees
//!   the same cases every time: about 11 s on two cores.
//! - Long, on demand: `PROPTEST_CASES=100000 cargo test -p contopt-scene --test fuzz`, for every
//!   property; add `PROPTEST_RNG_SEED=<u64>` for other cases than CI's, and one test's name
//!   after `--` for one property (5000 cases of a scene property take one to two minutes).
//!   Proptest's `PROPTEST_*` variables win over the defaults here.
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
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Duration;

use contopt_core::{ElasticBody, Geometry, Interface, Material, RigidBody};
use contopt_fem::{Analysis, Component, ElementKind, FeBody, FeModel, Mesh, Spacing};
use contopt_greens::{AxisymmetricHalfSpace, HalfPlane, HalfSpace, PlaneState};
use contopt_scene::geometry::{
    half_space_block, Cylinder, PunchLoad, PunchMesh, PunchOnBase, Support,
};
use contopt_scene::{Format, Scene};
use proptest::prelude::*;
use proptest::sample::{select, Index};
use proptest::test_runner::{Config, FileFailurePersistence, RngSeed};
use toml::Value;

// ---------------------------------------------------------------------------------------------
// Guards: time, memory, stack.

/// The longest one case may take (a tiny scene's run builds its bodies: the bundled scenes
/// parse in well under a second each in the test profile).
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

/// The names of the schema's variants.
const VARIANTS: &[&str] = &[
    "q8",
    "q9",
    "axisymmetric",
    "plane_stress",
    "plane_strain",
    "clamped",
    "axial",
    "symmetry",
    "strip",
    "disc",
    "box",
    "punch_on_base",
    "rigid_on_half_space",
    "rigid_on_axisymmetric_half_space",
    "rigid_on_half_plane",
    "roller",
    "rigid_on_block",
    "sphere",
    "cylinder",
    "flat_punch",
    "straight",
    "iso",
    "lundberg",
    "johns_gohar",
    "fujiwara_kawase",
    "table",
    "optimised",
    "robust",
    "fujiwara_kawase_tuned",
    "qp",
    "active_set",
    "penalty",
    "augmented_lagrangian",
    "polonsky_keer",
    "given_load",
    "given_displacement",
    "linear_programme",
    "load_split",
    "constant",
    "trapezoid",
    "cubic",
    "product",
    "x",
    "y",
    "z",
];

/// Dotted keys for sweeps and named cases.
const DOTTED: &[&str] = &[
    "problem.mesh.elements",
    "problem.mesh.layers",
    "problem.mesh.grading",
    "problem.punch.radius_mm",
    "problem.base.height_mm",
    "problem.base.supports",
    "problem.base.material.e_mpa",
    "problem.analysis.plane_stress.thickness_mm",
    "optimisation.omega_v.radius_mm",
    "optimisation.omega_v.from_mm",
    "problem.cells",
    "problem.cells.0",
    "problem.rings",
    "problem.strips",
    "problem.elements",
    "problem.material.e_mpa",
    "problem.material.nu",
    "problem.load.force_n",
    "problem.load.pressure_mpa",
    "problem.radius_mm",
    "problem.zone_mm",
    "problem.diameter_mm",
    "problem.load_n",
    "problem.tilt_arcmin",
    "problem.indenter.radius_mm",
    "problem.profile",
    "problem.profile.kind",
    "problem.kind",
    "problem",
    "optimisation.controller.l1_mm",
    "optimisation.controller.l2_mm",
    "optimisation.controller",
    "optimisation.max_iterations",
    "solver.c_mpa_per_mm",
    "solver",
    "output.subsurface.depths",
    "dense_limit_mb",
    "sweep.values",
    "case",
    "name",
    "",
    ".",
    "..",
    "a..b",
    "problem..kind",
];

/// Key names of the schema, and some that are not.
const KEYS: &[&str] = &[
    "name",
    "description",
    "problem",
    "solver",
    "optimisation",
    "sweep",
    "case",
    "envelope",
    "dense_limit_mb",
    "memory_limit_mb",
    "output",
    "subsurface",
    "max_depth_mm",
    "depths",
    "sections",
    "along",
    "at_mm",
    "key",
    "values",
    "label",
    "set",
    "load_factors",
    "tilts_arcmin",
    "e_mpa",
    "nu",
    "kind",
    "analysis",
    "thickness_mm",
    "punch",
    "base",
    "supports",
    "height_mm",
    "centre_mm",
    "from_mm",
    "to_mm",
    "material",
    "load",
    "mesh",
    "elements",
    "layers",
    "grading",
    "element",
    "cells",
    "cell_mm",
    "indenter",
    "shape",
    "radius_mm",
    "rings",
    "strips",
    "half_width_mm",
    "datum_mm",
    "diameter_mm",
    "length_mm",
    "raceway_diameter_mm",
    "roller",
    "raceway",
    "load_n",
    "tilt_arcmin",
    "reach_b",
    "profile",
    "k1",
    "k2",
    "z_m_mm",
    "file",
    "zone_mm",
    "size_mm",
    "c_mpa_per_mm",
    "tolerance",
    "max_steps",
    "mode",
    "controller",
    "tolh_mm2",
    "max_iterations",
    "omega_v",
    "profile_axis",
    "level",
    "l1_mm",
    "l2_mm",
    "axis",
    "a",
    "b",
    "force_n",
    "approach_mm",
    "pressure_mpa",
    "displacement_mm",
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

fn opt(s: BoxedStrategy<Value>) -> BoxedStrategy<Option<Value>> {
    proptest::option::weighted(0.7, s).boxed()
}

fn kind_name(pool: &'static [&'static str]) -> BoxedStrategy<Value> {
    prop_oneof![4 => select(pool).prop_map(text), 1 => string()].boxed()
}

fn material() -> BoxedStrategy<Value> {
    (opt(number()), opt(number()))
        .prop_map(|(e, nu)| table(vec![("e_mpa", e), ("nu", nu)]))
        .boxed()
}

fn profile() -> BoxedStrategy<Value> {
    const KINDS: &[&str] = &[
        "straight",
        "iso",
        "lundberg",
        "johns_gohar",
        "fujiwara_kawase",
        "table",
        "optimised",
        "robust",
        "fujiwara_kawase_tuned",
    ];
    (
        kind_name(KINDS),
        opt(number()),
        opt(number()),
        opt(number()),
        proptest::option::weighted(0.3, string()),
    )
        .prop_map(|(kind, k1, k2, z_m, file)| {
            table(vec![
                ("kind", Some(kind)),
                ("k1", k1),
                ("k2", k2),
                ("z_m_mm", z_m),
                ("file", file),
            ])
        })
        .boxed()
}

fn controller() -> BoxedStrategy<Value> {
    let leaf = (
        kind_name(&["constant", "trapezoid", "cubic"]),
        opt(number()),
        opt(number()),
        opt(number()),
        proptest::option::weighted(0.3, count()),
    )
        .prop_map(|(kind, level, l1, l2, axis)| {
            table(vec![
                ("kind", Some(kind)),
                ("level", level),
                ("l1_mm", l1),
                ("l2_mm", l2),
                ("axis", axis),
            ])
        });
    products(leaf, 6, 32)
}

fn optimisation() -> BoxedStrategy<Value> {
    const MODES: &[&str] = &[
        "given_load",
        "given_displacement",
        "linear_programme",
        "load_split",
    ];
    (
        kind_name(MODES),
        controller(),
        opt(number()),
        opt(count()),
        opt(number()),
        proptest::option::weighted(0.4, omega_v()),
        proptest::option::weighted(0.4, count()),
    )
        .prop_map(|(mode, c, tolh, iterations, tolerance, omega_v, axis)| {
            table(vec![
                ("mode", Some(mode)),
                ("controller", Some(c)),
                ("tolh_mm2", tolh),
                ("max_iterations", iterations),
                ("tolerance", tolerance),
                ("omega_v", omega_v),
                ("profile_axis", axis),
            ])
        })
        .boxed()
}

fn solver() -> BoxedStrategy<Value> {
    const KINDS: &[&str] = &[
        "qp",
        "active_set",
        "penalty",
        "augmented_lagrangian",
        "polonsky_keer",
    ];
    (
        kind_name(KINDS),
        opt(number()),
        proptest::option::weighted(0.4, number()),
        proptest::option::weighted(0.4, count()),
    )
        .prop_map(|(kind, c, tolerance, steps)| {
            table(vec![
                ("kind", Some(kind)),
                ("c_mpa_per_mm", c),
                ("tolerance", tolerance),
                ("max_steps", steps),
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

fn numbers(max: usize) -> BoxedStrategy<Value> {
    proptest::collection::vec(number(), 0..max)
        .prop_map(Value::Array)
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
    proptest::strategy::Union::new(problem_sections().into_iter().chain(other_sections())).boxed()
}

/// A section of the schema at `path`.
fn at(
    path: &'static [&'static str],
    s: BoxedStrategy<Value>,
) -> BoxedStrategy<(Vec<&'static str>, Value)> {
    s.prop_map(move |v| (path.to_vec(), v)).boxed()
}

/// The parts of a `[problem]`, with hostile leaves.
fn problem_sections() -> Vec<BoxedStrategy<(Vec<&'static str>, Value)>> {
    const PROBLEM_NUMBERS: &[&str] = &[
        "rings",
        "radius_mm",
        "strips",
        "half_width_mm",
        "datum_mm",
        "diameter_mm",
        "length_mm",
        "raceway_diameter_mm",
        "load_n",
        "tilt_arcmin",
        "reach_b",
        "zone_mm",
        "elements",
        "size_mm",
    ];
    const LOADS: &[&str] = &["force_n", "approach_mm", "pressure_mpa", "displacement_mm"];
    let mesh = (
        count(),
        opt(count()),
        opt(number()),
        opt(kind_name(&["q8", "q9"])),
    )
        .prop_map(|(elements, layers, grading, element)| {
            table(vec![
                ("elements", Some(elements)),
                ("layers", layers),
                ("grading", grading),
                ("element", element),
            ])
        })
        .boxed();
    let indenter = (
        kind_name(&["sphere", "cylinder", "flat_punch"]),
        opt(number()),
    )
        .prop_map(|(shape, r)| table(vec![("shape", Some(shape)), ("radius_mm", r)]))
        .boxed();
    let load = (select(LOADS), number())
        .prop_map(|(k, v)| table(vec![(k, Some(v))]))
        .boxed();
    let cells = proptest::collection::vec(count(), 0..4)
        .prop_map(Value::Array)
        .boxed();
    let problem_number = (select(PROBLEM_NUMBERS), prop_oneof![count(), number()])
        .prop_map(|(k, v)| (vec!["problem", k], v))
        .boxed();
    vec![
        at(&["problem", "profile"], profile()),
        at(&["problem", "mesh"], mesh),
        at(&["problem", "cells"], cells),
        at(&["problem", "cell_mm"], numbers(4)),
        at(&["problem", "indenter"], indenter),
        at(&["problem", "load"], load),
        at(&["problem", "material"], material()),
        at(&["problem", "roller"], material()),
        at(&["problem", "raceway"], material()),
        at(&["problem", "kind"], kind_name(VARIANTS)),
        at(&["problem", "analysis"], analysis()),
        at(&["problem", "punch"], body(false)),
        at(&["problem", "base"], body(true)),
        at(&["problem", "base", "supports"], supports()),
        problem_number,
    ]
}

/// A finite-element analysis: a name, or a plane analysis with its thickness.
fn analysis() -> BoxedStrategy<Value> {
    prop_oneof![
        kind_name(VARIANTS),
        (kind_name(&["plane_stress", "plane_strain"]), opt(number())).prop_map(
            |(name, thickness)| {
                let inner = table(vec![("thickness_mm", thickness)]);
                match name {
                    Value::String(name) => Value::Table([(name, inner)].into_iter().collect()),
                    other => other,
                }
            }
        ),
    ]
    .boxed()
}

/// A punch's or (with `supports`) a base's dimensions, material and supports.
fn body(supported: bool) -> BoxedStrategy<Value> {
    (
        opt(number()),
        opt(number()),
        proptest::option::weighted(0.3, material()),
        proptest::option::weighted(if supported { 0.8 } else { 0.1 }, supports()),
    )
        .prop_map(|(radius, height, material, supports)| {
            table(vec![
                ("radius_mm", radius),
                ("height_mm", height),
                ("material", material),
                ("supports", supports),
            ])
        })
        .boxed()
}

/// A base's supports: names, some not supports, repeated or missing.
fn supports() -> BoxedStrategy<Value> {
    proptest::collection::vec(kind_name(&["clamped", "axial", "symmetry"]), 0..4)
        .prop_map(Value::Array)
        .boxed()
}

/// Ω_v: a strip, a disc or a box, with hostile numbers.
fn omega_v() -> BoxedStrategy<Value> {
    (
        kind_name(&["strip", "disc", "box"]),
        proptest::option::weighted(0.4, count()),
        proptest::option::weighted(0.5, prop_oneof![number(), numbers(3)]),
        proptest::option::weighted(0.5, prop_oneof![number(), numbers(3)]),
        proptest::option::weighted(0.3, numbers(3)),
        proptest::option::weighted(0.3, number()),
    )
        .prop_map(|(shape, axis, from, to, centre, radius)| {
            table(vec![
                ("shape", Some(shape)),
                ("axis", axis),
                ("from_mm", from),
                ("to_mm", to),
                ("centre_mm", centre),
                ("radius_mm", radius),
            ])
        })
        .boxed()
}

/// The sections other than the problem's.
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
        at(&["optimisation", "controller"], controller()),
        at(&["optimisation", "omega_v"], omega_v()),
        at(&["output"], subsurface()),
        at(&["envelope"], envelope),
        at(&["sweep"], sweep),
        at(&["case"], named_cases()),
        at(&["dense_limit_mb"], number()),
        at(&["memory_limit_mb"], number()),
        at(&["name"], string()),
    ]
}

// ---------------------------------------------------------------------------------------------
// Strategy 1: the bundled scenes, mutated.

/// Every bundled scene.
const SCENES: &[(&str, &str)] = contopt_scene::BUNDLED;

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

/// Puts `value` at `path` of `root`, making the tables on the way (replacing what is not one).
fn set_section(root: &mut Value, path: &[&str], value: Value) {
    let mut node = root;
    for (k, key) in path.iter().enumerate() {
        if !matches!(node, Value::Table(_)) {
            *node = Value::Table(Default::default());
        }
        let Value::Table(t) = node else {
            unreachable!()
        };
        let last = k + 1 == path.len();
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
        let mut root: Value = toml::from_str(SCENES[self.scene].1).expect("a bundled scene");
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
            SCENES[self.scene].0, self.mutations
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

/// Parses `text`: `Ok` or `Err`, within the case limit; a scene that parses expands into cases,
/// and its first and last case check again (each check builds the bodies that factorise
/// nothing: all of them would rebuild a sweep's shared bodies once per value).
fn parse(text: String, format: Format) {
    let text: Arc<str> = text.into();
    let input = text.clone();
    guarded("parse", input, move || {
        match Scene::parse(&text, format, Path::new("fuzz.toml")) {
            Ok(scene) => {
                let cases = scene
                    .cases()
                    .expect("a scene that parsed expands into cases");
                assert!(!cases.is_empty(), "a scene that parsed has no case");
                for case in [cases.first(), cases.last()].into_iter().flatten() {
                    if let Err(e) = case.check() {
                        panic!(
                            "case {} of a scene that parsed fails its check: {e}",
                            case.label
                        );
                    }
                }
            }
            Err(e) => {
                let _ = e.to_string();
            }
        }
    })
}

proptest! {
    #![proptest_config(config(128))]

    /// Mutated bundled scenes, as TOML and as JSON.
    #[test]
    fn mutated_scenes(case in mutated_scene()) {
        let (toml, json) = case.texts();
        if let Some(toml) = toml {
            parse(toml, Format::Toml);
        }
        parse(json, Format::Json);
    }
}

// ---------------------------------------------------------------------------------------------
// Strategy 1b: scenes made from the schema, each value mostly plausible and sometimes hostile,
// so that most of them get past the parser to the bodies (and, when tiny, to the solvers).

/// A float in `lo..hi`, or (one time in eight) a hostile number.
fn real_in(lo: f64, hi: f64) -> BoxedStrategy<Value> {
    prop_oneof![7 => (lo..hi).prop_map(Value::Float), 1 => number()].boxed()
}

/// An integer in `lo..=hi`, or (one time in eight) a hostile count.
fn count_in(lo: i64, hi: i64) -> BoxedStrategy<Value> {
    prop_oneof![7 => (lo..=hi).prop_map(int), 1 => count()].boxed()
}

/// One of `names`, or (one time in eight) a hostile string.
fn one_of(names: &'static [&'static str]) -> BoxedStrategy<Value> {
    prop_oneof![7 => select(names).prop_map(text), 1 => string()].boxed()
}

fn maybe(p: f64, s: BoxedStrategy<Value>) -> BoxedStrategy<Option<Value>> {
    proptest::option::weighted(p, s).boxed()
}

fn plausible_material() -> BoxedStrategy<Value> {
    (real_in(1e4, 3e5), real_in(0.0, 0.45))
        .prop_map(|(e, nu)| table(vec![("e_mpa", Some(e)), ("nu", Some(nu))]))
        .boxed()
}

fn plausible_indenter() -> BoxedStrategy<Value> {
    (
        one_of(&["sphere", "cylinder", "flat_punch"]),
        real_in(0.5, 50.0),
    )
        .prop_map(|(shape, r)| table(vec![("shape", Some(shape)), ("radius_mm", Some(r))]))
        .boxed()
}

fn rigid_load() -> BoxedStrategy<Value> {
    prop_oneof![
        real_in(1.0, 1e4).prop_map(|f| table(vec![("force_n", Some(f))])),
        real_in(1e-4, 0.1).prop_map(|a| table(vec![("approach_mm", Some(a))])),
    ]
    .boxed()
}

fn plausible_problem() -> BoxedStrategy<Value> {
    prop_oneof![
        plausible_punch_on_base(),
        plausible_half_space(),
        plausible_rings(),
        plausible_strips(),
        plausible_roller(),
        plausible_block(),
    ]
    .boxed()
}

/// A plane analysis with a thickness, or (one time in eight) a hostile value.
fn plausible_analysis(names: &'static [&'static str]) -> BoxedStrategy<Value> {
    (one_of(names), real_in(1.0, 20.0))
        .prop_map(|(name, thickness)| match name {
            Value::String(name) if name != "axisymmetric" => {
                let inner = table(vec![("thickness_mm", Some(thickness))]);
                Value::Table([(name, inner)].into_iter().collect())
            }
            other => other,
        })
        .boxed()
}

/// A punch's or a base's radius, height and (sometimes) its own material.
fn plausible_body(radius: (f64, f64)) -> BoxedStrategy<Value> {
    (
        real_in(radius.0, radius.1),
        real_in(1.0, 100.0),
        maybe(0.3, plausible_material()),
    )
        .prop_map(|(r, h, m)| {
            table(vec![
                ("radius_mm", Some(r)),
                ("height_mm", Some(h)),
                ("material", m),
            ])
        })
        .boxed()
}

fn plausible_punch_on_base() -> BoxedStrategy<Value> {
    const SUPPORTS: &[&[&str]] = &[
        &["clamped"],
        &["axial"],
        &["axial", "symmetry"],
        &["clamped", "symmetry"],
        &[],
    ];
    (
        plausible_analysis(&["axisymmetric", "plane_stress", "plane_strain"]),
        maybe(0.8, plausible_material()),
        (plausible_body((1.0, 100.0)), plausible_body((2.0, 200.0))),
        select(SUPPORTS),
        prop_oneof![
            real_in(1.0, 500.0).prop_map(|p| table(vec![("pressure_mpa", Some(p))])),
            real_in(-0.1, -1e-4).prop_map(|w| table(vec![("displacement_mm", Some(w))])),
        ],
        (
            count_in(1, 8),
            maybe(0.5, count_in(1, 8)),
            maybe(0.3, real_in(0.2, 5.0)),
            maybe(0.3, one_of(&["q8", "q9"])),
        ),
    )
        .prop_map(|(analysis, m, (punch, mut base), supports, load, mesh)| {
            if let Value::Table(t) = &mut base {
                let names = supports.iter().map(|s| text(s)).collect();
                t.insert("supports".into(), Value::Array(names));
            }
            table(vec![
                ("kind", Some(text("punch_on_base"))),
                ("analysis", Some(analysis)),
                ("material", m),
                ("punch", Some(punch)),
                ("base", Some(base)),
                ("load", Some(load)),
                (
                    "mesh",
                    Some(table(vec![
                        ("elements", Some(mesh.0)),
                        ("layers", mesh.1),
                        ("grading", mesh.2),
                        ("element", mesh.3),
                    ])),
                ),
            ])
        })
        .boxed()
}

fn plausible_half_space() -> BoxedStrategy<Value> {
    (
        plausible_material(),
        (count_in(1, 32), count_in(1, 32)),
        (real_in(1e-3, 1.0), real_in(1e-3, 1.0)),
        plausible_indenter(),
        rigid_load(),
    )
        .prop_map(|(m, (nx, ny), (dx, dy), indenter, load)| {
            table(vec![
                ("kind", Some(text("rigid_on_half_space"))),
                ("material", Some(m)),
                ("cells", Some(Value::Array(vec![nx, ny]))),
                ("cell_mm", Some(Value::Array(vec![dx, dy]))),
                ("indenter", Some(indenter)),
                ("load", Some(load)),
            ])
        })
        .boxed()
}

fn plausible_rings() -> BoxedStrategy<Value> {
    (
        plausible_material(),
        count_in(1, 60),
        real_in(0.1, 20.0),
        plausible_indenter(),
        rigid_load(),
    )
        .prop_map(|(m, rings, radius, indenter, load)| {
            table(vec![
                ("kind", Some(text("rigid_on_axisymmetric_half_space"))),
                ("material", Some(m)),
                ("rings", Some(rings)),
                ("radius_mm", Some(radius)),
                ("indenter", Some(indenter)),
                ("load", Some(load)),
            ])
        })
        .boxed()
}

fn plausible_strips() -> BoxedStrategy<Value> {
    (
        plausible_material(),
        plausible_analysis(&["plane_stress", "plane_strain"]),
        count_in(1, 60),
        real_in(0.1, 20.0),
        maybe(0.3, real_in(1.0, 1000.0)),
        plausible_indenter(),
        rigid_load(),
    )
        .prop_map(|(m, analysis, strips, half_width, datum, indenter, load)| {
            table(vec![
                ("kind", Some(text("rigid_on_half_plane"))),
                ("material", Some(m)),
                ("analysis", Some(analysis)),
                ("strips", Some(strips)),
                ("half_width_mm", Some(half_width)),
                ("datum_mm", datum),
                ("indenter", Some(indenter)),
                ("load", Some(load)),
            ])
        })
        .boxed()
}

fn plausible_roller() -> BoxedStrategy<Value> {
    const PROFILES: &[&str] = &[
        "straight",
        "iso",
        "lundberg",
        "johns_gohar",
        "fujiwara_kawase",
        "table",
        "optimised",
        "robust",
        "fujiwara_kawase_tuned",
    ];
    let crown = (
        one_of(PROFILES),
        (real_in(0.1, 3.0), real_in(0.05, 1.0), real_in(1e-4, 0.05)),
        string(),
    )
        .prop_map(|(kind, (k1, k2, z_m), file)| {
            let name = kind.as_str().unwrap_or_default().to_string();
            table(vec![
                ("kind", Some(kind)),
                ("k1", (name == "fujiwara_kawase").then_some(k1)),
                ("k2", (name == "fujiwara_kawase").then_some(k2)),
                ("z_m_mm", (name == "fujiwara_kawase").then_some(z_m)),
                ("file", (name == "table").then_some(file)),
            ])
        });
    (
        (real_in(1.0, 50.0), real_in(1.0, 50.0)),
        maybe(0.3, real_in(-200.0, 200.0)),
        (plausible_material(), plausible_material()),
        real_in(10.0, 1e4),
        maybe(0.3, real_in(-10.0, 10.0)),
        (
            count_in(1, 32),
            count_in(1, 15).prop_map(|n| match n {
                Value::Integer(k) if (0..100).contains(&k) => int(2 * k + 1),
                other => other,
            }),
        ),
        maybe(0.3, real_in(0.5, 5.0)),
        crown,
    )
        .prop_map(
            |((d, l), raceway, (m1, m2), load, tilt, (nx, ny), reach, profile)| {
                table(vec![
                    ("kind", Some(text("roller"))),
                    ("diameter_mm", Some(d)),
                    ("length_mm", Some(l)),
                    ("raceway_diameter_mm", raceway),
                    ("roller", Some(m1)),
                    ("raceway", Some(m2)),
                    ("load_n", Some(load)),
                    ("tilt_arcmin", tilt),
                    ("cells", Some(Value::Array(vec![nx, ny]))),
                    ("reach_b", reach),
                    ("profile", Some(profile)),
                ])
            },
        )
        .boxed()
}

fn plausible_block() -> BoxedStrategy<Value> {
    (
        plausible_material(),
        real_in(0.5, 20.0),
        count_in(1, 6),
        real_in(10.0, 500.0),
        plausible_indenter(),
        rigid_load(),
    )
        .prop_map(|(m, zone, elements, size, indenter, load)| {
            table(vec![
                ("kind", Some(text("rigid_on_block"))),
                ("material", Some(m)),
                ("zone_mm", Some(zone)),
                ("elements", Some(elements)),
                ("size_mm", Some(size)),
                ("indenter", Some(indenter)),
                ("load", Some(load)),
            ])
        })
        .boxed()
}

fn plausible_solver() -> BoxedStrategy<Value> {
    prop_oneof![
        Just(table(vec![("kind", Some(text("qp")))])),
        Just(table(vec![("kind", Some(text("active_set")))])),
        real_in(1e3, 1e10).prop_map(|c| table(vec![
            ("kind", Some(text("penalty"))),
            ("c_mpa_per_mm", Some(c))
        ])),
        (
            real_in(1e3, 1e10),
            maybe(0.3, real_in(1e-12, 1e-3)),
            maybe(0.3, count_in(1, 200))
        )
            .prop_map(|(c, tolerance, steps)| table(vec![
                ("kind", Some(text("augmented_lagrangian"))),
                ("c_mpa_per_mm", Some(c)),
                ("tolerance", tolerance),
                ("max_steps", steps),
            ])),
        (
            maybe(0.3, real_in(1e-12, 1e-3)),
            maybe(0.3, count_in(1, 2000))
        )
            .prop_map(|(tolerance, steps)| table(vec![
                ("kind", Some(text("polonsky_keer"))),
                ("tolerance", tolerance),
                ("max_steps", steps),
            ])),
    ]
    .boxed()
}

fn plausible_controller() -> BoxedStrategy<Value> {
    let leaf = prop_oneof![
        real_in(0.1, 1.0).prop_map(|level| table(vec![
            ("kind", Some(text("constant"))),
            ("level", Some(level))
        ])),
        (
            one_of(&["trapezoid", "cubic"]),
            real_in(0.0, 10.0),
            real_in(0.0, 60.0),
            maybe(0.3, count_in(0, 2))
        )
            .prop_map(|(kind, l1, l2, axis)| table(vec![
                ("kind", Some(kind)),
                ("l1_mm", Some(l1)),
                ("l2_mm", Some(l2)),
                ("axis", axis),
            ])),
    ];
    products(leaf, 2, 4)
}

/// Controllers from `leaf`, and `{ kind = "product", a, b }` of them nested up to `depth` deep
/// with at most `size` controllers in all.
fn products(
    leaf: impl Strategy<Value = Value> + 'static,
    depth: u32,
    size: u32,
) -> BoxedStrategy<Value> {
    leaf.prop_recursive(depth, size, 2, |inner| {
        (inner.clone(), inner).prop_map(|(a, b)| {
            table(vec![
                ("kind", Some(text("product"))),
                ("a", Some(a)),
                ("b", Some(b)),
            ])
        })
    })
    .boxed()
}

fn plausible_optimisation() -> BoxedStrategy<Value> {
    (
        one_of(&[
            "given_load",
            "given_displacement",
            "linear_programme",
            "load_split",
        ]),
        plausible_controller(),
        maybe(0.3, real_in(1e-9, 1e-3)),
        maybe(0.7, count_in(1, 20)),
        maybe(0.3, real_in(1e-10, 1e-3)),
        maybe(0.3, plausible_omega_v()),
        maybe(0.3, count_in(0, 2)),
    )
        .prop_map(|(mode, c, tolh, iterations, tolerance, omega_v, axis)| {
            table(vec![
                ("mode", Some(mode)),
                ("controller", Some(c)),
                ("tolh_mm2", tolh),
                ("max_iterations", iterations),
                ("tolerance", tolerance),
                ("omega_v", omega_v),
                ("profile_axis", axis),
            ])
        })
        .boxed()
}

/// Ω_v: a strip along x or y, a disc about the origin or a box around it.
fn plausible_omega_v() -> BoxedStrategy<Value> {
    let pair = |v: Value| Value::Array(vec![v.clone(), v]);
    let negative = |v: &Value| match v {
        Value::Float(x) => Value::Float(-x),
        other => other.clone(),
    };
    prop_oneof![
        (count_in(0, 1), real_in(0.0, 10.0)).prop_map(move |(axis, h)| table(vec![
            ("shape", Some(text("strip"))),
            ("axis", Some(axis)),
            ("from_mm", Some(negative(&h))),
            ("to_mm", Some(h)),
        ])),
        real_in(0.0, 20.0).prop_map(move |r| table(vec![
            ("shape", Some(text("disc"))),
            ("centre_mm", Some(pair(Value::Float(0.0)))),
            ("radius_mm", Some(r)),
        ])),
        real_in(0.0, 10.0).prop_map(move |h| table(vec![
            ("shape", Some(text("box"))),
            ("from_mm", Some(pair(negative(&h)))),
            ("to_mm", Some(pair(h))),
        ])),
    ]
    .boxed()
}

fn plausible_subsurface() -> BoxedStrategy<Value> {
    let section = (one_of(&["x", "y"]), real_in(-10.0, 10.0))
        .prop_map(|(along, at)| table(vec![("along", Some(along)), ("at_mm", Some(at))]));
    (
        maybe(0.5, real_in(0.01, 10.0)),
        maybe(0.7, count_in(1, 20)),
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

/// A scene made from the schema.
#[derive(Clone)]
struct GeneratedScene(Value);

impl GeneratedScene {
    fn texts(&self) -> (Option<String>, String) {
        let json = serde_json::to_string_pretty(&to_json(&self.0)).expect("JSON writes any tree");
        (toml::to_string(&self.0).ok(), json)
    }

    /// Whether its cases are small enough to run: few cells, rings, strips, elements, cases
    /// and steps, and no crown design that solves the contact many times.
    fn tiny(&self) -> bool {
        let get = |path: &[&str]| {
            path.iter()
                .try_fold(&self.0, |v, k| v.as_table().and_then(|t| t.get(*k)))
        };
        let at_most = |path: &[&str], max: i64| match get(path) {
            None => true,
            Some(Value::Integer(k)) => *k <= max,
            Some(_) => true,
        };
        let cells = match get(&["problem", "cells"]) {
            Some(Value::Array(a)) => a
                .iter()
                .map(|v| v.as_integer().unwrap_or(1))
                .fold(1i64, i64::saturating_mul),
            _ => 1,
        };
        let list = |path: &[&str]| match get(path) {
            Some(Value::Array(a)) => a.len(),
            _ => 1,
        };
        // The dense methods (the QP, the linear programme) take seconds past a few hundred
        // points (14 s for the linear programme on 26 × 31 cells).
        (0..=256).contains(&cells)
            && at_most(&["problem", "rings"], 60)
            && at_most(&["problem", "strips"], 60)
            && at_most(&["problem", "elements"], 6)
            && at_most(&["problem", "mesh", "elements"], 8)
            && at_most(&["problem", "mesh", "layers"], 8)
            && at_most(&["optimisation", "max_iterations"], 20)
            && at_most(&["solver", "max_steps"], 2000)
            && at_most(&["output", "subsurface", "depths"], 20)
            && list(&["sweep", "values"]) <= 3
            && list(&["envelope", "load_factors"]) * list(&["envelope", "tilts_arcmin"]) <= 4
            // The default of 100 iterations is not tiny.
            && (get(&["optimisation"]).is_none()
                || get(&["optimisation", "max_iterations"]).is_some())
            // A tuned or robust crown solves the contact a hundred times and more (16 s for a
            // tuned crown on 22 × 25 cells by the QP).
            && !matches!(
                get(&["problem", "profile", "kind"]).and_then(Value::as_str),
                Some("fujiwara_kawase_tuned" | "robust")
            )
    }
}

impl std::fmt::Debug for GeneratedScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let (toml, json) = self.texts();
        writeln!(f, "generated scene (tiny: {}):", self.tiny())?;
        writeln!(f, "{}", preview_block(toml.as_deref().unwrap_or(&json)))
    }
}

fn generated_scene() -> impl Strategy<Value = GeneratedScene> {
    (
        prop_oneof![9 => Just(text("fuzz")), 1 => string()],
        plausible_problem(),
        plausible_solver(),
        maybe(0.4, plausible_optimisation()),
        prop_oneof![
            6 => Just(None),
            1 => (
                select(DOTTED),
                proptest::collection::vec(prop_oneof![real_in(0.0, 50.0), count_in(1, 8)], 1..4),
            )
                .prop_map(|(key, values)| Some(table(vec![
                    ("key", Some(text(key))),
                    ("values", Some(Value::Array(values))),
                ]))),
        ],
        maybe(0.3, plausible_subsurface()),
        maybe(
            0.1,
            (
                proptest::collection::vec(real_in(0.1, 2.0), 1..3),
                proptest::collection::vec(real_in(-5.0, 5.0), 1..3),
            )
                .prop_map(|(f, t)| {
                    table(vec![
                        ("load_factors", Some(Value::Array(f))),
                        ("tilts_arcmin", Some(Value::Array(t))),
                    ])
                })
                .boxed(),
        ),
        (
            maybe(0.1, real_in(1.0, 5000.0)),
            maybe(0.1, real_in(1.0, 5000.0)),
        ),
    )
        .prop_map(
            |(name, problem, solver, optimisation, sweep, output, envelope, (dense, memory))| {
                GeneratedScene(table(vec![
                    ("name", Some(name)),
                    ("problem", Some(problem)),
                    ("solver", Some(solver)),
                    ("optimisation", optimisation),
                    ("sweep", sweep),
                    ("output", output),
                    ("envelope", envelope),
                    ("dense_limit_mb", dense),
                    ("memory_limit_mb", memory),
                ]))
            },
        )
}

/// Parses a generated scene; a tiny one that parses is also run, every case: `Ok` (converged
/// or not) or `Err`, never a panic.
fn parse_and_run(text: String, format: Format, run: bool) {
    let text: Arc<str> = text.into();
    let input = text.clone();
    guarded("parse and run", input, move || {
        let Ok(scene) = Scene::parse(&text, format, Path::new("fuzz.toml")) else {
            return;
        };
        let run_all = scene.run().expect("a scene that parsed expands into cases");
        if run {
            for report in run_all.flatten() {
                let _ = serde_json::to_string(&report);
            }
        }
    })
}

proptest! {
    #![proptest_config(config(128))]

    /// Scenes made from the schema, as TOML and as JSON; the tiny ones are run too (as TOML).
    #[test]
    fn generated_scenes(scene in generated_scene()) {
        let (toml, json) = scene.texts();
        let tiny = scene.tiny();
        if let Some(toml) = toml {
            parse_and_run(toml, Format::Toml, tiny);
        }
        parse(json, Format::Json);
    }
}

// ---------------------------------------------------------------------------------------------
// Strategy 2: arbitrary text.

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
    "problem",
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
    "rigid_on_half_space",
    "punch_on_base",
    "roller",
    "elements",
    "cells",
    "[problem]",
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
                    let lines: Vec<&str> = SCENES[scene.index(SCENES.len())].1.lines().collect();
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
        .find(|(name, _)| *name == "paper-table1")
        .expect("paper-table1 is bundled")
        .1;
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
    #![proptest_config(config(256))]

    /// Arbitrary text, as TOML and as JSON.
    #[test]
    fn arbitrary_text(input in text_input()) {
        let text = input.render();
        parse(text.clone(), Format::Toml);
        parse(text, Format::Json);
    }
}

// ---------------------------------------------------------------------------------------------
// Strategy 3: the libraries' public constructors.

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

proptest! {
    #![proptest_config(config(256))]

    /// `Material::new` and the elliptic integrals.
    #[test]
    fn constructors_material_elliptic(e in real(), nu in real(), k in real()) {
        construct(format!("Material::new({e:?}, {nu:?}); elliptic::complete({k:?})"), move || {
            if let Ok(m) = Material::new(e, nu) {
                let _ = m.plane_strain_modulus();
            }
            let _ = contopt_greens::elliptic::complete(k);
        });
    }

    /// `Constant::new`, `Profile::trapezoid` / `cubic`, `along`, and their values.
    #[test]
    fn constructors_controllers(
        level in real(),
        l1 in real(),
        l2 in real(),
        axis in size(),
        x in (real(), real(), real()),
    ) {
        construct(
            format!("Constant::new({level:?}); Profile::trapezoid/cubic({l1:?}, {l2:?}).along({axis}); value({x:?})"),
            move || {
                use contopt_optimise::{Constant, Controller, Profile};
                let x = [x.0, x.1, x.2];
                if let Ok(c) = Constant::new(level) {
                    let _ = c.value(x);
                }
                for p in [Profile::trapezoid(l1, l2), Profile::cubic(l1, l2)] {
                    if let Ok(p) = p.and_then(|p| p.along(axis)) {
                        let _ = p.value(x);
                    }
                }
            },
        );
    }

    /// The crowns of `contopt_roller::Crown` and their drops.
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
                let _ = crown.drop(x, length);
            }
        });
    }

    /// `HalfSpace::grid` and `periodic`, `pressed` and `upper`.
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
                let body = if periodic {
                    HalfSpace::periodic("fuzz", material, nx, ny, dx, dy, origin)
                } else {
                    HalfSpace::grid("fuzz", material, nx, ny, dx, dy, origin)
                };
                if let Ok(body) = body {
                    let _ = body.upper().pressed(force);
                }
            },
        );
    }

    /// `HalfPlane::new` and `AxisymmetricHalfSpace::new`.
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
                let _ = HalfPlane::new("fuzz", material, state, thickness, &edges, datum);
                let _ = AxisymmetricHalfSpace::new("fuzz", material, &edges);
            },
        );
    }

    /// `Interface::new`, `RigidBody::fixed` / `pressed`, `GapShape::new` / `extruded` /
    /// `symmetric`, `InterfaceProblem::new` and `Optimisation::new`.
    #[test]
    fn constructors_interface(
        points in proptest::collection::vec((real(), real(), real()), 0..8),
        weights in proptest::collection::vec(real(), 0..8),
        normal in prop_oneof![Just((0.0, 0.0, 1.0)), Just((0.0, 1.0, 0.0)), (real(), real(), real())],
        geometry in 0..3usize,
        axis in (real(), real(), real()),
        force in real(),
        shape_axis in size(),
        rows in proptest::collection::vec(proptest::collection::vec((size(), real()), 0..3), 0..8),
        node in size(),
    ) {
        construct(
            format!("Interface::new(geometry {geometry}, points {points:?}, weights {weights:?}, normal {normal:?}); \
                     RigidBody::pressed(axis {axis:?}, {force:?}); GapShape axis {shape_axis}, rows {rows:?}; reference {node}"),
            move || {
                use contopt_contact::InterfaceProblem;
                use contopt_core::GapShape;
                use contopt_optimise::{Constant, Optimisation, Region};
                let geometry = match geometry {
                    0 => Geometry::Axisymmetric,
                    1 => Geometry::Plane { thickness: 1.0 },
                    _ => Geometry::Surface,
                };
                let n = points.len();
                let points: Vec<[f64; 3]> = points.into_iter().map(|(a, b, c)| [a, b, c]).collect();
                let normals = vec![[normal.0, normal.1, normal.2]; n];
                let _ = GapShape::new(points.clone(), rows);
                let Ok(interface) = Interface::new(geometry, points, weights, normals) else {
                    return;
                };
                let _ = GapShape::extruded(&interface, shape_axis);
                let _ = GapShape::symmetric(&interface, shape_axis);
                let shape = GapShape::pointwise(&interface);
                let v = Constant::new(1.0).expect("level 1");
                let fixed = RigidBody::fixed("fixed", &interface);
                let _ = RigidBody::pressed("pressed", &interface, [axis.0, axis.1, axis.2], force);
                // A rigid body on a rigid body: an error, not a panic.
                let other = RigidBody::fixed("other", fixed.interface());
                let gap = vec![0.0; interface.len()];
                if let Ok(problem) = InterfaceProblem::new(&fixed, &other, &gap) {
                    if let Ok(opt) = Optimisation::new(&problem, &shape, &v) {
                        let regions = vec![Region::OmegaV; interface.len()];
                        let _ = opt.with_regions(regions).and_then(|o| o.with_reference(node));
                    }
                };
            },
        );
    }

    /// `Spacing::*`, `Mesh::rectangle` / `stacked` / `new`.
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
                    let _ = x.restrict(a, b);
                    for y in &ok {
                        // Only small meshes: a large one is a legitimate, slow request.
                        if x.len() * y.len() <= 400 {
                            let _ = Mesh::rectangle(kind, x, y);
                            let _ = Mesh::stacked(kind, x, y, (a, b), y);
                        }
                        let _ = x.then(y);
                    }
                }
                let nodes = nodes.into_iter().map(|(x, y)| [x, y]).collect();
                let _ = Mesh::new(kind, nodes, elements);
            },
        );
    }

    /// `FeModel::new`, its supports and loads, and `FeBody::new`, on small rectangles.
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
        construct(
            format!("FeModel on {nx} x {ny} elements of width {width:?}, material {m:?}, analysis {analysis} thickness {thickness:?}; \
                     value {value:?}, node {node}, face {face:?}"),
            move || {
                let analysis = match analysis {
                    0 => Analysis::Axisymmetric,
                    1 => Analysis::PlaneStress { thickness },
                    _ => Analysis::PlaneStrain { thickness },
                };
                let (Ok(x), Ok(y)) = (Spacing::uniform(0.0, width, nx), Spacing::uniform(-width, 0.0, ny)) else {
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
                let _ = model.prescribe(&[node], Component::Y, value);
                let _ = model.nodal_force(node, [value, value]);
                let _ = model.pressure(&[contopt_fem::Face { element: face.0, local: face.1 }], value);
                let _ = model.traction(&top, [value, 0.0]);
                let _ = model.fix(&bottom, Component::Y).and_then(|m| m.fix(&bottom, Component::X));
                let _ = model.pressure(&top, value);
                let _ = FeBody::new("fuzz", model.clone(), &top);
                let _ = FeBody::new("fuzz", model, &[contopt_fem::Face { element: face.0, local: face.1 }]);
            },
        );
    }

    /// `geometry::PunchOnBase::bodies` and `geometry::half_space_block` (with `FeBody::new`).
    #[test]
    fn constructors_fe_bodies(
        geometry in (real(), real(), real(), real()),
        m in material_args(),
        analysis in 0..3usize,
        thickness in real(),
        supports in proptest::collection::vec(
            select(&[Support::Clamped, Support::Axial, Support::Symmetry][..]),
            0..4,
        ),
        pressure in any::<bool>(),
        load in real(),
        q9 in any::<bool>(),
        elements in size(),
        grading in real(),
        layers in size(),
        block in (real(), size(), real()),
    ) {
        construct(
            format!("PunchOnBase::bodies(punch radius/height, base radius/height {geometry:?}, material {m:?}, \
                     analysis {analysis} thickness {thickness:?}, supports {supports:?}, \
                     {} {load:?}, q9 {q9}, elements {elements}, grading {grading:?}, layers {layers}); \
                     half_space_block(zone {:?}, elements {}, size {:?})",
                if pressure { "pressure" } else { "displacement" }, block.0, block.1, block.2),
            move || {
                let material = material_or_steel(m);
                let analysis = match analysis {
                    0 => Analysis::Axisymmetric,
                    1 => Analysis::PlaneStress { thickness },
                    _ => Analysis::PlaneStrain { thickness },
                };
                let cylinder = |radius, height| Cylinder { radius, height, material };
                let geometry = PunchOnBase {
                    analysis,
                    punch: cylinder(geometry.0, geometry.1),
                    base: cylinder(geometry.2, geometry.3),
                    supports,
                    load: if pressure { PunchLoad::Pressure(load) } else { PunchLoad::Displacement(load) },
                    mesh: PunchMesh {
                        element: if q9 { ElementKind::Q9 } else { ElementKind::Q8 },
                        elements,
                        grading,
                        layers: Some(layers),
                    },
                };
                let _ = geometry.check();
                let _ = geometry.bodies();
                if let Ok((model, contact)) = half_space_block(block.0, block.1, block.2, material) {
                    let _ = FeBody::new("block", model, &contact);
                }
            },
        );
    }

    /// `Roller::bodies` (two half-space grids) with its Hertz contact.
    #[test]
    fn constructors_roller(
        d in real(),
        l in real(),
        raceway in proptest::option::of(real()),
        m in (material_args(), material_args()),
        load in real(),
        tilt in real(),
        nx in size(),
        ny in size(),
        reach in real(),
    ) {
        construct(
            format!("Roller {{ diameter {d:?}, length {l:?}, raceway {raceway:?}, materials {m:?}, load {load:?}, tilt {tilt:?} }}.bodies({nx}, {ny}, {reach:?})"),
            move || {
                use contopt_roller::{Crown, Roller};
                let roller = Roller {
                    diameter: d,
                    length: l,
                    raceway_diameter: raceway,
                    roller: material_or_steel(m.0),
                    raceway: material_or_steel(m.1),
                    load,
                    tilt,
                    crown: Crown::Straight,
                };
                let _ = roller.e_star();
                let _ = roller.radius();
                let _ = roller.hertz();
                let _ = roller.bodies(nx, ny, reach);
            },
        );
    }

    /// `nelder_mead` with hostile starts, steps and tolerances.
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
                let objective = |x: &[f64]| Ok(x.iter().map(|v| v * v).sum::<f64>());
                let _ = contopt_optimise::nelder_mead(objective, &start, &step, tolerance, max_evaluations);
            },
        );
    }
}
