//! A roller's free ends: Hetényi's superposition of half-spaces for the quarter-space, the
//! image pressure's weight that matches it, and what free ends change in the crowns.
//!
//! 1. Hetényi's superposition (`contopt::greens::hetenyi_load`) under a Hertz strip running
//!    into the end face: its rounds, and how the image weight it implies settles as the face's
//!    depth and the columns it reaches grow (truncation).
//! 2. The roller of `roller-study` (D = l = 10 mm, Q = 5446 N, steel) on its raceway: the
//!    contact solved with the image of weight w, the weight fitted to Hetényi's displacement
//!    under that contact's pressure, and solved again until the two agree — for the straight,
//!    Lundberg, ISO and an optimised crown; beside the half-space's.
//! 3. The crowns of `roller-study` and `roller-envelope` with the roller's ends free (the
//!    image of the default weight) and without: p_max and the end column's peak, for the
//!    crowns as given and as designed again with free ends.
//!
//! `cargo run --example free_ends` (a few minutes in the dev profile).

use contopt::greens::{hetenyi_load, FacedGrid, FreeEnds, HetenyiSettings};
use contopt::prelude::*;
use contopt::roller::{Crown, Roller, RollerEnds};
use contopt::scene::{Format, Scene, FREE_END_WEIGHT};

const LOAD: f64 = 5446.0;
const E: f64 = 2.1e5;
const NU: f64 = 0.3;

