//! Stresses below a half-space grid: accuracy against Hertz's closed forms on the axis, and
//! run time at the roller's production size. Prints the tables of the book's "Below the
//! surface" section and charts the finest grids' stresses along the axis against the closed
//! forms, `results/subsurface_stresses/axis_{line,sphere}.{svg,png}`.
//!
//! `cargo run --release --example subsurface_stresses` (or `-- speed N` for the run-time
//! table alone at N depths, to compare peak memory across depth counts).

use std::time::Instant;

use contopt::greens::HalfSpace;
use contopt::prelude::*;
use contopt::report::LineChart;
use contopt::{Section, SectionAxis, StressTensor, Subsurface, SubsurfaceRequest};

const NU: f64 = 0.3;

fn steel() -> Material {
    Material::new(2e5, NU).expect("steel is a valid material")
}

/// An odd grid centred on the origin, loaded by `pressure` at the cell centres.
fn grid(n: [usize; 2], h: [f64; 2], pressure: impl Fn(f64, f64) -> f64) -> (HalfSpace, Vec<f64>) {
    let origin = [
        -((n[0] - 1) as f64) / 2.0 * h[0],
        -((n[1] - 1) as f64) / 2.0 * h[1],
    ];
    let body = HalfSpace::grid("half-space", steel(), n[0], n[1], h[0], h[1], origin)
        .expect("a valid grid");
    let p = body
        .interface()
        .points()
        .iter()
        .map(|x| pressure(x[0], x[1]))
        .collect();
    (body, p)
}

/// Depths from `from` to `to` in `count` equal steps.
fn depths(from: f64, to: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| from + (to - from) * k as f64 / (count - 1) as f64)
        .collect()
}

/// The largest value of `criterion` along a depth profile, and where.
fn profile_peak(
    depths: &[f64],
    stress: impl Fn(f64) -> StressTensor,
    criterion: fn(&StressTensor) -> f64,
) -> (f64, f64) {
    depths
        .iter()
        .map(|&z| (criterion(&stress(z)), z))
        .fold((f64::MIN, 0.0), |m, v| if v.0 > m.0 { v } else { m })
}

/// The axis (centre of the section through y = 0) of a computed subsurface field.
fn axis_peak(sub: &Subsurface, criterion: fn(&StressTensor) -> f64) -> (f64, f64) {
    let s = &sub.sections[0];
    let centre = s.positions.len() / 2;
    (0..s.depths.len())
        .map(|k| (criterion(s.at(k, centre)), s.depths[k]))
        .fold((f64::MIN, 0.0), |m, v| if v.0 > m.0 { v } else { m })
}

/// The chart of the criteria along the axis of a computed field against the closed form
/// `exact` (p₀ = 1, depths in b or a): `results/subsurface_stresses/axis_<name>.{svg,png}`.
fn axis_chart(name: &str, sub: &Subsurface, exact: fn(f64) -> StressTensor) -> std::io::Result<()> {
    let s = &sub.sections[0];
    let centre = s.positions.len() / 2;
    let title = format!("Hertz {name} contact: stresses below the axis, ν = {NU}");
    let depth = if name == "line" {
        "depth z / b"
    } else {
        "depth z / a"
    };
    let mut chart = LineChart::new(&title, depth, "stress / p₀");
    for (criterion, f) in CRITERIA {
        let computed: Vec<(f64, f64)> = (0..s.depths.len())
            .map(|k| (s.depths[k], f(s.at(k, centre))))
            .collect();
        let closed: Vec<(f64, f64)> = s.depths.iter().map(|&z| (z, f(&exact(z)))).collect();
        chart = chart
            .line(&format!("{criterion}, grid"), &computed)
            .reference(&format!("{criterion}, closed form"), &closed);
    }
    let dir = std::path::Path::new("results/subsurface_stresses");
    std::fs::create_dir_all(dir)?;
    for (file, bytes) in chart.draw()?.files(&format!("axis_{name}"))? {
        std::fs::write(dir.join(file), bytes)?;
    }
    Ok(())
}

/// McEwen's line-contact stresses on the axis (p₀ = b = 1), plane strain.
fn line_axis(z: f64) -> StressTensor {
    let root = (1.0 + z * z).sqrt();
    let (xx, zz) = (-((1.0 + 2.0 * z * z) / root - 2.0 * z), -1.0 / root);
    StressTensor {
        xx,
        yy: NU * (xx + zz),
        zz,
        ..Default::default()
    }
}

