//! How an imported mesh's build and optimisation grow with its size: the paper's punch on its
//! base (Table 1: axisymmetric, 100 MPa on the punch, the C¹ controller with L1 = 30 mm),
//! both bodies meshed apart in Gmsh with a refined contact face
//! (`meshes/bench/punch-on-base.geo.inc`), from about 12 000 to 200 000 nodes, each run
//! through the bundled scene `paper-table1` as a user's scene runs: read and checked (the
//! meshes imported, the contact surveyed, the memory estimated against the scene's limit),
//! the bodies paired, assembled, factorised and condensed onto the contact, then the given-load
//! optimisation. The table of the book's performance chapter.
//!
//! The meshes are not in the repository (11 MB for the largest, in Gmsh's binary format):
//!
//! ```text
//! python3 meshes/generate.py --bench target/gmsh-bench   # once, pip install gmsh; ~1 min
//! cargo run --release --example mesh_scaling             # [FOLDER [MESH...]]
//! ```
//!
//! Columns: the nodes of both bodies; the contact points; `read` the scene's read and check
//! (import, survey, estimate); `factor` the assembly and factorisation of both bodies;
//! `condense` their condensation onto the points; `build` the whole build (with the pairing and
//! the projection onto the first body's field); `optimise` the given-load optimisation; the
//! check's memory estimate and the measured peak heap of the case (the scene's limit is
//! 4000 MB); p_max of the optimised pressure and its difference from the finest mesh's and from
//! the bundled scene's built-in mesh (18 elements across the face).

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use contopt::prelude::*;
use contopt::scene::{Built, Case, Format, Layout};
use contopt_validation::fixtures::PeakAlloc;

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

/// The meshes, coarse to fine, in Gmsh's binary format (`meshes/bench/NAME.geo`).
const MESHES: [&str; 3] = [
    "punch-on-base-12k-binary.msh",
    "punch-on-base-50k-binary.msh",
    "punch-on-base-200k-binary.msh",
];

/// The row of Table 1 optimised: the controller's L1 \[mm\].
const L1: &str = "30.0";

/// What one mesh measured.
struct Row {
    nodes: usize,
    points: usize,
    read: Duration,
    factor: Duration,
    condense: Duration,
    build: Duration,
    optimise: Duration,
    estimate_mb: f64,
    peak_mib: f64,
    p_max: f64,
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut args = std::env::args().skip(1);
    let folder = args
        .next()
        .map_or_else(|| root.join("target/gmsh-bench"), PathBuf::from);
    let chosen: Vec<String> = args.collect();
    let meshes: Vec<&str> = match chosen.is_empty() {
        true => MESHES.to_vec(),
        false => chosen.iter().map(String::as_str).collect(),
    };
    if let Some(missing) = meshes.iter().find(|m| !folder.join(m).is_file()) {
        return Err(format!(
            "{} is missing: generate the meshes with `python3 meshes/generate.py --bench {}` \
             (pip install gmsh)",
            folder.join(missing).display(),
            folder.display()
        )
        .into());
    }
    let row = [("sweep", None), ("optimisation.controller.l1_mm", Some(L1))];
    let built_in = Scene::bundled_with("paper-table1", &row)?.cases()[0]
        .run()?
        .p_max_mpa
        .ok_or("the built-in mesh's case did not converge")?;
    // The scene reads a relative path from its own folder (scenes/).
    let folder = std::fs::canonicalize(&folder)?;
    let rows = meshes
        .iter()
        .map(|m| measure(&folder.join(m)))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    print(&rows, built_in);
    Ok(())
}

