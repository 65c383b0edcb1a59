//! The bearing roller at production size: the crown optimised by the load split with the
//! matrix-free Polonsky–Keer solver, one core, each case in its own process so that its peak
//! memory is its own. Prints the tables of the book's performance section and writes
//! `results/roller_scaling/{scaling.csv,scaling.svg,scaling.png}` (`chart` redraws the chart
//! from that CSV without solving).
//!
//! The roller: D = 10 mm, l = 10 mm, Q = 5446 N, steel on steel as a rigid cylinder (R = 5 mm)
//! on one half-space of the pair's modulus (E = 1.05·10⁵ MPa, ν = 0.3); the C¹ controller along
//! the axis with L2 = l/2; Ω_v the centre row. Hertz line contact for the nominal 544.6 N/mm:
//! b = 0.17334 mm, p₀ = 2000.1 MPa.
//!
//! `cargo run --release --example roller_scaling` (add `large` for an 800 × 417 grid too, or
//! name the sections to run: `production`, `dense`, `straight`, `scaling`).

use std::cell::Cell;
use std::process::Command;
use std::time::Instant;

use contopt::prelude::*;
use contopt::report::{log_log, Panel};
use contopt_validation::fixtures::Exact;
use contopt_validation::roller::{CylinderGrid, Roller};

/// The load split's tolerance: Ω_v pressure within 1e-8·p_max of v·p_max.
const TOLERANCE: f64 = 1e-8;

/// Hertz's peak p₀ for the roller's line load `q` [N/mm].
fn hertz_p0(q: f64) -> f64 {
    Roller::line().peak_pressure(q)
}

/// Peak resident memory of this process [MB] (Linux), or NaN.
fn peak_mb() -> f64 {
    contopt_validation::fixtures::peak_resident_mib() * 1.048_576
}

/// Polonsky–Keer's steps inside a load split: on the roller's grid (level 1, below the
/// split) and on the coarser grids of its cold starts (level 2 and deeper, a quarter of the
/// points each level down).
#[derive(Default)]
struct Steps {
    fine: Cell<usize>,
    coarse: Cell<usize>,
}

impl Observer for Steps {
    fn observe(&self, e: &Event) -> Flow {
        if e.method == Method::PolonskyKeer && e.end.is_none() {
            let count = if e.level <= 1 {
                &self.fine
            } else {
                &self.coarse
            };
            count.set(count.get() + 1);
        }
        Flow::Continue
    }
}

/// How an optimum is found.
#[derive(Clone, Copy)]
enum Route {
    /// The load split with Polonsky–Keer.
    Split,
    /// The load split with Polonsky–Keer solving every update to its full tolerance.
    ExactSplit,
    /// The load split with the dense active set.
    DenseSplit,
    /// The LP (3.5) on the dense matrix.
    DenseLp,
}

/// The optimum of `body` under the rigid cylinder of gap `h` and `load`, controller `v`, and
/// its time \[s\]; the optimum says how its method ended.
fn optimum(
    grid: &CylinderGrid,
    load: f64,
    v: &dyn Controller,
    route: Route,
    observer: &dyn Observer,
) -> Result<(Optimum, f64)> {
    let iface = grid.body.interface();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], load).unwrap();
    let problem = InterfaceProblem::new(&grid.body, &roller, &grid.gap).unwrap();
    let shape = GapShape::extruded(iface, 0).unwrap();
    let opt = Optimisation::new(&problem, &shape, v)
        .unwrap()
        .with_regions(grid.centre_row(Region::OmegaNv))
        .unwrap()
        .with_observer(observer);
    let t = Instant::now();
    let split = LoadSplitSettings {
        tolerance: TOLERANCE,
        max_iterations: 100,
    };
    let optimum = match route {
        Route::Split => {
            opt.load_split(&PolonskyKeer::new(PolonskyKeerSettings::default())?, &split)
        }
        Route::ExactSplit => opt.load_split(
            &Exact(PolonskyKeer::new(PolonskyKeerSettings::default())?),
            &split,
        ),
        Route::DenseSplit => opt.load_split(&ActiveSet::new(ActiveSetSettings::default())?, &split),
        Route::DenseLp => opt.linear_programme(
            &ActiveSet::new(ActiveSetSettings::default())?,
            &LinearProgrammeSettings::default(),
        ),
    }?;
    Ok((optimum, t.elapsed().as_secs_f64()))
}