fn steel() -> Material {
    Material::new(E, NU).unwrap()
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

/// The grid of `r` (`nx` × `ny` cells reaching ±`reach`·b) with its end faces at the grid's
/// ends, as Hetényi's superposition takes it.
fn faced(r: &Roller, nx: usize, ny: usize, reach: f64) -> FacedGrid {
    let [dx, dy] = r.cell(nx, ny, reach).unwrap();
    let face = 0.5 * r.length;
    FacedGrid {
        nx,
        ny,
        dx,
        dy,
        origin: [-0.5 * r.length + 0.5 * dx, -(((ny - 1) / 2) as f64) * dy],
        nu: NU,
        faces: [Some(-face), Some(face)],
    }
}

/// The weight w (and shift c) with C(p + w·Mp) + c closest to Hetényi's C(I + M)T over the
/// cells where p > 0, least squares; C the roller's half-space operator, M the reflection,
/// T Hetényi's load for p. Also the rounds Hetényi took.
fn fitted_weight(g: &FacedGrid, p: &[f64], settings: &HetenyiSettings) -> (f64, usize) {
    let n = g.nx * g.ny;
    let image = |w: f64| {
        FreeEnds::grid("r", steel(), g.nx, g.ny, g.dx, g.dy, g.origin, g.faces, w).unwrap()
    };
    let (one, zero) = (image(1.0), image(0.0));
    let t = hetenyi_load(g, p, settings).unwrap();
    let force = |q: &[f64]| -> Vec<f64> { q.iter().map(|v| v * g.dx * g.dy).collect() };
    let (mut uh, mut u0, mut u1) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    one.apply_influence(&force(&t.load), &mut uh);
    zero.apply_influence(&force(p), &mut u0);
    one.apply_influence(&force(p), &mut u1);
    // r = uh − u0 ≈ w·m + c, m = u1 − u0.
    let (mut smm, mut sm, mut s1, mut srm, mut sr) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for k in (0..n).filter(|&k| p[k] > 0.0) {
        let (r, m) = (uh[k] - u0[k], u1[k] - u0[k]);
        (smm, sm, s1, srm, sr) = (smm + m * m, sm + m, s1 + 1.0, srm + r * m, sr + r);
    }
    ((srm * s1 - sr * sm) / (smm * s1 - sm * sm), t.rounds)
}

/// The contact of `r` on `nx` × `ny` cells, its roller's ends free with the image's `weight`
/// (or a half-space roller).
fn solve(r: &Roller, nx: usize, ny: usize, reach: f64, weight: Option<f64>) -> ContactState {
    let solver = PolonskyKeer::new(PolonskyKeerSettings::default()).unwrap();
    match weight {
        None => {
            let (a, b, gap) = r.bodies(nx, ny, reach).unwrap();
            let problem = InterfaceProblem::new(&a, &b, &gap).unwrap();
            solver.solve(&problem).unwrap()
        }
        Some(weight) => {
            let ends = RollerEnds {
                chamfer_mm: 0.0,
                weight,
            };
            let (a, b, gap) = r.free_end_bodies(nx, ny, reach, &ends).unwrap();
            let problem = InterfaceProblem::new(&a, &b, &gap).unwrap();
            solver.solve(&problem).unwrap()
        }
    }
}

/// The largest pressure and the end columns' largest.
fn figures(p: &[f64], nx: usize) -> (f64, f64) {
    let top = p.iter().fold(0.0f64, |m, v| m.max(*v));
    let end = (0..p.len())
        .filter(|k| k % nx == 0 || k % nx == nx - 1)
        .map(|k| p[k])
        .fold(0.0f64, f64::max);
    (top, end)
}

/// Part 1: Hetényi under a Hertz strip of uniform height running into the faces of a roller's
/// grid, and the weight it implies as the face's depth and the columns grow.
fn truncation() {
    println!("## Hetényi's superposition under a Hertz strip running into the end faces\n");
    println!("b = 0.1733 mm (the roller's Hertz half-width), 100 × 41 cells over 10 mm × ±2.6 b, ν = 0.3");
    println!("(the weight: the image's that matches Hetényi's deflection, by least squares over the strip)\n");
    println!(" face depth [cells of 0.0225 mm] | rows beyond the grid's | columns [of 0.1 mm] | rounds | weight");
    let r = roller(Crown::Straight);
    let (b, _) = r.hertz().unwrap();
    let strip = |g: &FacedGrid| -> Vec<f64> {
        (0..g.nx * g.ny)
            .map(|k| {
                let y = g.origin[1] + (k / g.nx) as f64 * g.dy;
                (1.0 - (y / b).powi(2)).max(0.0).sqrt()
            })
            .collect()
    };
    let g = faced(&r, 100, 41, 2.6);
    for (depth, margin, columns) in [
        (20, 0, 40),
        (40, 0, 40),
        (40, 20, 40),
        (80, 40, 40),
        (120, 40, 40),
        (80, 80, 40),
        (80, 40, 60),
    ] {
        let settings = HetenyiSettings {
            depth_cells: depth,
            margin_rows: margin,
            columns,
            ..Default::default()
        };
        let (w, rounds) = fitted_weight(&g, &strip(&g), &settings);
        println!(" {depth:32} | {margin:21} | {columns:19} | {rounds:6} | {w:.3}");
    }
    // The same on a grid twice as fine both ways (the face's cells with it).
    let fine = faced(&r, 200, 81, 2.6);
    let settings = HetenyiSettings {
        depth_cells: 160,
        margin_rows: 80,
        columns: 80,
        ..Default::default()
    };
    let (w, rounds) = fitted_weight(&fine, &strip(&fine), &settings);
    println!("\nOn 200 × 81 cells (the face 160 cells deep, 80 rows beyond, 80 columns of 0.05 mm): {rounds} rounds, weight {w:.3}");
}

/// Part 2: the weight that makes the image model's contact agree with Hetényi's, per crown.
fn self_consistent() {
    println!("\n## The image weight that agrees with Hetényi in the roller's contact\n");
    println!("D = l = 10 mm, Q = 5446 N, steel on steel, flat raceway, 100 × 41 cells (±2.6 b); the end faces at the");
    println!("grid's ends. Solved with weight w, w fitted to Hetényi's deflection under that pressure, solved again.\n");
    println!(" crown | half-space: p_max, end [MPa] | w = 1 (image): p_max, end | settled w | p_max, end");
    let (nx, ny, reach) = (100, 41, 2.6);
    let settings = HetenyiSettings::default();
    let e_star = E / (2.0 * (1.0 - NU * NU));
    for (name, crown) in [
        ("straight", Crown::Straight),
        ("Lundberg", Crown::lundberg(LOAD, 10.0, e_star).unwrap()),
        ("ISO/TS 16281", Crown::iso(10.0).unwrap()),
    ] {
        let r = roller(crown);
        let half = figures(&solve(&r, nx, ny, reach, None).pressure, nx);
        let image = figures(&solve(&r, nx, ny, reach, Some(1.0)).pressure, nx);
        let mut w = 1.0;
        let mut settled = image;
        for _ in 0..8 {
            let s = solve(&r, nx, ny, reach, Some(w));
            settled = figures(&s.pressure, nx);
            let (fit, _) = fitted_weight(&faced(&r, nx, ny, reach), &s.pressure, &settings);
            let done = (fit - w).abs() < 0.002;
            w = fit;
            if done {
                break;
            }
        }
        println!(
            " {name} | {:.1}, {:.1} | {:.1}, {:.1} | {w:.3} | {:.1}, {:.1}",
            half.0, half.1, image.0, image.1, settled.0, settled.1
        );
    }
}

/// A roller scene of `cells` with the roller's ends free (`free`) or not, and the cases of
/// `cases` (TOML `[[case]]` tables).
fn roller_scene(cells: [usize; 2], free: bool, cases: &str, envelope: bool) -> Scene {
    let ends = match free {
        true => format!("free_ends = {{ faces_mm = [-5.0, 5.0], weight = {FREE_END_WEIGHT} }}"),
        false => String::new(),
    };
    let envelope = match envelope {
        true => "[envelope]\nload_factors = [0.5, 1.0, 1.5]\ntilts_arcmin = [-2.0, 0.0, 2.0]\n",
        false => "",
    };
    let text = format!(
        "name = \"free-ends\"\n\
         [contact]\n\
         zone = {{ kind = \"grid\", cells = [{}, {}] }}\n\
         gap = {{ kind = \"roller\", diameter_mm = 10.0, length_mm = 10.0 }}\n\
         load = {{ force_n = {LOAD} }}\n\
         [[body]]\nname = \"raceway\"\nkind = \"half_space\"\nmaterial = {{ e_mpa = {E}, nu = {NU} }}\n\
         [[body]]\nname = \"roller\"\nkind = \"half_space\"\nmaterial = {{ e_mpa = {E}, nu = {NU} }}\n{ends}\n\
         [solver]\nkind = \"polonsky_keer\"\n{envelope}{cases}",
        cells[0], cells[1]
    );
    Scene::parse(&text, Format::Toml, std::path::Path::new("free-ends.toml")).unwrap()
}

/// Part 3: the crowns of the roller study and the envelope with and without free ends.
fn crowns() {
    let cells = [100, 53];
    println!("\n## What free ends change in the crowns ({} × {} cells, the image of weight {FREE_END_WEIGHT})\n", cells[0], cells[1]);
    let study = "[[case]]\nlabel = \"ISO/TS 16281\"\nset = { \"contact.gap.profile\" = \"iso\" }\n\
         [[case]]\nlabel = \"Lundberg\"\nset = { \"contact.gap.profile\" = \"lundberg\" }\n\
         [[case]]\nlabel = \"optimised at Q, L1 = 5 mm\"\nset = { optimisation = { method = \"load_split\", controller = { kind = \"cubic\", l1_mm = 5.0, l2_mm = 5.0 } } }\n";
    let envelope = "[[case]]\nlabel = \"robust, L1 = 5 mm\"\nset = { optimisation = { method = { kind = \"envelope_split\", tolerance = 1e-7 }, controller = { kind = \"cubic\", l1_mm = 5.0, l2_mm = 5.0 } } }\n\
         [[case]]\nlabel = \"Fujiwara-Kawase tuned\"\nset = { optimisation = { method = \"profile_search\" } }\n";
    println!(" crown | half-space roller: p_max, end [MPa], end drop [µm] | free ends: the same | worst over the envelope: half-space, free");
    let run = |scene: Scene| -> Vec<(String, f64, f64, f64, Option<f64>)> {
        scene
            .run()
            .map(|r| {
                let r = r.unwrap();
                let nx = cells[0];
                let p: Vec<f64> = r.interface.iter().map(|q| q.p_mpa).collect();
                let (top, end) = figures(&p, nx);
                let roller = r.roller.as_ref();
                let drop = roller.map_or(f64::NAN, |x| x.crown_drop_end_um);
                let worst = roller.and_then(|x| x.worst_p_max_mpa);
                (r.label, top, end, drop, worst)
            })
            .collect()
    };
    for (cases, env) in [(study, false), (envelope, true)] {
        let plain = run(roller_scene(cells, false, cases, env));
        let free = run(roller_scene(cells, true, cases, env));
        for (a, b) in plain.iter().zip(&free) {
            let worst = match (a.4, b.4) {
                (Some(x), Some(y)) => format!("{x:.1}, {y:.1}"),
                _ => "-".into(),
            };
            println!(
                " {} | {:.1}, {:.1}, {:.2} | {:.1}, {:.1}, {:.2} | {worst}",
                a.0, a.1, a.2, a.3, b.1, b.2, b.3
            );
        }
    }
    println!(
        "\n(the designed crowns are designed again with free ends: each row compares two designs)"
    );
}

fn main() {
    truncation();
    self_consistent();
    crowns();
}
