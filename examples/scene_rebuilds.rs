//! How much of a scene's run is building its bodies: the bundled Table 2 scene (five values
//! of L1, one problem) on a finer mesh, run as a whole ([`Scene::run`], which builds the
//! bodies once for all five cases) against one build of its bodies plus its five
//! optimisations, and against each case run on its own (a build per case).
//!
//! `cargo run --release --example scene_rebuilds [elements]` (default 144 elements across the
//! contact radius, and as many layers).

use std::path::Path;
use std::time::Instant;

use contopt::scene::{Format, Scene, SceneError, BUNDLED};

/// The whole run may take at most this much longer than one build and the optimisations.
const OVERHEAD: f64 = 1.2;

fn main() -> Result<(), SceneError> {
    let elements: usize = match std::env::args().nth(1) {
        Some(arg) => arg.parse().map_err(|e| SceneError::Parse {
            file: "scene_rebuilds".into(),
            message: format!("elements {arg:?}: {e}"),
        })?,
        None => 144,
    };
    let text = BUNDLED
        .iter()
        .find(|(name, _)| *name == "paper-table2")
        .map(|(_, text)| text.replace("elements = 18", &format!("elements = {elements}")))
        .unwrap_or_default();
    let file = Path::new("paper-table2.toml");

    // The whole scene: parse (checks, builds nothing), then every case.
    let start = Instant::now();
    let scene = Scene::parse(&text, Format::Toml, file)?;
    let parsed = start.elapsed().as_secs_f64();
    let run = scene.run()?;
    let builds = run.builds();
    let reports = run.collect::<Result<Vec<_>, _>>()?;
    let whole = start.elapsed().as_secs_f64();

    let ms = |key: &str| -> Vec<f64> {
        reports
            .iter()
            .map(|r| 1e-3 * r.timings_ms.get(key).copied().unwrap_or(0.0))
            .collect()
    };
    let build = ms("build")[0];
    let optimisations: f64 = ms("optimise").iter().sum();

    // The old way: each case builds its own bodies.
    let start = Instant::now();
    for case in scene.cases()? {
        case.run()?;
    }
    let separately = start.elapsed().as_secs_f64();

    println!(
        "Table 2 scene, {elements} elements across the contact radius: {} cases, {builds} build(s)",
        reports.len()
    );
    println!("{:<44} {:>9}", "", "time s");
    println!(
        "{:<44} {:>9.4}",
        "parse and check (no factorisation)", parsed
    );
    println!("{:<44} {:>9.4}", "one build of the bodies", build);
    println!("{:<44} {:>9.4}", "the five optimisations", optimisations);
    println!(
        "{:<44} {:>9.4}",
        "one build + the optimisations",
        build + optimisations
    );
    println!("{:<44} {:>9.4}", "the whole scene (Scene::run)", whole);
    println!(
        "{:<44} {:>9.4}",
        "each case on its own (Case::run)", separately
    );
    let ratio = whole / (build + optimisations);
    println!("ratio whole / (build + optimisations): {ratio:.3} (at most {OVERHEAD})");
    for r in &reports {
        println!(
            "  {:<12} build {:>8.1} ms, optimise {:>8.1} ms, bound p_max {:.2} MPa",
            r.label,
            r.timings_ms.get("build").copied().unwrap_or(0.0),
            r.timings_ms.get("optimise").copied().unwrap_or(0.0),
            r.bound_p_max.unwrap_or(f64::NAN)
        );
    }
    Ok(())
}