/// One case, in this process: prints `seconds peak_MB p_max centre_miss dh_min dh_ref dh_max
/// solves steps coarse` on one line (steps: the contact solver's conjugate-gradient steps on
/// the grid, summed over the solves; coarse: those on the coarser grids of its cold starts).
fn case(nx: usize, ny: usize, l1: f64, route: Route) {
    let grid = Roller::grid(nx, ny).unwrap();
    let v = Profile::cubic(l1, 0.5 * Roller::LENGTH).unwrap();
    let steps = Steps::default();
    let (opt, seconds) = optimum(&grid, Roller::LOAD, &v, route, &steps).unwrap();
    assert!(opt.is_converged(), "the load split {}", opt.termination);
    let regions = grid.centre_row(Region::OmegaNv);
    let iface = grid.body.interface();
    // The largest miss of p = v·p_max on Ω_v, relative to v·p_max, where v > 1 %.
    let miss = (0..iface.len())
        .filter(|&i| regions[i] == Region::OmegaV)
        .map(|i| (v.value(iface.points()[i]), opt.pressure[i]))
        .filter(|(v, _)| *v > 0.01)
        .map(|(v, p)| (p / (v * opt.p_max) - 1.0).abs())
        .fold(0.0, f64::max);
    let dh_min = opt.dh.iter().fold(f64::INFINITY, |m, v| m.min(*v));
    let reference = opt
        .dh
        .iter()
        .zip(GapShape::extruded(iface, 0).unwrap().nodes())
        .min_by(|a, b| a.1[0].abs().total_cmp(&b.1[0].abs()))
        .map_or(f64::NAN, |(d, _)| *d);
    println!(
        "{seconds} {} {} {miss} {dh_min} {reference} {} {} {} {}",
        peak_mb(),
        opt.p_max,
        opt.dh_max(),
        opt.passes.len(),
        steps.fine.get(),
        steps.coarse.get()
    );
    assert_eq!(
        steps.fine.get() + steps.coarse.get(),
        opt.passes.iter().map(|p| p.iterp).sum::<usize>(),
        "every step is observed"
    );
}

/// A case run in a child process.
struct Row {
    nx: usize,
    ny: usize,
    l1: f64,
    seconds: f64,
    peak_mb: f64,
    p_max: f64,
    miss: f64,
    dh_min: f64,
    dh_ref: f64,
    dh_max: f64,
    solves: usize,
    steps: usize,
    coarse: usize,
}

fn child(nx: usize, ny: usize, l1: f64) -> Row {
    child_by(nx, ny, l1, "split")
}

/// A case run in a child process by the load split with Polonsky–Keer, its updates solved
/// inexactly (`split`) or each to the full tolerance (`exact`).
fn child_by(nx: usize, ny: usize, l1: f64, route: &str) -> Row {
    let out = Command::new(std::env::current_exe().unwrap())
        .args([
            "case",
            &nx.to_string(),
            &ny.to_string(),
            &l1.to_string(),
            route,
        ])
        .output()
        .expect("the example runs itself");
    let text = String::from_utf8_lossy(&out.stdout);
    let f: Vec<f64> = text
        .split_whitespace()
        .map(|t| t.parse().unwrap_or(f64::NAN))
        .collect();
    assert!(
        f.len() == 10,
        "case {nx} x {ny}, L1 = {l1}: {text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    Row {
        nx,
        ny,
        l1,
        seconds: f[0],
        peak_mb: f[1],
        p_max: f[2],
        miss: f[3],
        dh_min: f[4],
        dh_ref: f[5],
        dh_max: f[6],
        solves: f[7] as usize,
        steps: f[8] as usize,
        coarse: f[9] as usize,
    }
}