/// The edits of the bundled Table 1 for one row (L1 = 30 mm) on the meshes of `mesh`.
fn edits(mesh: &str) -> Vec<(&'static str, Option<String>)> {
    let steel = "{ e_mpa = 2.0e5, nu = 0.3 }";
    let bodies = format!(
        r#"[
  {{ kind = "fe_mesh", name = "base", mesh = "{mesh}", surface = "base", contact = "base_face",
     extent_mm = [100.0, 50.0], material = {steel},
     supports = [{{ group = "base_bottom", fix = ["x", "y"] }}] }},
  {{ kind = "fe_mesh", name = "punch", mesh = "{mesh}", surface = "punch",
     contact = "punch_face", extent_mm = [50.0, 50.0], material = {steel},
     loads = [{{ group = "punch_top", pressure_mpa = 100.0 }}] }},
]"#
    );
    vec![
        ("sweep", None),
        ("optimisation.controller.l1_mm", Some(L1.to_string())),
        (
            "contact.zone",
            Some(r#"{ kind = "mesh", analysis = "axisymmetric" }"#.into()),
        ),
        ("body", Some(bodies)),
    ]
}

/// Reads, builds and optimises the case on the meshes of `file`.
fn measure(file: &Path) -> std::result::Result<Row, Box<dyn std::error::Error>> {
    let scene_file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/paper-table1.toml");
    let text = std::fs::read_to_string(&scene_file)?;
    let mesh = file.to_string_lossy().into_owned();
    let owned = edits(&mesh);
    let edits: Vec<(&str, Option<&str>)> = owned.iter().map(|(k, v)| (*k, v.as_deref())).collect();
    let heap = PeakAlloc::start();
    let start = Instant::now();
    let scene = Scene::parse_with(&text, Format::Toml, &scene_file, &edits)?;
    let read = start.elapsed();
    let case: &Case = &scene.cases()[0];
    let start = Instant::now();
    let built: Built = case.build()?;
    let build = start.elapsed();
    let start = Instant::now();
    let report = case.run_on(&built, &Silent)?;
    let optimise = start.elapsed();
    let peak_mib = PeakAlloc::peak_since(heap);
    if !report.is_solved() {
        return Err(format!("{}: {:?}", file.display(), report.termination).into());
    }
    let stats = built.stats().ok_or("the bodies were not paired")?;
    let Layout::Mesh(surface) = case.layout() else {
        return Err("not a zone of imported meshes".into());
    };
    Ok(Row {
        nodes: surface.nodes.iter().flatten().sum(),
        points: report.interface.len(),
        read,
        factor: stats.iter().map(|s| s.assembly + s.factorisation).sum(),
        condense: stats.iter().map(|s| s.condensation).sum(),
        build,
        optimise,
        estimate_mb: case.memory().estimate_bytes as f64 * 1e-6,
        peak_mib,
        p_max: report.p_max_mpa.ok_or("no p_max")?,
    })
}

/// The table, p_max against the finest mesh's and the built-in mesh's.
fn print(rows: &[Row], built_in: f64) {
    let finest = rows.last().map_or(f64::NAN, |r| r.p_max);
    println!(
        "{:>8} {:>6} {:>7} {:>7} {:>9} {:>7} {:>9} {:>9} {:>9} {:>8} {:>8} {:>8}",
        "nodes",
        "points",
        "read s",
        "factor s",
        "condense s",
        "build s",
        "optimise s",
        "estim. MB",
        "peak MiB",
        "p_max",
        "Δ fine %",
        "Δ 18el %"
    );
    let s = |d: Duration| d.as_secs_f64();
    for r in rows {
        println!(
            "{:>8} {:>6} {:>7.2} {:>8.2} {:>10.2} {:>7.2} {:>10.2} {:>9.0} {:>9.0} {:>8.2} {:>+8.3} {:>+8.3}",
            r.nodes,
            r.points,
            s(r.read),
            s(r.factor),
            s(r.condense),
            s(r.build),
            s(r.optimise),
            r.estimate_mb,
            r.peak_mib,
            r.p_max,
            100.0 * (r.p_max / finest - 1.0),
            100.0 * (r.p_max / built_in - 1.0),
        );
    }
}
