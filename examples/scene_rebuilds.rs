//! How much of a scene's run is building its bodies: the bundled Table 2 scene (five values
//! of L1, one problem) on a finer mesh, run as a whole ([`Scene::run`], which builds the
//! bodies once for all five cases) against one build of its bodies plus its five
//! optimisations, and against each case run on its own (a build per case). The builds are
//! counted as well as timed: the pairs of bodies built (`Run::builds`) and the numeric
//! factorisations of stiffness matrices (`contopt::fem::factorisations`), which a machine's
//! load does not move; on one and two threads ([`Scene::run_parallel`]), the builds it reports
//! (two factorisations each, a body's on the thread that built it).
//!
//! `cargo run --release --example scene_rebuilds [elements]` (default 144 elements across the
//! contact radius, and as many layers).

use std::time::Instant;

use contopt::fem::factorisations;
use contopt::prelude::*;
use contopt::results::CaseReport;

/// The whole run may take at most this much longer than one build and the optimisations.
const OVERHEAD: f64 = 1.2;

/// What a way of running the scene cost: seconds, pairs of bodies built and numeric
/// factorisations.
struct Cost {
    seconds: f64,
    builds: usize,
    factorisations: u64,
}

/// The whole scene by [`Scene::run`]: its reports and cost.
fn whole(scene: &Scene) -> std::result::Result<(Vec<CaseReport>, Cost), SceneError> {
    let (start, factorised) = (Instant::now(), factorisations());
    let mut run = scene.run();
    let reports = run.by_ref().collect::<std::result::Result<Vec<_>, _>>()?;
    let cost = Cost {
        seconds: start.elapsed().as_secs_f64(),
        builds: run.builds(),
        factorisations: factorisations() - factorised,
    };
    Ok((reports, cost))
}

/// The old way: each case builds its own bodies ([`Case::run`]).
fn separately(scene: &Scene) -> std::result::Result<Cost, SceneError> {
    let (start, factorised) = (Instant::now(), factorisations());
    for case in scene.cases() {
        case.run()?;
    }
    Ok(Cost {
        seconds: start.elapsed().as_secs_f64(),
        builds: scene.cases().len(),
        factorisations: factorisations() - factorised,
    })
}

/// The time of `key` in each report \[s\].
fn seconds(reports: &[CaseReport], key: &str) -> Vec<f64> {
    reports
        .iter()
        .map(|r| 1e-3 * r.timings_ms.get(key).copied().unwrap_or(0.0))
        .collect()
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let elements: usize = match std::env::args().nth(1) {
        Some(arg) => arg.parse().map_err(|e| format!("elements {arg:?}: {e}"))?,
        None => 144,
    };
    // The whole scene: parse (checks, builds nothing), then every case.
    let (start, factorised) = (Instant::now(), factorisations());
    let n = elements.to_string();
    let scene = Scene::bundled_with("paper-table2", &[("contact.zone.elements", Some(&n))])?;
    let parsed = start.elapsed().as_secs_f64();
    let parse_factorisations = factorisations() - factorised;
    let (reports, run) = whole(&scene)?;
    let build = seconds(&reports, "build")[0];
    let optimisations: f64 = seconds(&reports, "optimise").iter().sum();
    let alone = separately(&scene)?;

    println!(
        "Table 2 scene, {elements} elements across the contact radius: {} cases, {} build(s)",
        reports.len(),
        run.builds
    );
    println!(
        "{:<44} {:>9} {:>7} {:>15}",
        "", "time s", "builds", "factorisations"
    );
    let line = |what: &str, s: f64, counts: Option<(usize, u64)>| match counts {
        Some((b, f)) => println!("{what:<44} {s:>9.4} {b:>7} {f:>15}"),
        None => println!("{what:<44} {s:>9.4}"),
    };
    line(
        "parse and check (no factorisation)",
        parsed,
        Some((0, parse_factorisations)),
    );
    line("one build of the bodies", build, None);
    line("the five optimisations", optimisations, None);
    line("one build + the optimisations", build + optimisations, None);
    let total = parsed + run.seconds;
    line(
        "the whole scene (Scene::run)",
        total,
        Some((run.builds, run.factorisations)),
    );
    line(
        "each case on its own (Case::run)",
        alone.seconds,
        Some((alone.builds, alone.factorisations)),
    );
    for jobs in [1, 2] {
        let start = Instant::now();
        let ran = scene.run_parallel(0..reports.len(), jobs, &|| {})?;
        line(
            &format!("the whole scene on {jobs} thread(s) (run_parallel)"),
            start.elapsed().as_secs_f64(),
            Some((ran.builds, 2 * ran.builds as u64)),
        );
    }
    let ratio = total / (build + optimisations);
    println!("ratio whole / (build + optimisations): {ratio:.3} (at most {OVERHEAD})");
    for r in &reports {
        let ms = |key: &str| r.timings_ms.get(key).copied().unwrap_or(0.0);
        println!(
            "  {:<12} build {:>8.1} ms, optimise {:>8.1} ms, fields {:>8.1} ms, bound p_max {:.2} MPa",
            r.label,
            ms("build"),
            ms("optimise"),
            ms("fields"),
            r.bound_p_max_mpa.unwrap_or(f64::NAN)
        );
    }
    Ok(())
}
