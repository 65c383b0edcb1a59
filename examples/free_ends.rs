//! A roller's free ends: the image pressure and Hetényi's free face against the half-space,
//! under a given pressure and in the contact of a roller on its raceway.
//!
//! `cargo run --example free_ends`.

use contopt::greens::{hetenyi_load, FacedGrid, FreeEnds, HetenyiSettings};
use contopt::prelude::*;
use contopt::roller::{Crown, Roller, RollerEnds};

const LOAD: f64 = 5446.0;

fn steel() -> Material {
    Material::new(2.1e5, 0.3).unwrap()
}

fn roller(crown: Crown) -> Roller {
    Roller {
        diameter: 10.0,
        length: 10.0,
        raceway_diameter: None,
        roller: steel(),
        raceway: steel(),
        load: LOAD,
        tilt: 0.0,
        crown,
    }
}

/// The grid of `r` as Hetényi's superposition takes it.
fn faced(r: &Roller, nx: usize, ny: usize, reach: f64, ends: &RollerEnds) -> FacedGrid {
    let [dx, dy] = r.cell(nx, ny, reach).unwrap();
    let face = 0.5 * r.length + ends.chamfer_mm;
    FacedGrid {
        nx,
        ny,
        dx,
        dy,
        origin: [-0.5 * r.length + 0.5 * dx, -(((ny - 1) / 2) as f64) * dy],
        nu: 0.3,
        faces: [Some(-face), Some(face)],
    }
}

/// The weight w and shift c with C(p + w·Mp) + c closest to Hetényi's C(I + M)T over the
/// cells in contact (least squares).
fn fitted_weight(grid: &FacedGrid, p: &[f64], settings: &HetenyiSettings) -> (f64, f64) {
    let g = grid;
    let n = g.nx * g.ny;
    let one = FreeEnds::grid("i", steel(), g.nx, g.ny, g.dx, g.dy, g.origin, g.faces, 1.0).unwrap();
    let zero =
        FreeEnds::grid("h", steel(), g.nx, g.ny, g.dx, g.dy, g.origin, g.faces, 0.0).unwrap();
    let t = hetenyi_load(grid, p, settings).unwrap();
    let (mut uh, mut u0, mut u1) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    one.apply_influence(&t.load, &mut uh);
    zero.apply_influence(p, &mut u0);
    one.apply_influence(p, &mut u1);
    // r = uh − u0 ≈ w·m + c, m = u1 − u0, over the loaded cells.
    let (mut smm, mut sm, mut s1, mut srm, mut sr) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in (0..n).filter(|&k| p[k] > 0.0) {
        let (r, m) = (uh[k] - u0[k], u1[k] - u0[k]);
        smm += m * m;
        sm += m;
        s1 += 1.0;
        srm += r * m;
        sr += r;
    }
    let det = smm * s1 - sm * sm;
    let w = (srm * s1 - sr * sm) / det;
    let c = (smm * sr - sm * srm) / det;
    println!("    Hetényi: {} rounds", t.rounds);
    (w, c)
}

fn solve(r: &Roller, nx: usize, ny: usize, reach: f64, ends: Option<&RollerEnds>) -> ContactState {
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap();
    match ends {
        None => {
            let (a, b, gap) = r.bodies(nx, ny, reach).unwrap();
            let problem = InterfaceProblem::new(&a, &b, &gap).unwrap();
            solver.solve(&problem).unwrap()
        }
        Some(e) => {
            let (a, b, gap) = r.free_end_bodies(nx, ny, reach, e).unwrap();
            let problem = InterfaceProblem::new(&a, &b, &gap).unwrap();
            solver.solve(&problem).unwrap()
        }
    }
}

/// The largest pressure and the end column's largest.
fn figures(p: &[f64], nx: usize) -> (f64, f64) {
    let top = p.iter().fold(0.0f64, |m, v| m.max(*v));
    let end = (0..p.len())
        .filter(|k| k % nx == 0 || k % nx == nx - 1)
        .map(|k| p[k])
        .fold(0.0f64, f64::max);
    (top, end)
}

fn main() {
    let (nx, ny, reach) = (100, 41, 2.6);
    let settings = HetenyiSettings {
        depth_cells: 20,
        columns: 40,
        ..Default::default()
    };
    for (name, crown) in [
        ("straight", Crown::Straight),
        ("ISO", Crown::iso(10.0).unwrap()),
        (
            "Lundberg",
            Crown::lundberg(LOAD, 10.0, 2.1e5 / 0.91 / 2.0).unwrap(),
        ),
    ] {
        let r = roller(crown);
        println!("{name}:");
        let mut w = 1.0;
        for _ in 0..6 {
            let ends = RollerEnds {
                chamfer_mm: 0.0,
                weight: w,
            };
            let s = solve(&r, nx, ny, reach, Some(&ends));
            let (top, end) = figures(&s.pressure, nx);
            let (fit, shift) =
                fitted_weight(&faced(&r, nx, ny, reach, &ends), &s.pressure, &settings);
            println!(
                "  w {w:.3}: p_max {top:.1}, end {end:.1}; fitted {fit:.3} (shift {:.3} µm)",
                1e3 * shift
            );
            if (fit - w).abs() < 0.005 {
                break;
            }
            w = fit.clamp(0.0, 2.0);
        }
        let s = solve(&r, nx, ny, reach, None);
        let (top, end) = figures(&s.pressure, nx);
        println!("  half-space: p_max {top:.1}, end {end:.1}");
    }
}
