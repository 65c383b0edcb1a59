//! The linear programme (3.5) beside the other methods, where each applies: the bearing
//! roller on grids whose dense matrices fit the default limit, against the load split; the
//! steel punch with its rim in Ω_nv (the bundled scene `steel-on-aluminium`), against the
//! iteration of §3.2; a strip of points only in contact (`Region::Contact`), against both. Prints the tables of the optimisation chapter.
//!
//! `cargo run --release --example linear_programme` (add `large` for the rollers of 100 × 53 and
//! 130 × 67 cells; name
//! the sections to run: `roller`, `rim`, `strip`).

use std::time::Instant;

use contopt::prelude::*;
use contopt::scene::Scene;
use contopt_validation::roller::{CylinderGrid, Roller};

/// Polonsky–Keer with its default settings.
fn polonsky_keer() -> PolonskyKeer {
    PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap()
}

/// `run`'s optimum and its time \[s\].
fn timed(run: impl FnOnce() -> Result<Optimum>) -> (Optimum, f64) {
    let t = Instant::now();
    let optimum = run().unwrap();
    (optimum, t.elapsed().as_secs_f64())
}

/// The largest |Δh_a − Δh_b| relative to the largest Δh_b.
fn dh_difference(a: &Optimum, b: &Optimum) -> f64 {
    let top = b.dh_max();
    a.dh.iter()
        .zip(&b.dh)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
        / top
}

/// The interior-point iterations of an optimum's passes.
fn iterations(o: &Optimum) -> usize {
    o.passes.iter().map(|p| p.iterp).sum()
}

