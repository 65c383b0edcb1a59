//! A uniform pressure p on r < a of a large axisymmetric block, against the elastic
//! half-space (Timoshenko & Goodier §138): the surface deflection profile relative to the
//! centre, w(0) − w(r), in a CSV and a chart (SVG and PNG) under `results/circular_load/`.
//!
//! `cargo run --release --example circular_load`

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::fs;

use contopt::fem::{Analysis, Component, ElementKind, FeModel, Material, Mesh, Spacing};
use contopt::greens::elliptic;
use contopt::report::LineChart;

const E: f64 = 2.0e5;
const NU: f64 = 0.3;
const P: f64 = 100.0;
const A: f64 = 10.0;

/// Half-space surface deflection under p on r < a.
fn half_space(r: f64) -> f64 {
    let c = 4.0 * (1.0 - NU * NU) * P / (PI * E);
    if r <= A {
        c * A * elliptic::complete(r / A).1
    } else {
        let (k, e) = elliptic::complete(A / r);
        c * r * (e - (1.0 - A * A / (r * r)) * k)
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let size = 30.0 * A;
    let r = Spacing::uniform(0.0, A, 12)?.then(&Spacing::geometric(A, size, 30, 60.0)?)?;
    let z = Spacing::geometric(-size, 0.0, 32, 1.0 / 80.0)?;
    let mut model = FeModel::new(
        Mesh::rectangle(ElementKind::Q8, &r, &z)?,
        Material::new(E, NU)?,
        Analysis::Axisymmetric,
    )?;
    let bottom = model.mesh().nodes_on_y(-size, 0.0, size);
    let load = model.mesh().faces_on_y(0.0, 0.0, A);
    model
        .fix(&bottom, Component::X)?
        .fix(&bottom, Component::Y)?
        .pressure(&load, P)?;
    let t = std::time::Instant::now();
    let solution = model.solve()?;
    let elapsed = t.elapsed();

    let mut surface: Vec<(f64, f64)> = model
        .mesh()
        .nodes_on_y(0.0, 0.0, 3.0 * A)
        .into_iter()
        .map(|n| (model.mesh().nodes()[n][0], -solution.at(n)[1]))
        .collect();
    surface.sort_by(|a, b| a.0.total_cmp(&b.0));
    let w0 = surface[0].1;
    let mut csv = String::from("r_mm,fe_w0_minus_w_um,half_space_w0_minus_w_um\n");
    let (mut fe_curve, mut exact_curve) = (vec![], vec![]);
    for &(r, w) in &surface {
        let (fe, exact) = (1e3 * (w0 - w), 1e3 * (half_space(0.0) - half_space(r)));
        writeln!(csv, "{r:.6},{fe:.6},{exact:.6}")?;
        fe_curve.push((r, fe));
        exact_curve.push((r, exact));
    }
    let at_edge = |c: &[(f64, f64)]| c.iter().find(|p| (p.0 - A).abs() < 1e-9).unwrap().1;
    let (fe_edge, exact_edge) = (at_edge(&fe_curve), at_edge(&exact_curve));
    let dir = "results/circular_load";
    fs::create_dir_all(dir)?;
    fs::write(format!("{dir}/surface.csv"), csv)?;
    let chart = LineChart::new(
        "Surface under p on r < a: w(0) − w(r)",
        "r [mm]",
        "w(0) − w(r) [µm]",
    )
    .line("finite elements", &fe_curve)
    .reference("half-space (Timoshenko & Goodier §138)", &exact_curve);
    for (name, bytes) in chart.draw()?.files("surface")? {
        fs::write(format!("{dir}/{name}"), bytes)?;
    }
    let summary = format!(
        "uniform pressure {P} MPa on r < {A} mm of a {size} x {size} mm axisymmetric block (E = {E} MPa, nu = {NU})\n\
         {} unknowns, solved in {:.1} ms\n\
         w(0) - w(a): finite elements {fe_edge:.4} um, half-space {exact_edge:.4} um ({:+.2} %)\n\
         wrote {dir}/surface.csv and {dir}/surface.{{svg,png}}\n",
        2 * model.mesh().nodes().len(),
        elapsed.as_secs_f64() * 1e3,
        100.0 * (fe_edge / exact_edge - 1.0)
    );
    fs::write(format!("{dir}/summary.txt"), &summary)?;
    print!("{summary}");
    Ok(())
}
