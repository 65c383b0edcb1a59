//! A steel cylinder on a steel block in plane strain, both meshed in Gmsh apart and read from
//! one file (`meshes/cylinder-on-block.geo.inc`), against Hertz's line contact: the bundled
//! scene `cylinder-on-block` on each mesh of the series, elements of b/4 to b/32 at the
//! contact (b = 0.2971 mm, Hertz's half-width under q = 800 N/mm). p₀ is the largest point
//! pressure, b the half-width of the least-squares fit of p² = p₀² − (p₀/b)²x² to the points
//! that carry more than half of it (`fit_line_contact`).
//!
//! `cargo run --release --example cylinder_on_block`

use std::path::Path;
use std::time::Instant;

use contopt::prelude::*;
use contopt::scene::Format;
use contopt_validation::closed_form::{contact_modulus, fit_line_contact, HertzLine};

/// The meshes: elements of b/k at the contact.
const REFINEMENTS: [u32; 4] = [4, 8, 16, 32];

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/cylinder-on-block.toml");
    let text = std::fs::read_to_string(&file)?;
    let steel = Material::new(2.1e5, 0.3)?;
    let hertz = HertzLine {
        radius: 10.0,
        modulus: contact_modulus(&[steel, steel]),
    };
    // 40 MPa on the flat top of the disk's lower half, 2R = 20 mm wide.
    let q = 40.0 * 20.0;
    let (b, p0) = (hertz.half_width(q), hertz.peak_pressure(q));
    println!("Hertz: q = {q} N/mm, p0 = {p0:.2} MPa, b = {b:.5} mm");
    println!(
        "{:>10} {:>7} {:>10} {:>9} {:>9} {:>9} {:>8}",
        "element mm", "points", "p0 MPa", "p0 err %", "b mm", "b err %", "time s"
    );
    for k in REFINEMENTS {
        let mesh = format!("\"../meshes/cylinder-on-block-b{k}.msh\"");
        let edits = [("body.0.mesh", Some(&*mesh)), ("body.1.mesh", Some(&*mesh))];
        let scene = Scene::parse_with(&text, Format::Toml, &file, &edits)?;
        let start = Instant::now();
        let report = scene.cases()[0].run()?;
        let seconds = start.elapsed().as_secs_f64();
        let peak = report.p_max_mpa.ok_or("the case did not converge")?;
        let samples: Vec<(f64, f64)> = report
            .interface
            .iter()
            .map(|q| (q.x_mm[0], q.p_mpa))
            .collect();
        let (_, fitted) = fit_line_contact(&samples).ok_or("no contact to fit")?;
        println!(
            "{:>10.5} {:>7} {:>10.2} {:>+9.3} {:>9.5} {:>+9.3} {:>8.2}",
            b / f64::from(k),
            report.interface.len(),
            peak,
            100.0 * (peak / p0 - 1.0),
            fitted,
            100.0 * (fitted / b - 1.0),
            seconds
        );
    }
    Ok(())
}
