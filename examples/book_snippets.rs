//! The book's Rust snippets, compiled and run: each chapter includes its snippet from here by
//! its anchor, so that no snippet in the book can stop compiling. `cargo run --example
//! book_snippets` prints what each gives.

use contopt::fem::{ElementKind, Mesh, Spacing};
use contopt::greens::HalfSpace;
use contopt::prelude::*;
use contopt::scene::Scene;

/// The contact chapter's first snippet: the paper's punch on its base, from its bundled scene,
/// solved by the augmented Lagrangian with the paper's c = E·10⁴.
fn paper_punch() -> std::result::Result<(), Box<dyn std::error::Error>> {
    // ANCHOR: contact_first
    let scene = Scene::bundled_with("paper-table1", &[("sweep", None)])?;
    let problem = scene.cases()[0].problem()?; // the base below, the punch above, built
    let solver = AugmentedLagrangian::new(AugmentedLagrangianSettings::new(2.0e5 * 1e4))?;
    let state = solver.solve(&problem)?;
    assert!(state.is_converged(), "{}", state.termination);
    println!(
        "p_max = {:.2} MPa after {} Uzawa steps; the punch sinks by {:.3} µm",
        state.p_max(),
        state.iterations,
        1e3 * state.approach().unwrap_or(0.0)
    );
    // ANCHOR_END: contact_first
    Ok(())
}

/// The Green's-function chapter's snippet: a rigid sphere pressed by a force into a half-space
/// grid, solved matrix-free.
fn sphere_on_grid() -> Result<()> {
    let (material, cells, h, force, radius) =
        (Material::new(2.0e5, 0.3)?, 64, 0.0125, 1000.0, 10.0);
    let corner = -0.5 * (cells as f64 - 1.0) * h;
    // ANCHOR: greens_grid
    let body = HalfSpace::grid("half-space", material, cells, cells, h, h, [corner, corner])?;
    let gap: Vec<f64> = body
        .interface()
        .points()
        .iter()
        .map(|x| (x[0] * x[0] + x[1] * x[1]) / (2.0 * radius))
        .collect();
    // Pressed along +z, away from the half-space below: the indenter floats.
    let indenter = RigidBody::pressed("indenter", body.interface(), [0.0, 0.0, 1.0], force)?;
    let problem = InterfaceProblem::new(&body, &indenter, &gap)?;
    let state = PolonskyKeer::new(PolonskyKeerSettings::default())?.solve(&problem)?;
    // ANCHOR_END: greens_grid
    println!(
        "Hertz on a {cells}² grid: p_max = {:.1} MPa ({}), approach {:.3} µm",
        state.p_max(),
        state.termination,
        1e3 * state.approach().unwrap_or(0.0)
    );
    // ANCHOR: greens_edge
    // The grid ends inside the contact? (None: the half-space holds it; the indenter ends with
    // the grid along neither axis.)
    if let Some(edge) = body.edge_reached(&state.pressure, [false, false])? {
        eprintln!("warning: {}", edge.warning());
    }
    // ANCHOR_END: greens_edge
    assert_eq!(body.edge_reached(&state.pressure, [false, false])?, None);
    let heavier = RigidBody::pressed("indenter", body.interface(), [0.0, 0.0, 1.0], 8.0 * force)?;
    let heavy = InterfaceProblem::new(&body, &heavier, &gap)?;
    let cut = PolonskyKeer::new(PolonskyKeerSettings::default())?.solve(&heavy)?;
    let edge = body.edge_reached(&cut.pressure, [false, false])?;
    println!(
        "{} N on the same grid: {}",
        8.0 * force,
        edge.map_or("inside".into(), |e| e.warning())
    );
    Ok(())
}

/// The finite-element chapter's snippet: the element boundaries of a punch on its base.
fn meshes() -> Result<()> {
    // ANCHOR: fem_mesh
    let x = Spacing::graded(0.0, 100.0, 40, &[50.0], 8.0)?; // fine at the punch edge r = 50
    let (base, punch) = Mesh::stacked(
        ElementKind::Q8,
        &x,
        &Spacing::uniform(0.0, 50.0, 10)?,
        (0.0, 50.0),
        &Spacing::uniform(50.0, 100.0, 10)?,
    )?;
    // ANCHOR_END: fem_mesh
    println!(
        "stacked meshes: base {} nodes, punch {} nodes",
        base.nodes().len(),
        punch.nodes().len()
    );
    Ok(())
}

/// The optimisation chapter's snippet: Table 1's optimum for L1 = 20 mm by the iteration of
/// §3.2 under the given load, from Rust.
fn table_one() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let scene = Scene::bundled_with("paper-table1", &[("sweep", None), ("optimisation", None)])?;
    let problem = scene.cases()[0].problem()?;
    // ANCHOR: optimise_iterate
    let shape = problem
        .pressure_basis()
        .cloned() // a finite-element face: Δh at the face nodes
        .unwrap_or_else(|| GapShape::pointwise(problem.interface()));
    let controller = ControllerSettings::Cubic {
        l1_mm: 20.0,
        l2_mm: 50.0,
        axis: 0,
    }
    .build()?;
    let penalty = Penalty::new(PenaltySettings {
        c_mpa_per_mm: 2.0e9,
    })?;
    let optimum = Optimisation::new(&problem, &shape, controller.as_ref())?.iterate(
        Mode::GivenLoad,
        &penalty,
        &IterationSettings::default(),
    )?;
    println!(
        "L1 = 20 mm: p_max = {:.1} MPa, Δh_max = {:.2} µm ({}, {} passes)",
        optimum.p_max,
        1e3 * optimum.passes.last().map_or(0.0, |p| p.dh_max),
        optimum.termination,
        optimum.passes.len()
    );
    // ANCHOR_END: optimise_iterate
    Ok(())
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    paper_punch()?;
    sphere_on_grid()?;
    meshes()?;
    table_one()?;
    Ok(())
}
