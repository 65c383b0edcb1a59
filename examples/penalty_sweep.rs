//! The penalty parameter on the paper's punch (the bundled scene `paper-table1`, zero initial
//! gap, no optimisation): c = E·10ᵏ for k = 0 … 12, the augmented Lagrangian with plain Uzawa
//! steps and the penalty, each against the QP's pressure (largest difference over p_max), with
//! the penalty's penetration. The table of the book's contact chapter; the test
//! `penalty_parameter_sweep` asserts what it shows.
//!
//! `cargo run --release --example penalty_sweep`

use contopt::prelude::*;

/// The bodies' Young's modulus [MPa], the scale of c.
const E: f64 = 2.0e5;
/// Uzawa steps allowed (plain steps converge slowly at small c).
const MAX_STEPS: usize = 5000;
/// The largest exponent k of c = E·10ᵏ.
const LARGEST_K: i32 = 12;

fn main() -> std::result::Result<(), Box<dyn std::error::Error>> {
    // The paper's punch on its base, built by the bundled scene (one case: no sweep).
    let scene = Scene::bundled_with("paper-table1", &[("sweep", None)])?;
    let problem = scene.cases()[0].problem()?;
    let reference = Qp::new(QpSettings::default())?.solve(&problem)?;
    let error = |st: &ContactState| {
        st.pressure
            .iter()
            .zip(&reference.pressure)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max)
            / reference.p_max()
    };
    println!("| k | AL error | Uzawa steps | penalty error | penetration mm |");
    println!("| --- | --- | --- | --- | --- |");
    for k in 0..=LARGEST_K {
        let c = E * 10f64.powi(k);
        let al = AugmentedLagrangian::new(AugmentedLagrangianSettings {
            max_steps: MAX_STEPS,
            accelerate: false,
            ..AugmentedLagrangianSettings::new(c)
        })?
        .solve(&problem)?;
        let penalty = Penalty::new(PenaltySettings { c_mpa_per_mm: c })?.solve(&problem)?;
        // A solve that stopped short is shown with how it ended.
        let steps = match &al.termination {
            Termination::Converged => al.iterations.to_string(),
            other => format!("{} ({other})", al.iterations),
        };
        println!(
            "| {k} | {:.1e} | {steps} | {:.1e} | {:.1e} |",
            error(&al),
            error(&penalty),
            penalty.residuals.penetration
        );
    }
    Ok(())
}