/// Hertz's sphere stresses on the axis (p₀ = a = 1).
fn sphere_axis(z: f64) -> StressTensor {
    let rr = -((1.0 + NU) * (1.0 - z * (1.0 / z).atan()) - 0.5 / (1.0 + z * z));
    StressTensor {
        xx: rr,
        yy: rr,
        zz: -1.0 / (1.0 + z * z),
        ..Default::default()
    }
}

fn through_centre() -> Vec<Section> {
    vec![Section {
        axis: SectionAxis::X,
        at: 0.0,
    }]
}

type Criterion = (&'static str, fn(&StressTensor) -> f64);

/// A validation case: its name, the loaded grid and the closed form on its axis.
type Case = (&'static str, HalfSpace, Vec<f64>, fn(f64) -> StressTensor);

const CRITERIA: [Criterion; 2] = [
    ("Tresca", StressTensor::tresca),
    ("von Mises", StressTensor::von_mises),
];

/// Hertz's line contact and sphere at three resolutions against the closed forms.
fn validation() {
    println!("## Hertz contacts below the axis, ν = 0.3 (values / p₀, depths / b or a)\n");
    println!("| contact | cells per b or a | criterion | peak | exact | depth | exact | time |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- |");
    let fine = depths(0.3, 1.2, 451);
    for per in [16usize, 32, 64] {
        let h = 1.0 / per as f64;
        let line = |x: f64, _: f64| (1.0 - x * x).max(0.0).sqrt();
        // 100 b cells along the line, where the pressure does not change.
        let cases: [Case; 2] = {
            let (lb, lp) = grid([2 * (5 * per / 4) + 1, 201], [h, 100.0], line);
            let sphere = |x: f64, y: f64| (1.0 - x * x - y * y).max(0.0).sqrt();
            let n = 2 * (5 * per / 4) + 1;
            let (sb, sp) = grid([n, n], [h, h], sphere);
            [("line", lb, lp, line_axis), ("sphere", sb, sp, sphere_axis)]
        };
        for (name, body, p, exact) in cases {
            let request = SubsurfaceRequest {
                depths: fine.clone(),
                sections: through_centre(),
            };
            let start = Instant::now();
            let sub = body.stresses_below(&p, &request).expect("a valid request");
            let time = start.elapsed().as_secs_f64();
            if per == 64 {
                axis_chart(name, &sub, exact).expect("results/subsurface_stresses is writable");
            }
            for (criterion, f) in CRITERIA {
                let (value, depth) = axis_peak(&sub, f);
                let (want, want_depth) = profile_peak(&fine, exact, f);
                println!(
                    "| {name} | {per} | {criterion} | {value:.4} | {want:.4} | {depth:.3} | \
                     {want_depth:.3} | {time:.2} s |"
                );
            }
        }
    }
}

/// The roller's production grid: 200 × 105 cells, `count` depths, peaks and three sections.
fn speed(count: usize) {
    println!("\n## Run time: every cell at every depth, peaks and three sections (one core)\n");
    println!("| grid | depths | time | per depth | largest von Mises | at depth |");
    println!("| --- | --- | --- | --- | --- | --- |");
    // A line contact of half-width 0.17 mm, 2000 MPa, over the middle 8 of 10 mm.
    let (b, p0) = (0.17334, 2000.0);
    let pressure = |x: f64, y: f64| {
        if y.abs() < 4.0 {
            p0 * (1.0 - (x / b).powi(2)).max(0.0).sqrt()
        } else {
            0.0
        }
    };
    for (nx, ny) in [(105usize, 200usize), (209, 400)] {
        let (body, p) = grid(
            [nx, ny],
            [2.6 * 2.0 * b / nx as f64, 10.0 / ny as f64],
            pressure,
        );
        let request = SubsurfaceRequest {
            depths: depths(0.01, 0.6, count),
            sections: [0.0, 3.5, 3.9]
                .iter()
                .map(|&at| Section {
                    axis: SectionAxis::X,
                    at,
                })
                .collect(),
        };
        let start = Instant::now();
        let sub = body.stresses_below(&p, &request).expect("a valid request");
        let time = start.elapsed().as_secs_f64();
        println!(
            "| {nx} × {ny} | {count} | {time:.2} s | {:.1} ms | {:.1} MPa | {:.3} mm |",
            1e3 * time / count as f64,
            sub.peaks.von_mises.value,
            sub.peaks.von_mises.depth
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    match args.get(1).map(String::as_str) {
        Some("speed") => speed(args.get(2).and_then(|n| n.parse().ok()).unwrap_or(40)),
        _ => {
            validation();
            speed(40);
        }
    }
}