/// The roller on each grid: the load split and the LP, both with Polonsky–Keer.
fn roller(grids: &[(usize, usize)]) {
    println!("## The bearing roller: the LP (3.5) against the load split (L1 = 3 mm)\n");
    println!("| grid | points | dense MB | split s | LP s | LP passes | interior-point iterations | p_max MPa | LP / split − 1 | largest Δh difference / Δh_max | largest p − v·p_max on Ω_nv MPa |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let v = Profile::cubic(3.0, 0.5 * Roller::LENGTH).unwrap();
    for &(nx, ny) in grids {
        let grid = Roller::grid(nx, ny).unwrap();
        let iface = grid.body.interface();
        let body = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
        let problem = InterfaceProblem::new(&grid.body, &body, &grid.gap).unwrap();
        let shape = GapShape::extruded(iface, 0).unwrap();
        let opt = Optimisation::new(&problem, &shape, &v)
            .unwrap()
            .with_regions(grid.centre_row(Region::OmegaNv))
            .unwrap();
        let (split, split_s) = timed(|| opt.load_split(&polonsky_keer(), &Default::default()));
        let settings = LinearProgrammeSettings::default();
        let (lp, lp_s) = timed(|| opt.linear_programme(&polonsky_keer(), &settings));
        let n = iface.len();
        let mb = (n * n * 8) as f64 * LinearProgrammeSettings::DENSE_COPIES as f64 / 1e6;
        for (name, o) in [("split", &split), ("LP", &lp)] {
            assert!(o.is_converged(), "{nx} × {ny}, {name}: {}", o.termination);
        }
        println!(
            "| {nx} × {ny} | {n} | {mb:.0} | {split_s:.2} | {lp_s:.2} | {} | {} | {:.4} | {:+.1e} | {:.1e} | {:+.2e} |",
            lp.passes.len(),
            iterations(&lp),
            lp.p_max,
            lp.p_max / split.p_max - 1.0,
            dh_difference(&lp, &split),
            lp.omega_nv_excess.unwrap_or(f64::NAN)
        );
    }
}

/// The bundled scene `steel-on-aluminium`: the steel punch on the aluminium base with the
/// whole face in Ω_v, and, in its last two cases, the outermost Gauss point (r = 19.89 mm) in
/// Ω_nv, by the iteration and by the LP.
fn rim() {
    println!("\n## The punch with its rim in Ω_nv: the iteration of §3.2 against the LP (3.5)\n");
    println!("| case | method | p̂ MPa | p_max MPa | Δh_max µm | largest p − v·p̂ on Ω_nv MPa | passes | time s |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let scene = Scene::bundled("steel-on-aluminium").unwrap();
    for report in scene.run() {
        let report = report.unwrap();
        assert!(
            report.is_solved(),
            "{}: {}",
            report.label,
            report.termination
        );
        let figure = |v: Option<f64>| v.map_or("".to_string(), |v| format!("{v:.4}"));
        println!(
            "| {} | {} | {} | {} | {} | {} | {} | {:.3} |",
            report.label,
            report.method.map_or("".to_string(), |m| m.to_string()),
            figure(report.bound_p_max_mpa),
            figure(report.p_max_mpa),
            figure(report.dh_max_um),
            report
                .omega_nv_excess_mpa
                .map_or("none".to_string(), |e| format!("{e:+.2e}")),
            report.passes.len(),
            1e-3 * report
                .timings_ms
                .get("optimise")
                .copied()
                .unwrap_or(f64::NAN)
        );
    }
}

/// The roller's strip (R = 10 mm, 12 kN, v = 1) on 40 × 25 = 1000 cells with only its centre
/// row in Ω_opt: the other points are only in contact, their gap following their column.
fn strip() {
    println!("\n## A strip of points only in contact (Region::Contact), 1000 points\n");
    println!("| method | p_max MPa | Δh_max µm | p_max / LP − 1 | largest Δh difference / Δh_max | passes | time s |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    let strip = CylinderGrid::steel(40, 25, 0.25, 0.04, 10.0).unwrap();
    let iface = strip.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], 12_000.0).unwrap();
    let problem = InterfaceProblem::new(&strip.body, &roller, &strip.gap).unwrap();
    let regions = strip.centre_row(Region::Contact);
    let shape = GapShape::extruded(iface, 0).unwrap();
    let opt = Optimisation::new(&problem, &shape, &Constant::new(1.0).unwrap())
        .unwrap()
        .with_regions(regions)
        .unwrap();
    let solver = ActiveSet::new(ActiveSetSettings::default()).unwrap();
    let (lp, lp_s) = timed(|| opt.linear_programme(&solver, &LinearProgrammeSettings::default()));
    let tight = IterationSettings {
        tolh_mm2: 1e-16,
        max_iterations: 200,
    };
    let (iterated, iterated_s) = timed(|| opt.iterate(Mode::GivenLoad, &solver, &tight));
    let (split, split_s) = timed(|| opt.load_split(&solver, &Default::default()));
    for (name, o, s) in [
        ("LP (3.5)", &lp, lp_s),
        ("iteration of §3.2", &iterated, iterated_s),
        ("load split", &split, split_s),
    ] {
        assert!(o.is_converged(), "{name}: {}", o.termination);
        println!(
            "| {name} | {:.4} | {:.4} | {:+.1e} | {:.1e} | {} | {s:.2} |",
            o.p_max,
            1e3 * o.dh_max(),
            o.p_max / lp.p_max - 1.0,
            dh_difference(o, &lp),
            o.passes.len()
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let wanted = |name: &str| {
        args.iter().any(|a| a == name) || !args.iter().any(|a| SECTIONS.contains(&a.as_str()))
    };
    if wanted("roller") {
        let mut grids = vec![(20, 21), (26, 31), (40, 21), (50, 27)];
        if args.iter().any(|a| a == "large") {
            // 100 × 53, and the largest grid of the roller's shape whose three dense copies
            // fit the default limit of 2 GB.
            grids.extend([(100, 53), (130, 67)]);
        }
        roller(&grids);
    }
    if wanted("rim") {
        rim();
    }
    if wanted("strip") {
        strip();
    }
}

/// The sections the example can run alone.
const SECTIONS: [&str; 3] = ["roller", "rim", "strip"];
