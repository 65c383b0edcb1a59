//! The linear programme (3.5) beside the other methods, where each applies: the bearing
//! roller on grids whose dense matrices fit the default limit, against the load split; the
//! steel punch with its rim in Ω_nv (the bundled scene `steel-on-aluminium`), against the
//! iteration of §3.2; a strip of points only in contact (`Region::Contact`), against both. Prints the tables of the optimisation chapter.
//!
//! `cargo run --release --example linear_programme` (add `large` for the rollers of 100 × 53 and
//! 130 × 67 cells; name
//! the sections to run: `roller`, `rim`, `strip`).

use std::time::Instant;

use contopt::greens::HalfSpace;
use contopt::prelude::*;
use contopt::scene::Scene;

const NU: f64 = 0.3;

/// The bearing roller of the optimisation chapter: D = 10 mm, l = 10 mm, Q = 5446 N as a
/// rigid cylinder (R = 5 mm) on the steel pair's half-space (E = 1.05·10⁵ MPa), the C¹
/// controller along the axis from L1 = 3 mm to l/2, Ω_v the centre row, on `nx` × `ny` cells
/// over the length and ±2.6 b across.
struct Roller {
    body: HalfSpace,
    gap: Vec<f64>,
}

impl Roller {
    const E: f64 = 1.05e5;
    const RADIUS: f64 = 5.0;
    const LENGTH: f64 = 10.0;
    const LOAD: f64 = 5446.0;

    fn new(nx: usize, ny: usize) -> Self {
        let estar = Self::E / (1.0 - NU * NU);
        let b = (4.0 * Self::LOAD / Self::LENGTH * Self::RADIUS / (std::f64::consts::PI * estar))
            .sqrt();
        let half = ((ny - 1) / 2) as f64;
        let (dx, dy) = (Self::LENGTH / nx as f64, 2.6 * b / half);
        let origin = [-0.5 * Self::LENGTH + 0.5 * dx, -half * dy];
        let material = Material::new(Self::E, NU).unwrap();
        let body = HalfSpace::grid("raceway", material, nx, ny, dx, dy, origin).unwrap();
        let gap = body
            .interface()
            .points()
            .iter()
            .map(|x| x[1] * x[1] / (2.0 * Self::RADIUS))
            .collect();
        Self { body, gap }
    }

    /// Ω_v the centre row, the rest `outside` (Ω_nv, or only in contact).
    fn regions(&self, outside: Region) -> Vec<Region> {
        let points = self.body.interface().points();
        let dy = points[self.body.cells().0][1] - points[0][1];
        points
            .iter()
            .map(|x| match x[1].abs() < 0.5 * dy {
                true => Region::OmegaV,
                false => outside,
            })
            .collect()
    }
}

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
        let roller = Roller::new(nx, ny);
        let iface = roller.body.interface();
        let body = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], Roller::LOAD).unwrap();
        let problem = InterfaceProblem::new(&roller.body, &body, &roller.gap).unwrap();
        let shape = GapShape::extruded(iface, 0).unwrap();
        let opt = Optimisation::new(&problem, &shape, &v)
            .unwrap()
            .with_regions(roller.regions(Region::OmegaNv))
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
    let (nx, ny, dx, dy) = (40, 25, 0.25, 0.04);
    let origin = [-5.0 + 0.5 * dx, -12.0 * dy];
    let material = Material::new(2.0e5, NU).unwrap();
    let body = HalfSpace::grid("half-space", material, nx, ny, dx, dy, origin).unwrap();
    let iface = body.interface();
    let gap: Vec<f64> = iface.points().iter().map(|x| x[1] * x[1] / 20.0).collect();
    let roller = RigidBody::pressed("roller", iface, [0.0, 0.0, 1.0], 12_000.0).unwrap();
    let problem = InterfaceProblem::new(&body, &roller, &gap).unwrap();
    let regions = iface
        .points()
        .iter()
        .map(|x| match x[1].abs() < 0.5 * dy {
            true => Region::OmegaV,
            false => Region::Contact,
        })
        .collect();
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
