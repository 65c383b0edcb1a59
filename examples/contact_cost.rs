//! Every contact solver on Hertz on the finite-element half-space stand-in (interfaces of about
//! 50, 200 and 1000 points): one solve each, its time, and its errors against the QP's solution
//! (pressure over p_max, gap over the approach, approach relative). The table of the book's
//! contact chapter; `cargo bench --bench contact` times the same solves with criterion.
//!
//! A rigid sphere (R = 100 mm) presses the block with the force that gives a 1 mm contact
//! radius inside a 1.5 mm candidate zone, so a third of the points stay open. With three Gauss
//! points per quadratic face the QP's minimisers share d and λ but not p at elements partly in
//! contact: there the pressure column says which minimiser a method returns.
//!
//! `cargo run --release --example contact_cost`

use std::time::Instant;

use contopt::prelude::*;
use contopt_validation::fixtures::hertz_on_block;

/// The block's modulus E [MPa] ([`hertz_on_block`]).
const E: f64 = 2.0e5;
/// The penalty parameter of the penalty and the augmented Lagrangian [MPa/mm].
const C: f64 = E * 1e4;
/// Contact faces of the three interfaces (three points each).
const FACES: [usize; 3] = [17, 67, 333];

/// The largest difference of `a` from `b`.
fn difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The solvers with their labels, the QP (the reference) first.
fn solvers() -> Result<[(&'static str, Box<dyn ContactSolver>); 4]> {
    Ok([
        ("QP (clarabel)", Box::new(Qp::new(QpSettings::default())?)),
        (
            "active set",
            Box::new(ActiveSet::new(ActiveSetSettings::default())?),
        ),
        (
            "augmented Lagrangian",
            Box::new(AugmentedLagrangian::new(AugmentedLagrangianSettings::new(
                C,
            ))?),
        ),
        (
            "penalty",
            Box::new(Penalty::new(PenaltySettings { c_mpa_per_mm: C })?),
        ),
    ])
}

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    let solvers = solvers()?;
    println!(
        "{:>6}  {:<22} {:>8} {:>8} {:>8} {:>6} {:>6} {:>6} {:>9}",
        "points", "solver", "p error", "d error", "λ error", "iters", "iterp", "iterd", "time ms"
    );
    for faces in FACES {
        let problem = hertz_on_block(faces)?;
        let t = Instant::now();
        let reference = solvers[0].1.solve(&problem)?;
        let reference_ms = t.elapsed().as_secs_f64() * 1e3;
        let approach = reference.approach().unwrap_or(f64::NAN);
        for (k, (label, solver)) in solvers.iter().enumerate() {
            // The reference (the first solver) is solved once.
            let t = Instant::now();
            let (st, ms) = match k {
                0 => (reference.clone(), reference_ms),
                _ => (solver.solve(&problem)?, t.elapsed().as_secs_f64() * 1e3),
            };
            let dp = difference(&st.pressure, &reference.pressure) / reference.p_max();
            let dd = difference(&st.gap, &reference.gap) / approach.abs();
            let dl = (st.approach().unwrap_or(f64::NAN) / approach - 1.0).abs();
            // The first solver is the reference: its errors are blank.
            let errors = [dp, dd, dl].map(|e| match k {
                0 => "—".to_string(),
                _ => format!("{e:.1e}"),
            });
            println!(
                "{:>6}  {:<22} {:>8} {:>8} {:>8} {:>6} {:>6} {:>6} {ms:>9.2}",
                problem.len(),
                label,
                errors[0],
                errors[1],
                errors[2],
                st.iterations,
                st.iterp,
                st.iterd
            );
            if !st.is_converged() {
                println!("        {label} {}", st.termination);
            }
        }
    }
    Ok(())
}
