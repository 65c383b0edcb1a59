//! The bundled `filleted-punch` (the chapter "Your own part"): the paper's punch with its rim
//! rounded by a fillet, on its base, both meshed in Gmsh apart (`meshes/filleted-punch*.geo`).
//!
//! 1. Before the design (the scene without `[optimisation]`): the largest nodal contact
//!    pressure and where it acts, the largest mean pressure over a face of the base and how far
//!    the contact reaches, for the sharp punch on meshes of 1 to 0.125 mm at its rim, and
//!    fillets of 2, 5 and 10 mm on meshes of 0.1 to 0.0125 mm where the fillet begins. The
//!    sharp rim's peak grows as the mesh is refined (its pressure is singular); a fillet's
//!    face mean converges once the elements are a fraction of the contact's reach onto it
//!    (about 0.1 mm), while the nodal pressures oscillate over the last faces in contact, and
//!    falls as its radius grows.
//! 2. The design (`L1 = 0`, the C¹ controller falling to 0 at L2 = 45 mm, where the fillet
//!    begins) on meshes of 1 to 0.1 mm there: the bound p̂ against the closed form of the
//!    punch's equilibrium, p̂ = R²·p̃ / (2∫₀^L2 v r dr) = p̃R²/(0.3·L2²), the largest pressure,
//!    the largest |p − v·p̂| and where, and Δh_max. On 0.1 mm the design ends infeasible: the
//!    node where the fillet begins (in Ω_v, v = 0) carries pressure (the fillet, moved with the
//!    edge's Δh, keeps its drawn tangent while the designed face leaves the edge sloped: see
//!    the chapter); on 0.05 mm it is refused as infeasible at the fillet's first node.
//!
//! `cargo run --release --example filleted_punch`

use std::path::Path;
use std::time::Instant;

use contopt::prelude::*;
use contopt::results::CaseReport;
use contopt::scene::Format;

/// The punch's radius, the pressure on its top \[mm, MPa\] and where the fillet of 5 mm
/// begins, the controller's L2 \[mm\].
const RADIUS: f64 = 50.0;
const TOP_PRESSURE: f64 = 100.0;
const L2: f64 = 45.0;

/// The meshes before the design: (fillet radius, element size at the fillet or rim) \[mm\].
const BEFORE: [(&str, &str); 10] = [
    ("0", "1"),
    ("0", "0.5"),
    ("0", "0.25"),
    ("0", "0.125"),
    ("5", "0.1"),
    ("5", "0.05"),
    ("5", "0.025"),
    ("5", "0.0125"),
    ("2", "0.025"),
    ("10", "0.025"),
];

/// The mesh file of a fillet `rho` with elements of `h` where it begins (the bundled one for 5
/// and 0.25).
fn mesh(rho: &str, h: &str) -> String {
    match (rho, h) {
        ("5", "0.25") => "\"../meshes/filleted-punch.msh\"".into(),
        _ => format!("\"../meshes/filleted-punch-r{rho}-h{h}.msh\""),
    }
}

/// The bundled scene's first case (L1 = 0) on the mesh of `rho` and `h`, designed or not.
fn run(rho: &str, h: &str, design: bool) -> Result<(CaseReport, f64), Box<dyn std::error::Error>> {
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/filleted-punch.toml");
    let text = std::fs::read_to_string(&file)?;
    let mesh = mesh(rho, h);
    let mut edits = vec![
        ("body.0.mesh", Some(&*mesh)),
        ("body.1.mesh", Some(&*mesh)),
        ("sweep", None),
    ];
    if design {
        edits.push(("optimisation.controller.l1_mm", Some("0.0")));
    } else {
        edits.push(("optimisation", None));
    }
    let scene = Scene::parse_with(&text, Format::Toml, &file, &edits)?;
    let start = Instant::now();
    let report = scene.cases()[0].run()?;
    let ends_infeasible = matches!(report.termination, Termination::Infeasible { .. });
    if !(report.is_solved() || design && ends_infeasible) || report.limit.is_some() {
        return Err(format!(
            "{rho} mm, {h} mm: {:?} {:?}",
            report.termination, report.limit
        )
        .into());
    }
    Ok((report, start.elapsed().as_secs_f64()))
}

