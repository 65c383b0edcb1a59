//! The paper's axisymmetric punch without optimisation (§4): 100 MPa on the punch top,
//! frictionless contact with the base, the augmented Lagrangian with c = E·10⁴. Prints the
//! pressure at the axis (at every interface point with `--points`) and the edge peak p_max (the
//! paper: 272.53 MPa for its mesh), then how p_max moves under mesh refinement, and the ratio of
//! the peaks under the two loadings of Tables 1 and 2.
//!
//! `cargo run --release --example paper_unoptimised`

use contopt::prelude::*;
use contopt::scene::FacesZone;

/// The paper's penalty parameter c = E·10⁴ \[MPa/mm\] (E = 2·10⁵ MPa), here the augmented
/// Lagrangian's.
const C: f64 = 2.0e9;

/// A solve of the punch on its base: the radii of the points, the state and the size of the
/// elements at the punch edge \[mm\].
struct Solved {
    r: Vec<f64>,
    state: ContactState,
    edge: f64,
}

/// The paper's punch on its base on `elements` uniform quadratic elements across the contact
/// radius (as many layers through each body), zero initial gap, solved without optimisation:
/// the bundled scene `name`, `paper-table1` under 100 MPa or `paper-table2` pressed down by
/// w = −0.05 mm.
fn solve(name: &str, elements: usize) -> std::result::Result<Solved, Box<dyn std::error::Error>> {
    let elements = elements.to_string();
    let scene = Scene::bundled_with(
        name,
        &[
            ("contact.zone.elements", Some(&elements)),
            ("sweep", None),
            ("optimisation", None),
        ],
    )?;
    let case = &scene.cases()[0];
    let edge = match case.spec.contact.zone.downcast::<FacesZone>() {
        Some(faces) => faces.edge_size()?,
        None => f64::NAN,
    };
    let problem = case.problem()?;
    let state = AugmentedLagrangian::new(AugmentedLagrangianSettings::new(C))?.solve(&problem)?;
    let r = problem.interface().points().iter().map(|x| x[0]).collect();
    Ok(Solved { r, state, edge })
}

/// Every point's radius, pressure and gap, by radius.
fn print_points(r: &[f64], state: &ContactState) {
    println!("{:>10} {:>12} {:>14}", "r [mm]", "p [MPa]", "d [µm]");
    let mut order: Vec<usize> = (0..r.len()).collect();
    order.sort_by(|&a, &b| r[a].total_cmp(&r[b]));
    for &i in &order {
        println!(
            "{:>10.3} {:>12.3} {:>14.6}",
            r[i],
            state.pressure[i],
            1e3 * state.gap[i]
        );
    }
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let Solved { r, state, edge } = solve("paper-table1", 18)?;
    println!("Axisymmetric punch on base, 100 MPa, 18 contact elements (edge {edge:.2} mm), augmented Lagrangian c = E·10⁴");
    println!(
        "{} Uzawa steps, iterp {}, iterd {}",
        state.iterations, state.iterp, state.iterd
    );
    if !state.is_converged() {
        println!("the solve {}", state.termination);
    }
    if std::env::args().any(|a| a == "--points") {
        print_points(&r, &state);
    }
    let axis = (0..r.len())
        .min_by(|&a, &b| r[a].total_cmp(&r[b]))
        .unwrap_or(0);
    println!(
        "p = {:.2} MPa at r = {:.3} mm, the point nearest the axis (--points prints every point)",
        state.pressure[axis], r[axis]
    );
    let peak = (0..r.len())
        .max_by(|&a, &b| state.pressure[a].total_cmp(&state.pressure[b]))
        .unwrap_or(0);
    println!(
        "p_max = {:.2} MPa at r = {:.3} mm (paper: 272.53 MPa for its mesh)\n",
        state.p_max(),
        r[peak]
    );

    println!(
        "Refinement (uniform contact elements; the edge is a singular point, p_max ~ h^-0.23):"
    );
    println!(
        "{:>9} {:>10} {:>12} {:>14} {:>10}",
        "elements", "edge mm", "p_max MPa", "p_max(w) MPa", "ratio"
    );
    for n in [9, 18, 36, 72] {
        let by_load = solve("paper-table1", n)?;
        let by_motion = solve("paper-table2", n)?;
        let (p, pw) = (by_load.state.p_max(), by_motion.state.p_max());
        println!(
            "{n:>9} {:>10.3} {p:>12.2} {pw:>14.2} {:>10.4}",
            by_load.edge,
            pw / p
        );
    }
    println!("(paper: 272.53 under 100 MPa, 338.9 under w = -0.05 mm; ratio 1.2435)");
    Ok(())
}