/// Item 4's table: both grids, every L1.
fn production(grids: &[(usize, usize)]) -> Vec<Row> {
    eprintln!("\n## The optimised roller (load split, Polonsky–Keer, one core)\n");
    println!("| grid | L1 mm | time s | peak MB | solves | CG steps (+ coarser grids) | p_max MPa | Δp_max to the finer grid | largest miss of v·p_max on Ω_v | Δh_max µm | min Δh µm | Δh at x = 0 µm |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let l1s = [0.0, 2.0, 3.0, 4.0, 5.0];
    let rows: Vec<Row> = grids
        .iter()
        .flat_map(|&(nx, ny)| l1s.iter().map(move |&l1| child(nx, ny, l1)))
        .collect();
    for r in &rows {
        let finer = rows
            .iter()
            .find(|o| o.l1 == r.l1 && o.nx == 2 * r.nx)
            .map_or("".to_string(), |o| {
                format!("{:+.4} %", 100.0 * (r.p_max / o.p_max - 1.0))
            });
        println!(
            "| {} × {} | {} | {:.2} | {:.0} | {} | {} (+{}) | {:.2} | {finer} | {:.1e} | {:.3} | {:.1e} | {:.1e} |",
            r.nx,
            r.ny,
            r.l1,
            r.seconds,
            r.peak_mb,
            r.solves,
            r.steps,
            r.coarse,
            r.p_max,
            r.miss,
            1e3 * r.dh_max,
            1e3 * r.dh_min,
            1e3 * r.dh_ref
        );
    }
    rows
}

/// The load split against the dense paths on the first roller scene's grids (R = 10 mm, 12 kN,
/// E = 2·10⁵ MPa, v = 1, cells 0.5 or 0.25 × 0.04 mm): the LP (3.5) on the dense matrix, and
/// the load split with the dense active set in place of Polonsky–Keer.
fn dense_agreement() {
    eprintln!("\n## Against the dense paths\n");
    println!("| grid | dense path | its time s | split (Polonsky–Keer) s | p_max MPa | p_max split / dense − 1 | largest Δh difference / Δh_max |");
    println!("| --- | --- | --- | --- | --- | --- | --- |");
    for nx in [20, 40] {
        let (ny, dx, dy) = (21, 10.0 / nx as f64, 0.04);
        let grid = CylinderGrid::steel(nx, ny, dx, dy, 10.0).unwrap();
        let v = Constant::new(1.0).unwrap();
        let (split, split_s) = optimum(&grid, 12_000.0, &v, Route::Split, &Silent).unwrap();
        assert!(split.is_converged(), "the load split {}", split.termination);
        for (name, route) in [
            ("LP (3.5)", Route::DenseLp),
            ("split, active set", Route::DenseSplit),
        ] {
            match optimum(&grid, 12_000.0, &v, route, &Silent) {
                Ok((dense, _)) if !dense.is_converged() => {
                    println!("| {nx} × {ny} | {name} | {} | | | | |", dense.termination)
                }
                Ok((dense, dense_s)) => {
                    let dh = split
                        .dh
                        .iter()
                        .zip(&dense.dh)
                        .map(|(a, b)| (a - b).abs())
                        .fold(0.0, f64::max)
                        / dense.dh_max();
                    println!(
                        "| {nx} × {ny} | {name} | {dense_s:.2} | {split_s:.3} | {:.6} | {:+.1e} | {dh:.1e} |",
                        dense.p_max,
                        split.p_max / dense.p_max - 1.0
                    );
                }
                Err(e) => println!("| {nx} × {ny} | {name} | failed: {e} | | | | |"),
            }
        }
    }
}

/// The straight roller against Hertz's line contact with the local centre line load.
fn straight(grids: &[(usize, usize)]) {
    eprintln!("\n## The straight roller against Hertz (local centre line load)\n");
    println!("| grid | cell mm | centre line load N/mm | p at the centre MPa | Hertz local p₀ | error | / nominal p₀ 2000.1 | end pressure MPa (cell-dependent) | CG steps | time s |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for &(nx, ny) in grids {
        let CylinderGrid { body, gap, .. } = Roller::grid(nx, ny).unwrap();
        let load = Roller::LOAD;
        let roller = RigidBody::pressed("roller", body.interface(), [0.0, 0.0, 1.0], load).unwrap();
        let problem = InterfaceProblem::new(&body, &roller, &gap).unwrap();
        let t = Instant::now();
        let st = PolonskyKeer::new(PolonskyKeerSettings::default())
            .and_then(|solver| solver.solve(&problem))
            .unwrap();
        assert!(st.is_converged(), "Polonsky–Keer {}", st.termination);
        let seconds = t.elapsed().as_secs_f64();
        let iface = body.interface();
        let dx = Roller::LENGTH / nx as f64;
        // The two columns either side of x = 0.
        let centre: Vec<usize> = (0..iface.len())
            .filter(|&i| iface.points()[i][0].abs() < dx)
            .collect();
        let q: f64 = centre
            .iter()
            .map(|&i| iface.weights()[i] * st.pressure[i])
            .sum::<f64>()
            / (2.0 * dx);
        let p = centre.iter().map(|&i| st.pressure[i]).fold(0.0, f64::max);
        let p0 = hertz_p0(q);
        println!(
            "| {nx} × {ny} | {dx} | {q:.2} | {p:.1} | {p0:.1} | {:+.3} % | {:.4} | {:.0} | {} | {seconds:.2} |",
            100.0 * (p / p0 - 1.0),
            p / hertz_p0(Roller::LOAD / Roller::LENGTH),
            st.p_max(),
            st.iterations
        );
    }
}

/// The chart of run time against points (from the scaling's rows): `dir/scaling.{svg,png}`.
fn chart(points: &[(f64, f64)], dir: &std::path::Path) -> std::io::Result<()> {
    let Some(&(n0, t0)) = points.first() else {
        return Ok(());
    };
    let linear: Vec<(f64, f64)> = points.iter().map(|&(n, _)| (n, t0 * n / n0)).collect();
    let series: [(&str, &[(f64, f64)]); 2] = [
        ("load split, Polonsky-Keer", points),
        ("slope 1 (time ∝ points)", &linear),
    ];
    let figure = log_log(
        "Optimised roller crown: run time against grid size",
        &[Panel {
            title: "L1 = 3 mm, one thread",
            x_label: "interface points",
            y_label: "run time [s]",
            series: &series,
        }],
    )?;
    for (name, bytes) in figure.files("scaling")? {
        std::fs::write(dir.join(name), bytes)?;
    }
    Ok(())
}

/// (points, seconds) of each row of a `scaling.csv` this example wrote.
fn read_scaling(csv: &str) -> Vec<(f64, f64)> {
    csv.lines()
        .skip(1)
        .filter_map(|line| {
            let fields: Vec<&str> = line.split(',').collect();
            Some((fields.get(2)?.parse().ok()?, fields.get(5)?.parse().ok()?))
        })
        .collect()
}

/// The solve against the number of points (L1 = 3 mm): the CSV and the log-log chart.
fn scaling(grids: &[(usize, usize)]) -> std::io::Result<()> {
    eprintln!("\n## Scaling (L1 = 3 mm)\n");
    println!("| grid | points | solves | CG steps on the grid | on coarser grids | time s | time per solve ms | peak MB | every solve exact: solves, steps (+ coarser), time s |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    let mut csv =
        String::from("nx,ny,points,solves,steps,seconds,peak_mb,p_max_mpa,coarse_steps\n");
    let mut points = vec![];
    for &(nx, ny) in grids {
        let r = child(nx, ny, 3.0);
        let e = child_by(nx, ny, 3.0, "exact");
        let n = nx * ny;
        println!(
            "| {nx} × {ny} | {n} | {} | {} | {} | {:.3} | {:.1} | {:.0} | {}, {} (+{}), {:.3} |",
            r.solves,
            r.steps,
            r.coarse,
            r.seconds,
            1e3 * r.seconds / r.solves as f64,
            r.peak_mb,
            e.solves,
            e.steps,
            e.coarse,
            e.seconds
        );
        csv.push_str(&format!(
            "{nx},{ny},{n},{},{},{},{},{},{}\n",
            r.solves, r.steps, r.seconds, r.peak_mb, r.p_max, r.coarse
        ));
        points.push((n as f64, r.seconds));
    }
    let dir = std::path::Path::new("results/roller_scaling");
    std::fs::create_dir_all(dir)?;
    std::fs::write(dir.join("scaling.csv"), csv)?;
    chart(&points, dir)?;
    eprintln!("\nwritten: results/roller_scaling/{{scaling.csv,scaling.svg,scaling.png}}");
    Ok(())
}

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("chart") {
        let dir = std::path::Path::new("results/roller_scaling");
        let rows = read_scaling(&std::fs::read_to_string(dir.join("scaling.csv"))?);
        chart(&rows, dir)?;
        println!("written: results/roller_scaling/scaling.{{svg,png}} from scaling.csv");
        return Ok(());
    }
    if args.first().map(String::as_str) == Some("case") {
        let num = |k: usize| args[k].parse::<f64>().expect("case NX NY L1 [exact]");
        let route = match args.get(4).map(String::as_str) {
            Some("exact") => Route::ExactSplit,
            _ => Route::Split,
        };
        case(num(1) as usize, num(2) as usize, num(3), route);
        return Ok(());
    }
    // Sections named on the command line, or all of them.
    let wanted = |name: &str| {
        args.iter().any(|a| a == name) || !args.iter().any(|a| SECTIONS.contains(&a.as_str()))
    };
    let production_grids = [(200, 105), (400, 209)];
    if wanted("production") {
        production(&production_grids);
    }
    if wanted("dense") {
        dense_agreement();
    }
    if wanted("straight") {
        straight(&production_grids);
    }
    if wanted("scaling") {
        let mut grids = vec![(50, 27), (100, 53), (200, 105), (400, 209)];
        if args.iter().any(|a| a == "large") {
            grids.push((800, 417));
        }
        scaling(&grids)?;
    }
    Ok(())
}

/// The sections the example can run alone.
const SECTIONS: [&str; 4] = ["production", "dense", "straight", "scaling"];
