//! The paper's axisymmetric punch without optimisation (§4): 100 MPa on the punch top,
//! frictionless contact with the base, the augmented Lagrangian with c = E·10⁴. Prints the
//! pressure at the axis (at every interface point with `--points`) and the edge peak p_max (the
//! paper: 272.53 MPa for its mesh), then how p_max moves under mesh refinement, and the ratio of
//! the peaks under the two loadings of Tables 1 and 2.
//!
//! `cargo run --release --example paper_unoptimised`

use contopt::contact::{AugmentedLagrangian, ContactSolver, InterfaceProblem};
use contopt::fem::ElementKind;
use contopt::scene::geometry::{PunchLoad, PunchMesh, PunchOnBase};
use contopt::ElasticBody;

/// The paper's axisymmetric punch on its base: the bundled scene `paper-table1`.
fn paper() -> PunchOnBase {
    PunchOnBase::bundled("paper-table1").expect("the bundled scene paper-table1 is valid")
}

fn solve(
    load: PunchLoad,
    mesh: &PunchMesh,
) -> Result<(Vec<f64>, contopt::ContactState), contopt::Error> {
    let geometry = PunchOnBase {
        load,
        mesh: *mesh,
        ..paper()
    };
    let (base, punch) = geometry.bodies()?;
    let problem = InterfaceProblem::new(&base, &punch, &vec![0.0; base.interface().len()])?;
    let c = geometry.punch.material.e() * 1e4;
    let state = AugmentedLagrangian::new(c).solve(&problem)?;
    let r = base.interface().points.iter().map(|x| x[0]).collect();
    Ok((r, state))
}

fn main() -> Result<(), contopt::Error> {
    let radius = paper().punch.radius;
    let mesh = paper().mesh;
    let (r, state) = solve(PunchLoad::Pressure(100.0), &mesh)?;
    println!("Axisymmetric punch on base, 100 MPa, {} contact elements (edge {:.2} mm), augmented Lagrangian c = E·10⁴", mesh.elements, mesh.edge_size(radius)?);
    println!(
        "{} Uzawa steps, iterp {}, iterd {}",
        state.iterations, state.iterp, state.iterd
    );
    if std::env::args().any(|a| a == "--points") {
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
    let axis = (0..r.len())
        .min_by(|&a, &b| r[a].total_cmp(&r[b]))
        .unwrap_or(0);
    println!(
        "p = {:.2} MPa at r = {:.3} mm, the point nearest the axis (--points prints every point)",
        state.pressure[axis], r[axis]
    );
    let peak = (0..r.len())
        .max_by(|&a, &b| state.pressure[a].total_cmp(&state.pressure[b]))
        .unwrap();
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
        let mesh = PunchMesh::uniform(ElementKind::Q8, n);
        let (_, by_load) = solve(PunchLoad::Pressure(100.0), &mesh)?;
        let (_, by_motion) = solve(PunchLoad::Displacement(-0.05), &mesh)?;
        println!(
            "{n:>9} {:>10.3} {:>12.2} {:>14.2} {:>10.4}",
            mesh.edge_size(radius)?,
            by_load.p_max(),
            by_motion.p_max(),
            by_motion.p_max() / by_load.p_max()
        );
    }
    println!("(paper: 272.53 under 100 MPa, 338.9 under w = -0.05 mm; ratio 1.2435)");
    Ok(())
}