/// The largest mean pressure over a face of the base, (pₐ + 4pₘ + p_b)/6 of the quadratic
/// field of its face nodes' pressures (mortar: contact is checked at the base's face nodes),
/// and the largest radius in contact \[MPa, mm\]. The nodes sorted along r alternate corner,
/// middle, corner from the first face beyond the axis (the axis face's middle node carries no
/// contact of its own).
fn face_peak(report: &CaseReport) -> (f64, f64) {
    let mut nodes: Vec<(f64, f64)> = report
        .interface
        .iter()
        .map(|p| (p.x_mm[0], p.p_mpa))
        .collect();
    nodes.sort_by(|a, b| a.0.total_cmp(&b.0));
    let peak = nodes[1..]
        .windows(3)
        .step_by(2)
        .map(|w| (w[0].1 + 4.0 * w[1].1 + w[2].1) / 6.0)
        .fold(0.0, f64::max);
    let reach = nodes
        .iter()
        .filter(|n| n.1 > 0.0)
        .map(|n| n.0)
        .fold(0.0, f64::max);
    (peak, reach)
}

/// The C¹ controller of the design, L1 = 0.
fn v(r: f64) -> f64 {
    let s = (r / L2).min(1.0);
    1.0 - 3.0 * s * s + 2.0 * s * s * s
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    println!("Before the design: 100 MPa on the punch, the largest contact pressure");
    println!(
        "{:>9} {:>10} {:>7} {:>10} {:>9} {:>10} {:>9} {:>7}",
        "fillet mm",
        "element mm",
        "points",
        "p_max MPa",
        "at r mm",
        "face MPa",
        "reach mm",
        "time s"
    );
    for (rho, h) in BEFORE {
        let (report, seconds) = run(rho, h, false)?;
        let peak = report
            .interface
            .iter()
            .max_by(|a, b| a.p_mpa.total_cmp(&b.p_mpa))
            .ok_or("no points")?;
        let fillet = if rho == "0" { "sharp" } else { rho };
        let (face, reach) = face_peak(&report);
        println!(
            "{:>9} {:>10} {:>7} {:>10.1} {:>9.3} {:>10.1} {:>9.3} {:>7.2}",
            fillet,
            h,
            report.interface.len(),
            peak.p_mpa,
            peak.x_mm[0],
            face,
            reach,
            seconds
        );
    }
    let closed = TOP_PRESSURE * RADIUS * RADIUS / (0.3 * L2 * L2);
    println!();
    println!("The design, fillet 5 mm, L1 = 0, L2 = {L2} mm: closed-form p̂ = {closed:.2} MPa");
    println!(
        "{:>10} {:>10} {:>9} {:>10} {:>12} {:>9} {:>10} {:>7}",
        "element mm",
        "bound MPa",
        "err %",
        "p_max MPa",
        "|p-v·p̂| MPa",
        "at r mm",
        "Δh_max µm",
        "time s"
    );
    for h in ["1", "0.5", "0.25", "0.1"] {
        let (report, seconds) = run("5", h, true)?;
        if !report.is_solved() {
            println!("{h:>10} ends: {}", report.termination);
            continue;
        }
        let bound = report.bound_p_max_mpa.ok_or("no bound")?;
        let (excess, at) = report
            .interface
            .iter()
            .map(|p| ((p.p_mpa - v(p.x_mm[0]) * bound).abs(), p.x_mm[0]))
            .fold((0.0, 0.0), |a, b| if b.0 > a.0 { b } else { a });
        println!(
            "{:>10} {:>10.2} {:>+9.3} {:>10.2} {:>12.1e} {:>9.3} {:>10.2} {:>7.2}",
            h,
            bound,
            100.0 * (bound / closed - 1.0),
            report.p_max_mpa.ok_or("no p_max")?,
            excess,
            at,
            report.dh_max_um.ok_or("no Δh")?,
            seconds
        );
    }
    Ok(())
}
