//! Hertz's point contact between two solids meshed apart in Gmsh: a quarter of a steel sphere
//! (R = 20 mm) on a quarter of a steel block, at several resolutions of the contact
//! (`contopt_validation::solids`): p₀ (the centre cell against Hertz's mean over it) and the
//! contact radius (the cells' second moment; the fit of Hertz's cell means beside it) against
//! Hertz, with the sub-rules k of the two bodies and, last, the fit at the cells' centres of
//! earlier versions. Then the two estimates of a on Hertz solved on the half-space grid, whose
//! influence is exact: their own error on cells of each size. The convergence tables of the
//! book's chapter "Parts in three dimensions" (`cargo xtask book --only sphere_on_block`).
//!
//! ```text
//! python3 meshes/generate.py --bench target/gmsh-bench   # once (pip install gmsh)
//! cargo run --release --example sphere_on_block -- target/gmsh-bench
//! ```
//!
//! Without a folder, the bundled mesh alone (`meshes/solid-sphere-on-block.msh`, 0.25 mm).

use std::time::Instant;

use contopt_validation::solids::{half_space_estimates, sphere_on_block};

/// Element sizes at the contact of the bench meshes (`meshes/bench/solid-sphere-on-block-*.geo`).
const FINE: [&str; 5] = ["0.4", "0.18", "0.13", "0.09", "0.06"];

/// Cells per contact radius of the half-space grid's table.
const CELLS_PER_A: [usize; 7] = [3, 4, 5, 6, 8, 12, 16];

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let root = env!("CARGO_MANIFEST_DIR");
    let mut meshes = vec![(
        "0.25 (bundled)".to_string(),
        format!("{root}/meshes/solid-sphere-on-block.msh"),
    )];
    if let Some(folder) = std::env::args().nth(1) {
        for f in FINE {
            meshes.push((
                f.to_string(),
                format!("{folder}/solid-sphere-on-block-{f}-binary.msh"),
            ));
        }
    }
    println!(
        "| size at contact mm | nodes | cells | k block, sphere | p₀ MPa (centre cell) \
         | p₀/Hertz − 1 | a mm (second moment) | a/Hertz − 1 | cell fit: a, p₀ \
         | half-space grid, same cells: a (moment), a (fit) | at centres: p₀, a | time s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    for (size, path) in meshes {
        let start = Instant::now();
        let c = sphere_on_block(&path)?;
        let took = start.elapsed().as_secs_f64();
        let same = half_space_estimates(c.cell)?;
        println!(
            "| {size} | {} | {} | {}, {} | {:.1} | {:+.2} % | {:.4} | {:+.2} % | {:+.2} %, {:+.1} % \
             | {:+.2} %, {:+.2} % | {:+.1} %, {:+.1} % | {:.1} |",
            c.nodes,
            c.points,
            c.sub_rule[0],
            c.sub_rule[1],
            c.p0[0],
            100.0 * (c.p0[0] / c.p0[1] - 1.0),
            c.a[0],
            100.0 * (c.a[0] / c.a[1] - 1.0),
            100.0 * (c.fitted[1] / c.a[1] - 1.0),
            100.0 * (c.fitted[0] / c.p0[1] - 1.0),
            100.0 * (same[0] - 1.0),
            100.0 * (same[1] - 1.0),
            100.0 * (c.centres[0] / c.p0[1] - 1.0),
            100.0 * (c.centres[1] / c.a[1] - 1.0),
            took
        );
    }
    println!();
    println!(
        "| half-space grid: cells per a | a/Hertz − 1 (second moment) | a/Hertz − 1 (cell fit) |"
    );
    println!("|---|---|---|");
    for n in CELLS_PER_A {
        let [moment, fitted] = half_space_estimates(1.0 / n as f64)?;
        println!(
            "| {n} | {:+.2} % | {:+.2} % |",
            100.0 * (moment - 1.0),
            100.0 * (fitted - 1.0)
        );
    }
    Ok(())
}
